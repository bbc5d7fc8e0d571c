/*
 * epuck_lib.h - the functions of GCtronic's e-puck library (e-puck1,
 * dsPIC30F6014A) that platforms/epuck1/hal calls, declared here with their documented
 * signatures so that our code compiles without the library's headers.
 *
 * The library itself is user-supplied (EPUCK_LIB_DIR, see
 * tools/make/firmware.mk) and never copied into this repository.  Each
 * declaration names the library header it comes from, relative to the
 * library's `library/` folder.  On XC16 `int` is 16 bits: these prototypes
 * keep the library's own types (int, unsigned int, char *) so that they
 * match its definitions bit for bit; hal_epuck.c converts at the boundary.
 *
 * Modules (one of each kind must be linked; see tools/make/firmware.mk):
 *   motor_led/advance_one_timer   agenda (timer 2), motors, LEDs
 *   camera/fast_2_timer           poxxxx camera driver (timers 4 and 5)
 *   uart                          UART1 = the Bluetooth serial link
 *   utility                       selector switch
 * The A/D converter and IR communication modules depend on the image's IR
 * backend: epuck_lib_adscan.h + epuck_lib_randb.h (range-and-bearing
 * turret) or epuck_lib_ircom.h (libIrcom, which brings its own A/D module).
 */
#ifndef EPUCK_LIB_H
#define EPUCK_LIB_H

/* motor_led/e_init_port.h: configures every port of the robot. */
void e_init_port(void);

/* motor_led/advance_one_timer/e_agenda.h: callbacks run from the timer 2
 * interrupt every `cycle` tenths of a millisecond. */
int e_activate_agenda(void (*func)(void), int cycle);
void e_start_agendas_processing(void);

/* motor_led/advance_one_timer/e_motors.h: stepper motors, speed in
 * steps/s (-1000..1000), step counters (16-bit on the dsPIC, wrapping). */
void e_init_motors(void);
void e_set_speed_left(int motor_speed);
void e_set_speed_right(int motor_speed);
int e_get_steps_left(void);
int e_get_steps_right(void);

/* motor_led/advance_one_timer/e_led.h: ring LEDs 0..7, body and front LED
 * (value 0 off, 1 on). */
void e_set_led(unsigned int led_number, unsigned int value);
void e_set_body_led(unsigned int value);
void e_set_front_led(unsigned int value);

/* camera/fast_2_timer/e_poxxxx.h: the camera.  init returns the sensor's
 * version (0x3030, 0x6030, 0x8030); config returns 0 when the window is
 * valid; the capture fills `buf` in the background (interrupts) and
 * is_img_ready turns non-zero when the frame is complete.  Orientation:
 * 0 sensor mounted vertically, 1 horizontal, 2 horizontal inverted, -1
 * unknown. */
int e_poxxxx_init_cam(void);
int e_poxxxx_config_cam(unsigned int sensor_x1, unsigned int sensor_y1,
                        unsigned int sensor_width, unsigned int sensor_height,
                        unsigned int zoom_fact_width, unsigned int zoom_fact_height,
                        int color_mode);
void e_poxxxx_write_cam_registers(void);
void e_poxxxx_launch_capture(char *buf);
int e_poxxxx_is_img_ready(void);
int e_poxxxx_get_orientation(void);
/** e_poxxxx.h: color_mode value of RGB565 frames (2 bytes per pixel, high
 *  byte first). */
#define EPL_RGB_565_MODE 1
/** e_poxxxx.h: the sensor array the window is cut from, pixels. */
#define EPL_ARRAY_WIDTH 640u
#define EPL_ARRAY_HEIGHT 480u

/* uart/e_uart_char.h: UART1, the Bluetooth module's serial link (115200
 * 8N1).  send_uart1_char starts an interrupt-driven transmission of `buff`,
 * which must stay unchanged until e_uart1_sending() returns 0. */
void e_init_uart1(void);
void e_send_uart1_char(const char *buff, int length);
int e_uart1_sending(void);
/* uart/e_uart_char.h, uart/e_uart1_rx_char.s: never blocks.  Takes the
 * oldest unread byte of the receive interrupt's 64-byte ring into *car and
 * returns 1, or returns 0 when none is waiting.  The interrupt does not
 * check the ring for room: bytes not read within 64 bytes' time (5.6 ms at
 * 115200 baud) are overwritten (platforms/epuck1/hal/host_link.h). */
int e_getchar_uart1(char *car);

/* utility/utility.h: position of the 16-way selector switch, 0..15. */
int getselector(void);

#endif
