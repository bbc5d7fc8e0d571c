/*
 * host_port.c - pil_port_exchange for a PIL image compiled for this PC:
 * the same generated main, run loop, HAL and controller as the emulated
 * ATmega2560's image, speaking the emulator's pipe protocol (an EMU report,
 * zero cycles, before each frame; the simulator's answer read back), so the
 * tests drive both with one driver and compare them step by step.  Built
 * with UBSan's alignment check, and once with -funsigned-char: the
 * differences the AVR cannot show (docs/reference/pil.md).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pil/pil_msg.h"
#include "pil/pil_robot.h"

static void put(const uint8_t *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(1, p, n);
        if (k <= 0) {
            exit(0);
        }
        p += k;
        n -= (size_t)k;
    }
}

static int get(uint8_t *p, size_t n)
{
    while (n > 0) {
        ssize_t k = read(0, p, n);
        if (k <= 0) {
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

void pil_port_exchange(uint8_t *mailbox, uint16_t cap, uint16_t len)
{
    uint8_t rep[PIL_FRAME_BYTES(32u)], head[PIL_HEADER_BYTES];
    pil_emu_t m;
    memset(&m, 0, sizeof m);
    m.event = PIL_EMU_FRAME;
    m.first_mark = PIL_NO_MARK;
    m.last_mark = PIL_NO_MARK;
    uint16_t n = pil_emu_encode(rep + PIL_HEADER_BYTES, 32u, &m);
    put(rep, pil_frame_seal(rep, sizeof rep, PIL_EMU, 0u, n));
    put(mailbox, len);
    if (get(head, sizeof head) != 0) {
        exit(0);   /* the driver is done */
    }
    uint16_t size = pil_frame_size(head);
    memcpy(mailbox, head, sizeof head);
    if (size > PIL_HEADER_BYTES) {
        static uint8_t rest[PIL_FRAME_MAX];
        if (get(rest, (size_t)(size - PIL_HEADER_BYTES)) != 0) {
            exit(0);
        }
        memcpy(mailbox + PIL_HEADER_BYTES, rest,
               (size_t)((size < cap ? size : cap) > PIL_HEADER_BYTES ? (size < cap ? size : cap) - PIL_HEADER_BYTES : 0));
    }
}

void pil_port_mark(void)
{
}
