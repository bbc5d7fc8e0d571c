/*
 * calibrate_main.c - a test image for the emulated Cortex-M4F that checks
 * what its instruction counts count: each step runs, between the run
 * loop's two marks, a loop of exactly 2 * PIL_M4_CAL_LOOPS + 1
 * instructions (SUBS and BNE per turn, and the MOVW before), so the
 * measured controller step must be that, plus the few instructions of a
 * mark, to the SysTick's resolution (about 6 instructions: 168 MHz ticks
 * against one instruction per emulated ns).  pil_tests.sh reads it from
 * pil_compare's --json.
 */
#include <stdint.h>

#include "hal_pil.h"

/** Turns of the loop (a MOVW immediate): 100,001 instructions a step. */
#define PIL_M4_CAL_LOOPS 50000u

static struct hal app_hal;
static uint8_t app_mailbox[PIL_MAILBOX_BYTES(0u)];

int main(void)
{
    hal_pil_config_t cfg;
    pil_hello_t hello = { 100u, 16u, 1u, 0u, 0u, 0u, 0u, 0u, 0u, "calibrate", "none" };
    hal_pil_default_config(&cfg);
    hal_pil_init(&app_hal, &cfg, app_mailbox, (uint16_t)sizeof app_mailbox);
    (void)hal_pil_hello(&app_hal, &hello);
    hal_pil_ready(&app_hal);
    for (;;) {
        pil_port_mark();
        __asm__ __volatile__("movw r0, %0\n1:\n\tsubs r0, #1\n\tbne 1b" : : "i"(PIL_M4_CAL_LOOPS) : "r0", "cc");
        pil_port_mark();
        hal_pil_end_step(&app_hal);
    }
}
