/*
 * chain_fixture.h - the fixture test_pfias.c and test_tsasr.c share: one
 * chain controller C (pfias_t, which tsasr_t is) on the fake HAL H
 * (fake_hal.h) as robot 7, seeded 42, with the helpers that feed it frames
 * and read what it sent.  The including test names its controller's entry
 * points first:
 *
 *   #define CHAIN_INIT tsasr_init         (or pfias_init)
 *   #define CHAIN_STEP tsasr_step         (or pfias_step)
 *   #define CHAIN_DECODE tsasr_msg_decode (or pfias_msg_decode)
 *   #include "chain_fixture.h"
 */
#ifndef TESTS_CHAIN_FIXTURE_H
#define TESTS_CHAIN_FIXTURE_H

#include <stdint.h>

#include "fake_hal.h"
#include "pfias/pfias.h"
#include "pfias/pfias_msg.h"

static hal_t H;
static pfias_t C;

/** A probability of 1 per step (rng_chance). */
#define ALWAYS 65535u

static void start_with(const pfias_params_t *p)
{
    fake_hal_init(&H, 7u);
    CHAIN_INIT(&C, p, 42u);
}

static void step(void)
{
    CHAIN_STEP(&C, &H);
    fake_hal_end_step(&H);
}

static void hear(uint16_t frame, uint16_t range_mm, int16_t bearing_mrad)
{
    assert_true(fake_hal_push(&H, frame, range_mm, bearing_mrad));
}

/* The last frame the robot sent, decoded. */
static pfias_msg_t last_sent(void)
{
    pfias_msg_t m;
    (void)CHAIN_DECODE(H.last_sent, &m);
    return m;
}

#endif
