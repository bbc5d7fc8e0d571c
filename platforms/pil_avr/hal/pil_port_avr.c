/*
 * pil_port_avr.c - pil_port_exchange on the emulated ATmega2560: the
 * mailbox is ordinary RAM, and the doorbell is the general-purpose I/O
 * register GPIOR0, which does nothing on a real chip.
 *
 * The port writes a six-byte descriptor on its stack (the mailbox's
 * address, its capacity, the frame's length, little-endian), puts the
 * descriptor's address in GPIOR1 (low) and GPIOR2 (high), and writes
 * PIL_AVR_BELL to GPIOR0.  The emulator (platforms/pil_avr/emu/) watches
 * that write: it stops the core before the next instruction, hands the
 * frame to the simulator, writes the simulator's answer into the mailbox,
 * and resumes.  So the exchange costs the robot the few cycles of this
 * function, and the copy none: a mailbox, not a UART, because a UART at
 * the robot's 115,200 baud would take longer than a control period for a
 * camera frame, and a baud-less emulated one would still charge the core
 * an I/O access and an interrupt per byte that no real robot spends on
 * its sensors.
 */
#include <stdint.h>

#include "pil/pil_robot.h"
#include "pil_port_avr.h"

void pil_port_exchange(uint8_t *mailbox, uint16_t cap, uint16_t len)
{
    volatile uint8_t desc[6];
    uint16_t at = (uint16_t)(uintptr_t)mailbox, here = (uint16_t)(uintptr_t)desc;
    desc[0] = (uint8_t)(at & 0xFFu);
    desc[1] = (uint8_t)(at >> 8);
    desc[2] = (uint8_t)(cap & 0xFFu);
    desc[3] = (uint8_t)(cap >> 8);
    desc[4] = (uint8_t)(len & 0xFFu);
    desc[5] = (uint8_t)(len >> 8);
    PIL_AVR_REG(PIL_AVR_GPIOR1) = (uint8_t)(here & 0xFFu);
    PIL_AVR_REG(PIL_AVR_GPIOR2) = (uint8_t)(here >> 8);
    PIL_AVR_REG(PIL_AVR_GPIOR0) = PIL_AVR_BELL;
    /* The answer is in the mailbox now: nothing read before the bell. */
    __asm__ __volatile__("" ::: "memory");
}

void pil_port_mark(void)
{
    PIL_AVR_REG(PIL_AVR_GPIOR0) = PIL_AVR_MARK;
}
