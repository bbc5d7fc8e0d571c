/*
 * misbehave_main.c - a test image for the emulated ATmega2560 that runs
 * the protocol properly for three steps and then, by the robot id its
 * CONFIG gives, does one thing a broken image can do, so that the tests
 * (platform.mk's pil-avr-errors) see each one named as an error with its
 * robot and step, never a hang:
 *
 *   0  nothing: a well-behaved robot     5  an ACT with a bad CRC
 *   1  writes outside its RAM (crash)    6  halts (sleep, interrupts off)
 *   2  never answers (cycle budget)      7  a REQUEST the protocol lacks
 *   3  jumps to the reset vector         8  two IR messages in a period of one
 *   4  recurses into its static data     9  an ACT of another step
 *
 * It builds for the emulated Cortex-M4F too (platforms/pil_m4/), where
 * cases 1, 3, 4 and 6 are that core's: a write to unmapped memory (a
 * fault), a system reset (SYSRESETREQ), a recursion into the stack's
 * guard (the stack is below the static data there) and WFI with
 * interrupts off.  (A test image: the only chip-specific code of
 * an image, under the compiler's own macros.)
 */
#include <stdint.h>

#include "hal_pil.h"
#include "pil/pil_frame.h"
#include "pil/pil_msg.h"

static struct hal app_hal;
static uint8_t app_mailbox[PIL_MAILBOX_BYTES(0u)];

/* Deep enough to reach the static data from the top of RAM. */
static uint16_t recurse(uint16_t n)
{
    volatile uint8_t pad[32];
    pad[0] = (uint8_t)n;
    return n == 0u ? pad[0] : (uint16_t)(recurse((uint16_t)(n - 1u)) + pad[0]);
}

/* A frame of `type` with `len` payload bytes already in the mailbox,
 * sealed with the step's sequence number, then damaged as asked. */
static void send_raw(uint8_t type, uint16_t len, uint8_t seq, uint8_t bad_crc)
{
    uint16_t n = pil_frame_seal(app_mailbox, sizeof app_mailbox, type, seq, len);
    if (bad_crc) {
        app_mailbox[n - 1u] ^= 0xFFu;
    }
    pil_port_exchange(app_mailbox, sizeof app_mailbox, n);
}

static void misbehave(uint16_t how)
{
    pil_robot_t *r = &app_hal.link;
    uint8_t *p = app_mailbox + PIL_HEADER_BYTES;
    pil_act_t act = { 0, 0, 0u, 0u, 0u, { 0u, 0u, 0u }, 0u, (const uint8_t *)0 };
    switch (how) {
    case 1:
#ifdef __arm__
        *(volatile uint32_t *)(uintptr_t)0xA0000000u = 1u;   /* the FSMC's registers: none in QEMU */
#else
        *(volatile uint8_t *)(uintptr_t)0x2400u = 1u;   /* past RAMEND (0x21FF) */
#endif
        break;
    case 2:
        for (;;) {
            __asm__ __volatile__("nop");
        }
    case 3:
#ifdef __arm__
        *(volatile uint32_t *)(uintptr_t)0xE000ED0Cu = 0x05FA0004u;   /* AIRCR: SYSRESETREQ */
        for (;;) {
        }
#else
        ((void (*)(void))0)();
#endif
        break;
    case 4:
        (void)recurse(1000u);
        break;
    case 5:
        send_raw(PIL_ACT, pil_act_encode(p, 256u, &act), r->seq, 1u);
        break;
    case 6:
#ifdef __arm__
        for (;;) {
            __asm__ __volatile__("cpsid i\n\twfi");
        }
#else
        __asm__ __volatile__("cli\n\tsleep");
#endif
        break;
    case 7:
        p[0] = 42u;
        p[1] = 0u;
        send_raw(PIL_REQUEST, 2u, r->seq, 0u);
        break;
    case 8:
        act.tx_count = 2u;
        send_raw(PIL_ACT, pil_act_encode(p, 256u, &act), r->seq, 0u);
        break;
    case 9:
        send_raw(PIL_ACT, pil_act_encode(p, 256u, &act), (uint8_t)(r->seq + 3u), 0u);
        break;
    default:
        break;
    }
}

int main(void)
{
    hal_pil_config_t cfg;
    pil_hello_t hello = { 100u, 16u, 1u, 0u, 0u, 0u, 0u, 0u, 0u, "misbehave", "none" };
    hal_pil_default_config(&cfg);
    hal_pil_init(&app_hal, &cfg, app_mailbox, (uint16_t)sizeof app_mailbox);
    (void)hal_pil_hello(&app_hal, &hello);
    hal_pil_ready(&app_hal);
    for (;;) {
        hal_set_wheel_speeds(&app_hal, 100, -100);
        (void)hal_ir_proximity(&app_hal, 0u);
        if (hal_time_ms(&app_hal) == 300u) {
            misbehave(hal_robot_id(&app_hal));
        }
        hal_pil_end_step(&app_hal);
    }
}
