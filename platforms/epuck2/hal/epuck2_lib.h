/*
 * epuck2_lib.h - the functions of GCtronic's e-puck2 main-processor library
 * (e-puck2_main-processor, STM32F407 over ChibiOS) that platforms/epuck2/hal
 * calls, declared here with the signatures of the library's public headers
 * so that our code compiles without the library (and without ChibiOS,
 * whose hal.h would shadow ours).
 *
 * The library is user-supplied (EPUCK2_LIB_DIR: platforms/epuck2/platform.mk)
 * and never copied into this repository.  Each group names the library
 * header it comes from, relative to the library's src/ folder.  `int` is
 * 32 bits there (arm-none-eabi); these prototypes keep the library's own
 * types and hal_epuck2.c converts at the boundary.  Parameters of the
 * library's enum types (led_name_t, format_t, subsampling_t,
 * capture_mode_t) are declared int with the enumerators' values: an
 * argument takes a 32-bit register or stack word either way (AAPCS), and
 * the values fit every enum size.
 *
 * The native API, not the e-puck1 compatibility layer of src/epuck1x/:
 * that layer's agenda (e_activate_agenda) never calls its callback, its
 * UART1 calls block on ChibiOS's serial queues (e_getchar_uart1 waits for
 * a byte, e_uart1_sending always says 0), e_play_sound plays one of five
 * fixed frequencies chosen by the offset, and e_poxxxx_config_cam turns
 * any zoom other than 1, 2 or 4 into 4 (docs/hardware/epuck2.md).
 */
#ifndef EPUCK2_LIB_H
#define EPUCK2_LIB_H

#include <stdint.h>

/* The robot's facts the simulator shares (the motors' limit, the camera's
 * sensor, the microphones' count and rate) are in hal/platform_facts.h,
 * written once: EPUCK2_MOTOR_SPEED_LIMIT, EPUCK2_MIC_COUNT,
 * EPUCK2_MIC_RATE_HZ, EPUCK2_CAMERA_SENSOR_WIDTH_PX and _HEIGHT_PX. */
#include "platform_facts.h"

/* motors.h: stepper motors, speed in steps/s (MOTOR_SPEED_LIMIT 1100),
 * position counters in steps (32-bit). */
void motors_init(void);
void left_motor_set_speed(int speed);
void right_motor_set_speed(int speed);
int32_t left_motor_get_pos(void);
int32_t right_motor_get_pos(void);
/* motors.h MOTOR_SPEED_LIMIT, steps/s: EPUCK2_MOTOR_SPEED_LIMIT (platform_facts.h). */

/* leds.h: the 4 red LEDs (led_name_t: LED1 front, LED3 right, LED5 back,
 * LED7 left = 0..3), value 0 off, 1 on; the 4 RGB LEDs between them
 * (rgb_led_name_t: LED2 front-right, LED4 back-right, LED6 back-left, LED8
 * front-left = 0..3), each colour 0..RGB_MAX_INTENSITY (100), driven by the
 * ESP32 over SPI (spi_comm.h); the body and front LEDs. */
void set_led(int led_number, unsigned int value);
void set_rgb_led(int led_number, uint8_t red_val, uint8_t green_val, uint8_t blue_val);
void set_body_led(unsigned int value);
void set_front_led(unsigned int value);
void clear_leds(void);
#define EPUCK2_RGB_MAX_INTENSITY 100u

/* spi_comm.h: the SPI link to the ESP32 (the RGB LEDs, the button); it
 * must be suspended while the camera's DCMI captures (the library's own
 * e_poxxxx_launch_capture does so). */
void spi_comm_start(void);
void spi_comm_suspend(void);
void spi_comm_resume(void);

/* selector.h: the 16-way selector, 0..15. */
int get_selector(void);

/* sensors/proximity.h: the 8 IR sensors, sampled by the library's own
 * thread (FAST_UPDATE: 100 Hz; SLOW_UPDATE: 20 Hz, for the
 * range-and-bearing turret); calibrated proximity (larger = closer) and
 * ambient light (LED off; raw 12-bit A/D).  calibrate_ir: nothing within
 * ~10 cm while it runs.  Not with the ircom module (epuck2_lib_ircom.h). */
void proximity_start(uint8_t mode);
void calibrate_ir(void);
int get_calibrated_prox(unsigned int sensor_number);
int get_ambient_light(unsigned int sensor_number);
#define EPUCK2_PROX_FAST_UPDATE 0u
#define EPUCK2_PROX_SLOW_UPDATE 1u

/* camera/camera.h, camera/dcmi_camera.h: the PO8030 (640 x 480) behind
 * the STM32's DCMI.  cam_advanced_config cuts a window (x1, y1, width,
 * height: sensor pixels) subsampled by 1, 2 or 4 (subsampling_t
 * SUBSAMPLING_X1 0x20, X2 0x40, X4 0x80); FORMAT_COLOR (1) is RGB565 on
 * the PO8030 (PO8030_FORMAT_RGB565, two bytes a pixel, high byte first).
 * The frame goes to the library's own buffer (MAX_BUFF_SIZE 38,400 B: one
 * QQVGA colour frame); in one-shot mode dcmi_capture_start takes one
 * frame, image_is_ready says when it is complete, dcmi_get_last_image_ptr
 * lends it (NULL while lent) until dcmi_release_last_image_ptr. */
void cam_start(void);
int8_t cam_advanced_config(int fmt, unsigned int x1, unsigned int y1, unsigned int width,
                           unsigned int height, int subsampling_x, int subsampling_y);
uint16_t cam_get_id(void);
int8_t dcmi_start(void);
int8_t dcmi_prepare(void);
int8_t dcmi_disable_double_buffering(void);
void dcmi_set_capture_mode(int mode);
void dcmi_capture_start(void);
uint8_t image_is_ready(void);
uint8_t *dcmi_get_last_image_ptr(void);
void dcmi_release_last_image_ptr(void);
#define EPUCK2_CAM_FORMAT_COLOR 1
#define EPUCK2_CAM_SUBSAMPLING_X4 0x80
#define EPUCK2_DCMI_CAPTURE_ONE_SHOT 0
#define EPUCK2_PO8030_WIDTH EPUCK2_CAMERA_SENSOR_WIDTH_PX
#define EPUCK2_PO8030_HEIGHT EPUCK2_CAMERA_SENSOR_HEIGHT_PX
#define EPUCK2_DCMI_BUFFER_BYTES 38400u

/* audio/microphone.h, audio/mp45dt02_processing.h: the 4 MEMS microphones
 * (PDM, decimated to 16 kHz PCM by the library).  mic_start(NULL) keeps
 * the last 10 ms in one buffer of MIC_BUFFER_LEN = 640 int16 samples, the
 * 4 microphones interleaved (index 4 i + MIC_RIGHT 0 / MIC_LEFT 1 /
 * MIC_BACK 2 / MIC_FRONT 3), refilled every 10 ms; mic_buffer_is_ready says
 * a buffer has been filled since mic_buffer_ready_reset. */
void mic_start(void (*full_buffer_cb)(int16_t *data, uint16_t length));
int16_t *mic_get_buffer_ptr(void);
uint8_t mic_buffer_is_ready(void);
void mic_buffer_ready_reset(void);
/* EPUCK2_MIC_COUNT and EPUCK2_MIC_RATE_HZ: platform_facts.h. */
#define EPUCK2_MIC_BUFFER_LEN 640u
#define EPUCK2_MIC_RIGHT 0u
#define EPUCK2_MIC_LEFT 1u
#define EPUCK2_MIC_BACK 2u
#define EPUCK2_MIC_FRONT 3u

/* audio/audio_thread.h: the speaker through the STM32's DAC: dac_start
 * powers the amplifier, dac_play(f) plays a sine of f Hz (a 360-sample
 * table clocked by a timer) until dac_stop. */
void dac_start(void);
void dac_play(uint16_t freq);
void dac_stop(void);

/* i2c_bus.h: the I2C bus of the extensions (the range-and-bearing turret,
 * the ground sensors).  Register reads and writes of the device at 8-bit
 * address `addr`; they return ChibiOS's msg_t (MSG_OK = 0). */
void i2c_start(void);
int8_t read_reg(uint8_t addr, uint8_t reg, uint8_t *value);
int8_t write_reg(uint8_t addr, uint8_t reg, uint8_t value);

/* sensors/ground.h: the ground-sensor module (e-puck2 version): its
 * thread reads it over I2C; sensors 0 left, 1 centre, 2 right (3, 4 the
 * cliff sensors); get_ground_prox is the reflected IR (larger = lighter
 * floor). */
void ground_start(void);
int get_ground_prox(unsigned int sensor_number);

#endif
