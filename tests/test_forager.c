/*
 * test_forager.c - seed 000's forager (firmware/forager) on a fake HAL:
 * the decision in the nest under each policy, searching, returning,
 * depositing, losing the token, and the reports to the beacon.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal.h"
#include "foraging/forager.h"
#include "foraging/nest_link.h"

#define T1 50u
#define SPEED 388
#define FOOD_Q4(tokens) ((int32_t)((tokens) * 16))

static hal_t H;
static forager_t F;

static void start_with(const forager_params_t *p, uint32_t seed)
{
    fake_hal_init(&H, 7u);
    forager_init(&F, p, seed);
}

/* The motion and decision tests below start from eq 6 as written (theta
 * = 0 at the start, so P_s = 1) and outside the nest (no leaving phase);
 * the defaults of both are tested on their own further down. */
static void start(ta_policy_t policy)
{
    forager_params_t p;
    forager_default_params(&p);
    p.policy = policy;
    p.drtm_theta = (uint8_t)TA_THETA_RAW;
    p.leave_nest = 0u;
    start_with(&p, 42u);
}

static void step(void)
{
    forager_step(&F, &H);
    fake_hal_end_step(&H);
}

/* A held token fills the 977 mrad view of the camera. */
#define HELD_MRAD 977u

/* `n` steps, each hearing one beacon frame from `range_mm`. */
static void hear_beacon_steps(uint32_t n, uint16_t range_mm)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        assert_true(fake_hal_push(&H, nest_link_encode_waiting(3u), range_mm, 0));
        step();
    }
}

/* The beacon's three frames, heard from `range_mm`. */
static void beacon(int32_t food_q4, uint16_t n_waiting, uint32_t mean_oae_q8, uint16_t range_mm)
{
    assert_true(fake_hal_push(&H, nest_link_encode_food(food_q4), range_mm, 0));
    assert_true(fake_hal_push(&H, nest_link_encode_waiting(n_waiting), range_mm, 0));
    assert_true(fake_hal_push(&H, nest_link_encode_mean_oae(mean_oae_q8), range_mm, 0));
}

/* `n` steps in the nest hearing the beacon say F tokens, N_W, M_A = 0. */
static void wait_steps(uint32_t n, int32_t food_q4, uint16_t n_waiting)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        beacon(food_q4, n_waiting, 0u, 300u);
        step();
    }
}

/* DRTM at the seed's start (F = 5, everyone waiting, no OAE): theta = 0,
 * P_s = 1, so the robot leaves at its first decision. */
static void to_search(void)
{
    start(TA_DRTM);
    wait_steps(T1, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_SEARCH);
}

/* Approach a token (near and centred), then hold it centred for
 * grasp_confirm steps: RETURN. */
static void grasp(void)
{
    uint8_t k;
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, 400u);
    step();
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, HELD_MRAD);
    for (k = 0; k < F.params.grasp_confirm; k++) {
        assert_int_equal(F.state, FORAGER_SEARCH);
        step();
    }
    assert_int_equal(F.state, FORAGER_RETURN);
}

static void to_return(void)
{
    to_search();
    grasp();
}

static void test_leaves_after_t1_when_theta_zero(void **state)
{
    (void)state;
    start(TA_DRTM);
    assert_int_equal(F.state, FORAGER_WAIT);
    wait_steps(T1 - 1u, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_int_equal(F.t1, T1 - 1u);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    wait_steps(1u, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* S = 20 - 5 = 15; k = (20 - 20) / 16 = 0; M_A = 0: theta = 0, P_s = 1. */
    assert_float_equal(F.S, 15.0, 1e-6);
    assert_float_equal(F.k, 0.0, 0.0);
    assert_float_equal(F.theta, 0.0, 0.0);
    assert_float_equal(F.P_s, 1.0, 0.0);
    assert_int_equal(forager_paper_state(F.state), 'S');
}

static void test_drtm_threshold_from_beacon(void **state)
{
    (void)state;
    start(TA_DRTM);
    /* N_W = 6 -> k = 14 / 16 = 0.875; M_A = 473/256 = 1.84766:
     * theta = 3 * 0.875 + 2 * 1.84766 = 6.32031. */
    {
        uint32_t i;
        for (i = 0; i < T1; i++) {
            beacon(FOOD_Q4(19), 6u, 473u, 300u);   /* S = 1: P tiny */
            step();
        }
    }
    assert_float_equal(F.k, 0.875, 1e-6);
    assert_float_equal(F.M_A, 473.0 / 256.0, 1e-6);
    assert_float_equal(F.theta, 3.0 * 0.875 + 2.0 * 473.0 / 256.0, 1e-5);
    assert_int_equal(F.beacon_range_mm, 300);
}

static void test_stays_when_stimulus_not_positive(void **state)
{
    (void)state;
    start(TA_DRTM);
    /* F = 25 > F_d: S = -5, P = 0 even with theta = 0. */
    wait_steps(20u * T1, FOOD_Q4(25), 20u);
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.S, -5.0, 1e-6);
    assert_float_equal(F.P_s, 0.0, 0.0);
    /* F = F_d exactly: S = 0, still nobody leaves. */
    wait_steps(20u * T1, FOOD_Q4(20), 20u);
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.P_s, 0.0, 0.0);
}

static void test_stays_without_beacon_info(void **state)
{
    uint32_t i;
    (void)state;
    start(TA_DRTM);
    for (i = 0; i < 20u * T1; i++) {
        step();
    }
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.P_s, 0.0, 0.0);
    /* Food alone is not enough for DRTM (N_W and M_A unknown). */
    for (i = 0; i < 20u * T1; i++) {
        assert_true(fake_hal_push(&H, nest_link_encode_food(FOOD_Q4(5)), 300u, 0));
        step();
    }
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_int_equal(F.beacon_known, FORAGER_KNOWS_FOOD);
    /* Over an 8-bit link the frames arrive truncated: still nothing. */
    start(TA_DRTM);
    for (i = 0; i < 20u * T1; i++) {
        assert_true(fake_hal_push(&H, (uint16_t)(nest_link_encode_food(FOOD_Q4(5)) & 0xFFu), 300u, 0));
        step();
    }
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_int_equal(F.beacon_known, 0);
}

static void test_search_to_return_on_wide_blob(void **state)
{
    (void)state;
    to_search();
    /* A narrow red blob is a token far away: keep searching. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, 300u);
    step();
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* A wide blob that is not red is not a token. */
    fake_hal_show_blob(&H, HAL_COLOUR_GREEN, 0, 900u);
    step();
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* A wide red blob with no approach just before it (another robot's
     * token passing in front) is not a grasp, however long it stays. */
    fake_hal_clear_blobs(&H);
    for (int k = 0; k < 12; k++) {
        step();
    }
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 40, HELD_MRAD);
    for (int k = 0; k < 10; k++) {
        step();
        assert_int_equal(F.state, FORAGER_SEARCH);
    }
    /* Approached, then wide but off centre: not held either. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, 400u);
    step();
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 400, HELD_MRAD);
    step();
    step();
    step();
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* Approached and held centred for grasp_confirm (3) steps: RETURN. */
    grasp();
    assert_int_equal(F.carrying, 1);
    assert_int_equal(forager_paper_state(F.state), 'R');
}

/* A token the gripper took in passing (no approach before it) stays wide
 * and centred while the robot drives on: after 20 steps (2 s) it counts as
 * held; a blob that leaves the centre even once starts the count again. */
static void test_held_without_approach_after_two_seconds(void **state)
{
    (void)state;
    to_search();
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 60, HELD_MRAD);
    for (int k = 0; k < 19; k++) {
        step();
        assert_int_equal(F.state, FORAGER_SEARCH);
    }
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 600, HELD_MRAD);   /* off centre once */
    step();
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 60, HELD_MRAD);
    for (int k = 0; k < 19; k++) {
        step();
        assert_int_equal(F.state, FORAGER_SEARCH);
    }
    step();
    assert_int_equal(F.state, FORAGER_RETURN);
}

static void test_search_steers_toward_blob(void **state)
{
    (void)state;
    to_search();
    /* Left of centre (CCW positive): the right wheel goes faster.
     * d = 800 * 300 / 1000 = 240: 388 -+ 240. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 300, 100u);
    step();
    assert_int_equal(H.left, SPEED - 240);
    assert_int_equal(H.right, SPEED + 240);
    /* Right of centre: the left wheel goes faster. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, -300, 100u);
    step();
    assert_true(H.left > H.right);
    assert_int_equal(H.left, SPEED + 240);
    /* Straight ahead: straight on. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, 100u);
    step();
    assert_int_equal(H.left, SPEED);
    assert_int_equal(H.right, SPEED);
    /* Clamped to the wheels' limit. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 2000, 100u);
    step();
    assert_int_equal(H.right, HAL_WHEEL_SPEED_MAX);
}

static void test_search_obstacle_vs_token_echo(void **state)
{
    uint32_t oae;
    (void)state;
    to_search();
    oae = F.walk.oae_count;
    /* Something in front and the blob is off to the side: avoid (an OAE). */
    H.proximity[0] = 1000u;
    H.proximity[7] = 1000u;
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 400, 300u);
    step();
    assert_int_equal(F.walk.oae_count, oae + 1u);
    assert_int_equal(F.walk.state, RW_AVOID);
    assert_true(H.left == -H.right && H.left != 0);
    /* The echo is the token itself, centred and near: drive into it. */
    F.walk.state = RW_FORWARD;
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 100, 300u);
    step();
    assert_int_equal(F.walk.oae_count, oae + 1u);
    assert_int_equal(H.left, SPEED - 80);
    assert_int_equal(H.right, SPEED + 80);
}

static void test_search_keeps_oae_count(void **state)
{
    (void)state;
    start(TA_DRTM);
    F.walk.oae_count = 5u;
    F.walk.state = RW_AVOID;
    wait_steps(T1, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* A fresh run of the walk, the OAE total kept. */
    assert_int_equal(F.walk.state, RW_FORWARD);
    assert_int_equal(F.walk.oae_count, 5);
    H.proximity[1] = 2000u;
    step();
    assert_int_equal(F.walk.oae_count, 6);
}

static void test_return_to_deposit_in_nest(void **state)
{
    (void)state;
    to_return();
    /* 700 mm is inside the 750 mm nest but not by the 100 mm margin. */
    hear_beacon_steps(5u, 700u);
    assert_int_equal(F.state, FORAGER_RETURN);
    /* A noisy range: two frames inside, one outside, restart the count. */
    hear_beacon_steps(2u, 600u);
    hear_beacon_steps(1u, 700u);
    hear_beacon_steps(2u, 600u);
    assert_int_equal(F.state, FORAGER_RETURN);
    /* The third frame in a row inside the nest means arrival. */
    hear_beacon_steps(1u, 600u);
    assert_int_equal(F.state, FORAGER_DEPOSIT);
    assert_int_equal(forager_paper_state(F.state), 'R');
    assert_int_equal(H.left, -SPEED);
    assert_int_equal(H.right, -SPEED);
}

/* park_steps: on arrival the robot drives on toward the lamp (PARK, paper
 * state S_R) for park_steps steps, the arrival step the first, then
 * deposits; a token lost meanwhile sends it back to SEARCH. */
static void test_park_then_deposit(void **state)
{
    forager_params_t p;
    uint32_t i;
    (void)state;
    forager_default_params(&p);
    p.drtm_theta = (uint8_t)TA_THETA_RAW;
    p.leave_nest = 0u;
    p.park_steps = 4u;
    start_with(&p, 42u);
    wait_steps(T1, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_SEARCH);
    grasp();
    hear_beacon_steps(3u, 600u);                 /* arrival */
    assert_int_equal(F.state, FORAGER_PARK);
    assert_int_equal(forager_paper_state(F.state), 'R');
    assert_string_equal(forager_state_name(&F), "park");
    assert_true(H.left > 0 || H.right > 0);      /* driving on, not backing out */
    for (i = 0; i < 3u; i++) {
        hear_beacon_steps(1u, 300u);
        assert_int_equal(F.state, FORAGER_PARK);
    }
    hear_beacon_steps(1u, 300u);
    assert_int_equal(F.state, FORAGER_DEPOSIT);
    assert_int_equal(H.left, -SPEED);

    /* The token gone while parking: lost_steps later, SEARCH. */
    start_with(&p, 42u);
    wait_steps(T1, FOOD_Q4(5), 20u);
    grasp();
    hear_beacon_steps(3u, 600u);
    assert_int_equal(F.state, FORAGER_PARK);
    fake_hal_clear_blobs(&H);
    for (i = 0; i < F.params.lost_steps; i++) {
        assert_int_equal(F.state, FORAGER_PARK);
        hear_beacon_steps(1u, 300u);
    }
    assert_int_equal(F.state, FORAGER_SEARCH);
}

static void test_deposit_backs_then_waits(void **state)
{
    uint32_t i;
    int found;
    nest_link_frame_t f;
    (void)state;
    to_return();
    hear_beacon_steps(3u, 200u);
    assert_int_equal(F.state, FORAGER_DEPOSIT);
    /* The token lets go as we back off. */
    fake_hal_clear_blobs(&H);
    for (i = 1; i < 5u; i++) {
        step();
        assert_int_equal(F.state, FORAGER_DEPOSIT);
        assert_int_equal(H.left, -SPEED);
        assert_int_equal(H.right, -SPEED);
    }
    assert_int_equal(F.deposits, 0);
    step();
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_int_equal(F.deposits, 1);
    assert_int_equal(F.t1, 0);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    /* Of the next two reports, the deposit one carries the new total. */
    step();
    step();
    found = 0;
    for (i = H.out_count - 2u; i < H.out_count; i++) {
        if (nest_link_decode(H.outbox[i], &f) == NL_DEPOSITS) {
            assert_int_equal(f.value, 1);
            found++;
        }
    }
    assert_int_equal(found, 1);
}

static void test_deposit_gives_up_when_token_stays(void **state)
{
    uint32_t i;
    (void)state;
    to_return();
    hear_beacon_steps(3u, 200u);
    assert_int_equal(F.state, FORAGER_DEPOSIT);
    /* The token stays in view: back for 2 * deposit_steps, then WAIT
     * without counting a deposit. */
    for (i = 1; i < 10u; i++) {
        step();
        assert_int_equal(F.state, FORAGER_DEPOSIT);
        assert_int_equal(H.left, -SPEED);
    }
    step();
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_int_equal(F.deposits, 0);
}

static void test_return_to_search_when_token_lost(void **state)
{
    (void)state;
    to_return();
    fake_hal_clear_blobs(&H);
    step();
    step();
    assert_int_equal(F.state, FORAGER_RETURN);
    /* Seen again in time: the count starts over. */
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, HELD_MRAD);
    step();
    fake_hal_clear_blobs(&H);
    step();
    step();
    assert_int_equal(F.state, FORAGER_RETURN);
    step();
    assert_int_equal(F.state, FORAGER_SEARCH);
    assert_int_equal(F.carrying, 0);
}

static void test_return_phototaxis(void **state)
{
    (void)state;
    to_return();
    /* Brightest at IR7 (+17 deg = 297 mrad, front left): d = 237. */
    H.ambient[7] = 1000u;
    H.ambient[6] = 2000u;
    step();
    assert_int_equal(H.left, SPEED - 237);
    assert_int_equal(H.right, SPEED + 237);
    /* Brightest at IR3 (-150 deg, behind right): turn clockwise in place. */
    H.ambient[7] = 4000u;
    H.ambient[6] = 4000u;
    H.ambient[3] = 1000u;
    step();
    assert_int_equal(H.left, F.params.walk.turn_speed_steps_s);
    assert_int_equal(H.right, -F.params.walk.turn_speed_steps_s);
    /* Too dim (above light_detect): no light, random walk. */
    H.ambient[3] = 3700u;
    F.walk.state = RW_FORWARD;
    F.walk.params.turn_chance = 0u;
    step();
    assert_int_equal(H.left, SPEED);
    assert_int_equal(H.right, SPEED);
    assert_int_equal(F.state, FORAGER_RETURN);
}

static void test_inbox_drained_while_searching(void **state)
{
    (void)state;
    to_search();
    /* A beacon frame heard while searching near the nest ... */
    assert_true(fake_hal_push(&H, nest_link_encode_food(0), 100u, 0));
    step();
    assert_int_equal(H.in_count, 0);
    /* ... is not taken for the nest once the token is grasped. */
    grasp();
    step();
    assert_int_equal(F.state, FORAGER_RETURN);
}

static void test_reports_alternate(void **state)
{
    forager_params_t p;
    nest_link_frame_t f;
    uint32_t i, first;
    (void)state;
    forager_default_params(&p);
    start_with(&p, 3u);
    H.id = 70u;                 /* 6-bit ids: 70 -> 6 */
    F.deposits = 2u;
    F.walk.oae_count = 300u;    /* sent mod 256: 44 */
    first = H.out_count;
    for (i = 0; i < 10u; i++) {
        step();
    }
    assert_int_equal(H.out_count - first, 10);
    for (i = 0; i < 10u; i++) {
        uint8_t type = nest_link_decode(H.outbox[first + i], &f);
        assert_int_equal(type, (i % 2u == 0u) ? NL_DEPOSITS : NL_OAES);
        assert_int_equal(f.robot_id, 6);
        assert_int_equal(f.value, (type == NL_DEPOSITS) ? 2 : 44);
    }
}

/* report_steps = 3: one report every third step, on the steps where
 * (step + id) % 3 == 0, still alternating deposits and OAEs. */
static void test_report_steps_staggered(void **state)
{
    forager_params_t p;
    nest_link_frame_t f;
    uint32_t i, first, sent = 0u;
    (void)state;
    forager_default_params(&p);
    p.report_steps = 3u;
    start_with(&p, 3u);
    H.id = 4u;
    first = H.out_count;
    for (i = 0; i < 12u; i++) {
        uint32_t before = H.out_count;
        step();
        assert_int_equal(H.out_count - before, ((i + 4u) % 3u == 0u) ? 1 : 0);
    }
    assert_int_equal(H.out_count - first, 4);
    for (i = 0; i < 4u; i++) {
        uint8_t type = nest_link_decode(H.outbox[first + i], &f);
        assert_int_equal(type, (i % 2u == 0u) ? NL_DEPOSITS : NL_OAES);
        sent++;
    }
    assert_int_equal(sent, 4);
}

/* Out of the nest a robot sends only its OAE total, every 5 steps (for a
 * beacon in range to count OAEs as they happen); never its deposit total,
 * by which the beacon counts robots waiting. */
static void test_oae_reports_out_of_the_nest(void **state)
{
    uint32_t sent, k;
    nest_link_frame_t f;
    (void)state;
    to_search();
    sent = H.out_count;
    for (k = 0; k < 10u; k++) {
        uint32_t before = H.out_count;
        step();
        if (H.out_count != before) {
            assert_int_equal(nest_link_decode(H.last_sent, &f), NL_OAES);
            assert_int_equal(f.robot_id, 7);
        }
    }
    assert_int_equal(H.out_count, sent + 2u);
}

/* ARTM with n = 9 and S tiny next to theta: P ~ 0, the robot stays and
 * decides every T1. */
static void test_artm_theta_follows_stimulus(void **state)
{
    forager_params_t p;
    (void)state;
    forager_default_params(&p);
    p.policy = TA_ARTM;
    p.n_min = 9u;
    p.n_max = 9u;
    start_with(&p, 5u);
    assert_float_equal(F.theta, 3.3, 1e-6);
    /* First decision: S_prev = S, no change. */
    wait_steps(T1, 319, 20u);          /* F = 19.9375, S = 0.0625 */
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.S, 0.0625, 1e-6);
    assert_float_equal(F.theta, 3.3, 1e-6);
    /* Stimulus rises: theta falls by delta. */
    wait_steps(T1, 318, 20u);          /* S = 0.125 */
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.theta, 2.8, 1e-6);
    /* Stimulus falls: theta rises. */
    wait_steps(T1, 319, 20u);
    assert_float_equal(F.theta, 3.3, 1e-6);
    /* Unchanged: theta unchanged. */
    wait_steps(T1, 319, 20u);
    assert_float_equal(F.theta, 3.3, 1e-6);
    /* Falling all the way: clipped at theta_max = 10. */
    {
        int32_t food = 319;
        uint32_t d;
        for (d = 0; d < 20u; d++) {
            food += 1;                 /* F rises: S falls (soon negative) */
            wait_steps(T1, food, 20u);
        }
    }
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.theta, 10.0, 1e-6);
}

static void test_frtm_theta_fixed(void **state)
{
    forager_params_t p;
    (void)state;
    forager_default_params(&p);
    p.policy = TA_FRTM;
    p.n_min = 9u;
    p.n_max = 9u;
    start_with(&p, 5u);
    wait_steps(T1, 319, 20u);
    assert_float_equal(F.theta, 3.3, 0.0);
    wait_steps(T1, 318, 20u);
    wait_steps(T1, 317, 20u);
    assert_int_equal(F.state, FORAGER_WAIT);
    assert_float_equal(F.theta, 3.3, 0.0);
    /* S = 0.1875, theta 3.3, n 9: P = 1 / (1 + 17.6^9) = 6.2e-12. */
    assert_true(F.P_s < 1e-10f);
    assert_true(F.P_s > 0.0f);
}

static void test_n_per_robot_in_range(void **state)
{
    forager_params_t p;
    uint32_t seed;
    uint16_t seen = 0u;
    (void)state;
    forager_default_params(&p);
    for (seed = 0; seed < 500u; seed++) {
        start_with(&p, seed);
        assert_in_range(F.n, 2u, 9u);
        seen = (uint16_t)(seen | (1u << F.n));
    }
    /* Every value of 2..9 occurs across robots. */
    assert_int_equal(seen, 0x3FCu);
    /* Drawn from the seed: the same robot gets the same n after reset. */
    start_with(&p, 77u);
    {
        uint8_t n = F.n;
        forager_reset(&F);
        assert_int_equal(F.n, n);
    }
}

static void test_names(void **state)
{
    (void)state;
    assert_int_equal(forager_paper_state(FORAGER_WAIT), 'W');
    assert_int_equal(forager_paper_state(FORAGER_SEARCH), 'S');
    assert_int_equal(forager_paper_state(FORAGER_RETURN), 'R');
    assert_int_equal(forager_paper_state(FORAGER_DEPOSIT), 'R');
    {
        forager_t probe;
        probe.state = FORAGER_WAIT;
        assert_string_equal(forager_state_name(&probe), "wait");
        probe.state = FORAGER_DEPOSIT;
        assert_string_equal(forager_state_name(&probe), "deposit");
    }
    /* The walk runs at the forager's speed (0.05 m/s). */
    start(TA_DRTM);
    assert_int_equal(F.walk.params.speed_steps_s, SPEED);
}

/* DRTM's threshold modes: offset (the default) starts at theta0 = 3.3 and
 * rises with traffic; clip starts at theta_min = 1; both stay in [1, 10];
 * raw is eq 6 as written. */
static void test_drtm_theta_modes_and_bounds(void **state)
{
    static const struct { uint8_t mode; float start, mid, top; } cases[] = {
        /* mid: k = 0.875, M_A = 473/256: eq 6 = 6.3203 */
        { TA_THETA_OFFSET, 3.3f, 3.3f + 6.3203125f, 10.0f },
        { TA_THETA_CLIP, 1.0f, 6.3203125f, 10.0f },
        { TA_THETA_RAW, 0.0f, 6.3203125f, 3.0f * 0.875f + 2.0f * 4000.0f / 256.0f },
    };
    (void)state;
    for (unsigned c = 0; c < 3; c++) {
        forager_params_t p;
        forager_default_params(&p);
        p.drtm_theta = cases[c].mode;
        p.leave_nest = 0u;
        start_with(&p, 42u);
        assert_float_equal(F.theta, cases[c].start, 1e-6);
        for (uint32_t i = 0; i < T1; i++) {
            beacon(FOOD_Q4(19), 6u, 473u, 300u);
            step();
        }
        assert_float_equal(F.theta, cases[c].mid, 1e-4);
        for (uint32_t i = 0; i < T1 && F.state == FORAGER_WAIT; i++) {
            beacon(FOOD_Q4(19), 6u, 4000u, 300u);   /* congestion: M_A = 15.6 */
            step();
        }
        assert_float_equal(F.theta, cases[c].top, 1e-3);
    }
    forager_params_t d;
    forager_default_params(&d);
    assert_int_equal(d.drtm_theta, TA_THETA_OFFSET);
}

/* T1 is a minimum waiting time: once it has passed the robot draws every
 * step (the default), or only every T1 (decide_each_step = 0). */
static void test_decision_cadence(void **state)
{
    (void)state;
    for (int each = 0; each < 2; each++) {
        forager_params_t p;
        forager_default_params(&p);
        p.drtm_theta = (uint8_t)TA_THETA_RAW;
        p.leave_nest = 0u;
        p.decide_each_step = (uint8_t)each;
        start_with(&p, 42u);
        /* S = 20 - 19.75 = 0.25 against theta = 3 * 14/16 = 2.625: P_s is
         * small but not 0; count the draws by the roulette's stream. */
        uint32_t draws = 0;
        for (uint32_t i = 0; i < 4u * T1 && F.state == FORAGER_WAIT; i++) {
            rng_t before = F.rng;
            beacon(4 * 79, 6u, 0u, 300u);
            step();
            draws += memcmp(&before, &F.rng, sizeof before) != 0;
        }
        if (each) {
            assert_true(draws >= 3u * T1);   /* every step from T1 on */
        } else {
            assert_int_equal(draws, 4u);     /* at T1, 2 T1, 3 T1, 4 T1 */
        }
    }
}

/* Leaving the nest: the robot turns away from the lamp and drives out,
 * ignores red blobs meanwhile, and stops leaving once the beacon is heard
 * from outside the nest (or after leave_max_steps). */
static void test_leaving_the_nest(void **state)
{
    forager_params_t p;
    (void)state;
    forager_default_params(&p);
    p.drtm_theta = (uint8_t)TA_THETA_RAW;   /* P_s = 1: leaves at T1 */
    start_with(&p, 42u);
    wait_steps(T1, FOOD_Q4(5), 20u);
    assert_int_equal(F.state, FORAGER_SEARCH);
    assert_int_equal(F.leaving, 1);
    /* The lamp straight ahead (IR0, -17 deg): away from it is behind, so
     * the robot turns in place. */
    H.ambient[0] = 1000u;
    hear_beacon_steps(1, 300u);
    assert_true(H.left == -H.right && H.left != 0);
    /* The lamp behind on the left (IR4, +150 deg): away from it is 30 deg
     * to the right, so it drives on, turning right. */
    H.ambient[0] = 4000u;
    H.ambient[4] = 1000u;
    fake_hal_show_blob(&H, HAL_COLOUR_RED, 0, 400u);   /* a token in the nest? not now */
    hear_beacon_steps(1, 300u);
    assert_true(H.left > 0 && H.left > H.right);
    assert_int_equal(F.approach, 0);
    assert_int_equal(F.state, FORAGER_SEARCH);
    /* Out: the beacon heard three times from beyond the nest's 750 + 100 mm. */
    hear_beacon_steps(2, 900u);
    assert_int_equal(F.leaving, 1);
    hear_beacon_steps(1, 900u);
    assert_int_equal(F.leaving, 0);
    /* And the lamp never goes out of view: it gives up after 300 steps. */
    start_with(&p, 42u);
    wait_steps(T1, FOOD_Q4(5), 20u);
    H.ambient[2] = 1000u;   /* the lamp in view all along */
    for (uint32_t i = 0; i < 299u; i++) {
        hear_beacon_steps(1, 300u);
        assert_int_equal(F.leaving, 1);
    }
    hear_beacon_steps(1, 300u);
    assert_int_equal(F.leaving, 0);
}

/* Garbled and hostile frames (every kind, every id, any range, many a
 * step) and garbage blobs for 30,000 steps under each policy: the forager
 * stays in its states, its wheel speeds within the motors' range, its
 * probabilities in [0, 1] (and UBSan sees no overflow). */
static void test_hostile_inbox(void **state)
{
    static const ta_policy_t policies[] = { TA_DRTM, TA_ARTM, TA_FRTM };
    uint32_t x = 777u, i, k, pol;
    (void)state;
    for (pol = 0; pol < 3u; pol++) {
        start(policies[pol]);
        for (i = 0; i < 30000u; i++) {
            for (k = 0; k < 10u; k++) {
                x = x * 1664525u + 1013904223u;
                (void)fake_hal_push(&H, (uint16_t)(x >> 16), (uint16_t)(x & 2047u), (int16_t)(x % 6283u) - 3141);
            }
            x = x * 1664525u + 1013904223u;
            if (x & 1u) {
                fake_hal_show_blob(&H, (uint8_t)((x >> 1) % 4u), (int16_t)((x >> 8) % 2000u) - 1000,
                                   (uint16_t)((x >> 20) % 1200u));
            } else {
                fake_hal_clear_blobs(&H);
            }
            H.proximity[(x >> 3) % HAL_IR_COUNT] = (uint16_t)(x >> 12);
            step();
            assert_true(F.state <= FORAGER_DEPOSIT);
            assert_true(H.left >= -1000 && H.left <= 1000 && H.right >= -1000 && H.right <= 1000);
            assert_true(F.P_s >= 0.0f && F.P_s <= 1.0f);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_leaves_after_t1_when_theta_zero),
        cmocka_unit_test(test_drtm_threshold_from_beacon),
        cmocka_unit_test(test_stays_when_stimulus_not_positive),
        cmocka_unit_test(test_stays_without_beacon_info),
        cmocka_unit_test(test_search_to_return_on_wide_blob),
        cmocka_unit_test(test_held_without_approach_after_two_seconds),
        cmocka_unit_test(test_search_steers_toward_blob),
        cmocka_unit_test(test_search_obstacle_vs_token_echo),
        cmocka_unit_test(test_search_keeps_oae_count),
        cmocka_unit_test(test_return_to_deposit_in_nest),
        cmocka_unit_test(test_park_then_deposit),
        cmocka_unit_test(test_deposit_backs_then_waits),
        cmocka_unit_test(test_deposit_gives_up_when_token_stays),
        cmocka_unit_test(test_return_to_search_when_token_lost),
        cmocka_unit_test(test_return_phototaxis),
        cmocka_unit_test(test_inbox_drained_while_searching),
        cmocka_unit_test(test_reports_alternate),
        cmocka_unit_test(test_report_steps_staggered),
        cmocka_unit_test(test_oae_reports_out_of_the_nest),
        cmocka_unit_test(test_artm_theta_follows_stimulus),
        cmocka_unit_test(test_frtm_theta_fixed),
        cmocka_unit_test(test_n_per_robot_in_range),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_hostile_inbox),
        cmocka_unit_test(test_drtm_theta_modes_and_bounds),
        cmocka_unit_test(test_decision_cadence),
        cmocka_unit_test(test_leaving_the_nest),
    };
    return cmocka_run_group_tests_name("forager", tests, NULL, NULL);
}
