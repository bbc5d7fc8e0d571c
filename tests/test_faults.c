/*
 * test_faults.c - faults injected into robots (sim_host/models/faults/faults.c):
 * who fails and when (the fraction, the onset, the seed), what each fault
 * does through the HAL, the record of it (events, summary counts), the
 * liar bounded by the beacon, and the scenario keys' errors.
 */
#include <math.h>
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
#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
/* Who was drawn to fail, and faults_stopped: the model's own header. */
#include "models/faults/faults.h"
#include "foraging/nest_beacon.h"

/* Loads YAML text (through a temporary file) with overrides. */
static int load_text(const char *yaml, const char *const *sets, scenario_t *sc, char err[SIM_ERR_MAX])
{
    char path[] = "/tmp/test_faults_XXXXXX";
    scenario_override_t ov[8];
    size_t n = 0;
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
    close(fd);
    while (sets && sets[n]) {
        ov[n].text = sets[n];
        n++;
    }
    int rc = scenario_load(path, ov, n, sc, err);
    unlink(path);
    return rc;
}

static sim_t *make(const char *yaml, const char *const *sets, uint64_t seed, scenario_t **out)
{
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (load_text(yaml, sets, sc, err) != 0) fail_msg("%s", err);
    sim_t *sim = sim_create(sc, seed, err);
    if (!sim) fail_msg("sim_create: %s", err);
    *out = sc;
    return sim;
}

static void drive_all(sim_t *sim, int16_t l, int16_t r)
{
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        hal_set_wheel_speeds(sim_robot_hal(sim, i), l, r);
    }
}

#define IDLE20 "duration: 100\nrobots:\n  - {count: 20, controller: idle, placement: {shape: grid}}\n"

/* round(0.3 x 20) = 6 robots, all at 1 s; the same seed picks the same
 * robots, another seed others; each onset is an event. */
static void test_fraction_onset_and_seed(void **state)
{
    (void)state;
    const char *sets[] = { "robots.0.faults=[{kind: stop, fraction: 0.3, at: 1}]", NULL };
    scenario_t *sc;
    uint32_t picked[3][20] = { { 0 } };
    uint64_t seeds[3] = { 7, 7, 8 };
    for (int run = 0; run < 3; run++) {
        sim_t *sim = make(IDLE20, sets, seeds[run], &sc);
        const sim_event_rec_t *ev;
        for (int s = 0; s < 10; s++) {
            sim_step(sim);
            assert_int_equal(sim_events(sim, &ev), 0);
        }
        sim_step(sim);                       /* step 10: t = 1 s */
        uint32_t n = sim_events(sim, &ev), on = 0;
        assert_int_equal(n, 6);
        for (uint32_t k = 0; k < n; k++) {
            assert_string_equal(ev[k].kind, "fault");
            assert_string_equal(ev[k].detail, "stop");
            assert_int_equal(ev[k].value, 1);
            picked[run][ev[k].robot] = 1;
        }
        for (uint32_t i = 0; i < 20; i++) on += faults_stopped(sim, i);
        assert_int_equal(on, 6);
        metric_list_t m;
        metrics_final(sim, &m);
        int found = 0;
        for (unsigned k = 0; k < m.count; k++) {
            if (!strcmp(m.name[k], "faulty_robots")) {
                assert_int_equal((int)m.value[k], 6);
                found = 1;
            }
        }
        assert_true(found);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_memory_equal(picked[0], picked[1], sizeof picked[0]);
    assert_memory_not_equal(picked[0], picked[2], sizeof picked[0]);
}

/* A stopped robot stays where it is and its controller is not stepped; a
 * fault with a duration ends (and is an event). */
static void test_stop_halts_and_recovers(void **state)
{
    (void)state;
    const char *sets[] = { "robots.0.faults=[{kind: stop, fraction: 1, at: 0, duration: 2}]", NULL };
    scenario_t *sc;
    sim_t *sim = make("duration: 100\nrobots:\n  - {count: 1, controller: idle}\n", sets, 1, &sc);
    double x0, y0, t0, x1, y1, t1;
    sim_robot_pose(sim, 0, &x0, &y0, &t0);
    for (int s = 0; s < 20; s++) {
        drive_all(sim, 500, 500);
        sim_step(sim);
    }
    sim_robot_pose(sim, 0, &x1, &y1, &t1);
    assert_true(hypot(x1 - x0, y1 - y0) < 1e-6);
    const sim_event_rec_t *ev;
    drive_all(sim, 500, 500);
    sim_step(sim);                           /* step 20: t = 2 s, it ends */
    assert_int_equal(sim_events(sim, &ev), 1);
    assert_int_equal(ev[0].value, 0);
    for (int s = 0; s < 10; s++) {
        drive_all(sim, 500, 500);
        sim_step(sim);
    }
    sim_robot_pose(sim, 0, &x1, &y1, &t1);
    assert_true(hypot(x1 - x0, y1 - y0) > 0.05);   /* 64 mm/s for 1 s */
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A stalled left wheel turns a robot driving straight; a drift of 0.5
 * curves it less. */
static void test_wheel_stall_and_drift(void **state)
{
    (void)state;
    const char *kinds[] = { "robots.0.faults=[{kind: wheel_stall, at: 0}]",
                            "robots.0.faults=[{kind: wheel_drift, value: 0.5, at: 0}]" };
    double turned[2];
    for (int k = 0; k < 2; k++) {
        const char *sets[] = { kinds[k], "robots.0.heading=0", NULL };
        scenario_t *sc;
        sim_t *sim = make("duration: 100\narena: {width: 4, height: 4}\nrobots:\n  - {count: 1, controller: idle, "
                          "placement: {shape: circle, radius: 0.01}}\n", sets, 1, &sc);
        double x, y, t0, t1;
        sim_robot_pose(sim, 0, &x, &y, &t0);
        for (int s = 0; s < 10; s++) {
            drive_all(sim, 300, 300);
            sim_step(sim);
        }
        sim_robot_pose(sim, 0, &x, &y, &t1);
        turned[k] = t1 - t0;
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_true(turned[0] > 0.5);                 /* left wheel still: turns left (CCW) */
    assert_true(turned[1] > 0.1 && turned[1] < turned[0]);
}

/* IR fails (reads 0 beside a wall) or gets noisy; the camera goes blind. */
static void test_sensor_faults(void **state)
{
    (void)state;
    const char *yaml = "duration: 100\narena: {width: 0.1, height: 0.1}\n"
                       "robots:\n  - {count: 1, controller: idle, heading: 0, placement: {shape: circle, radius: 0.001}}\n";
    const char *none[] = { NULL };
    const char *fail[] = { "robots.0.faults=[{kind: ir_fail, at: 0}]", NULL };
    const char *noisy[] = { "robots.0.faults=[{kind: ir_noise, value: 500, at: 0}]", NULL };
    const char *const *sets[3] = { none, fail, noisy };
    uint32_t sum[3], spread[3];
    for (int k = 0; k < 3; k++) {
        scenario_t *sc;
        sim_t *sim = make(yaml, sets[k], 1, &sc);
        uint16_t lo = 65535, hi = 0;
        sum[k] = 0;
        for (int s = 0; s < 20; s++) {
            sim_step(sim);
            uint16_t v = hal_ir_proximity(sim_robot_hal(sim, 0), 0);
            sum[k] += v;
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        spread[k] = (uint32_t)(hi - lo);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_true(sum[0] > 20u * 300u);          /* a wall 1.5 cm ahead */
    assert_int_equal(sum[1], 0);
    assert_true(spread[2] > spread[0] + 500u);

    const char *cam = "duration: 100\nrobots:\n  - {count: 1, controller: idle, heading: 0, placement: "
                      "{shape: poses, poses: [{x: 0, y: 0}]}}\nobjects:\n  - {shape: cylinder, x: 0.3, y: 0, "
                      "radius: 0.05, colour: red}\ncamera: {fps: 0}\n";   /* blobs from the first step */
    const char *blind[] = { "robots.0.faults=[{kind: camera_fail, at: 0}]", NULL };
    hal_blob_t b[HAL_MAX_BLOBS];
    for (int k = 0; k < 2; k++) {
        scenario_t *sc;
        sim_t *sim = make(cam, k ? blind : none, 1, &sc);
        sim_step(sim);
        uint8_t n = hal_camera_blobs(sim_robot_hal(sim, 0), b, HAL_MAX_BLOBS);
        assert_int_equal(n, k ? 0 : 1);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* Two robots side by side: robot 0 sends every step.  A dropout on robot 0
 * silences it; a dropout on robot 1 deafens it; babble makes robot 0 send
 * without its controller. */
static void test_radio_faults(void **state)
{
    (void)state;
    const char *yaml = "duration: 100\nrobots:\n  - {count: 1, controller: idle, placement: {shape: poses, "
                       "poses: [{x: 0, y: 0}]}}\n  - {count: 1, controller: idle, placement: {shape: poses, "
                       "poses: [{x: 0.1, y: 0}]}}\nircom: {loss: 0}\n";
    const char *none[] = { NULL };
    const char *mute[] = { "robots.0.faults=[{kind: radio_dropout, at: 0}]", NULL };
    const char *deaf[] = { "robots.1.faults=[{kind: radio_dropout, at: 0}]", NULL };
    const char *const *sets[3] = { none, mute, deaf };
    int heard[3];
    for (int k = 0; k < 3; k++) {
        scenario_t *sc;
        sim_t *sim = make(yaml, sets[k], 1, &sc);
        hal_ircom_msg_t m;
        heard[k] = 0;
        for (int s = 0; s < 10; s++) {
            hal_ircom_send(sim_robot_hal(sim, 0), 0x55);
            sim_step(sim);
            while (hal_ircom_receive(sim_robot_hal(sim, 1), &m) == HAL_OK) heard[k]++;
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_true(heard[0] >= 9);
    assert_int_equal(heard[1], 0);
    assert_int_equal(heard[2], 0);

    const char *babble[] = { "robots.0.faults=[{kind: babble, at: 0}]", NULL };
    scenario_t *sc;
    sim_t *sim = make(yaml, babble, 1, &sc);
    hal_ircom_msg_t m;
    int got = 0, distinct = 0;
    uint16_t last = 0;
    for (int s = 0; s < 20; s++) {
        sim_step(sim);             /* robot 0's controller sends nothing */
        while (hal_ircom_receive(sim_robot_hal(sim, 1), &m) == HAL_OK) {
            distinct += got && m.value != last;
            last = m.value;
            got++;
        }
    }
    assert_true(got >= 18);
    assert_true(distinct >= 15);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A lying forager reports a deposit every step; the beacon credits it no
 * faster than one per 20 steps and its ledger stays bounded. */
static void test_liar_is_bounded_by_the_beacon(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX];
    scenario_override_t ov[] = { { "robots.0.faults=[{kind: liar, fraction: 0.05, at: 0}]" },
                                 { "foraging.desired_food=1" } };   /* S < 0: everyone stays home, in range */
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (scenario_load("../sim_host/scenarios/foraging_base.yaml", ov, 2, sc, err) != 0) fail_msg("%s", err);
    sim_t *sim = sim_create(sc, 3, err);
    if (!sim) fail_msg("%s", err);
    for (int s = 0; s < 3000; s++) sim_step(sim);
    const nest_beacon_t *b = NULL;
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        if (!strcmp(sim_robot_def(sim, i)->name, NEST_BEACON_NAME)) b = sim_robot_controller_const(sim, i);
    }
    assert_non_null(b);
    const fault_run_t *drawn;
    assert_int_equal(faults_drawn(sim, &drawn), 1);
    uint32_t liar = drawn[0].robot;
    /* Its credited total (mod 256): one deposit per 20 steps, not 3000. */
    assert_true(b->last_deposits[liar] >= 148u && b->last_deposits[liar] <= 150u);
    assert_true(b->ledger_units <= NB_LEDGER_LIMIT_TOKENS * 1500);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void expect_error(const char *set, const char *want)
{
    char err[SIM_ERR_MAX];
    const char *sets[] = { set, NULL };
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (load_text("duration: 10\nrobots:\n  - {count: 2, controller: random_walk}\n", sets, sc, err) == 0) {
        fail_msg("loaded: %s", set);
    }
    if (!strstr(err, want)) fail_msg("error '%s' lacks '%s'", err, want);
    scenario_free(sc);
    free(sc);
}

static void test_fault_key_errors(void **state)
{
    (void)state;
    expect_error("robots.0.faults=[{kind: melt}]", "robots[0].faults[0].kind: expected one of stop|wheel_stall");
    expect_error("robots.0.faults=[{kind: wheel_drift, value: 5}]", "wheel_drift needs a speed factor in [0, 2]");
    expect_error("robots.0.faults=[{kind: ir_noise}]", "ir_noise needs a noise sd > 0");
    expect_error("robots.0.faults=[{kind: radio_bursts, value: 3}]", "radio_bursts needs a mean gap");
    expect_error("robots.0.faults=[{kind: stop, at: 3, rate: 0.1}]", "give `at` or `rate`, not both");
    expect_error("robots.0.faults=[{kind: stop, fraction: 1.5}]", "robots[0].faults[0].fraction: 1.5 is out of range");
    expect_error("robots.0.faults=[{kind: liar}]", "has no task that defines what a lying robot sends");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fraction_onset_and_seed),
        cmocka_unit_test(test_stop_halts_and_recovers),
        cmocka_unit_test(test_wheel_stall_and_drift),
        cmocka_unit_test(test_sensor_faults),
        cmocka_unit_test(test_radio_faults),
        cmocka_unit_test(test_liar_is_bounded_by_the_beacon),
        cmocka_unit_test(test_fault_key_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
