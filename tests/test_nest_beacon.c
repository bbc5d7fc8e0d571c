/*
 * test_nest_beacon.c - the nest beacon (firmware/nest_beacon) on a fake HAL:
 * exact consumption, deposits, OAE window, healing of lost reports, N_W,
 * broadcast frames, and that it never moves.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "fake_hal.h"
#include "foraging/nest_beacon.h"
#include "foraging/nest_link.h"

static hal_t H;
static nest_beacon_t B;

/* Defaults with the costs that a test does not look at switched off. */
static void start(nest_beacon_params_t *p, int quiet)
{
    fake_hal_init(&H, 99u);
    if (quiet) {
        p->c_rate_milli_tokens_per_min = 0u;
        p->move_cost = 0u;
    }
    nest_beacon_init(&B, p, 1u);
}

static void step(void)
{
    nest_beacon_step(&B, &H);
    fake_hal_end_step(&H);
}

static void steps(uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        step();
    }
}

static void report(uint8_t type, uint16_t id, uint32_t total)
{
    uint16_t frame = (type == NL_DEPOSITS) ? nest_link_encode_deposits(id, total)
                                           : nest_link_encode_oaes(id, total);
    assert_true(fake_hal_push(&H, frame, 50u, 0));
}

static void test_consumption_exact_per_minute(void **state)
{
    nest_beacon_params_t p;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    p.move_cost = 0u;
    start(&p, 0);
    /* F0 = 5 tokens = 7500 units; 2 tokens/min = 3000 units/min = 5 units
     * per 100 ms step, every step. */
    assert_int_equal(B.ledger_units, 7500);
    for (k = 1; k <= 600u; k++) {
        step();
        assert_int_equal(B.ledger_units, 7500 - 5 * (int32_t)k);
    }
    assert_int_equal(B.ledger_units, 4500);
}

static void test_consumption_carries_remainder(void **state)
{
    nest_beacon_params_t p;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    p.move_cost = 0u;
    start(&p, 0);
    /* 75 ms steps: 3000 units/min = 3.75 units per step; after k steps
     * exactly floor(3.75 k) are gone, 3000 after 800 steps (one minute). */
    H.period_ms = 75u;
    for (k = 1; k <= 800u; k++) {
        step();
        assert_int_equal(B.ledger_units, 7500 - (int32_t)((k * 375u) / 100u));
    }
    assert_int_equal(B.ledger_units, 4500);
}

static void test_consumption_odd_rate(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    p.move_cost = 0u;
    p.c_rate_milli_tokens_per_min = 1333u;   /* 1999.5 units/min */
    start(&p, 0);
    /* Over 1200 steps of 100 ms (2 min): 3999 units, exactly. */
    steps(1200u);
    assert_int_equal(B.ledger_units, 7500 - 3999);
}

static void test_movement_cost(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 0);
    /* Nobody heard: 20 robots foraging (20 units) + nest (5). */
    step();
    assert_int_equal(B.ledger_units, 7500 - 25);
    /* Three robots report their deposits from the nest: 17 foraging.  An
     * OAE report (robot 4, out foraging) is no sign of waiting. */
    report(NL_DEPOSITS, 1u, 0u);
    report(NL_DEPOSITS, 2u, 0u);
    report(NL_DEPOSITS, 3u, 0u);
    report(NL_OAES, 4u, 0u);
    step();
    assert_int_equal(B.n_waiting, 3);
    assert_int_equal(B.ledger_units, 7500 - 25 - 22);
}

static void test_deposits_add_token_energy(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    steps(60);                   /* robots have been out foraging a while */
    report(NL_DEPOSITS, 3u, 1u);
    step();
    assert_int_equal(B.ledger_units, 7500 + 1500);
    assert_int_equal(B.deposits_total, 1);
    /* The same total again (the robot reports every other step): nothing. */
    report(NL_DEPOSITS, 3u, 1u);
    step();
    assert_int_equal(B.ledger_units, 9000);
    assert_int_equal(B.deposits_total, 1);
    /* The report of total 2 was lost; total 3 brings both. */
    steps(60);
    report(NL_DEPOSITS, 3u, 3u);
    step();
    assert_int_equal(B.ledger_units, 9000 + 3000);
    assert_int_equal(B.deposits_total, 3);
    /* Another robot's totals are its own. */
    report(NL_DEPOSITS, 4u, 1u);
    step();
    assert_int_equal(B.deposits_total, 4);
    assert_int_equal(B.ledger_units, 13500);
}

static void test_counts_heal_across_wrap(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    steps(254);
    /* Baseline 0: a first report of 250 means 250 events since the start. */
    report(NL_OAES, 9u, 250u);
    step();
    assert_int_equal(B.oae_total, 250);
    /* 250 -> 260 is sent as 250 -> 4: ten more. */
    steps(20);
    report(NL_OAES, 9u, 260u);
    step();
    assert_int_equal(B.oae_total, 260);
    assert_int_equal(B.ledger_units, 7500 - 2600);
}

/* Reports credit no faster than a robot can act: a deposit per
 * min_deposit_steps, an OAE per step, since the robot was last credited;
 * what a report claims beyond that is credited by later reports (its total
 * is cumulative), so a real rise is never lost, only spread out. */
static void test_reports_credit_no_faster_than_a_robot(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    steps(39);                   /* budget 40 after the next step's ageing */
    report(NL_DEPOSITS, 5u, 5u); /* five deposits claimed at once */
    step();
    assert_int_equal(B.deposits_total, 2);                   /* 40 / 20 */
    steps(59);
    report(NL_DEPOSITS, 5u, 5u); /* the same total later: the rest is paid */
    step();
    assert_int_equal(B.deposits_total, 5);
    assert_int_equal(B.ledger_units, 7500 + 5 * 1500);
    /* OAEs: one a step. */
    steps(9);
    report(NL_OAES, 6u, 200u);
    step();
    assert_int_equal(B.oae_total, 110);  /* robot 6's budget: the 110 steps since the start */
}

/* The defect a review found: robot 0 alternately reporting cumulative
 * totals 255 and 254 (frames 0x40FF / 0x40FE), 8 a step, wrapped the signed
 * 32-bit ledger at step 1,397 (undefined behaviour; -128 tokens broadcast).
 * Now the ledger saturates and the liar gains one token per 20 steps. */
static void test_hostile_deposit_stream_stays_bounded(void **state)
{
    nest_beacon_params_t p;
    uint32_t i, k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 0);
    for (i = 0; i < 20000u; i++) {
        for (k = 0; k < 8u; k++) {
            assert_true(fake_hal_push(&H, (k & 1u) ? 0x40FEu : 0x40FFu, 50u, 0));
        }
        step();
        assert_true(B.ledger_units <= NB_LEDGER_LIMIT_TOKENS * 1500);
        assert_true(B.food_q4 >= 0);         /* never wrapped negative */
    }
    assert_true(B.deposits_total <= 20000u / 20u + 1u);
    assert_true(B.deposits_total >= 20000u / 20u - 1u);
    /* The broadcast F(t) is the 12-bit maximum, not a wrapped value. */
    assert_int_equal(nest_link_encode_food(B.food_q4), nest_link_encode_food(NL_FOOD_Q4_MAX));
}

/* Garbled frames of every kind from every id, many a step: the ledger and
 * every counter stay within their bounds (and UBSan sees no overflow). */
static void test_garbled_stream_stays_bounded(void **state)
{
    nest_beacon_params_t p;
    uint32_t x = 12345u, i, k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 0);
    for (i = 0; i < 30000u; i++) {
        for (k = 0; k < 12u; k++) {
            x = x * 1664525u + 1013904223u;
            (void)fake_hal_push(&H, (uint16_t)(x >> 16), (uint16_t)(x & 1023u), 0);
        }
        step();
        assert_true(B.ledger_units <= NB_LEDGER_LIMIT_TOKENS * 1500);
        assert_true(B.ledger_units >= -NB_LEDGER_LIMIT_TOKENS * 1500);
        assert_true(B.food_q4 >= NL_FOOD_Q4_MIN * 16 && B.food_q4 <= 2048 * 16);
        assert_true(B.n_waiting <= NB_SLOTS);
    }
    /* 64 ids could not have done more than this in 30,000 steps. */
    assert_true(B.deposits_total <= 64u * (30000u / 20u + 1u));
    assert_true(B.oae_total <= 64u * 30000u);
}

static void test_oae_window(void **state)
{
    nest_beacon_params_t p;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    /* An OAE in the first step (a robot can have one a step): E_a = 10, in
     * the window for T2 = 400 steps (the step of the report included). */
    report(NL_OAES, 2u, 1u);
    step();
    assert_int_equal(B.ledger_units, 7500 - 10);
    assert_int_equal(B.oae_total, 1);
    assert_int_equal(B.m_t2, 1);
    for (k = 1; k < 400u; k++) {
        step();
        assert_int_equal(B.m_t2, 1);
    }
    step();   /* step 400: out of the window */
    assert_int_equal(B.m_t2, 0);
    assert_int_equal(B.oae_total, 1);
    assert_int_equal(B.ledger_units, 7500 - 10);
    /* Four more from the same robot (total 5) enter a fresh window. */
    report(NL_OAES, 2u, 5u);
    step();
    assert_int_equal(B.m_t2, 4);
    assert_int_equal(B.oae_total, 5);
    assert_int_equal(B.ledger_units, 7500 - 50);
}

static void test_oae_window_sums_robots_and_bins(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    p.t2_steps = 100u;   /* 10 bins */
    start(&p, 1);
    report(NL_OAES, 1u, 1u);
    step();              /* step 0: 1 */
    steps(49u);
    report(NL_OAES, 2u, 4u);
    step();              /* step 50: 4 more */
    assert_int_equal(B.m_t2, 5);
    steps(49u);          /* through step 99 */
    assert_int_equal(B.m_t2, 5);
    step();              /* step 100: step 0's OAE leaves */
    assert_int_equal(B.m_t2, 4);
    steps(49u);
    step();              /* step 150: step 50's leave */
    assert_int_equal(B.m_t2, 0);
}

static void test_t2_clamped(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    p.t2_steps = 5000u;   /* more than 64 bins: clamped to 640 steps */
    start(&p, 1);
    assert_int_equal(B.n_bins, NB_MAX_BINS);
    report(NL_OAES, 1u, 1u);
    steps(640u);
    assert_int_equal(B.m_t2, 1);
    step();
    assert_int_equal(B.m_t2, 0);

    p.t2_steps = 3u;      /* less than a bin: one bin of 10 steps */
    start(&p, 1);
    assert_int_equal(B.n_bins, 1);
    report(NL_OAES, 1u, 1u);
    steps(10u);
    assert_int_equal(B.m_t2, 1);
    step();
    assert_int_equal(B.m_t2, 0);
}

static void test_waiting_robots(void **state)
{
    nest_beacon_params_t p;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    step();
    assert_int_equal(B.n_waiting, 0);
    /* Three ids report in one step (id 65 is id 1's slot: 6-bit ids). */
    report(NL_DEPOSITS, 1u, 0u);
    report(NL_DEPOSITS, 2u, 0u);
    report(NL_DEPOSITS, 3u, 0u);
    report(NL_DEPOSITS, 65u, 0u);
    step();
    assert_int_equal(B.n_waiting, 3);
    /* Only id 2 keeps reporting: 1 and 3 are dropped after the timeout
     * (heard in 5 steps: the report's and the next 4). */
    for (k = 1; k < 5u; k++) {
        report(NL_DEPOSITS, 2u, 0u);
        step();
        assert_int_equal(B.n_waiting, 3);
    }
    report(NL_DEPOSITS, 2u, 0u);
    step();
    assert_int_equal(B.n_waiting, 1);
    steps(4u);
    assert_int_equal(B.n_waiting, 1);
    step();
    assert_int_equal(B.n_waiting, 0);
}

static void test_ignores_foreign_frames(void **state)
{
    nest_beacon_params_t p;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 1);
    /* Another beacon's frames and garbage change nothing. */
    assert_true(fake_hal_push(&H, nest_link_encode_food(-500), 100u, 0));
    assert_true(fake_hal_push(&H, nest_link_encode_waiting(7u), 100u, 0));
    assert_true(fake_hal_push(&H, 0u, 100u, 0));
    step();
    assert_int_equal(B.ledger_units, 7500);
    assert_int_equal(B.n_waiting, 0);
    assert_int_equal(B.deposits_total, 0);
    assert_int_equal(H.in_count, 0);
}

/* Round to nearest, half away from zero: F in 1/16 token. */
static int32_t expected_q4(int32_t units)
{
    int32_t num = units * 16;
    return (num >= 0) ? (num + 750) / 1500 : (num - 750) / 1500;
}

static void test_broadcast_matches_ledger(void **state)
{
    nest_beacon_params_t p;
    nest_link_frame_t f;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 0);
    for (k = 0; k < 30u; k++) {
        report(NL_DEPOSITS, (uint16_t)(k % 4u), 0u);   /* ids 0..3 waiting: N_W = 4 */
        report(NL_OAES, (uint16_t)(k % 4u), k);        /* and their OAEs */
        step();
        /* One frame per step, kinds 0, 1, 2 in turn. */
        assert_int_equal(H.out_count, k + 1u);
        assert_int_equal(nest_link_decode(H.last_sent, &f), NL_BEACON);
        assert_int_equal(f.kind, k % 3u);
        switch (f.kind) {
        case NL_KIND_FOOD:
            assert_int_equal(f.value, expected_q4(B.ledger_units));
            assert_int_equal(f.value, nest_beacon_food_q4(&B));
            break;
        case NL_KIND_WAITING:
            assert_int_equal(f.value, B.n_waiting);
            break;
        default:
            assert_int_equal(f.value, (int32_t)((B.m_t2 * 256u) / 20u));
            break;
        }
    }
    assert_int_equal(B.n_waiting, 4);
    assert_true(B.m_t2 > 0u);
}

static void test_broadcast_negative_and_mean_oae(void **state)
{
    nest_beacon_params_t p;
    nest_link_frame_t f;
    (void)state;
    nest_beacon_default_params(&p);
    p.f0_tokens = -3;
    start(&p, 1);
    steps(36);                  /* a robot has at most one OAE a step */
    report(NL_OAES, 1u, 37u);   /* M_T2 = 37: M_A = 37 / 20 = 1.85 = 473/256 */
    step();
    assert_int_equal(nest_link_decode(H.last_sent, &f), NL_BEACON);
    assert_int_equal(f.kind, NL_KIND_FOOD);
    /* -4500 - 370 units = -4870 = -3.2467 tokens = -51.95/16 -> -52. */
    assert_int_equal(f.value, -52);
    step();
    step();
    assert_int_equal(nest_link_decode(H.last_sent, &f), NL_BEACON);
    assert_int_equal(f.kind, NL_KIND_MEAN_OAE);
    assert_int_equal(f.value, 473);
}

static void test_never_moves(void **state)
{
    nest_beacon_params_t p;
    uint32_t k;
    (void)state;
    nest_beacon_default_params(&p);
    start(&p, 0);
    H.left = 123;
    H.right = -45;
    for (k = 0; k < 50u; k++) {
        H.proximity[0] = 4000u;   /* even with something pressing on it */
        step();
        assert_int_equal(H.left, 0);
        assert_int_equal(H.right, 0);
    }
    assert_int_equal(H.wheel_calls, 50);
    assert_int_equal(B.state, NB_RUN);
    assert_string_equal(nest_beacon_state_name(&B), "run");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_consumption_exact_per_minute),
        cmocka_unit_test(test_consumption_carries_remainder),
        cmocka_unit_test(test_consumption_odd_rate),
        cmocka_unit_test(test_movement_cost),
        cmocka_unit_test(test_deposits_add_token_energy),
        cmocka_unit_test(test_counts_heal_across_wrap),
        cmocka_unit_test(test_reports_credit_no_faster_than_a_robot),
        cmocka_unit_test(test_hostile_deposit_stream_stays_bounded),
        cmocka_unit_test(test_garbled_stream_stays_bounded),
        cmocka_unit_test(test_oae_window),
        cmocka_unit_test(test_oae_window_sums_robots_and_bins),
        cmocka_unit_test(test_t2_clamped),
        cmocka_unit_test(test_waiting_robots),
        cmocka_unit_test(test_ignores_foreign_frames),
        cmocka_unit_test(test_broadcast_matches_ledger),
        cmocka_unit_test(test_broadcast_negative_and_mean_oae),
        cmocka_unit_test(test_never_moves),
    };
    return cmocka_run_group_tests_name("nest_beacon", tests, NULL, NULL);
}
