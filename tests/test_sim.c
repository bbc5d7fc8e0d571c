/*
 * test_sim.c - the simulator's physics and sensor models against the
 * e-puck facts they are calibrated to (hal/units.h, the calibration
 * tables of sensors.c), and determinism.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "common/random_walk.h"
#include "hal.h"
#include "registry.h"
#include "units.h"
#include "swarmsim/rand.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "models/camera/camera.h"
#include "models/ir/ir.h"
#include "models/host/host.h"
#include "models/ircom/ircom.h"
#include "models/wheels/wheels.h"
#include "models/sound/sound.h"
#include "models/tracker/tracker.h"

#define PI 3.14159265358979


/* Mean of `n` readings of IR sensor `s`, one per control step. */
static double mean_ir(sim_t *sim, uint32_t robot, uint8_t s, int n)
{
    double sum = 0;
    for (int k = 0; k < n; k++) {
        sum += hal_ir_proximity(sim_robot_hal(sim, robot), s);
        sim_step(sim);
    }
    return sum / n;
}

/* ------------------------------------------------------------------ IR */

static void test_ir_follows_calibration_table(void **state)
{
    (void)state;
    static const double d_m[] = { 0.005, 0.010, 0.015, 0.020, 0.030, 0.040, 0.050, 0.060, 0.070 };
    static const double raw[] = { 2133, 1466, 601, 384, 235, 158, 120, 104, 67 };
    scenario_t *sc = fixture_idle_scenario(1, 2.0f);
    sim_t *sim = fixture_sim(sc, 1);
    for (size_t k = 0; k < sizeof d_m / sizeof d_m[0]; k++) {
        /* Heading +17 deg puts IR0's axis (-17 deg) square onto the +x wall. */
        double x = 1.0 - 0.033 - d_m[k];
        sim_set_robot_pose(sim, 0, x, 0.0, 17.0 * PI / 180.0);
        double m = mean_ir(sim, 0, 0, 200);
        /* Noise: 1 % relative + 5 counts absolute per reading; the mean of
         * 200 readings is within 4 standard errors plus rounding. */
        double tol = 4.0 * (0.01 * raw[k] + 5.0) / sqrt(200.0) + 1.0;
        if (fabs(m - raw[k]) > tol) {
            fail_msg("at %.3f m IR0 reads %.1f, calibration %.0f (tolerance %.1f)", d_m[k], m, raw[k], tol);
        }
    }
    /* Far from everything: near zero. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    assert_true(mean_ir(sim, 0, 0, 100) < 10.0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_ir_bearing_left_is_ir5(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 2.0f);
    const object_def_t obj = { .shape = SHAPE_CYLINDER, .x = 0.0f, .y = 0.035f + 0.01f + 0.05f, .radius = 0.05f,
                               .height = 0.05f };
    assert_int_equal(scenario_add_object(sc, &obj), 0);
    sc->groups[0].placement.shape = PLACE_RECTANGLE;
    sim_t *sim = fixture_sim(sc, 2);
    /* Robot at the origin heading +x: the cylinder is at +90 deg (left). */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    uint16_t v[HAL_IR_COUNT];
    for (uint8_t s = 0; s < HAL_IR_COUNT; s++) v[s] = hal_ir_proximity(sim_robot_hal(sim, 0), s);
    assert_true(v[5] > 1000);
    assert_true(v[2] < 50);
    for (uint8_t s = 0; s < HAL_IR_COUNT; s++) {
        if (s != 5) assert_true(v[s] < v[5]);
    }
    /* Turned by 180 deg the same obstacle is on the right: IR2. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, PI);
    assert_true(hal_ir_proximity(sim_robot_hal(sim, 0), 2) > 1000);
    assert_true(hal_ir_proximity(sim_robot_hal(sim, 0), 5) < 50);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_ir_sees_other_robot(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 2.0f);
    sim_t *sim = fixture_sim(sc, 3);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    /* Robot 1 just ahead: body surfaces 15 mm apart. */
    sim_set_robot_pose(sim, 1, 0.085, 0.0, 0.0);
    uint16_t front = hal_ir_proximity(sim_robot_hal(sim, 0), 0);
    uint16_t back = hal_ir_proximity(sim_robot_hal(sim, 0), 3);
    assert_true(front > 300);
    assert_true(back < 50);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* IR0's readings square onto a wall `gap_m` away, n steps, with the noise
 * drawn `draws` (noise_draws_t): their mean and sd, and (summed) the
 * largest distance of a reading from the noise-free curve's value plus its
 * own replayed RAND_SENSORS draw (8 a reading, IR0's first). */
static void ir0_at_wall(int draws, double gap_m, int n, double *mean, double *sd, double *worst)
{
    scenario_t *sc = fixture_idle_scenario(1, 2.0f);
    ir_config_mut(sc)->noise_draws = draws;
    sim_t *sim = fixture_sim(sc, 21);
    sim_set_robot_pose(sim, 0, 1.0 - 0.033 - gap_m, 0.0, 17.0 * PI / 180.0);
    sim_rand_t r;
    sim_rand_seed(&r, 21, 0, RAND_SENSORS);
    double v0 = ir_curve((float)gap_m, 0.1f), sum = 0.0, sq = 0.0;
    *worst = 0.0;
    for (int k = 0; k < n; k++) {
        double v = hal_ir_proximity(sim_robot_hal(sim, 0), 0), z[HAL_IR_COUNT];
        sum += v;
        sq += v * v;
        sim_rand_normals(&r, z, HAL_IR_COUNT);
        double want = floor(v0 + sqrt(pow(0.01 * v0, 2) + 25.0) * z[0] + 0.5);
        *worst = fmax(*worst, fabs(v - want));
        sim_step(sim);
    }
    *mean = sum / n;
    *sd = sqrt(sq / n - *mean * *mean);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* noise_draws: summed draws one normal per sensor for both noise parts:
 * each reading is exactly the curve's value plus sqrt((0.01 v)^2 + 5^2)
 * times its draw (to a count: the distance's float rounding), the same
 * distribution as two draws.  Both ways, the sd within 5 % of that (and
 * 1/12 of the rounding) at a reading where the relative part leads (2133
 * counts: without the additive part the sd would be 2.7 % low, which only
 * the replay resolves) and where the additive one does (235: without the
 * relative part 9 % low). */
static void test_ir_noise_draws_summed(void **state)
{
    (void)state;
    static const double gap[] = { 0.005, 0.030 }, raw[] = { 2133, 235 };
    enum { N = 4000 };
    for (int k = 0; k < 2; k++) {
        double want_sd = sqrt(pow(0.01 * raw[k], 2) + 25.0 + 1.0 / 12.0), mean[2], sd[2], worst[2];
        for (int draws = 0; draws < 2; draws++) {
            ir0_at_wall(draws, gap[k], N, &mean[draws], &sd[draws], &worst[draws]);
            print_message("%s at %.0f counts: mean %.2f, sd %.3f (want %.3f), replay off by %.0f\n",
                          draws ? "summed" : "per_term", raw[k], mean[draws], sd[draws], want_sd, worst[draws]);
            /* 4 standard errors of the mean; the sd's is 1/sqrt(2N) = 1.1 %. */
            assert_true(fabs(mean[draws] - raw[k]) < 4.0 * want_sd / sqrt((double)N) + 0.5);
            assert_true(fabs(sd[draws] / want_sd - 1.0) < 0.05);
        }
        assert_true(worst[1] <= 1.0);
        assert_true(worst[0] > 5.0);   /* per term the first draw alone is not the reading */
    }
}

/* --------------------------------------------------------------- light */

static void test_light_falls_with_distance(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 6.0f);
    sc->light_count = 1;
    sc->lights[0] = (light_def_t){ .x = 0.0f, .y = 0.0f, .height = 0.1f, .intensity = 1.0f };
    ir_config_mut(sc)->ambient.noise_rel = 0.0f;
    sim_t *sim = fixture_sim(sc, 4);
    double prev = 0;
    static const double dist[] = { 0.3, 0.6, 1.2, 2.4 };
    for (size_t k = 0; k < 4; k++) {
        /* Robot on the -x side facing the lamp (+x): IR0/IR7 look at it. */
        sim_set_robot_pose(sim, 0, -dist[k], 0.0, 0.0);
        double front = hal_ir_ambient(sim_robot_hal(sim, 0), 0);
        double back = hal_ir_ambient(sim_robot_hal(sim, 0), 3);
        /* Raw counts rise (less light) as the lamp gets farther. */
        assert_true(front > prev);
        /* A sensor facing away sees less light (higher raw value). */
        assert_true(back > front);
        prev = front;
    }
    assert_true(prev < ir_config_mut(sc)->ambient.dark);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* -------------------------------------------------------------- camera */

static uint8_t blobs_of(sim_t *sim, uint32_t i, hal_blob_t *b)
{
    sim_step(sim);   /* a fresh step: the camera is sampled once per step */
    return hal_camera_blobs(sim_robot_hal(sim, i), b, HAL_MAX_BLOBS);
}

static void test_camera_field_of_view_and_occlusion(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 3.0f);
    camera_config_mut(sc)->fps = 0.0f;   /* blobs of each step's poses: the geometry under test */
    assert_int_equal(scenario_add_object(sc, &(object_def_t){ .shape = SHAPE_CYLINDER, .x = 0.4f, .y = 0.0f,
                                                             .radius = 0.03f, .height = 0.05f,
                                                             .colour = HAL_COLOUR_RED }), 0);
    sim_t *sim = fixture_sim(sc, 5);
    hal_blob_t b[HAL_MAX_BLOBS];
    sim_set_robot_pose(sim, 1, -1.0, -1.0, 0.0);   /* out of the way */

    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);     /* facing it */
    assert_int_equal(blobs_of(sim, 0, b), 1);
    assert_int_equal(b[0].colour, HAL_COLOUR_RED);
    assert_true(abs(b[0].bearing_mrad) < 10);
    assert_true(b[0].width_mrad > 150 && b[0].width_mrad < 180);   /* 2 asin(0.03/0.365) */

    /* Turned 20 deg to the right, the object appears on the left.  The
     * lens sits at the front of the body (35 mm from the centre), so the
     * bearing is 349 mrad plus the parallax atan(12.0 / 367.1) = 382 mrad. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, -20.0 * PI / 180.0);
    assert_int_equal(blobs_of(sim, 0, b), 1);
    assert_true(abs(b[0].bearing_mrad - 382) < 5);

    /* Outside the 56 deg field of view. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, PI / 2);
    assert_int_equal(blobs_of(sim, 0, b), 0);

    /* Hidden behind another robot. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.2, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 0);

    /* Within the camera range (0.9 m to its nearest point: 0.885 m), then
     * beyond it (1.335 m). */
    sim_set_robot_pose(sim, 1, -1.0, -1.0, 0.0);
    sim_set_robot_pose(sim, 0, -0.55, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 1);
    sim_set_robot_pose(sim, 0, -1.0, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* -------------------------------------------------------------- motion */

static void test_motion_straight_500_steps(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 4.0f);
    sim_t *sim = fixture_sim(sc, 6);
    sim_set_robot_pose(sim, 0, -1.0, 0.0, 0.0);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 500, 500);
    for (int k = 0; k < 100; k++) sim_step(sim);     /* 10 s */
    double x, y, t;
    sim_robot_pose(sim, 0, &x, &y, &t);
    double speed = (x + 1.0) / 10.0;
    /* 500 steps/s x 0.12881 mm = 64.4 mm/s, within 2 %. */
    assert_true(fabs(speed - 0.0644) < 0.02 * 0.0644);
    assert_true(fabs(y) < 1e-3);
    int16_t l, r;
    hal_wheel_steps(sim_robot_hal(sim, 0), &l, &r);
    assert_int_equal(l, 5000);
    assert_int_equal(r, 5000);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_motion_rotation_in_place(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 4.0f);
    sim_t *sim = fixture_sim(sc, 7);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), -300, 300);
    double turned = 0, x, y, t, prev = 0;
    for (int k = 0; k < 10; k++) {                   /* 1 s */
        sim_step(sim);
        sim_robot_pose(sim, 0, &x, &y, &t);
        double d = t - prev;
        turned += d > PI ? d - 2 * PI : (d < -PI ? d + 2 * PI : d);
        prev = t;
    }
    /* omega = 2 v / axle = 2 x 300 x 0.12881 mm / 53 mm = 1.458 rad/s. */
    double expect = 2.0 * 300 * EPUCK_STEP_M / EPUCK_AXLE_M;
    assert_true(fabs(turned - expect) < 0.02 * expect);
    assert_true(hypot(x, y) < 1e-3);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_speed_is_clamped_and_counters_wrap(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 20.0f);
    sim_t *sim = fixture_sim(sc, 8);
    sim_set_robot_pose(sim, 0, -9.0, 0.0, 0.0);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 3000, 3000);   /* clamps to 1000 */
    for (int k = 0; k < 400; k++) sim_step(sim);              /* 40 s: 40000 steps */
    int16_t l, r;
    hal_wheel_steps(sim_robot_hal(sim, 0), &l, &r);
    assert_int_equal(l, (int16_t)(uint16_t)40000u);
    double x, y, t;
    sim_robot_pose(sim, 0, &x, &y, &t);
    assert_true(fabs((x + 9.0) - 40 * 1000 * EPUCK_STEP_M) < 0.02 * 40 * 1000 * EPUCK_STEP_M);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_robot_cannot_pass_wall_and_pushes_robot(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 1.0f);
    sim_t *sim = fixture_sim(sc, 9);
    sim_set_robot_pose(sim, 0, 0.3, 0.2, 0.0);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 1000, 1000);
    /* Robot 1 drives into robot 0's path, robot 0 drives into the wall. */
    sim_set_robot_pose(sim, 1, -0.3, -0.2, 0.0);
    sim_set_robot_pose(sim, 0, -0.1, -0.2, 0.0);
    hal_set_wheel_speeds(sim_robot_hal(sim, 1), 1000, 1000);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 200, 200);
    for (int k = 0; k < 300; k++) sim_step(sim);
    double x0, y0, t0, x1, y1, t1;
    sim_robot_pose(sim, 0, &x0, &y0, &t0);
    sim_robot_pose(sim, 1, &x1, &y1, &t1);
    assert_true(x0 <= 0.5 - 0.035 + 0.006);       /* stopped by the wall */
    assert_true(hypot(x1 - x0, y1 - y0) >= 0.07 - 0.006);  /* never overlap */
    assert_true(sim_metrics(sim)->robot_contacts >= 1);
    assert_true(sim_metrics(sim)->static_contacts >= 1);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* ---------------------------------------------------------- robustness */

static void test_twenty_robots_100k_steps_stay_inside(void **state)
{
    (void)state;
    scenario_t *sc = calloc(1, sizeof *sc);
    scenario_defaults(sc);      /* random walk, 20 robots, 4 x 4 m */
    const object_def_t obj = { .shape = SHAPE_BOX, .x = 0.5f, .y = 0.5f, .width = 0.5f, .depth = 0.1f,
                               .angle = 30.0f, .height = 0.05f };
    assert_int_equal(scenario_add_object(sc, &obj), 0);
    sim_t *sim = fixture_sim(sc, 10);
    for (int k = 0; k < 100000; k++) {
        sim_step(sim);
    }
    const sim_metrics_t *m = sim_metrics(sim);
    assert_int_equal(m->escaped, 0);
    /* Box2D resolves contacts to within its linear slop (5 mm): never a
     * deeper overlap with a wall. */
    if (m->min_wall_clearance_m < -0.005) fail_msg("overlap %.4f m", m->min_wall_clearance_m);
    uint64_t oaes = 0;
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        oaes += ((const random_walk_t *)sim_robot_controller(sim, i))->oae_count;
    }
    assert_true(oaes > 0);
    assert_true(m->distance_m > 20 * 100.0);   /* they really moved */
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* --------------------------------------------------------- determinism */

static uint64_t run_hash(uint64_t seed, int steps)
{
    scenario_t *sc = calloc(1, sizeof *sc);
    scenario_defaults(sc);
    wheels_config_mut(sc)->speed_noise_rel = 0.05f;
    sim_t *sim = fixture_sim(sc, seed);
    for (int k = 0; k < steps; k++) sim_step(sim);
    uint64_t h = sim_state_hash(sim);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
    return h;
}

static void test_same_seed_same_state(void **state)
{
    (void)state;
    assert_true(run_hash(42, 600) == run_hash(42, 600));
    assert_true(run_hash(42, 600) != run_hash(43, 600));
}

/* ----------------------------------------------------- wheel bias (eq 3) */

/* Robot i's wheel bias (left or right), steps/s, read through the run's
 * fields (sim_field), as a binding reads robots' arrays.  Writable: the
 * saturation test sets a bias by hand. */
static double *bias_of(const sim_t *sim, uint32_t i, int right)
{
    sim_field_t f;
    assert_int_equal(sim_field(sim, right ? "wheels.bias_right" : "wheels.bias_left", &f), 0);
    assert_int_equal(f.type, SIM_FIELD_F64);
    assert_int_equal(f.count, 1);
    assert_true(i < sim_robot_count(sim));
    return (double *)(uintptr_t)((const char *)f.base + (size_t)i * f.stride);
}

/* wheels.bias_sd: each robot's two biases are drawn once a run, Gaussian with
 * the key's sd (m/s), from their own stream; off by default. */
static void test_wheel_bias_draws(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(400, 20.0f);
    sim_t *sim = fixture_sim(sc, 5);
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        assert_true(*bias_of(sim, i, 0) == 0.0 && *bias_of(sim, i, 1) == 0.0);
    }
    sim_destroy(sim);
    wheels_config_mut(sc)->bias_sd = 0.02f;                       /* 2 cm/s = 155 steps/s */
    sim = fixture_sim(sc, 5);
    sim_t *same = fixture_sim(sc, 5), *other = fixture_sim(sc, 6);
    double sum = 0, sq = 0;
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        const double bl = *bias_of(sim, i, 0), br = *bias_of(sim, i, 1);
        assert_true(bl != br);
        assert_true(bl == *bias_of(same, i, 0));
        assert_true(bl != *bias_of(other, i, 0));
        sum += bl + br;
        sq += bl * bl + br * br;
    }
    const double n = 2.0 * sim_robot_count(sim), sd = sqrt(sq / n), expect = 0.02 / EPUCK_STEP_M;
    /* 800 draws: the sd within 10 % (about 4 standard errors), the mean
     * within 4 standard errors of 0. */
    if (fabs(sd - expect) > 0.10 * expect || fabs(sum / n) > 4.0 * expect / sqrt(n)) {
        fail_msg("bias sd %.1f steps/s (expected %.1f), mean %.1f", sd, expect, sum / n);
    }
    sim_destroy(sim);
    sim_destroy(same);
    sim_destroy(other);
    scenario_free(sc);
    free(sc);
}

/* a = f (w + b): a robot driving drifts by its biases (speed and turn rate);
 * a robot commanded to stand still does not creep (ARGoS adds the noise only
 * while a wheel is commanded); the sum saturates at the e-puck's 1000 steps/s. */
static void test_wheel_bias_moves_and_saturates(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 8.0f);
    wheels_config_mut(sc)->bias_sd = 0.02f;
    sim_t *sim = fixture_sim(sc, 9);
    sim_set_robot_pose(sim, 0, -2.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 2.0, 2.0, 0.0);
    const double bl = *bias_of(sim, 0, 0), br = *bias_of(sim, 0, 1);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 388, 388);
    double turned = 0, prev = 0, x, y, t;
    for (int k = 0; k < 10; k++) {                      /* 1 s */
        sim_step(sim);
        sim_robot_pose(sim, 0, &x, &y, &t);
        double d = t - prev;
        turned += d > PI ? d - 2 * PI : (d < -PI ? d + 2 * PI : d);
        prev = t;
    }
    const double w_expect = (br - bl) * EPUCK_STEP_M / EPUCK_AXLE_M;
    if (fabs(turned - w_expect) > 0.03 * fabs(w_expect) + 1e-3) {
        fail_msg("turned %.4f rad in 1 s, the biases say %.4f", turned, w_expect);
    }
    /* The arc's chord: 1 s at v = (388 + (bl + br) / 2) steps/s. */
    const double v = (388.0 + 0.5 * (bl + br)) * EPUCK_STEP_M;
    const double chord = fabs(turned) > 1e-6 ? 2.0 * v / w_expect * sin(0.5 * w_expect) : v;
    assert_true(fabs(hypot(x + 2.0, y) - fabs(chord)) < 0.03 * fabs(chord));
    sim_robot_pose(sim, 1, &x, &y, &t);                 /* commanded (0, 0) */
    assert_true(x == 2.0f && y == 2.0f);
    /* Saturation: a 0.5 m/s bias on both wheels drives at 1000 steps/s. */
    *bias_of(sim, 1, 0) = *bias_of(sim, 1, 1) = 0.5 / EPUCK_STEP_M;
    hal_set_wheel_speeds(sim_robot_hal(sim, 1), 100, 100);
    for (int k = 0; k < 10; k++) sim_step(sim);
    sim_robot_pose(sim, 1, &x, &y, &t);
    const double top = 1000.0 * EPUCK_STEP_M;           /* 12.9 cm/s */
    if (fabs((x - 2.0) - top) > 0.02 * top || fabs(y - 2.0) > 1e-3) {
        fail_msg("saturated robot moved %.4f m in 1 s, the motors' top speed is %.4f m/s", x - 2.0, top);
    }
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* wheels.bias_per_step: a new bias every step while the robot moves, with
 * the key's sd; deterministic per seed. */
static void test_wheel_bias_per_step(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 8.0f);
    wheels_config_mut(sc)->bias_sd = 0.02f;
    wheels_config_mut(sc)->bias_per_step = 1;
    sim_t *sim = fixture_sim(sc, 9), *same = fixture_sim(sc, 9);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 388, 388);
    hal_set_wheel_speeds(sim_robot_hal(same, 0), 388, 388);
    double sq = 0, prev = *bias_of(sim, 0, 0);
    int changed = 0;
    const int steps = 400;
    for (int k = 0; k < steps; k++) {
        sim_step(sim);
        sim_step(same);
        const double bl = *bias_of(sim, 0, 0), br = *bias_of(sim, 0, 1);
        assert_true(bl == *bias_of(same, 0, 0) && br == *bias_of(same, 0, 1));
        changed += bl != prev;
        prev = bl;
        sq += bl * bl + br * br;
        hal_set_wheel_speeds(sim_robot_hal(sim, 0), 388, 388);
        hal_set_wheel_speeds(sim_robot_hal(same, 0), 388, 388);
    }
    assert_int_equal(changed, steps);
    const double sd = sqrt(sq / (2.0 * steps)), expect = 0.02 / EPUCK_STEP_M;
    if (fabs(sd - expect) > 0.10 * expect) fail_msg("per-step bias sd %.1f steps/s, expected %.1f", sd, expect);
    sim_destroy(sim);
    sim_destroy(same);
    scenario_free(sc);
    free(sc);
}

/* --------------------------------------------------------------- ircom */

static void test_ircom_range_bearing_and_blocking(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 2.0f);
    ircom_config_mut(sc)->loss = 0.0f;
    const object_def_t obj = { .shape = SHAPE_CYLINDER, .x = 0.5f, .y = 0.5f, .radius = 0.03f, .height = 0.05f };
    assert_int_equal(scenario_add_object(sc, &obj), 0);
    sim_t *sim = fixture_sim(sc, 11);
    hal_ircom_msg_t m;
    /* Sender 0.15 m to the left of the receiver (heading +x): IR5. */
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.0, 0.15, 0.0);
    assert_int_equal(hal_ircom_send(sim_robot_hal(sim, 1), 0xA5), HAL_OK);
    assert_int_equal(hal_ircom_send(sim_robot_hal(sim, 1), 0x11), HAL_ERR_BUSY);   /* one per step */
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_ERR_EMPTY);  /* not before the step */
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_OK);
    assert_int_equal(m.value, 0xA5);
    assert_int_equal(m.sensor, 5);
    assert_int_equal(m.bearing_mrad, 1571);
    assert_true(m.range_mm > 75 && m.range_mm < 225);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 1), &m), HAL_ERR_EMPTY);  /* not to itself */

    /* 8-bit payloads (libIrcom) drop the high byte; 16-bit keep it. */
    assert_int_equal(hal_ircom_payload_bits(sim_robot_hal(sim, 1)), 8);
    hal_ircom_send(sim_robot_hal(sim, 1), 0x1234);
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_OK);
    assert_int_equal(m.value, 0x34);

    /* Out of range (0.25 m). */
    sim_set_robot_pose(sim, 1, 0.0, 0.4, 0.0);
    hal_ircom_send(sim_robot_hal(sim, 1), 1);
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_ERR_EMPTY);

    /* Blocked by the cylinder between them. */
    sim_set_robot_pose(sim, 0, 0.5, 0.4, 0.0);
    sim_set_robot_pose(sim, 1, 0.5, 0.6, 0.0);
    hal_ircom_send(sim_robot_hal(sim, 1), 2);
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_ERR_EMPTY);
    sim_destroy(sim);

    /* 16-bit payload (range-and-bearing turret). */
    ircom_config_mut(sc)->payload_bits = 16;
    sim = fixture_sim(sc, 13);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.0, 0.15, 0.0);
    hal_ircom_send(sim_robot_hal(sim, 1), 0xBEEF);
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_OK);
    assert_int_equal(m.value, 0xBEEF);
    sim_destroy(sim);

    /* Loss 1: nothing arrives. */
    ircom_config_mut(sc)->loss = 1.0f;
    sc->object_count = 0;
    sim = fixture_sim(sc, 12);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.0, 0.15, 0.0);
    hal_ircom_send(sim_robot_hal(sim, 1), 3);
    sim_step(sim);
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_ERR_EMPTY);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_placement_failure_is_reported(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(500, 0.5f);
    sc->groups[0].placement.shape = PLACE_RECTANGLE;
    char err[SIM_ERR_MAX] = "";
    sim_t *sim = sim_create(sc, 1, err);
    assert_null(sim);
    assert_non_null(strstr(err, "cannot place robot"));
    scenario_free(sc);
    free(sc);
}


/* ---------------------------------------------------------- groups */

/* Two idle groups: `first` robots then one more, which moves or not. */
static scenario_t *two_groups(uint32_t first, uint8_t second_moves)
{
    scenario_t *sc = fixture_idle_scenario(first, 2.0f);
    sc->group_count = 2;
    sc->groups[1] = sc->groups[0];
    strcpy(sc->groups[1].name, "post");
    sc->groups[1].count = 1;
    sc->groups[1].moves = second_moves;
    sc->groups[1].placement.shape = PLACE_POSES;
    sc->groups[1].placement.pose_count = 1;
    sc->groups[1].placement.poses[0] = (pose_def_t){ 0.5f, 0.5f, 90.0f };
    return sc;
}

/* A group that does not move is a static body: a robot driving into it
 * stops, and it stays where it was; a moving one is pushed away. */
static void test_static_group_is_not_pushed(void **state)
{
    (void)state;
    for (int moves = 0; moves < 2; moves++) {
        scenario_t *sc = two_groups(1, (uint8_t)moves);
        sim_t *sim = fixture_sim(sc, 3);
        double x, y, t;
        sim_robot_pose(sim, 1, &x, &y, &t);
        assert_true(x == 0.5f && y == 0.5f && fabs(t - PI / 2) < 1e-6);   /* its pose */
        assert_int_equal(sim_robot_group(sim, 1), 1);
        sim_set_robot_pose(sim, 0, 0.2, 0.5, 0.0);
        hal_set_wheel_speeds(sim_robot_hal(sim, 0), 800, 800);
        for (int k = 0; k < 200; k++) sim_step(sim);
        sim_robot_pose(sim, 1, &x, &y, &t);
        double moved = hypot(x - 0.5, y - 0.5);
        if (moves) assert_true(moved > 0.05);
        else assert_true(moved == 0.0);
        double x0, y0, t0;
        sim_robot_pose(sim, 0, &x0, &y0, &t0);
        assert_true(hypot(x0 - x, y0 - y) >= 0.07 - 0.006);   /* no overlap either way */
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* Every placement shape puts every body inside its region, at least
 * min_spacing apart, with the group's heading. */
static void test_placement_shapes(void **state)
{
    (void)state;
    for (int shape = PLACE_RECTANGLE; shape <= PLACE_GRID; shape++) {
        scenario_t *sc = fixture_idle_scenario(30, 4.0f);
        robot_group_t *g = &sc->groups[0];
        g->placement = (placement_def_t){ .shape = shape, .x = 0.5f, .y = -0.5f, .width = 1.2f,
                                          .height = 0.8f, .radius = 0.6f, .inner = 0.4f, .outer = 0.9f };
        g->min_spacing = 0.1f;
        g->heading = shape == PLACE_GRID ? NAN : 30.0f;
        sim_t *sim = fixture_sim(sc, 11);
        for (uint32_t i = 0; i < 30; i++) {
            double x, y, t, dx, dy, d;
            sim_robot_pose(sim, i, &x, &y, &t);
            dx = x - 0.5;
            dy = y + 0.5;
            d = hypot(dx, dy);
            switch (shape) {
            case PLACE_CIRCLE: assert_true(d <= 0.6 - 0.035 + 1e-6); break;
            case PLACE_RING: assert_true(d >= 0.4 + 0.035 - 1e-6 && d <= 0.9 - 0.035 + 1e-6); break;
            default: assert_true(fabs(dx) <= 0.6 && fabs(dy) <= 0.4); break;
            }
            if (shape != PLACE_GRID) assert_true(fabs(t - 30.0 * PI / 180.0) < 1e-6);
            for (uint32_t j = 0; j < i; j++) {
                double x2, y2, t2;
                sim_robot_pose(sim, j, &x2, &y2, &t2);
                assert_true(hypot(x - x2, y - y2) >= 0.1 - 1e-6);
            }
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* Two poses, by x, then y, then heading. */
static int pose_order(const void *a, const void *b)
{
    const double *p = a, *q = b;
    for (int k = 0; k < 3; k++) {
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    }
    return 0;
}

/* placement.order: space gives the order drawn's spots and headings to a
 * group's robots along the Morton curve of 0.5 m cells (ids near in
 * space; robots of one cell in the order drawn), once every group is
 * placed: a posed group and a random group placed after it are as in the
 * order drawn (a crowded arena: a renumbering before the later group would
 * move its spacing checks).  The same run for the same seed. */
static void test_placement_order_space(void **state)
{
    (void)state;
    enum { A = 300, B = 200, N = A + 1 + B };
    static double drawn[N][3], space[N][3];
    uint64_t hash[2];
    for (int run = 0; run < 3; run++) {
        scenario_t *sc = two_groups(A, 0);   /* A at random, then one posed */
        sc->arena.width = sc->arena.height = 3.0f;
        sc->groups[0].placement = (placement_def_t){ .shape = PLACE_RECTANGLE,
                                                     .order = run ? PLACE_ORDER_SPACE : PLACE_ORDER_DRAWN };
        sc->group_count = 3;
        sc->groups[2] = sc->groups[0];
        strcpy(sc->groups[2].name, "later");
        sc->groups[2].count = B;
        sc->groups[2].placement.order = PLACE_ORDER_DRAWN;
        sim_t *sim = fixture_sim(sc, 21);
        assert_non_null(sim);
        double (*pose)[3] = run ? space : drawn;
        for (uint32_t i = 0; i < N; i++) sim_robot_pose(sim, i, &pose[i][0], &pose[i][1], &pose[i][2]);
        if (run) hash[run - 1] = sim_state_hash(sim);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_true(hash[0] == hash[1]);
    uint64_t last = 0;
    int moved = 0, ties = 0;
    uint32_t last_drawn = 0;
    for (uint32_t i = 0; i < A; i++) {
        /* The Morton key of robot i's cell, as placement.c takes it (in
         * float, from the arena's corner): x's bits even, y's odd. */
        uint32_t cx = (uint32_t)(((float)space[i][0] + 1.5f) / 0.5f);
        uint32_t cy = (uint32_t)(((float)space[i][1] + 1.5f) / 0.5f);
        uint64_t key = 0;
        for (int b = 0; b < 16; b++) {
            key |= (uint64_t)((cx >> b) & 1u) << (2 * b) | (uint64_t)((cy >> b) & 1u) << (2 * b + 1);
        }
        uint32_t k = 0;   /* which robot drew this spot */
        while (k < A && pose_order(drawn[k], space[i]) != 0) k++;
        assert_true(k < A);
        assert_true(key >= last);
        if (i > 0 && key == last) {
            assert_true(k > last_drawn);   /* one cell's robots in the order drawn */
            ties++;
        }
        last = key;
        last_drawn = k;
        moved += k != i;
    }
    assert_true(moved > A / 2 && ties > A / 2);
    for (uint32_t i = A; i < N; i++) assert_int_equal(pose_order(drawn[i], space[i]), 0);
    qsort(drawn, A, sizeof drawn[0], pose_order);
    qsort(space, A, sizeof space[0], pose_order);
    assert_memory_equal(drawn, space, A * sizeof drawn[0]);
}

/* A pose on an obstacle is an error naming the group and the pose. */
static void test_bad_pose_is_reported(void **state)
{
    (void)state;
    scenario_t *sc = two_groups(2, 0);
    const object_def_t obj = { .shape = SHAPE_CYLINDER, .x = 0.5f, .y = 0.5f, .radius = 0.1f, .height = 0.05f };
    assert_int_equal(scenario_add_object(sc, &obj), 0);
    char err[SIM_ERR_MAX] = "";
    assert_null(sim_create(sc, 1, err));
    assert_non_null(strstr(err, "robots[1] (post): pose 0 at (0.5, 0.5) m is not free"));
    scenario_free(sc);
    free(sc);
}

/* Sensing and stepping read only the start of the step: any order of the
 * robots' steps gives the same run (task.h, phase 2). */
static void test_step_order_does_not_matter(void **state)
{
    (void)state;
    static const char *const files[] = { "../sim_host/scenarios/foraging_base.yaml",
                                         "../sim_host/scenarios/random_walk.yaml" };
    for (size_t f = 0; f < 2; f++) {
        scenario_t *sc = malloc(sizeof *sc);
        char err[SIM_ERR_MAX];
        uint64_t hash[3];
        assert_non_null(sc);
        if (scenario_load(files[f], NULL, 0, sc, err) != 0) fail_msg("%s", err);
        for (int order = 0; order < 3; order++) {
            sim_t *sim = fixture_sim(sc, 5);
            sim_set_step_order(sim, order, 99);
            for (int k = 0; k < 1500; k++) sim_step(sim);
            hash[order] = sim_state_hash(sim);
            sim_destroy(sim);
        }
        assert_true(hash[0] == hash[1] && hash[0] == hash[2]);
        scenario_free(sc);
        free(sc);
    }
}

/* FNV-1a over bytes, continuing from h. */
static uint64_t fnv_more(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t k = 0; k < n; k++) h = (h ^ b[k]) * UINT64_C(0x100000001b3);
    return h;
}

/* A run is the same on 1, 2 or 3 threads (sim_create_threads): 800 robots
 * of the full-sensing benchmark world (every sensor, an IR frame and a tone
 * every step, the sound field with a cutoff, 800 food tokens), so that every
 * parallel phase splits into several chunks.  Compared: the state hash, and
 * what each robot then holds: its IR inbox (value, sensor, bearing, range),
 * its microphones' levels, its blobs and its proximity readings.  Both with
 * the noise drawn per term and summed (noise_draws: summed, IR and sound),
 * whose readings must then be another sample (the state hash need not
 * differ: this world's foragers act on none of them within 40 steps). */
static void test_thread_count_does_not_matter(void **state)
{
    (void)state;
    static const scenario_override_t sets[] = { { "robots.0.count=800" }, { "arena.width=25.3" },
                                                { "arena.height=25.3" }, { "foraging.food_count=800" },
                                                { "ir.noise_draws=summed" }, { "sound.noise_draws=summed" } };
    uint64_t held_of[2];
    for (int draws = 0; draws < 2; draws++) {
        scenario_t *sc = malloc(sizeof *sc);
        char err[SIM_ERR_MAX];
        assert_non_null(sc);
        if (scenario_load("../tools/bench/bench_full_sensing.yaml", sets, draws ? 6 : 4, sc, err) != 0) {
            fail_msg("%s", err);
        }
        uint64_t hash[3], held[3];
        for (uint32_t t = 1; t <= 3; t++) {
            sim_t *sim = sim_create_threads(sc, 7, t, err);
            if (!sim) fail_msg("sim_create_threads: %s", err);
            for (int k = 0; k < 40; k++) sim_step(sim);
            hash[t - 1] = sim_state_hash(sim);
            uint64_t h = UINT64_C(0xcbf29ce484222325);
            uint32_t messages = 0;
            for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
                hal_t *hal = sim_robot_hal(sim, i);
                hal_ircom_msg_t m;
                while (hal_ircom_receive(hal, &m) == HAL_OK) {
                    h = fnv_more(h, &m.value, sizeof m.value);
                    h = fnv_more(h, &m.sensor, sizeof m.sensor);
                    h = fnv_more(h, &m.bearing_mrad, sizeof m.bearing_mrad);
                    h = fnv_more(h, &m.range_mm, sizeof m.range_mm);
                    messages++;
                }
                for (uint8_t band = 1; band < HAL_SOUND_BANDS; band++) {
                    uint32_t level = 0;
                    hal_status_t st = hal_mic_level(hal, 0, band, &level);
                    h = fnv_more(h, &st, sizeof st);
                    h = fnv_more(h, &level, sizeof level);
                }
                hal_blob_t b[HAL_MAX_BLOBS];
                uint8_t nb = hal_camera_blobs(hal, b, HAL_MAX_BLOBS);
                for (uint8_t k = 0; k < nb; k++) {   /* field by field: a struct has padding */
                    h = fnv_more(h, &b[k].colour, sizeof b[k].colour);
                    h = fnv_more(h, &b[k].bearing_mrad, sizeof b[k].bearing_mrad);
                    h = fnv_more(h, &b[k].width_mrad, sizeof b[k].width_mrad);
                    h = fnv_more(h, &b[k].pixels, sizeof b[k].pixels);
                }
                for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
                    uint16_t p = hal_ir_proximity(hal, k);
                    h = fnv_more(h, &p, sizeof p);
                }
            }
            held[t - 1] = h;
            print_message("%u thread(s): state %016llx, held %016llx (%u IR messages)\n", t,
                          (unsigned long long)hash[t - 1], (unsigned long long)h, messages);
            assert_true(messages > 800);   /* delivery did happen */
            sim_destroy(sim);
        }
        assert_true(hash[0] == hash[1] && hash[0] == hash[2]);
        assert_true(held[0] == held[1] && held[0] == held[2]);
        held_of[draws] = held[0];
        scenario_free(sc);
        free(sc);
    }
    assert_true(held_of[0] != held_of[1]);
}

/* ---------------------------------------------------------- HAL channels */

/* The overhead tracker: unavailable unless the scenario has one; ground
 * truth in mm and mrad without noise; noise of the stated sd; dropout. */
static void test_tracker_pose(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 2.0f);
    sim_t *sim = fixture_sim(sc, 4);
    hal_pose_t p;
    assert_int_equal(hal_pose(sim_robot_hal(sim, 0), &p), HAL_ERR_UNAVAILABLE);
    sim_destroy(sim);

    tracker_config_mut(sc)->enabled = 1;
    sim = fixture_sim(sc, 4);
    sim_set_robot_pose(sim, 0, 0.1234, -0.5678, 1.0);
    assert_int_equal(hal_pose(sim_robot_hal(sim, 0), &p), HAL_OK);
    assert_int_equal(p.x_mm, 123);
    assert_int_equal(p.y_mm, -568);
    assert_int_equal(p.heading_mrad, 1000);
    sim_destroy(sim);

    tracker_config_mut(sc)->noise_mm = 10.0f;
    sim = fixture_sim(sc, 4);
    double sum = 0, sq = 0;
    for (int k = 0; k < 400; k++) {
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        assert_int_equal(hal_pose(sim_robot_hal(sim, 0), &p), HAL_OK);
        sum += p.x_mm;
        sq += (double)p.x_mm * p.x_mm;
        sim_step(sim);
    }
    double mean = sum / 400, sd = sqrt(sq / 400 - mean * mean);
    assert_true(fabs(mean) < 2.0 && sd > 8.0 && sd < 12.0);
    sim_destroy(sim);

    tracker_config_mut(sc)->noise_mm = 0.0f;
    tracker_config_mut(sc)->dropout = 1.0f;
    sim = fixture_sim(sc, 4);
    assert_int_equal(hal_pose(sim_robot_hal(sim, 0), &p), HAL_ERR_UNAVAILABLE);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The host's messages: none configured is no link; each robot gets its own,
 * in order, not before their time; a short buffer leaves it waiting. */
static void test_host_messages(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 2.0f);
    sim_t *sim = fixture_sim(sc, 4);
    uint8_t buf[HAL_HOST_MSG_MAX], len = 9;
    assert_int_equal(hal_host_receive(sim_robot_hal(sim, 0), buf, sizeof buf, &len), HAL_ERR_UNAVAILABLE);
    assert_int_equal(len, 0);
    sim_destroy(sim);

    const struct { uint32_t robot; float at; uint8_t len, b0; } m[] = {
        { 1, 0.0f, 3, 0x11 }, { 0, 0.25f, 1, 0x22 }, { 1, 0.0f, 2, 0x33 },
    };
    for (uint32_t k = 0; k < 3; k++) {
        host_message_def_t d;
        memset(&d, 0, sizeof d);
        d.robot = m[k].robot;
        d.at = m[k].at;
        d.len = m[k].len;
        d.bytes[0] = m[k].b0;
        assert_int_equal(host_add_message(sc, &d), 0);
    }
    sim = fixture_sim(sc, 4);   /* 100 ms control period */
    hal_t *h0 = sim_robot_hal(sim, 0), *h1 = sim_robot_hal(sim, 1);
    assert_int_equal(hal_host_receive(h0, buf, sizeof buf, &len), HAL_ERR_EMPTY);   /* not before 0.25 s */
    assert_int_equal(hal_host_receive(h1, buf, 2, &len), HAL_ERR_RANGE);            /* 3 bytes wait */
    assert_int_equal(hal_host_receive(h1, buf, sizeof buf, &len), HAL_OK);
    assert_int_equal(len, 3);
    assert_int_equal(buf[0], 0x11);
    assert_int_equal(hal_host_receive(h1, buf, sizeof buf, &len), HAL_OK);
    assert_int_equal(buf[0], 0x33);
    assert_int_equal(hal_host_receive(h1, buf, sizeof buf, &len), HAL_ERR_EMPTY);
    for (int k = 0; k < 2; k++) sim_step(sim);
    assert_int_equal(hal_host_receive(h0, buf, sizeof buf, &len), HAL_ERR_EMPTY);  /* 0.2 s */
    sim_step(sim);
    assert_int_equal(hal_host_receive(h0, buf, sizeof buf, &len), HAL_OK);         /* 0.3 s */
    assert_int_equal(len, 1);
    assert_int_equal(buf[0], 0x22);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* One status convention: sound is unavailable unless the scenario enables
 * it, then OK, and busy the period after the robot's own tone; a channel
 * out of range says so either way; the camera tells its frame size. */
static void test_hal_status(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(1, 2.0f);
    camera_config_mut(sc)->width_px = 40;
    camera_config_mut(sc)->height_px = 20;
    sim_t *sim = fixture_sim(sc, 4);
    hal_t *hal = sim_robot_hal(sim, 0);
    uint32_t level = 5;
    uint16_t w = 0, h = 0;
    assert_int_equal(hal_mic_level(hal, 0, 1, &level), HAL_ERR_UNAVAILABLE);
    assert_int_equal(level, 0);
    assert_int_equal(hal_mic_level(hal, 3, 1, &level), HAL_ERR_RANGE);
    assert_int_equal(hal_mic_level(hal, 0, 0, &level), HAL_ERR_RANGE);
    assert_int_equal(hal_speaker_set(hal, 1), HAL_ERR_UNAVAILABLE);
    assert_int_equal(hal_speaker_set(hal, HAL_SOUND_BANDS), HAL_ERR_RANGE);
    assert_int_equal(hal_camera_frame_size(hal, &w, &h), HAL_OK);
    assert_true(w == 40 && h == 20);
    assert_int_equal(hal_ir_bearing_mrad(hal, 0), -297);
    assert_int_equal(hal_ir_bearing_mrad(hal, 4), 2618);
    assert_int_equal(hal_ir_bearing_mrad(hal, 8), 0);
    sim_destroy(sim);

    sound_config_mut(sc)->enabled = 1;
    sim = fixture_sim(sc, 4);
    hal = sim_robot_hal(sim, 0);
    assert_int_equal(hal_mic_level(hal, 2, 3, &level), HAL_OK);
    assert_int_equal(level, 0);   /* alone: no other robot to hear */
    assert_int_equal(hal_mic_level(hal, 3, 1, &level), HAL_ERR_RANGE);
    assert_int_equal(hal_mic_level(hal, 0, HAL_SOUND_BANDS, &level), HAL_ERR_RANGE);
    assert_int_equal(hal_speaker_set(hal, HAL_SOUND_BANDS), HAL_ERR_RANGE);
    assert_int_equal(hal_speaker_set(hal, 1), HAL_OK);
    assert_int_equal(hal_mic_level(hal, 0, 1, &level), HAL_OK);   /* plays from the next period */
    sim_step(sim);
    level = 5;
    assert_int_equal(hal_mic_level(hal, 0, 1, &level), HAL_ERR_BUSY);
    assert_int_equal(level, 0);
    assert_int_equal(hal_speaker_set(hal, 0), HAL_OK);
    sim_step(sim);
    assert_int_equal(hal_mic_level(hal, 0, 1, &level), HAL_OK);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A controller's observables by name: the random walkers' "oae" counters
 * sum to the summary's total; an unknown name is refused. */
static void test_observables(void **state)
{
    (void)state;
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    sim_t *sim = fixture_sim(sc, 4);
    for (int k = 0; k < 600; k++) sim_step(sim);
    double sum = 0;
    float v;
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        assert_int_equal(sim_robot_observable(sim, i, "oae", &v), 0);
        sum += v;
    }
    assert_true(sum > 0 && sum == fixture_metric(sim, "oae_total"));
    assert_int_equal(sim_robot_observable(sim, 0, "no_such_thing", &v), -1);
    sim_destroy(sim);
    free(sc);
}

/* ----------------------------------------------------- memory estimate */

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
/* Resident memory of this process, bytes (/proc/self/statm). */
static uint64_t resident_bytes(void)
{
    unsigned long pages = 0, resident = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    assert_non_null(f);
    assert_int_equal(fscanf(f, "%lu %lu", &pages, &resident), 2);
    fclose(f);
    return (uint64_t)resident * 4096u;
}
#endif

/* sim_memory_estimate against what a run's resident memory grows by: the
 * random walk of the benchmark worlds (20 robots/m^2) at 20,000 robots,
 * within 25 %.  Under a sanitizer memory is its own, so only plain builds
 * compare (the estimate must still grow with the robots). */
static void test_memory_estimate(void **state)
{
    (void)state;
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    sc->groups[0].count = 20000;
    sc->arena.width = sc->arena.height = 32.0f;
    sim_memory_t small, big;
    sim_memory_estimate(sc, 1, &big);
    sc->groups[0].count = 200;
    sim_memory_estimate(sc, 1, &small);
    assert_true(big.total > small.total + 19000u * 2000u);
    sc->groups[0].count = 20000;
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
    uint64_t before = resident_bytes();
    sim_t *sim = fixture_sim(sc, 1);
    for (int k = 0; k < 3; k++) sim_step(sim);
    uint64_t grew = resident_bytes() - before;
    print_message("20,000 robots: estimate %llu B, resident memory grew by %llu B (%.2f)\n",
                  (unsigned long long)big.total, (unsigned long long)grew, (double)big.total / (double)grew);
    assert_true((double)big.total > 0.75 * (double)grew && (double)big.total < 1.25 * (double)grew);
    sim_destroy(sim);
#endif
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ir_follows_calibration_table),
        cmocka_unit_test(test_ir_bearing_left_is_ir5),
        cmocka_unit_test(test_ir_sees_other_robot),
        cmocka_unit_test(test_ir_noise_draws_summed),
        cmocka_unit_test(test_light_falls_with_distance),
        cmocka_unit_test(test_camera_field_of_view_and_occlusion),
        cmocka_unit_test(test_motion_straight_500_steps),
        cmocka_unit_test(test_motion_rotation_in_place),
        cmocka_unit_test(test_speed_is_clamped_and_counters_wrap),
        cmocka_unit_test(test_robot_cannot_pass_wall_and_pushes_robot),
        cmocka_unit_test(test_ircom_range_bearing_and_blocking),
        cmocka_unit_test(test_placement_failure_is_reported),
        cmocka_unit_test(test_same_seed_same_state),
        cmocka_unit_test(test_twenty_robots_100k_steps_stay_inside),
        cmocka_unit_test(test_static_group_is_not_pushed),
        cmocka_unit_test(test_placement_shapes),
        cmocka_unit_test(test_placement_order_space),
        cmocka_unit_test(test_bad_pose_is_reported),
        cmocka_unit_test(test_step_order_does_not_matter),
        cmocka_unit_test(test_thread_count_does_not_matter),
        cmocka_unit_test(test_tracker_pose),
        cmocka_unit_test(test_host_messages),
        cmocka_unit_test(test_observables),
        cmocka_unit_test(test_memory_estimate),
        cmocka_unit_test(test_hal_status),
        cmocka_unit_test(test_wheel_bias_draws),
        cmocka_unit_test(test_wheel_bias_per_step),
        cmocka_unit_test(test_wheel_bias_moves_and_saturates),
    };
    return cmocka_run_group_tests_name("sim", tests, NULL, NULL);
}
