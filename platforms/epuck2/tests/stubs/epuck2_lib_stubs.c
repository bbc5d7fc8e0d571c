/* epuck2_lib_stubs.c - epuck2_stubs.h: the library's proximity, motors,
 * LEDs, camera, audio, I2C and ground functions (the ChibiOS glue's are
 * epuck2_os_stubs.c). */
#include "epuck2_stubs.h"

#include <stddef.h>
#include <string.h>

#include "epuck2_lib.h"

epuck2_stub_state_t epuck2_stub;

void epuck2_stub_reset(void)
{
    memset(&epuck2_stub, 0, sizeof epuck2_stub);
    epuck2_stub.tx_room = -1;
}

/* motors */
void motors_init(void) {}
void left_motor_set_speed(int speed) { epuck2_stub.speed_left = speed; epuck2_stub.speed_calls++; }
void right_motor_set_speed(int speed) { epuck2_stub.speed_right = speed; epuck2_stub.speed_calls++; }
int32_t left_motor_get_pos(void) { return epuck2_stub.pos_left; }
int32_t right_motor_get_pos(void) { return epuck2_stub.pos_right; }

/* LEDs, SPI, selector */
void set_led(int led_number, unsigned int value)
{
    if (led_number >= 0 && led_number < 4) {
        epuck2_stub.led[led_number] = value;
    }
    epuck2_stub.led_calls++;
}
void set_rgb_led(int led_number, uint8_t red_val, uint8_t green_val, uint8_t blue_val)
{
    if (led_number >= 0 && led_number < 4) {
        epuck2_stub.rgb[led_number][0] = red_val;
        epuck2_stub.rgb[led_number][1] = green_val;
        epuck2_stub.rgb[led_number][2] = blue_val;
    }
    epuck2_stub.led_calls++;
}
void set_body_led(unsigned int value) { epuck2_stub.body_led = value; epuck2_stub.led_calls++; }
void set_front_led(unsigned int value) { epuck2_stub.front_led = value; epuck2_stub.led_calls++; }
void clear_leds(void) {}
void spi_comm_start(void) {}
void spi_comm_suspend(void) { epuck2_stub.spi_suspended = 1; epuck2_stub.spi_suspends++; }
void spi_comm_resume(void) { epuck2_stub.spi_suspended = 0; epuck2_stub.spi_resumes++; }
int get_selector(void) { return epuck2_stub.selector; }

/* proximity */
void proximity_start(uint8_t mode) { epuck2_stub.prox_mode = mode; epuck2_stub.prox_started++; }
void calibrate_ir(void) { epuck2_stub.calibrated++; }
int get_calibrated_prox(unsigned int sensor_number) { return sensor_number < 8u ? epuck2_stub.prox[sensor_number] : 0; }
int get_ambient_light(unsigned int sensor_number) { return sensor_number < 8u ? epuck2_stub.ambient[sensor_number] : 0; }

/* camera */
void cam_start(void) {}
int8_t cam_advanced_config(int fmt, unsigned int x1, unsigned int y1, unsigned int width,
                           unsigned int height, int subsampling_x, int subsampling_y)
{
    (void)fmt;
    (void)x1;
    epuck2_stub.cam_y1 = y1;
    epuck2_stub.cam_w = width;
    epuck2_stub.cam_h = height;
    epuck2_stub.cam_subx = (unsigned)subsampling_x;
    epuck2_stub.cam_suby = (unsigned)subsampling_y;
    return (int8_t)epuck2_stub.cam_config_result;
}
uint16_t cam_get_id(void) { return 0x8030u; }
int8_t dcmi_start(void) { return 0; }
int8_t dcmi_prepare(void) { return (int8_t)epuck2_stub.cam_prepare_result; }
int8_t dcmi_disable_double_buffering(void) { return 0; }
void dcmi_set_capture_mode(int mode) { (void)mode; }
void dcmi_capture_start(void) { epuck2_stub.captures++; epuck2_stub.img_ready = 0u; }
uint8_t image_is_ready(void) { return epuck2_stub.img_ready; }
uint8_t *dcmi_get_last_image_ptr(void) { return epuck2_stub.img; }
void dcmi_release_last_image_ptr(void) { epuck2_stub.releases++; }

/* audio */
void mic_start(void (*full_buffer_cb)(int16_t *data, uint16_t length))
{
    (void)full_buffer_cb;
    epuck2_stub.mic_started++;
}
int16_t *mic_get_buffer_ptr(void) { return epuck2_stub.mic_pcm; }
uint8_t mic_buffer_is_ready(void) { return 1u; }
void mic_buffer_ready_reset(void) {}
void dac_start(void) { epuck2_stub.dac_started++; }
void dac_play(uint16_t freq) { epuck2_stub.play_hz = freq; epuck2_stub.plays++; }
void dac_stop(void) { epuck2_stub.play_hz = 0u; epuck2_stub.stops++; }

/* I2C: the turret (address 0x20).  Reading its data's low byte takes the
 * frame. */
void i2c_start(void) {}
int8_t read_reg(uint8_t addr, uint8_t reg, uint8_t *value)
{
    if (epuck2_stub.i2c_error != 0 || addr != 0x20u || reg >= 32u) {
        return -1;
    }
    *value = reg == 0u ? (uint8_t)(epuck2_stub.randb_frames > 0) : epuck2_stub.randb_reg[reg];
    if (reg == 2u && epuck2_stub.randb_frames > 0) {
        epuck2_stub.randb_frames--;
    }
    return 0;
}
int8_t write_reg(uint8_t addr, uint8_t reg, uint8_t value)
{
    if (epuck2_stub.i2c_error != 0 || addr != 0x20u) {
        return -1;
    }
    if (epuck2_stub.i2c_writes < EPUCK2_STUB_QUEUE * 4) {
        epuck2_stub.i2c_written_reg[epuck2_stub.i2c_writes] = reg;
        epuck2_stub.i2c_written_val[epuck2_stub.i2c_writes] = value;
    }
    epuck2_stub.i2c_writes++;
    return 0;
}

/* ground */
void ground_start(void) { epuck2_stub.ground_started++; }
int get_ground_prox(unsigned int sensor_number) { return sensor_number < 5u ? epuck2_stub.ground[sensor_number] : 0; }
