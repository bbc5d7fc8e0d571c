/*
 * test_per_robot.c - model parameters per robot id (models/per_robot.h: the
 * calibration kit's fragment): an IR sensor's gain and offset, a robot's
 * own noise, its wheels' gains and its microphones' gain per band apply to
 * the robot whose hal_robot_id has the entry, follow it when its id is set
 * after the run is made, and leave every other robot on the section's keys.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "hal.h"
#include "models/camera/camera.h"
#include "models/ir/ir.h"
#include "sim_fixture.h"

/* Two idle robots facing the +x wall, IR0 square on to it 10 mm away
 * (heading 17 deg: IR0 looks along +x), no noise; robot 1 has an entry. */
static const char *const SCENARIO =
    "arena: {width: 1.0, height: 1.0}\n"
    "robots:\n"
    "  - {count: 2, controller: idle, placement: {shape: poses, poses: [\n"
    "      {x: 0.457, y: 0.2, heading: 17}, {x: 0.457, y: -0.2, heading: 17}]}}\n"
    "ir:\n"
    "  noise_rel: 0\n"
    "  noise_abs: 0\n"
    "  robots:\n"
    "    - id: 1\n"
    "      sensors: [{gain: 2.0, offset: 30}, {}, {}, {}, {}, {}, {}, {gain: 0.5}]\n"
    "wheels:\n"
    "  gain_right: 1.0\n"
    "  robots: [{id: 1, gain_left: 0.5, gain_right: 0.5}]\n"
    "sound:\n"
    "  enabled: true\n"
    "  noise: 0\n"
    "  robots: [{id: 0, gain2: 3.0}]\n"
    "camera:\n"
    "  range: 0.8\n"
    "  robots: [{id: 1, range: 0.3}, {id: 0, fov: 40}]\n";

static scenario_t *load(const char *yaml)
{
    char path[] = "/tmp/test_per_robot.XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
    close(fd);
    char err[SIM_ERR_MAX];
    scenario_t *sc = scenario_create(path, NULL, 0, err);
    unlink(path);
    if (sc == NULL) fail_msg("%s", err);
    return sc;
}

static void test_ir_gain_and_offset_follow_the_id(void **state)
{
    (void)state;
    scenario_t *sc = load(SCENARIO);
    sim_t *sim = fixture_sim(sc, 1);
    float base = ir_curve(0.010f, ir_config(sc)->range);
    uint16_t r0 = hal_ir_proximity(sim_robot_hal(sim, 0), 0);
    uint16_t r1 = hal_ir_proximity(sim_robot_hal(sim, 1), 0);
    assert_int_equal(r0, (uint16_t)lroundf(base));
    assert_int_equal(r1, (uint16_t)lroundf(2.0f * base + 30.0f));
    /* The ids swap after the run is made: so do the parameters. */
    sim_set_robot_id(sim, 0, 1);
    sim_set_robot_id(sim, 1, 0);
    sim_step(sim);
    assert_int_equal(hal_ir_proximity(sim_robot_hal(sim, 0), 0), (uint16_t)lroundf(2.0f * base + 30.0f));
    assert_int_equal(hal_ir_proximity(sim_robot_hal(sim, 1), 0), (uint16_t)lroundf(base));
    sim_destroy(sim);
    scenario_destroy(sc);
}

static void test_wheel_gains(void **state)
{
    (void)state;
    scenario_t *sc = load(SCENARIO);
    sim_t *sim = fixture_sim(sc, 1);
    double x0[2], y0[2], t0[2];
    for (uint32_t i = 0; i < 2; i++) {
        sim_robot_pose(sim, i, &x0[i], &y0[i], &t0[i]);
        sim_set_robot_pose(sim, i, -0.3, i ? -0.2 : 0.2, 0.0);
        sim_robot_pose(sim, i, &x0[i], &y0[i], &t0[i]);
        hal_set_wheel_speeds(sim_robot_hal(sim, i), 500, 500);
    }
    sim_step_n(sim, 10);
    double x[2], y[2], t[2];
    for (uint32_t i = 0; i < 2; i++) sim_robot_pose(sim, i, &x[i], &y[i], &t[i]);
    double d0 = x[0] - x0[0], d1 = x[1] - x0[1];
    assert_true(d0 > 0.05);
    assert_float_equal(d1 / d0, 0.5, 1e-3);       /* both wheels at half speed */
    int16_t l, r;
    hal_wheel_steps(sim_robot_hal(sim, 1), &l, &r);
    assert_int_equal(l, 500);                       /* steps counted as commanded */
    sim_destroy(sim);
    scenario_destroy(sc);
}

static void test_mic_gain_per_band(void **state)
{
    (void)state;
    scenario_t *sc = load(SCENARIO);
    sim_t *sim = fixture_sim(sc, 1);
    hal_speaker_set(sim_robot_hal(sim, 1), 2);
    sim_step_n(sim, 2);
    uint32_t l0 = 0, l1 = 0;
    assert_int_equal(hal_mic_level(sim_robot_hal(sim, 0), 0, 2, &l0), HAL_OK);
    hal_speaker_set(sim_robot_hal(sim, 1), 0);
    hal_speaker_set(sim_robot_hal(sim, 0), 2);
    sim_step_n(sim, 2);
    assert_int_equal(hal_mic_level(sim_robot_hal(sim, 1), 0, 2, &l1), HAL_OK);
    assert_true(l1 > 0);
    assert_float_equal((double)l0 / l1, 3.0, 1e-3);   /* robot 0 hears band 2 three times as loud */
    sim_destroy(sim);
    scenario_destroy(sc);
}

/* camera.robots: an entry's keys for its id, the section's for the keys it
 * leaves out and for every other id. */
static void test_camera_lens(void **state)
{
    (void)state;
    scenario_t *sc = load(SCENARIO);
    const camera_config_t *c = camera_config(sc);
    float fov, range;
    camera_lens(c, 1, &fov, &range);
    assert_float_equal(fov, 56.0, 1e-6);
    assert_float_equal(range, 0.3, 1e-6);
    camera_lens(c, 0, &fov, &range);
    assert_float_equal(fov, 40.0, 1e-6);
    assert_float_equal(range, 0.8, 1e-6);
    camera_lens(c, 5, &fov, &range);
    assert_float_equal(fov, 56.0, 1e-6);
    assert_float_equal(range, 0.8, 1e-6);
    scenario_destroy(sc);
}

/* A group's first_id: its robots' ids from there; another group's stay its indices. */
static void test_first_id(void **state)
{
    (void)state;
    scenario_t *sc = load("arena: {width: 1.0, height: 1.0}\n"
                          "robots:\n"
                          "  - {count: 2, controller: idle, first_id: 7}\n"
                          "  - {count: 1, controller: idle}\n");
    sim_t *sim = fixture_sim(sc, 1);
    assert_int_equal(sim_robot_id(sim, 0), 7);
    assert_int_equal(sim_robot_id(sim, 1), 8);
    assert_int_equal(sim_robot_id(sim, 2), 2);
    sim_destroy(sim);
    scenario_destroy(sc);
}

static void test_refused(void **state)
{
    (void)state;
    char path[] = "/tmp/test_per_robot.XXXXXX";
    const char *yaml = "robots: [{count: 1, controller: idle}]\n"
                       "ambient:\n  robots: [{id: 3, dark: 3000}, {id: 3, half: 2}]\n";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
    close(fd);
    char err[SIM_ERR_MAX];
    scenario_t *sc = scenario_create(path, NULL, 0, err);
    unlink(path);
    assert_null(sc);
    assert_non_null(strstr(err, "ambient.robots[1].id"));
    assert_non_null(strstr(err, "robot id listed twice"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ir_gain_and_offset_follow_the_id),
        cmocka_unit_test(test_wheel_gains),
        cmocka_unit_test(test_mic_gain_per_band),
        cmocka_unit_test(test_camera_lens),
        cmocka_unit_test(test_first_id),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
