/*
 * epuck2_os.h - what platforms/epuck2/hal needs of ChibiOS itself, as plain
 * functions: the system clock, the non-blocking serial queues of UART3 (the
 * ESP32's Bluetooth SPP link, SD3 at 115200 8N1, started by the library's
 * serial_start), the idle sleep of the run loop, the start-up (halInit,
 * chSysInit, the library's message bus) and the robot id.
 *
 * ChibiOS's own calls are macros and inline functions over types of its
 * headers (sdAsynchronousWrite, chVTGetSystemTimeX, ST2MS), and its hal.h
 * would shadow hal/hal.h, so they are wrapped in platforms/epuck2/chibios/
 * epuck2_os.c, compiled by the real build alone against the user's
 * checkout (ChibiOS 3.1 as the library's submodule pins it); the gates and
 * host tests link tests/stubs/ instead.
 */
#ifndef EPUCK2_OS_H
#define EPUCK2_OS_H

#include <stdint.h>

/** halInit, chSysInit, mpu_init, the library's message bus (its modules
 *  publish on it), then serial_start (UART3) and i2c_start. */
void epuck2_os_init(void);

/** Milliseconds since start (ChibiOS's system time, 1 kHz: chconf.h
 *  CH_CFG_ST_FREQUENCY), wrapping at 2^32. */
uint32_t epuck2_os_time_ms(void);

/** Queues up to `len` bytes for UART3 without waiting: how many were
 *  queued (the output queue, SERIAL_BUFFERS_SIZE = 128 B, may be full). */
uint16_t epuck2_os_serial_write(const uint8_t *bytes, uint16_t len);

/** Takes up to `cap` received bytes of UART3 without waiting: how many. */
uint16_t epuck2_os_serial_read(uint8_t *buf, uint16_t cap);

/** Sleeps one system tick (1 ms), so that the library's threads of lower
 *  or equal priority run: the run loop's idle between steps. */
void epuck2_os_idle(void);

/** The robot id of this build (EPUCK2_ROBOT_ID, make epuck2-firmware
 *  ROBOT_ID=N; 0 if not given). */
uint16_t epuck2_os_robot_id(void);

#endif
