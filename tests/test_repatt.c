/*
 * test_repatt.c - seed 002's RepAtt (firmware/repatt) on a fake HAL: the
 * averaging queue and change of eqs 5-6, the gain table of Algorithm 1
 * lines 8-21, the integer odometry behind homing, the state machine
 * (search, acquire, broadcast, pick-up, homing, obstacle avoidance), the
 * random-walk policy, slotted and duplex listening, and hostile input.
 * The fake HAL does not move the robot: step() integrates the commanded
 * wheel speeds into the step counters and a true pose, as the simulator
 * would.  About 0.02 s (ASan/UBSan: 0.07 s).
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal.h"
#include "fake_drive.h"
#include "repatt/repatt.h"
#include "units.h"

#define M_PI UNITS_PI
#define PERIOD_MS 25u
#define PB_Q32 10737418u   /* 0.0025 x 2^32 */

static hal_t H;
static repatt_t R;
static uint32_t Q[REPATT_QUEUE_WORDS(REPATT_QUEUE_MAX)];
/* The robot as the world sees it (start frame), and the wheels' exact steps. */
static fake_drive_t D;
/* 1: the robot hears while it emits (sound.self_masking false). */
static int no_masking;

static void start_with(const repatt_params_t *p, uint32_t seed)
{
    fake_hal_init(&H, 3u);
    H.period_ms = PERIOD_MS;
    memset(&R, 0, sizeof R);
    repatt_attach_queue(&R, Q, (uint16_t)REPATT_QUEUE_MAX);
    repatt_init(&R, p, seed);
    fake_drive_start(&D, 0.0, 0.0, 0.0);
    no_masking = 0;
}

static void start(uint8_t policy, uint8_t listening)
{
    repatt_params_t p;
    repatt_default_params(&p);
    repatt_apply_policy(&p, policy);
    p.listening = listening;
    p.reach_width_mrad = 1200u;   /* these tests: stop at once (the all-round scenarios' rule) */
    p.approach_mm = 0u;
    start_with(&p, 42u);
}

/* One control period: the controller, then the wheels move as commanded. */
static void step(void)
{
    if (no_masking) {
        H.speaker_played = 0u;
    }
    repatt_step(&R, &H);
    fake_drive_move(&D, &H, PERIOD_MS);
    fake_hal_end_step(&H);
}

static void steps(uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        step();
    }
}

static void set_levels(uint32_t repulsion, uint32_t attraction)
{
    uint8_t m;
    for (m = 0; m < HAL_MIC_COUNT; m++) {
        H.mic[m][1] = repulsion;
        H.mic[m][2] = attraction;
    }
}

static void show_red(uint8_t n, int16_t bearing_mrad, uint16_t width_mrad)
{
    uint8_t i;
    H.n_blobs = n;
    for (i = 0; i < n; i++) {
        H.blobs[i].colour = HAL_COLOUR_RED;
        H.blobs[i].bearing_mrad = (int16_t)(bearing_mrad + 200 * i);
        H.blobs[i].width_mrad = (uint16_t)(i == 0 ? width_mrad : width_mrad / 2u);
        H.blobs[i].pixels = 10u;
    }
}

/* ------------------------------------------------------------ eqs 5-6 */

/* A ramp's change is seen once 2y readings are held: with y = 1 after
 * the second reading, with y = 40 after the 80th, never before; a falling
 * ramp gives -1, a flat one 0; I(t) is the mean of the last y. */
static void test_filter_ramp(void **state)
{
    static const uint16_t ys[] = { 1u, 40u };
    uint32_t ring[2u * 40u];
    chemo_filter_t f;
    uint32_t i, k;
    (void)state;
    for (k = 0; k < 2u; k++) {
        uint16_t y = ys[k];
        chemo_filter_init(&f, y);
        for (i = 1; i <= 2u * y; i++) {
            assert_int_equal(chemo_filter_sign(&f), 0);
            chemo_filter_push(&f, ring, 1000u + 10u * i);
        }
        assert_int_equal(chemo_filter_sign(&f), 1);
        /* Mean of readings y+1..2y: 1000 + 10 (3y + 1) / 2. */
        assert_int_equal(chemo_filter_level(&f), (1000u * 2u + 10u * (3u * y + 1u)) / 2u);
        for (i = 0; i < 2u * y; i++) {
            chemo_filter_push(&f, ring, 500u);   /* a fall, then flat */
            if (i == y - 1u) {
                assert_int_equal(chemo_filter_sign(&f), -1);
            }
        }
        assert_int_equal(chemo_filter_sign(&f), 0);
        assert_int_equal(chemo_filter_level(&f), 500u);
    }
}

/* The running sums equal eq 5's averages computed from scratch, for
 * random readings over the whole uint32 range and every queue size of
 * Figure 2c. */
static void test_filter_matches_eq5(void **state)
{
    static const uint16_t ys[] = { 1u, 8u, 20u, 40u, 80u, 120u };
    static uint32_t hist[3000];
    uint32_t ring[2u * 120u];
    chemo_filter_t f;
    uint32_t x = 12345u, t, k;
    (void)state;
    for (k = 0; k < 6u; k++) {
        uint16_t y = ys[k];
        chemo_filter_init(&f, y);
        for (t = 0; t < 3000u; t++) {
            x = x * 1664525u + 1013904223u;
            hist[t] = (t & 64u) ? x : x >> 12;   /* huge and small stretches */
            chemo_filter_push(&f, ring, hist[t]);
            if (t + 1u >= 2u * y) {
                uint64_t a = 0, b = 0;
                uint32_t j;
                for (j = 0; j < y; j++) {
                    a += hist[t - j];
                    b += hist[t - y - j];
                }
                assert_int_equal(chemo_filter_sign(&f), a > b ? 1 : (a < b ? -1 : 0));
                assert_int_equal(chemo_filter_level(&f), (uint32_t)(a / y));
            }
        }
    }
}

/* ------------------------------------------------------------ lines 8-21 */

/* Every sign combination with A4m100d-R1m10d, and the random walk's all-1
 * gains, against P_b x G_r x G_a. */
static void test_gain_table(void **state)
{
    const chemo_gains_t best = { 4u, 100u, 1u, 10u };
    const chemo_gains_t rw = { 1u, 1u, 1u, 1u };
    int dr, da;
    (void)state;
    for (dr = -1; dr <= 1; dr++) {
        for (da = -1; da <= 1; da++) {
            double gr = dr > 0 ? 1.0 : (dr < 0 ? 1.0 / 10.0 : 1.0);    /* r_m = 1, 1/r_d */
            double ga = da > 0 ? 1.0 / 100.0 : (da < 0 ? 4.0 : 1.0);  /* 1/a_d, a_m */
            double want = (double)PB_Q32 * gr * ga;
            uint32_t got = chemo_tumble_q32(PB_Q32, &best, (int8_t)dr, (int8_t)da);
            assert_true(fabs((double)got - want) <= 1.0);
            assert_int_equal(chemo_tumble_q32(PB_Q32, &rw, (int8_t)dr, (int8_t)da), PB_Q32);
        }
    }
    /* The table's corners by hand: 0.0025 x 4 = 0.01; 0.0025 / 10 / 100. */
    assert_int_equal(chemo_tumble_q32(PB_Q32, &best, 0, -1), 4u * PB_Q32);
    assert_int_equal(chemo_tumble_q32(PB_Q32, &best, -1, 1), PB_Q32 / 1000u);
    /* A probability above 1 is 1; gains 0 are 1, above 1000 are 1000. */
    {
        const chemo_gains_t big = { 1000u, 1u, 1000u, 1u };
        const chemo_gains_t odd = { 0u, 0u, 60000u, 0u };
        assert_int_equal(chemo_tumble_q32(UINT32_MAX / 2u, &big, 1, -1), UINT32_MAX);
        assert_int_equal(chemo_tumble_q32(PB_Q32, &odd, -1, 1), PB_Q32);
        assert_int_equal(chemo_tumble_q32(1000u, &odd, 1, -1), 1000u * 1000u);
    }
}

static void test_probability_q32(void **state)
{
    (void)state;
    assert_int_equal(chemo_probability_q32(0.0025f), PB_Q32);
    assert_int_equal(chemo_probability_q32(1.0f), UINT32_MAX);
    assert_int_equal(chemo_probability_q32(0.99999999f), UINT32_MAX);
    assert_int_equal(chemo_probability_q32(0.0f), 0u);
    assert_int_equal(chemo_probability_q32(-1.0f), 0u);
    assert_int_equal(chemo_probability_q32(NAN), 0u);
}

/* ------------------------------------------------------------ odometry */

static void test_trig_and_odometry(void **state)
{
    odometry_t o;
    int32_t a;
    int32_t x, y;
    int16_t dl, dr;
    int16_t l = 30000, r = 30000;   /* counters near their wrap */
    uint32_t i;
    (void)state;
    for (a = -3300; a <= 3300; a += 3) {   /* odometry's angles: within (-pi, pi] and a step */
        assert_true(fabs(odo_sin_q14(a) / 16384.0 - sin(a / 1000.0)) < 3e-4);
        assert_true(fabs(odo_cos_q14(a) / 16384.0 - cos(a / 1000.0)) < 3e-4);
    }
    for (x = -3000000; x <= 3000000; x += 123457) {
        for (y = -3000000; y <= 3000000; y += 98765) {
            double want = atan2((double)y, (double)x) * 1000.0;
            double got = odo_atan2_mrad(y, x);
            assert_true(fabs(fake_drive_wrap_pi((got - want) / 1000.0)) < 0.006);
        }
    }
    assert_int_equal(odo_atan2_mrad(0, 0), 0);
    assert_true(abs(odo_atan2_mrad(INT32_MIN, INT32_MIN) + 2356) <= 2);   /* no overflow at the extremes */

    /* 2000 steps straight across the counters' wrap: 257.6 mm ahead. */
    odometry_reset(&o);
    odometry_update(&o, l, r, &dl, &dr);
    for (i = 0; i < 100u; i++) {
        l = (int16_t)(uint16_t)((uint16_t)l + 20u);
        r = (int16_t)(uint16_t)((uint16_t)r + 20u);
        odometry_update(&o, l, r, &dl, &dr);
        assert_int_equal(dl, 20);
    }
    assert_true(labs(o.x_um - 257610L) < 100L);
    assert_true(labs(o.y_um) < 10L);
    assert_int_equal(odometry_home_bearing_mrad(&o), 3142);
    assert_false(odometry_within_mm(&o, 250u));
    assert_true(odometry_within_mm(&o, 260u));
    /* A quarter turn to the left (CCW), then on: y grows. */
    for (i = 0; i < 200u; i++) {
        l = (int16_t)(l - 3);
        r = (int16_t)(r + 3);
        odometry_update(&o, l, r, &dl, &dr);
        if (o.heading_urad >= 1570796L) {
            break;
        }
    }
    assert_true(o.heading_urad >= 1570796L && o.heading_urad < 1570796L + 14583L);   /* 6 x 2430.3 urad a step */
    for (i = 0; i < 100u; i++) {
        l = (int16_t)(l + 20);
        r = (int16_t)(r + 20);
        odometry_update(&o, l, r, &dl, &dr);
    }
    assert_true(labs(o.y_um - 257610L) < 3000L);
    /* At (257, 257) mm facing +y, home is behind on the left: 135 deg. */
    assert_true(abs(odometry_home_bearing_mrad(&o) - 2356) < 30);
}

/* ------------------------------------------------------------ states */

/* Searching: straight at 776 steps/s, broadcasting repulsion; a red blob
 * in view: acquire, turning toward it. */
static void test_search_then_acquire(void **state)
{
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    R.params.p_b = 0.0f;
    R.p_b_q32 = 0u;
    step();
    assert_int_equal(R.state, REPATT_SEARCH);
    assert_int_equal(H.left, 776);
    assert_int_equal(H.right, 776);
    assert_int_equal(H.speaker_band, REPATT_BAND_REPULSION);
    assert_string_equal(repatt_state_name(&R), "search");
    show_red(1u, 400, 100u);   /* ahead on the left, far */
    step();
    assert_int_equal(R.state, REPATT_ACQUIRE);
    assert_int_equal(R.found, 1u);
    assert_true(H.right > H.left);
    assert_int_equal(H.speaker_band, 0u);   /* 0 < found <= cap: silent */
    show_red(1u, -2500, 100u);              /* behind on the right: turn in place */
    step();
    assert_true(H.left > 0 && H.right < 0);
    fake_hal_clear_blobs(&H);
    step();
    assert_int_equal(R.state, REPATT_SEARCH);
    assert_int_equal(H.speaker_band, REPATT_BAND_REPULSION);
}

/* found > cap: attraction; found == cap: silence. */
static void test_attraction_when_found_exceeds_cap(void **state)
{
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    show_red(6u, 0, 100u);
    step();
    assert_int_equal(R.found, 6u);
    assert_int_equal(R.band, REPATT_BAND_ATTRACTION);
    assert_int_equal(H.speaker_band, REPATT_BAND_ATTRACTION);
    show_red(5u, 0, 100u);
    step();
    assert_int_equal(H.speaker_band, 0u);
    R.cap = 2u;
    show_red(3u, 0, 100u);
    step();
    assert_int_equal(H.speaker_band, REPATT_BAND_ATTRACTION);
}

/* Within reach: stopped for pick_time (200 periods of 25 ms); the blob
 * gone after the wait: carried (cap 4). */
static void test_pickup_counts_when_blob_goes_after_wait(void **state)
{
    uint32_t i;
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    show_red(1u, 50, 1300u);
    for (i = 0; i < 200u; i++) {
        step();
        assert_int_equal(R.state, REPATT_PICK);
        assert_int_equal(H.left, 0);
        assert_int_equal(H.right, 0);
    }
    fake_hal_clear_blobs(&H);   /* the task took it after 200 stopped periods */
    step();
    assert_int_equal(R.cap, 4u);
    assert_int_equal(R.pickups, 1u);
    assert_int_equal(R.state, REPATT_SEARCH);
    assert_int_equal(H.left, 776);
}

/* In a cluster: when the target is taken, the next one behind it shows in
 * the same direction but narrower (farther): that is a pick-up, not the
 * same target still there. */
static void test_pickup_counts_with_a_target_behind(void **state)
{
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    show_red(1u, 50, 1300u);
    steps(200u);
    assert_int_equal(R.state, REPATT_PICK);
    show_red(1u, 60, 800u);     /* the next target, about twice as far */
    step();
    assert_int_equal(R.cap, 4u);
    assert_int_equal(R.pickups, 1u);
    assert_int_equal(R.ignore, 0u);
}

/* Gone during the wait: another robot's; still there after it: given up
 * (not counted), and targets ignored for give_up_ms. */
static void test_pickup_not_counted_otherwise(void **state)
{
    uint32_t i;
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    show_red(1u, 0, 1300u);
    steps(100u);
    assert_int_equal(R.state, REPATT_PICK);
    fake_hal_clear_blobs(&H);
    step();
    assert_int_equal(R.cap, 5u);
    assert_int_equal(R.pickups, 0u);

    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    R.params.p_b = 0.0f;
    R.p_b_q32 = 0u;
    show_red(1u, 0, 1300u);
    steps(200u + 8u);
    assert_int_equal(R.state, REPATT_PICK);
    step();
    assert_int_equal(R.state, REPATT_SEARCH);
    assert_int_equal(R.cap, 5u);
    assert_int_equal(R.ignore, 400u);   /* 10 s */
    for (i = 0; i < 399u; i++) {
        step();
        assert_int_equal(R.state, REPATT_SEARCH);
        assert_int_equal(H.left, H.right);
    }
    step();
    assert_int_equal(R.state, REPATT_PICK);   /* seen again */
}

/* The defaults are the e-puck's front camera's: a blob 330 mrad wide near
 * straight ahead starts the blind approach, 46 mm straight on by the step
 * counters (within a period's travel), then the stop; off the axis the
 * robot first steers to it; a stop with nothing in view (the target below
 * the lens's view) waits the whole pick time and counts the target. */
static void test_front_camera_approach(void **state)
{
    repatt_params_t p;
    uint32_t i;
    double x0, y0, ran;
    (void)state;
    repatt_default_params(&p);
    assert_int_equal(p.reach_width_mrad, 330u);
    assert_int_equal(p.approach_mm, 46u);
    p.p_b = 0.0f;
    p.listening = REPATT_DUPLEX;
    start_with(&p, 5u);
    show_red(1u, 400, 330u);             /* wide enough, but 400 mrad off the axis */
    step();
    assert_int_equal(R.state, REPATT_ACQUIRE);
    assert_true(H.right > H.left);       /* steering left to it */
    show_red(1u, 20, 330u);              /* centred */
    x0 = D.x;
    y0 = D.y;
    step();
    assert_int_equal(R.state, REPATT_APPROACH);
    assert_string_equal(repatt_state_name(&R), "approach");
    assert_int_equal(H.left, H.right);
    fake_hal_clear_blobs(&H);            /* below the view from here on */
    for (i = 0; i < 40u && R.state == REPATT_APPROACH; i++) {
        assert_int_equal(H.left, H.right);
        step();
    }
    assert_int_equal(R.state, REPATT_PICK);
    ran = hypot(D.x - x0, D.y - y0);
    assert_true(ran > 46.0 - 2.6 && ran < 46.0 + 2.6);   /* 2.5 mm a period at 0.1 m/s */
    for (i = 0; i < 199u; i++) {         /* blind: the whole wait, though nothing is seen */
        step();
        assert_int_equal(R.state, REPATT_PICK);
        assert_int_equal(H.left, 0);
        assert_int_equal(H.right, 0);
    }
    step();
    assert_int_equal(R.state, REPATT_SEARCH);
    assert_int_equal(R.cap, 4u);
    assert_int_equal(R.pickups, 1u);
}

/* Drive out, take the last target: home by odometry, silent and deaf, to
 * within home_radius of the start point (the true pose says so too),
 * unload, search again. */
static void test_homing_by_odometry(void **state)
{
    repatt_params_t p;
    uint32_t i, readings;
    (void)state;
    repatt_default_params(&p);
    p.capacity = 1u;
    p.p_b = 0.0f;
    p.listening = REPATT_DUPLEX;
    start_with(&p, 7u);
    no_masking = 1;
    set_levels(5000u, 7000u);
    steps(400u);   /* 10 s at 0.1 m/s: about 1 m */
    /* A turn of the true pose to make homing non-trivial: a target on the left. */
    show_red(1u, 1000, 300u);
    for (i = 0; i < 400u && R.state != REPATT_PICK; i++) {
        H.blobs[0].width_mrad = (uint16_t)(H.blobs[0].width_mrad + 3u);
        H.blobs[0].bearing_mrad = (int16_t)(H.blobs[0].bearing_mrad * 9 / 10);
        step();
    }
    assert_int_equal(R.state, REPATT_PICK);
    steps(199u);
    fake_hal_clear_blobs(&H);
    assert_true(sqrt(D.x * D.x + D.y * D.y) > 900.0);
    step();
    assert_int_equal(R.cap, 0u);
    assert_int_equal(R.state, REPATT_HOME);
    assert_int_equal(R.band, 0u);
    readings = R.readings;
    for (i = 0; i < 4000u && R.unloads == 0u; i++) {
        step();
        if (R.unloads == 0u) {
            assert_int_equal(R.state, REPATT_HOME);
            assert_int_equal(H.speaker_band, 0u);
        }
    }
    assert_int_equal(R.unloads, 1u);
    assert_int_equal(R.readings, readings);   /* ignored the signals */
    assert_true(sqrt(D.x * D.x + D.y * D.y) < 110.0);
    assert_int_equal(R.cap, 1u);
    assert_int_equal(R.state, REPATT_SEARCH);
    step();
    assert_int_equal(H.speaker_band, REPATT_BAND_REPULSION);
    assert_int_equal(R.readings, readings + 1u);
}

/* Measures the avoidance turn of an obstacle on sensor `ir`, in rad
 * (true pose), and checks the run after it. */
static double avoidance_turn(uint8_t ir, uint32_t seed)
{
    repatt_params_t p;
    double th0;
    uint32_t i;
    repatt_default_params(&p);
    p.p_b = 0.0f;
    start_with(&p, seed);
    step();
    th0 = D.th;
    H.proximity[ir] = 2000u;
    step();
    assert_int_equal(R.state, REPATT_AVOID);
    assert_int_equal(R.oae_count, 1u);
    H.proximity[ir] = 0u;
    for (i = 0; i < 400u && R.state == REPATT_AVOID; i++) {
        assert_true(H.left == -H.right);
        step();
    }
    assert_true(R.state == REPATT_AVOID_RUN || R.state == REPATT_SEARCH);
    /* The run: straight, at most 165 mm, then the other states. */
    {
        double x0 = D.x, y0 = D.y, th1 = D.th;
        for (i = 0; i < 400u && R.state == REPATT_AVOID_RUN; i++) {
            assert_true(H.left == H.right && H.left > 0);
            step();
        }
        assert_int_equal(R.state, REPATT_SEARCH);
        assert_true(sqrt((D.x - x0) * (D.x - x0) + (D.y - y0) * (D.y - y0)) <= 165.0 + 3.0);
        assert_true(fabs(D.th - th1) < 1e-9);
        return fake_drive_wrap_pi(th1 - th0);
    }
}

static void test_obstacle_avoidance(void **state)
{
    double a;
    uint32_t s;
    (void)state;
    /* Right side (IR1, IR2): 45 deg to the left; left side: to the right. */
    a = avoidance_turn(1u, 1u);
    assert_true(fabs(a - M_PI / 4.0) < 0.02);
    a = avoidance_turn(2u, 2u);
    assert_true(fabs(a - M_PI / 4.0) < 0.02);
    a = avoidance_turn(6u, 3u);
    assert_true(fabs(a + M_PI / 4.0) < 0.02);
    a = avoidance_turn(5u, 4u);
    assert_true(fabs(a + M_PI / 4.0) < 0.02);
    /* Front: more than 90 deg, either way. */
    {
        int left = 0, right = 0;
        for (s = 10u; s < 40u; s++) {
            a = avoidance_turn((s & 1u) ? 0u : 7u, s);
            assert_true(fabs(a) > M_PI / 2.0 - 0.01 && fabs(a) <= M_PI + 0.01);
            if (a > 0) left++; else right++;
        }
        assert_true(left > 3 && right > 3);
    }
}

/* The random-walk policy never moves P_t from P_b whatever it hears; the
 * repatt policy does. */
static void test_random_walk_policy_keeps_pb(void **state)
{
    uint32_t i, x = 99u, moved = 0u, signs = 0u;
    (void)state;
    start(REPATT_POLICY_RANDOM_WALK, REPATT_DUPLEX);
    no_masking = 1;
    for (i = 0; i < 5000u; i++) {
        x = x * 1664525u + 1013904223u;
        set_levels(x >> 8, x >> 12);
        step();
        if (R.state != REPATT_AVOID && R.state != REPATT_AVOID_RUN) {
            assert_int_equal(R.p_t_q32, PB_Q32);
        }
        signs += (R.d_r != 0 || R.d_a != 0);
    }
    assert_true(signs > 4000u);
    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    no_masking = 1;
    for (i = 0; i < 5000u; i++) {
        x = x * 1664525u + 1013904223u;
        set_levels(x >> 8, x >> 12);
        step();
        moved += (R.p_t_q32 != PB_Q32);
    }
    assert_true(moved > 3000u);
}

/* Slotted: a searching robot emits in about half of the periods and takes
 * a reading only after a silent one; duplex without self-masking reads
 * every period; with self-masking a duplex robot that emits reads none. */
static void test_slotted_listening(void **state)
{
    uint32_t i, emitted = 0u, before;
    (void)state;
    start(REPATT_POLICY_REPATT, REPATT_SLOTTED);
    R.params.p_b = 0.0f;
    R.p_b_q32 = 0u;
    set_levels(1000u, 1000u);
    for (i = 0; i < 2000u; i++) {
        uint8_t silent_before = (uint8_t)(H.speaker_played == 0u);
        before = R.readings;
        step();
        assert_int_equal(R.readings - before, silent_before);
        emitted += (H.speaker_band == REPATT_BAND_REPULSION);
        assert_true(H.speaker_band == 0u || H.speaker_band == REPATT_BAND_REPULSION);
    }
    assert_true(emitted > 900u && emitted < 1100u);

    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    no_masking = 1;
    steps(100u);
    assert_int_equal(R.readings, 100u);
    assert_int_equal(R.filter[0].count, 2u * 40u);

    start(REPATT_POLICY_REPATT, REPATT_DUPLEX);
    steps(100u);
    assert_int_equal(R.readings, 1u);   /* the first period only: not yet emitting */
}

/* Only readings fill the queue: a rising repulsion level heard in the
 * slotted silent periods gives dI_r > 0 after 2y readings, not 2y periods,
 * and P_t = P_b x r_m (r_m = 1 here, so try r_m = 3 with policy custom). */
static void test_slotted_queue_counts_readings(void **state)
{
    repatt_params_t p;
    uint32_t i;
    (void)state;
    repatt_default_params(&p);
    repatt_apply_policy(&p, REPATT_POLICY_CUSTOM);
    p.gains.r_m = 3u;
    p.queue_size = 8u;
    start_with(&p, 5u);
    R.p_b_q32 = PB_Q32;
    for (i = 0; i < 400u && R.readings < 16u; i++) {
        set_levels(1000u + 10u * R.readings, 0u);
        assert_int_equal(R.d_r, 0);
        step();
    }
    assert_int_equal(R.readings, 16u);
    assert_true(i > 16u);
    assert_int_equal(R.d_r, 1);
    if (R.state == REPATT_SEARCH || R.state == REPATT_TUMBLE) {
        assert_int_equal(R.p_t_q32, 3u * PB_Q32);
    }
}

/* P_b = 1: a tumble at once, a turn in place; P_b = 0: never. */
static void test_tumble(void **state)
{
    repatt_params_t p;
    uint32_t i, tumbles = 0u;
    (void)state;
    repatt_default_params(&p);
    p.p_b = 0.0f;
    start_with(&p, 1u);
    for (i = 0; i < 2000u; i++) {
        step();
        assert_int_equal(R.state, REPATT_SEARCH);
    }
    p.p_b = 1.0f;
    start_with(&p, 1u);
    step();
    assert_int_equal(R.state, REPATT_TUMBLE);
    assert_true(H.left == -H.right);
    for (i = 0; i < 2000u; i++) {
        step();
        tumbles += (R.state == REPATT_TUMBLE && R.turn.done2 == 0);   /* a turn started */
    }
    assert_true(tumbles > 50u);   /* a turn takes up to 0.8 s */
}

/* Hostile input: levels at UINT32_MAX, no blobs or eight, random IR and
 * counter jumps, both listening modes and policies: no UB (UBSan), sane
 * outputs, and an exact mean of UINT32_MAX readings. */
static void test_hostile_input(void **state)
{
    uint32_t i, x = 4242u, mode;
    (void)state;
    for (mode = 0; mode < 4u; mode++) {
        start((uint8_t)(mode & 1u), (uint8_t)(mode >> 1));
        no_masking = (int)(mode & 1u);
        for (i = 0; i < 20000u; i++) {
            uint8_t k;
            x = x * 1664525u + 1013904223u;
            set_levels((x & 1u) ? UINT32_MAX : x, (x & 2u) ? UINT32_MAX : 0u);
            if (x & 4u) {
                H.n_blobs = (uint8_t)HAL_MAX_BLOBS;
                for (k = 0; k < HAL_MAX_BLOBS; k++) {
                    H.blobs[k].colour = (uint8_t)((x >> k) % 5u);
                    H.blobs[k].bearing_mrad = (int16_t)(x >> 16);
                    H.blobs[k].width_mrad = (uint16_t)(x >> (k + 3));
                }
            } else {
                fake_hal_clear_blobs(&H);
            }
            H.proximity[(x >> 5) % HAL_IR_COUNT] = (uint16_t)((x >> 9) & 0xFFFu);
            if ((x & 0x3F00u) == 0u) {
                D.acc_l += (double)(int16_t)(x >> 16) * 4.0;   /* counter jumps */
            }
            step();
            assert_true(R.state <= REPATT_AVOID_RUN);
            assert_true(H.left >= -1000 && H.left <= 1000 && H.right >= -1000 && H.right <= 1000);
            assert_true(R.found <= HAL_MAX_BLOBS);
            assert_true(R.cap <= R.params.capacity);
            assert_true(H.speaker_band <= 2u);
            assert_true(labs(R.odo.x_um) <= ODO_LIMIT_UM && labs(R.odo.y_um) <= ODO_LIMIT_UM);
        }
    }
    {
        uint32_t ring[2u * 120u];
        chemo_filter_t f;
        chemo_filter_init(&f, 120u);
        for (i = 0; i < 240u; i++) {
            chemo_filter_push(&f, ring, UINT32_MAX);
        }
        assert_int_equal(chemo_filter_level(&f), UINT32_MAX);
        assert_int_equal(chemo_filter_sign(&f), 0);
        chemo_filter_init(&f, 0u);
        assert_int_equal(f.y, 1u);
        chemo_filter_init(&f, 65535u);
        assert_int_equal(f.y, CHEMO_Y_MAX);
    }
}

/* Without queue storage nothing is kept: the robot walks at P_b; a queue
 * size above the storage is cut to it. */
static void test_queue_storage(void **state)
{
    repatt_params_t p;
    uint32_t small[REPATT_QUEUE_WORDS(4u)];
    uint32_t i;
    (void)state;
    repatt_default_params(&p);
    fake_hal_init(&H, 1u);
    H.period_ms = PERIOD_MS;
    memset(&R, 0, sizeof R);
    repatt_init(&R, &p, 1u);
    for (i = 0; i < 300u; i++) {
        set_levels(i * 100u, 0u);
        H.speaker_played = 0u;
        repatt_step(&R, &H);
        fake_hal_end_step(&H);
        assert_int_equal(R.d_r, 0);
    }
    memset(&R, 0, sizeof R);
    repatt_attach_queue(&R, small, 4u);
    repatt_init(&R, &p, 1u);
    assert_int_equal(R.filter[0].y, 4u);
    for (i = 0; i < 20u; i++) {
        set_levels(i * 100u, 0u);
        H.speaker_played = 0u;
        repatt_step(&R, &H);
        fake_hal_end_step(&H);
    }
    assert_int_equal(R.d_r, 1);
}

static void test_defaults_and_names(void **state)
{
    repatt_params_t p;
    (void)state;
    repatt_default_params(&p);
    assert_int_equal(p.gains.a_m, 4u);
    assert_int_equal(p.gains.a_d, 100u);
    assert_int_equal(p.gains.r_m, 1u);
    assert_int_equal(p.gains.r_d, 10u);
    assert_int_equal(p.capacity, 5u);
    assert_int_equal(p.speed_steps_s, units_mm_s_to_steps_s(100));
    assert_int_equal(p.oa_run_max_mm, 165u);
    assert_int_equal(repatt_def.ircom_bits, 0u);
    assert_string_equal(repatt_def.policies[0], "repatt");
    assert_string_equal(repatt_def.policies[1], "random_walk");
    assert_true(repatt_def.state_size >= sizeof(repatt_t) + 4u * REPATT_QUEUE_WORDS(120u));
    R.state = REPATT_HOME;
    assert_string_equal(repatt_state_name(&R), "home");
    R.state = 77u;
    assert_string_equal(repatt_state_name(&R), "?");
    assert_true(observable_count(repatt_observables) >= 8u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_filter_ramp),
        cmocka_unit_test(test_filter_matches_eq5),
        cmocka_unit_test(test_gain_table),
        cmocka_unit_test(test_probability_q32),
        cmocka_unit_test(test_trig_and_odometry),
        cmocka_unit_test(test_search_then_acquire),
        cmocka_unit_test(test_attraction_when_found_exceeds_cap),
        cmocka_unit_test(test_pickup_counts_when_blob_goes_after_wait),
        cmocka_unit_test(test_pickup_counts_with_a_target_behind),
        cmocka_unit_test(test_pickup_not_counted_otherwise),
        cmocka_unit_test(test_front_camera_approach),
        cmocka_unit_test(test_homing_by_odometry),
        cmocka_unit_test(test_obstacle_avoidance),
        cmocka_unit_test(test_random_walk_policy_keeps_pb),
        cmocka_unit_test(test_slotted_listening),
        cmocka_unit_test(test_slotted_queue_counts_readings),
        cmocka_unit_test(test_tumble),
        cmocka_unit_test(test_hostile_input),
        cmocka_unit_test(test_queue_storage),
        cmocka_unit_test(test_defaults_and_names),
    };
    return cmocka_run_group_tests_name("repatt", tests, NULL, NULL);
}
