/*
 * epuck2_os.c - epuck2_os.h over ChibiOS 3.1 and the e-puck2 library: the
 * one file of this platform compiled with the library's own Makefile
 * (against ChibiOS's headers, whose hal.h is not ours), by the real build
 * alone (platforms/epuck2/chibios/Makefile; the gates link
 * tests/stubs/ instead).  What it calls is named from the library's public
 * headers and ChibiOS 3.1's API; docs/hardware/epuck2.md says what was
 * built here and what only a robot can confirm.
 *
 * It also defines what the library expects its application to define
 * (the library's own src/main.c does, which an application does not
 * link): the message bus its modules publish on (main.h: bus), the
 * parameter tree's root (main.h: parameter_root), the stack protector's
 * guard (the library builds with -fstack-protector-all) and three of
 * newlib's system calls.
 */
#include <stdint.h>

#include "ch.h"
#include "hal.h"

#include "i2c_bus.h"
#include "main.h"
#include "memory_protection.h"
#include "serial_comm.h"

#include "../hal/epuck2_os.h"

#ifndef EPUCK2_ROBOT_ID
#define EPUCK2_ROBOT_ID 0
#endif

messagebus_t bus;
MUTEX_DECL(bus_lock);
CONDVAR_DECL(bus_condvar);
parameter_namespace_t parameter_root;

#define STACK_CHK_GUARD 0xe2dee396u
uintptr_t __stack_chk_guard = STACK_CHK_GUARD;
void __stack_chk_fail(void);
void __stack_chk_fail(void)
{
    chSysHalt("Stack smashing detected");
}

/* What newlib's abort() and raise() call, which the library's syscalls
 * (src/chibios-syscalls) do not define and newer arm-none-eabi toolchains
 * (GCC 12's newlib) link in: the robot halts, as on a failed assert. */
void _exit(int status);
int _kill(int pid, int sig);
int _getpid(void);
void _exit(int status)
{
    (void)status;
    chSysHalt("exit");
    for (;;) {
    }
}
int _kill(int pid, int sig)
{
    (void)pid;
    (void)sig;
    return -1;
}
int _getpid(void)
{
    return 1;
}

#if CH_CFG_ST_RESOLUTION != 32
#error "epuck2_os.c: the clock needs ChibiOS's 32-bit system time (chconf.h CH_CFG_ST_RESOLUTION)"
#endif

void epuck2_os_init(void)
{
    halInit();
    chSysInit();
    mpu_init();
    messagebus_init(&bus, &bus_lock, &bus_condvar);
    parameter_namespace_declare(&parameter_root, NULL, NULL);
    serial_start();
    i2c_start();
}

uint32_t epuck2_os_time_ms(void)
{
#if CH_CFG_ST_FREQUENCY == 1000
    return (uint32_t)chVTGetSystemTimeX();
#else
    /* ST2MS multiplies in 32 bits and overflows after ~71 min at 1 kHz. */
    return (uint32_t)(((uint64_t)chVTGetSystemTimeX() * 1000u) / CH_CFG_ST_FREQUENCY);
#endif
}

uint16_t epuck2_os_serial_write(const uint8_t *bytes, uint16_t len)
{
    return (uint16_t)sdAsynchronousWrite(&SD3, bytes, len);
}

uint16_t epuck2_os_serial_read(uint8_t *buf, uint16_t cap)
{
    return (uint16_t)sdAsynchronousRead(&SD3, buf, cap);
}

void epuck2_os_idle(void)
{
    chThdSleep(1);
}

uint16_t epuck2_os_robot_id(void)
{
    return (uint16_t)EPUCK2_ROBOT_ID;
}
