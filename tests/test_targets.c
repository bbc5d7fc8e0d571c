/*
 * test_targets.c - seed 002's world (sim_host/tasks/targets): the five
 * layouts of its Figure 1 (count, inside the square and the walls, outside
 * the nest, no overlaps, cluster spread, the same positions in the 50 m and
 * 100 m worlds and for every run seed), the pick-up rule (pick_time of
 * standing still within reach removes exactly one target, not a step
 * before; moving starts the wait over; of two robots the first to finish
 * takes it), the stop at 90 %, and the all-round camera stand-in (a target
 * behind is seen at bearing ~pi, left and right signs, occlusion across the
 * back, a blind sector for fov < 360, the nearest of a crowd first).
 * Idle robots: the test drives them through their hal_t.  (0.02 s; 0.1 s
 * under ASan/UBSan.)
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

#include "hal.h"
#include "registry.h"
#include "units.h"
#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
/* The wheels' keys, set in code (an internal header). */
#include "models/camera/camera.h"
#include "models/ir/ir.h"
#include "models/wheels/wheels.h"
#include "tasks/targets/targets.h"

#define PI 3.14159265358979
#define SCENARIOS "../sim_host/scenarios/"

/* `robots` idle robots in a square arena of side `arena`, 25 ms steps, the
 * targets task with its defaults (seed 002's One world at e-puck scale),
 * blobs fresh every step as in seed 002's scenarios. */
static scenario_t *world(uint32_t robots, float arena)
{
    scenario_t *sc = fixture_idle_scenario(robots, arena);
    sc->groups[0].placement.width = sc->groups[0].placement.height = 0.3f;
    sc->control_period_ms = 25;
    camera_config_mut(sc)->fps = 0.0f;
    ir_config_mut(sc)->noise_rel = ir_config_mut(sc)->noise_abs = 0.0f;
    wheels_config_mut(sc)->speed_noise_rel = 0.0f;
    sc->task_count = 1;
    sc->tasks[0].def = &targets_task;
    targets_task.default_config(sc->tasks[0].config.bytes);
    return sc;
}

static targets_config_t *config(scenario_t *sc)
{
    return (targets_config_t *)sc->tasks[0].config.bytes;
}

static targets_truth_t truth(const sim_t *sim)
{
    targets_truth_t t;
    assert_int_equal(targets_truth(sim, &t), 1);
    return t;
}

static int picked_up_this_step(const sim_t *sim, uint32_t *robot)
{
    const sim_event_rec_t *ev;
    uint32_t n = sim_events(sim, &ev), found = 0;
    for (uint32_t k = 0; k < n; k++) {
        if (!strcmp(ev[k].kind, "pickup")) {
            *robot = ev[k].robot;
            found++;
        }
    }
    return (int)found;
}

/* --------------------------------------------------------------- layouts */

static void test_layouts(void **state)
{
    (void)state;
    static const int clusters[] = { 1, 2, 4, 0, 0 };
    static const float sx[4] = { 1, -1, -1, 1 }, sy[4] = { 1, -1, 1, -1 };
    scenario_t *sc = world(1, 8.264f);
    targets_config_t *c = config(sc);
    float x[200], y[200];
    char err[SIM_ERR_MAX];
    assert_int_equal(c->count, 200);
    for (int d = TARGETS_ONE; d <= TARGETS_UNIFORM; d++) {
        c->distribution = d;
        if (targets_layout(c, x, y, err) != 0) fail_msg("%s", err);
        float half = c->layout_side / 2, quadrant[4] = { 0 };
        for (uint32_t k = 0; k < c->count; k++) {
            /* In the square (and so the 50 m world's walls), out of the nest. */
            assert_true(fabsf(x[k]) <= half - c->target_radius && fabsf(y[k]) <= half - c->target_radius);
            assert_true(hypotf(x[k], y[k]) > c->nest.radius + c->target_radius);
            for (uint32_t j = 0; j < k; j++) {
                assert_true(hypotf(x[k] - x[j], y[k] - y[j]) >= 2 * c->target_radius);
            }
            if (clusters[d] > 0) {   /* within its cluster's disc */
                int q = (int)(k % (uint32_t)clusters[d]);
                float dx = x[k] - sx[q] * c->cluster_offset, dy = y[k] - sy[q] * c->cluster_offset;
                assert_true(hypotf(dx, dy) <= c->cluster_radius + 1e-5f);
            }
            if (d == TARGETS_HALF && k % 2u == 0u) {   /* half_shape cluster: the evens in One's disc */
                assert_true(hypotf(x[k] - c->cluster_offset, y[k] - c->cluster_offset) <= c->cluster_radius + 1e-5f);
            }
            quadrant[(x[k] >= 0) + 2 * (y[k] >= 0)]++;
        }
        /* Spread: clusters fill their discs (targets beyond half the radius
         * from the centre); half and uniform reach both sides of the square. */
        if (d == TARGETS_ONE) {
            float far = 0;
            for (uint32_t k = 0; k < c->count; k++) {
                far = fmaxf(far, hypotf(x[k] - c->cluster_offset, y[k] - c->cluster_offset));
            }
            assert_true(far > 0.9f * c->cluster_radius);
            assert_int_equal(quadrant[3], 200);
        }
        if (d == TARGETS_FOUR) {
            for (int q = 0; q < 4; q++) assert_int_equal(quadrant[q], 50);
        }
        if (d == TARGETS_UNIFORM) {
            for (int q = 0; q < 4; q++) assert_true(quadrant[q] > 30);
        }
        if (d == TARGETS_HALF) {   /* 100 in the disc (+, +), the other 100 over the square */
            for (int q = 0; q < 3; q++) assert_true(quadrant[q] > 15);
            assert_true(quadrant[3] > 100 + 15);
        }
    }
    /* half_shape strip (the earlier reading): all uniform over x >= 0. */
    c->distribution = TARGETS_HALF;
    c->half_shape = TARGETS_HALF_STRIP;
    assert_int_equal(targets_layout(c, x, y, err), 0);
    float strip_q[4] = { 0 };
    for (uint32_t k = 0; k < c->count; k++) {
        assert_true(x[k] >= 0.0f);
        strip_q[(x[k] >= 0) + 2 * (y[k] >= 0)]++;
    }
    assert_true(strip_q[1] > 60 && strip_q[3] > 60 && strip_q[0] == 0 && strip_q[2] == 0);
    c->half_shape = TARGETS_HALF_CLUSTER;
    /* Another layout seed, another layout. */
    c->distribution = TARGETS_UNIFORM;
    float x2[200], y2[200];
    assert_int_equal(targets_layout(c, x, y, err), 0);
    c->layout_seed = 2;
    assert_int_equal(targets_layout(c, x2, y2, err), 0);
    assert_true(x[0] != x2[0] || y[0] != y2[0]);
    /* Too many for the room: an error, not a hang. */
    c->distribution = TARGETS_ONE;
    c->cluster_radius = 0.05f;
    assert_int_equal(targets_layout(c, x, y, err), -1);
    assert_non_null(strstr(err, "cannot place target"));
    scenario_free(sc);
    free(sc);
}

/* The 100 m world keeps the 50 m world's targets: the items of the two
 * worlds and of any run seed are the same, bit for bit. */
static void test_layout_same_in_both_worlds_and_every_seed(void **state)
{
    (void)state;
    scenario_t *w50 = world(1, 8.264f), *w100 = world(1, 16.529f);
    for (int d = TARGETS_ONE; d <= TARGETS_UNIFORM; d++) {
        config(w50)->distribution = config(w100)->distribution = d;
        sim_t *a = fixture_sim(w50, 1), *b = fixture_sim(w100, 1), *c = fixture_sim(w50, 987654321);
        assert_int_equal(truth(a).count, 200);
        for (uint32_t k = 0; k < 200; k++) {
            const sim_item_t *p = targets_item(a, k), *q = targets_item(b, k), *r = targets_item(c, k);
            assert_memory_equal(p, q, sizeof *p);
            assert_memory_equal(p, r, sizeof *p);
            assert_int_equal(p->colour, HAL_COLOUR_RED);
            assert_true(p->radius == 0.010f);
        }
        assert_null(targets_item(a, 200));
        sim_destroy(a);
        sim_destroy(b);
        sim_destroy(c);
    }
    free(w50);
    free(w100);
}

/* The scenario files of a world at 50 m and 100 m have the same targets:
 * section (so the same layout), and differ in their walls. */
static void read_section(const char *path, const char *section, char *out, size_t size)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int in = 0;
    size_t n = 0;
    if (!f) fail_msg("cannot open %s", path);
    out[0] = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] != ' ' && line[0] != '#' && line[0] != '\n') in = !strncmp(line, section, strlen(section));
        if (in && n + strlen(line) < size) {
            strcpy(out + n, line);
            n += strlen(line);
        }
    }
    fclose(f);
}

static void test_scenario_files_keep_the_layout(void **state)
{
    (void)state;
    static const char *const names[] = { "one", "two", "four", "half", "uniform" };
    char a[4096], b[4096], path[256];
    for (size_t d = 0; d < 5; d++) {
        snprintf(path, sizeof path, SCENARIOS "repatt_%s50.yaml", names[d]);
        read_section(path, "targets:", a, sizeof a);
        snprintf(path, sizeof path, SCENARIOS "repatt_%s100.yaml", names[d]);
        read_section(path, "targets:", b, sizeof b);
        assert_true(strlen(a) > 100);
        assert_string_equal(a, b);
        char want[64];
        snprintf(want, sizeof want, "distribution: %s\n", names[d]);
        assert_non_null(strstr(a, want));
        read_section(path, "arena:", b, sizeof b);
        assert_non_null(strstr(b, "16.529"));
    }
}

/* ------------------------------------------------------------- pick-up */

/* Robot `i` at distance `d` from target k, on its -x side, facing it. */
static void beside(sim_t *sim, uint32_t i, uint32_t k, double d, double side)
{
    const sim_item_t *t = targets_item(sim, k);
    sim_set_robot_pose(sim, i, t->x - side * d, t->y, side > 0 ? 0.0 : PI);
}

/* 20 targets uniform over the 8 m square: one alone within reach. */
static scenario_t *sparse_world(uint32_t robots)
{
    scenario_t *sc = world(robots, 8.264f);
    config(sc)->distribution = TARGETS_UNIFORM;
    config(sc)->count = 20;
    return sc;
}

static void test_pickup_after_pick_time_not_before(void **state)
{
    (void)state;
    scenario_t *sc = sparse_world(2);
    sim_t *sim = fixture_sim(sc, 3);
    const targets_config_t *c = config(sc);
    uint32_t steps = 200, who = 99;   /* 5 s at 25 ms */
    double reach = EPUCK_BODY_RADIUS_M + c->target_radius + c->pick_reach;
    sim_set_robot_pose(sim, 1, -3.5, -3.5, 0.0);   /* out of the way */
    beside(sim, 0, 0, reach - 0.002, 1);
    for (uint32_t s = 1; s < steps; s++) {
        sim_step(sim);
        assert_int_equal(picked_up_this_step(sim, &who), 0);
    }
    assert_true(isfinite(targets_item(sim, 0)->x));
    assert_int_equal(truth(sim).picked, 0);
    sim_step(sim);   /* the 200th still step */
    assert_int_equal(picked_up_this_step(sim, &who), 1);
    assert_int_equal(who, 0);
    assert_true(isnan(targets_item(sim, 0)->x) && isnan(targets_item(sim, 0)->y));
    assert_int_equal(truth(sim).picked, 1);
    /* Standing on: no other target is within reach, nothing more. */
    for (uint32_t s = 0; s < 3 * steps; s++) sim_step(sim);
    assert_int_equal(truth(sim).picked, 1);
    /* The camera no longer sees it: it is out of the world. */
    for (uint32_t k = 1; k < 20; k++) assert_true(isfinite(targets_item(sim, k)->x));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_pickup_needs_reach_and_stillness(void **state)
{
    (void)state;
    scenario_t *sc = sparse_world(2);
    sim_t *sim = fixture_sim(sc, 4);
    const targets_config_t *c = config(sc);
    double reach = EPUCK_BODY_RADIUS_M + c->target_radius + c->pick_reach;
    uint32_t who = 99;
    int events = 0;
    /* Robot 1 just out of reach: never (it stands 351 steps). */
    beside(sim, 1, 0, reach + 0.004, 1);
    /* Robot 0 waits 150 steps, moves for one step, and must wait 200 more. */
    beside(sim, 0, 0, reach - 0.003, -1);
    for (int s = 0; s < 150; s++) {
        sim_step(sim);
        events += picked_up_this_step(sim, &who);
    }
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 1, 1);   /* 0.13 mm/s: still within reach */
    sim_step(sim);
    events += picked_up_this_step(sim, &who);
    hal_set_wheel_speeds(sim_robot_hal(sim, 0), 0, 0);
    for (int s = 1; s < 200; s++) {
        sim_step(sim);
        events += picked_up_this_step(sim, &who);
    }
    assert_int_equal(events, 0);
    sim_step(sim);
    assert_int_equal(picked_up_this_step(sim, &who), 1);
    assert_int_equal(who, 0);
    assert_int_equal(truth(sim).picked, 1);
    assert_true(isnan(targets_item(sim, 0)->x));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Two robots at one target: the one that began its wait first takes it;
 * the other's wait ends without a target.  Begun on the same step: the
 * lower id. */
static void test_two_robots_first_to_finish_wins(void **state)
{
    (void)state;
    scenario_t *sc = world(2, 8.264f);
    targets_config_t *c = config(sc);
    c->count = 1;
    c->cluster_radius = 0.001f;
    double reach = EPUCK_BODY_RADIUS_M + c->target_radius + c->pick_reach;
    uint32_t who = 99;
    for (int late = 0; late < 2; late++) {
        sim_t *sim = fixture_sim(sc, 5);
        beside(sim, 0, 0, reach - 0.003, 1);
        beside(sim, 1, 0, reach - 0.003, -1);
        if (late) {   /* robot 0 starts 10 steps after robot 1 */
            hal_set_wheel_speeds(sim_robot_hal(sim, 0), 1, 1);
            for (int s = 0; s < 10; s++) sim_step(sim);
            hal_set_wheel_speeds(sim_robot_hal(sim, 0), 0, 0);
        }
        int events = 0;
        for (int s = 0; s < 600; s++) {
            sim_step(sim);
            events += picked_up_this_step(sim, &who) ? 1 : 0;
            if (events == 1 && s < 600 && who != (late ? 1u : 0u)) fail_msg("robot %u took it (late %d)", who, late);
        }
        assert_int_equal(events, 1);
        assert_int_equal(truth(sim).picked, 1);
        sim_destroy(sim);
    }
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------------------- the stop */

static void test_stop_count(void **state)
{
    (void)state;
    targets_config_t c;
    targets_task.default_config(&c);
    assert_int_equal(targets_stop_count(&c), 180);   /* 0.9f x 200 is 179.99999 */
    c.count = 12;
    c.stop_fraction = 0.75f;
    assert_int_equal(targets_stop_count(&c), 9);
    c.count = 10;
    c.stop_fraction = 0.9f;
    assert_int_equal(targets_stop_count(&c), 9);
    c.stop_fraction = 0.91f;
    assert_int_equal(targets_stop_count(&c), 10);
    c.stop_fraction = 0.0f;
    assert_int_equal(targets_stop_count(&c), 0);
}

/* One robot visits target after target (pick_time 0.1 s = 4 steps): the
 * run is done at the 9th of 10 (90 %), at that step's time, and the summary
 * says so; before it, it is not. */
static void test_done_at_ninety_percent(void **state)
{
    (void)state;
    scenario_t *sc = world(1, 8.264f);
    targets_config_t *c = config(sc);
    c->count = 10;
    c->distribution = TARGETS_UNIFORM;
    c->pick_time = 0.1f;
    sim_t *sim = fixture_sim(sc, 6);
    assert_int_equal(fixture_metric(sim, "finished"), 0);
    assert_true(isnan(fixture_metric(sim, "time_to_stop_s")));
    for (uint32_t k = 0; k < 9; k++) {
        assert_false(sim_done(sim));
        beside(sim, 0, k, 0.0, 1);
        for (int s = 0; s < 4; s++) sim_step(sim);
        assert_int_equal(truth(sim).picked, k + 1);
    }
    assert_true(sim_done(sim));
    double t = sim_time_s(sim);
    assert_true(fabs(t - 9 * 4 * 0.025) < 1e-9);
    assert_true(fabs(truth(sim).stop_time_s - t) < 1e-9);
    assert_true(fabs(fixture_metric(sim, "time_to_stop_s") - t) < 1e-9);
    assert_true(fabs(fixture_metric(sim, "completion_time_s") - t) < 1e-9);
    assert_int_equal(fixture_metric(sim, "finished"), 1);
    assert_int_equal(fixture_metric(sim, "stop_count"), 9);
    assert_int_equal(fixture_metric(sim, "picked"), 9);
    assert_int_equal(fixture_metric(sim, "robots"), 1);
    assert_true(fabs(fixture_metric(sim, "efficiency") - 9.0 / (1 * t)) < 1e-9);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The e-puck's own front camera (a pinhole 56 deg wide, its lens on the
 * rim, 4.3 frames a second) with the controller's defaults: the robots
 * collect targets.  Before the approach rule they collected none (a target
 * within reach is wider than the view: no blob ever reached the old
 * 1200 mrad); that setting is checked to still pick nothing in 60 s. */
static void test_repatt_front_camera_collects(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (scenario_load(SCENARIOS "repatt_front_camera.yaml", NULL, 0, sc, err) != 0) fail_msg("%s", err);
    const camera_config_t *cam = camera_config(sc);
    assert_true(cam->fov < 60.0f && isnan(cam->fps));   /* the default camera: each robot model's rate, the e-puck1's 4.3 */
    sim_t *sim = fixture_sim(sc, 1);
    uint32_t by[6] = { 0 }, robot = 0;
    while (!sim_done(sim) && sim_time_s(sim) < 300.0) {
        sim_step(sim);
        if (picked_up_this_step(sim, &robot) > 0 && robot < 6) by[robot]++;
    }
    assert_int_equal(truth(sim).picked, 9);
    assert_int_equal(fixture_metric(sim, "finished"), 1);
    uint32_t robots = 0;
    for (int i = 0; i < 6; i++) robots += by[i] > 0;
    assert_true(robots >= 2);   /* not one lucky robot */
    sim_destroy(sim);
    scenario_free(sc);

    scenario_override_t old[] = { { .text = "robots.0.params.reach_width_mrad=1200" },
                                  { .text = "robots.0.params.approach_mm=0" } };
    if (scenario_load(SCENARIOS "repatt_front_camera.yaml", old, 2, sc, err) != 0) fail_msg("%s", err);
    sim = fixture_sim(sc, 1);
    while (sim_time_s(sim) < 60.0) sim_step(sim);
    assert_int_equal(truth(sim).picked, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* ----------------------------------------------------- all-round camera */

static scenario_t *camera_world(float fov)
{
    scenario_t *sc = world(2, 3.0f);
    sc->task_count = 0;   /* obstacles instead of targets */
    camera_config_mut(sc)->fov = fov;
    camera_config_mut(sc)->range = 0.5f;
    camera_config_mut(sc)->width_px = 640;
    camera_config_mut(sc)->height_px = 60;
    const object_def_t obj = { .shape = SHAPE_CYLINDER, .x = 0.0f, .y = 0.0f, .radius = 0.02f, .height = 0.05f,
                               .colour = HAL_COLOUR_RED };
    assert_int_equal(scenario_add_object(sc, &obj), 0);
    return sc;
}

static uint8_t blobs_of(sim_t *sim, uint32_t i, hal_blob_t *b)
{
    sim_step(sim);   /* a fresh step: the camera is sampled once per step */
    return hal_camera_blobs(sim_robot_hal(sim, i), b, HAL_MAX_BLOBS);
}

static void test_all_round_camera_bearings(void **state)
{
    (void)state;
    scenario_t *sc = camera_world(360.0f);
    sim_t *sim = fixture_sim(sc, 7);
    hal_blob_t b[HAL_MAX_BLOBS];
    sim_set_robot_pose(sim, 1, -1.2, -1.2, 0.0);
    /* The object at (0, 0); the robot 0.3 m away, its lens on its axis. */
    static const struct { double x, y, heading, bearing; } cases[] = {
        { -0.3, 0.0, 0.0, 0.0 },            /* ahead */
        { 0.0, -0.3, 0.0, PI / 2 },         /* left: CCW positive */
        { 0.0, 0.3, 0.0, -PI / 2 },         /* right */
        { 0.3, 0.0, 0.0, PI },              /* straight behind: +-pi */
        { 0.3, 0.01, 0.0, -PI + atan2(0.01, 0.3) },   /* behind, a little right */
        { 0.3, -0.01, 0.0, PI - atan2(0.01, 0.3) },   /* behind, a little left */
        { -0.2, -0.2, PI, -3 * PI / 4 },    /* behind on the right */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        sim_set_robot_pose(sim, 0, cases[k].x, cases[k].y, cases[k].heading);
        assert_int_equal(blobs_of(sim, 0, b), 1);
        double err = fabs(remainder(b[0].bearing_mrad / 1000.0 - cases[k].bearing, 2 * PI));
        if (err > 0.003) fail_msg("case %zu: bearing %d mrad, expected %.0f", k, b[0].bearing_mrad, 1000 * cases[k].bearing);
        assert_true(b[0].bearing_mrad > -3142 && b[0].bearing_mrad <= 3142);
        /* The whole disc, from the robot's centre: 2 asin(0.02 / d). */
        double d = hypot(cases[k].x, cases[k].y);
        assert_true(fabs(b[0].width_mrad - 2000 * asin(0.02 / d)) <= 2);
    }
    /* Straight behind the blob is whole, not cut at the back. */
    sim_set_robot_pose(sim, 0, 0.3, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 1);
    assert_true(abs(abs(b[0].bearing_mrad) - 3142) <= 2);
    assert_true(fabs(b[0].width_mrad - 2000 * asin(0.02 / 0.3)) <= 2);
    /* Hidden by a robot behind (the occlusion across +-pi). */
    sim_set_robot_pose(sim, 1, 0.15, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 0);
    /* Beyond the range (0.5 m). */
    sim_set_robot_pose(sim, 1, -1.2, -1.2, 0.0);
    sim_set_robot_pose(sim, 0, 0.0, 0.6, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* fov 270: a blind sector of 90 deg behind the robot. */
static void test_all_round_camera_blind_sector(void **state)
{
    (void)state;
    scenario_t *sc = camera_world(270.0f);
    sim_t *sim = fixture_sim(sc, 8);
    hal_blob_t b[HAL_MAX_BLOBS];
    sim_set_robot_pose(sim, 1, -1.2, -1.2, 0.0);
    sim_set_robot_pose(sim, 0, 0.3, 0.0, 0.0);            /* behind: blind */
    assert_int_equal(blobs_of(sim, 0, b), 0);
    sim_set_robot_pose(sim, 0, 0.15, -0.3 * sin(PI / 3), 0.0);   /* 120 deg left: seen */
    assert_int_equal(blobs_of(sim, 0, b), 1);
    assert_true(abs(b[0].bearing_mrad - 2094) < 5);
    assert_true(fabs(b[0].width_mrad - 2000 * asin(0.02 / 0.3)) <= 2);
    sim_set_robot_pose(sim, 0, 0.3, -0.3 * tan(PI / 6), 0.0);   /* 150 deg: blind */
    assert_int_equal(blobs_of(sim, 0, b), 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Among 150 small targets in a 1 m square: more than 64 blobs in view, and the biggest
 * blob is the nearest target's (beside a target of a high index: not the
 * first 64 in index order), the eight largest in order. */
static void test_all_round_camera_in_a_crowd(void **state)
{
    (void)state;
    scenario_t *sc = world(1, 2.0f);
    targets_config_t *c = config(sc);
    c->distribution = TARGETS_UNIFORM;
    c->count = 150;
    c->layout_side = 1.0f;
    c->nest.radius = 0.05f;
    c->target_radius = 0.004f;   /* small: they hide little of each other */
    camera_config_mut(sc)->fov = 360.0f;
    camera_config_mut(sc)->range = 0.496f;
    camera_config_mut(sc)->width_px = 640;
    camera_config_mut(sc)->height_px = 60;
    sim_t *sim = fixture_sim(sc, 9);
    uint32_t high = 140;
    for (uint32_t k = 140; k < 150; k++) {
        const sim_item_t *t = targets_item(sim, k), *h = targets_item(sim, high);
        if (hypotf(t->x, t->y) < hypotf(h->x, h->y)) high = k;
    }
    double x = targets_item(sim, high)->x + 0.04, y = targets_item(sim, high)->y;
    hal_blob_t b[HAL_MAX_BLOBS];
    sim_set_robot_pose(sim, 0, x, y, 0.3);
    uint32_t in_range = 0, nearest_k = 0;
    double nearest = INFINITY, bearing = 0;
    for (uint32_t k = 0; k < c->count; k++) {
        const sim_item_t *t = targets_item(sim, k);
        double d = hypot(t->x - x, t->y - y);
        in_range += d - t->radius <= 0.496;
        if (d < nearest && d > t->radius) {
            nearest = d;
            nearest_k = k;
            bearing = remainder(atan2(t->y - y, t->x - x) - 0.3, 2 * PI);
        }
    }
    assert_true(in_range > 90);
    assert_true(nearest_k >= 100);
    assert_int_equal(blobs_of(sim, 0, b), HAL_MAX_BLOBS);
    for (unsigned k = 1; k < HAL_MAX_BLOBS; k++) assert_true(b[k - 1].pixels >= b[k].pixels);
    /* The nearest target is among them, whole (nothing is nearer), and no
     * blob is larger than it. */
    int found = -1;
    for (unsigned k = 0; k < HAL_MAX_BLOBS; k++) {
        if (fabs(b[k].bearing_mrad / 1000.0 - bearing) < 0.01
            && fabs(b[k].width_mrad - 2000 * asin(0.004 / nearest)) <= 2) found = (int)k;
    }
    assert_true(found >= 0);
    assert_int_equal(b[found].pixels, b[0].pixels);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The pinhole camera (fov up to 179) is the one it was: it does not see
 * behind, and its lens is at the front of the body (test_sim.c and the
 * golden runs check the rest). */
static void test_pinhole_unchanged(void **state)
{
    (void)state;
    scenario_t *sc = camera_world(56.0f);
    sim_t *sim = fixture_sim(sc, 10);
    hal_blob_t b[HAL_MAX_BLOBS];
    sim_set_robot_pose(sim, 1, -1.2, -1.2, 0.0);
    sim_set_robot_pose(sim, 0, 0.3, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 0);
    sim_set_robot_pose(sim, 0, -0.3, 0.0, 0.0);
    assert_int_equal(blobs_of(sim, 0, b), 1);
    /* From the lens 35 mm ahead of the centre: 2 asin(0.02 / 0.265). */
    assert_true(fabs(b[0].width_mrad - 2000 * asin(0.02 / 0.265)) <= 2);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_layouts),
        cmocka_unit_test(test_layout_same_in_both_worlds_and_every_seed),
        cmocka_unit_test(test_scenario_files_keep_the_layout),
        cmocka_unit_test(test_pickup_after_pick_time_not_before),
        cmocka_unit_test(test_pickup_needs_reach_and_stillness),
        cmocka_unit_test(test_two_robots_first_to_finish_wins),
        cmocka_unit_test(test_stop_count),
        cmocka_unit_test(test_done_at_ninety_percent),
        cmocka_unit_test(test_all_round_camera_bearings),
        cmocka_unit_test(test_all_round_camera_blind_sector),
        cmocka_unit_test(test_all_round_camera_in_a_crowd),
        cmocka_unit_test(test_pinhole_unchanged),
        cmocka_unit_test(test_repatt_front_camera_collects),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
