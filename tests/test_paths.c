/*
 * test_paths.c - seed 003's path-formation task (sim_host/tasks/paths) and
 * the random cylinders of its obstacle tests (placement.c).  Robots are
 * idle e-pucks posed by the test (sim_set_robot_pose) and driven through
 * their hal_t: a robot with wheels (0, 0) is a node, one with any other
 * command is not.  Chain detection (three nodes link nest and food; a gap
 * longer than R, a moving robot, or a cylinder across a link breaks it; the
 * chain's order; with `nodes: any` moving robots link too), the hold (a chain must stand `hold` s; a break starts it
 * over; the merge time is its first step), the food's first perception by a
 * moving robot, failure at the budget recorded at the budget (10,000 steps
 * for seed 003's 1000 s) and a merge after the budget not counted, the
 * section's checks, and the random cylinders (clear of each other, the
 * walls and the fixed robots by their gap; a new layout per run seed, one
 * layout for a layout_seed; random robots placed clear of them).  Also the
 * square arena and the half-scale maze as shipped, with their EAIPP
 * robots.  (0.02 s; 0.2 s under
 * ASan/UBSan.)
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
#include "tasks/paths/paths.h"
/* The IR sensors' keys, set in code (an internal header). */
#include "models/ir/ir.h"

/* Groups: 0 the nest at (-1, 0), 1 the food at (+1, 0), 2 `swarm` idle
 * robots in a row at y = -2 (out of everyone's range until posed). */
static scenario_t *world(uint32_t swarm)
{
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    sc->arena.width = sc->arena.height = 5.0f;
    sc->duration = 1000.0;
    sc->control_period_ms = 100;
    ir_config_mut(sc)->noise_rel = ir_config_mut(sc)->noise_abs = 0.0f;
    sc->group_count = 3;
    const char *names[3] = { "nest", "food", "swarm" };
    for (uint32_t g = 0; g < 3; g++) {
        robot_group_t *grp = &sc->groups[g];
        memset(grp, 0, sizeof *grp);
        strcpy(grp->controller, "idle");
        strcpy(grp->name, names[g]);
        grp->def = &idle_def;
        grp->heading = 0.0f;
        grp->min_spacing = 0.08f;
        grp->moves = g == 2;
        grp->placement.shape = PLACE_POSES;
        grp->count = g == 2 ? swarm : 1;
        grp->placement.pose_count = grp->count;
        for (uint32_t k = 0; k < grp->count; k++) {
            grp->placement.poses[k] = (pose_def_t){ g == 2 ? -2.0f + 0.2f * (float)k : (g == 0 ? -1.0f : 1.0f),
                                                    g == 2 ? -2.0f : 0.0f, NAN };
        }
    }
    sc->task_count = 1;
    sc->tasks[0].def = &paths_task;
    paths_task.default_config(sc->tasks[0].config.bytes);
    return sc;
}

static paths_config_t *config(scenario_t *sc)
{
    return (paths_config_t *)sc->tasks[0].config.bytes;
}

static paths_truth_t truth(const sim_t *sim)
{
    paths_truth_t t;
    assert_int_equal(paths_truth(sim, &t), 1);
    return t;
}

/* Robot 2 + k of the swarm to (x, y). */
static void pose(sim_t *sim, uint32_t k, double x, double y)
{
    sim_set_robot_pose(sim, 2 + k, x, y, 0.0);
}

static void drive(sim_t *sim, uint32_t k, int16_t speed)
{
    hal_set_wheel_speeds(sim_robot_hal(sim, 2 + k), speed, speed);
}

/* ----------------------------------------------------------------- chains */

static void test_chain_detection(void **state)
{
    (void)state;
    scenario_t *sc = world(4);
    config(sc)->hold = 0.0f;
    sim_t *sim = fixture_sim(sc, 1);
    /* Three nodes 0.5 m apart: nest -0.5 0 0.5 food, every link 0.5 m <= 0.6. */
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.5, 0.0);   /* the middle one is missing: a 1 m gap */
    sim_step(sim);
    paths_truth_t t = truth(sim);
    assert_false(t.linked);
    assert_int_equal(t.nodes, 4);
    assert_int_equal(t.nest_side, 1);
    assert_int_equal(t.food_side, 1);
    assert_int_equal(sim_done(sim), 0);
    /* A robot in the gap that is moving is no node. */
    pose(sim, 2, 0.0, 0.0);
    drive(sim, 2, 1);
    sim_step(sim);
    t = truth(sim);
    assert_false(t.linked);
    assert_int_equal(t.nodes, 3);
    assert_true(isnan(t.merge_time_s));
    /* It stops: the chain stands, nest first. */
    drive(sim, 2, 0);
    sim_step(sim);
    t = truth(sim);
    assert_true(t.linked);
    assert_int_equal(t.chain_nodes, 3);
    assert_int_equal(paths_chain_index(sim, 0), 0);   /* the nest */
    assert_int_equal(paths_chain_index(sim, 2), 1);
    assert_int_equal(paths_chain_index(sim, 4), 2);
    assert_int_equal(paths_chain_index(sim, 3), 3);
    assert_int_equal(paths_chain_index(sim, 1), 4);   /* the food */
    assert_int_equal(paths_chain_index(sim, 5), -1);  /* the fourth, at y = -2 */
    /* hold 0: merged at the end of this (the third) step, and the run is done. */
    assert_float_equal(t.merge_time_s, 0.3, 1e-9);
    assert_int_equal(sim_done(sim), 1);
    assert_float_equal(fixture_metric(sim, "success"), 1.0, 0);
    assert_float_equal(fixture_metric(sim, "merge_time_capped_s"), 0.3, 1e-9);
    assert_float_equal(fixture_metric(sim, "merge_steps_capped"), 3.0, 0);
    assert_float_equal(fixture_metric(sim, "chain_nodes"), 3.0, 0);
    assert_float_equal(fixture_metric(sim, "distance_m"), 2.0, 1e-6);
    assert_float_equal(fixture_metric(sim, "completed"), 1.0, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* nodes: any (NNEA's paths, robots travelling in a line): the same chain
 * of moving robots that `still` refuses links nest and food. */
static void test_moving_nodes(void **state)
{
    (void)state;
    scenario_t *sc = world(3);
    config(sc)->hold = 0.0f;
    config(sc)->nodes = PATHS_NODES_ANY;
    sim_t *sim = fixture_sim(sc, 1);
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.5, 0.0);
    pose(sim, 2, 0.0, 0.0);
    for (uint32_t k = 0; k < 3; k++) {
        drive(sim, k, 1);   /* every one moving */
    }
    sim_step(sim);
    paths_truth_t t = truth(sim);
    assert_true(t.linked);
    assert_int_equal(t.nodes, 3);
    assert_int_equal(t.chain_nodes, 3);
    assert_float_equal(t.merge_time_s, 0.1, 1e-9);
    assert_int_equal(sim_done(sim), 1);
    sim_destroy(sim);
    /* The default (still) refuses the same moving chain. */
    config(sc)->nodes = PATHS_NODES_STILL;
    sim = fixture_sim(sc, 1);
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.5, 0.0);
    pose(sim, 2, 0.0, 0.0);
    for (uint32_t k = 0; k < 3; k++) {
        drive(sim, k, 1);
    }
    sim_step(sim);
    t = truth(sim);
    assert_false(t.linked);
    assert_int_equal(t.nodes, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_links_need_range_and_sight(void **state)
{
    (void)state;
    scenario_t *sc = world(3);
    config(sc)->hold = 0.0f;
    /* A cylinder on the line y = 0 between the second and the third node. */
    assert_int_equal(scenario_add_object(sc, &(object_def_t){ .shape = SHAPE_CYLINDER, .x = 0.25f, .y = 0.0f,
                                                             .radius = 0.05f, .height = 0.1f }), 0);
    sim_t *sim = fixture_sim(sc, 1);
    /* Links of 0.61 m: one centimetre too long (above the cylinder). */
    pose(sim, 0, -0.39, 0.2);
    pose(sim, 1, 0.22, 0.2);
    pose(sim, 2, 0.83, 0.2);
    sim_step(sim);
    assert_false(truth(sim).linked);
    /* 0.5 m links, but the cylinder cuts the second one. */
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.0, 0.0);
    pose(sim, 2, 0.5, 0.0);
    sim_step(sim);
    paths_truth_t t = truth(sim);
    assert_false(t.linked);
    assert_int_equal(t.nest_side, 2);
    assert_int_equal(t.food_side, 1);
    /* 0.2 m higher, the links pass 0.2 m from its centre (0.54 m to nest and food). */
    pose(sim, 0, -0.5, 0.2);
    pose(sim, 1, 0.0, 0.2);
    pose(sim, 2, 0.5, 0.2);
    sim_step(sim);
    assert_true(truth(sim).linked);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_hold(void **state)
{
    (void)state;
    scenario_t *sc = world(3);
    config(sc)->hold = 1.0f;   /* 10 steps past the first */
    sim_t *sim = fixture_sim(sc, 1);
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.0, 0.0);
    pose(sim, 2, 0.5, 0.0);
    for (int s = 0; s < 5; s++) sim_step(sim);
    assert_true(truth(sim).linked);
    /* Broken at the sixth step: the hold starts over. */
    drive(sim, 1, 1);
    sim_step(sim);
    assert_false(truth(sim).linked);
    drive(sim, 1, 0);
    pose(sim, 1, 0.0, 0.0);
    for (int s = 0; s < 10; s++) {   /* steps 7 .. 16: not yet 10 steps past step 7 */
        sim_step(sim);
        assert_true(truth(sim).linked);
        assert_true(isnan(truth(sim).merge_time_s));
        assert_int_equal(sim_done(sim), 0);
    }
    sim_step(sim);   /* step 17 */
    assert_float_equal(truth(sim).merge_time_s, 0.7, 1e-9);   /* the end of step 7 */
    assert_int_equal(sim_done(sim), 1);
    assert_float_equal(fixture_metric(sim, "merge_time_s"), 0.7, 1e-9);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_food_perceived(void **state)
{
    (void)state;
    scenario_t *sc = world(1);
    sim_t *sim = fixture_sim(sc, 1);
    pose(sim, 0, 0.35, 0.0);   /* 0.65 m from the food */
    drive(sim, 0, 200);        /* 2.6 cm/s toward it */
    sim_step(sim);
    assert_int_equal(truth(sim).perceivers, 0);
    int steps = 1;
    while (isnan(truth(sim).food_time_s) && steps < 100) {
        sim_step(sim);
        steps++;
    }
    double x, y, th;
    sim_robot_pose(sim, 2, &x, &y, &th);
    assert_true(steps > 1 && steps < 100);
    assert_true(1.0 - x <= 0.6 && 1.0 - x > 0.59);   /* the first step within R */
    assert_float_equal(truth(sim).food_time_s, steps * 0.1, 1e-9);
    assert_int_equal(truth(sim).perceivers, 1);
    assert_false(truth(sim).linked);   /* perceived is not merged */
    assert_float_equal(fixture_metric(sim, "food_perceived"), 1.0, 0);
    assert_float_equal(fixture_metric(sim, "success"), 0.0, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_failure_at_budget(void **state)
{
    (void)state;
    scenario_t *sc = world(3);
    sc->duration = 3.0;
    config(sc)->budget = 2.0f;
    config(sc)->hold = 0.0f;
    sim_t *sim = fixture_sim(sc, 1);
    for (int s = 0; s < 20; s++) sim_step(sim);   /* the budget: nothing linked, nothing seen */
    pose(sim, 0, -0.5, 0.0);
    pose(sim, 1, 0.0, 0.0);
    pose(sim, 2, 0.5, 0.0);
    sim_step(sim);   /* a chain at 2.1 s: after the budget */
    assert_true(truth(sim).linked);
    assert_int_equal(sim_done(sim), 0);
    assert_float_equal(fixture_metric(sim, "success"), 0.0, 0);
    assert_true(isnan(fixture_metric(sim, "merge_time_s")));
    assert_float_equal(fixture_metric(sim, "merge_time_capped_s"), 2.0, 0);
    assert_float_equal(fixture_metric(sim, "merge_steps_capped"), 20.0, 0);
    assert_float_equal(fixture_metric(sim, "food_perceived"), 0.0, 0);   /* robot 4 is 0.5 m from the food, too late */
    assert_float_equal(fixture_metric(sim, "food_time_capped_s"), 2.0, 0);
    assert_true(isnan(fixture_metric(sim, "chain_nodes")));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
    /* Seed 003's budget: a failure is recorded at 10,000 steps. */
    sc = world(0);
    sim = fixture_sim(sc, 1);
    sim_step(sim);
    assert_float_equal(fixture_metric(sim, "merge_steps_capped"), 10000.0, 0);
    assert_float_equal(fixture_metric(sim, "budget_s"), 1000.0, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_checks(void **state)
{
    (void)state;
    scenario_t *sc = world(1);
    char key[64], msg[256];
    assert_int_equal(paths_task.check(config(sc), sc, key, msg), 0);
    strcpy(config(sc)->food_group, "feed");
    assert_int_equal(paths_task.check(config(sc), sc, key, msg), -1);
    assert_string_equal(key, "food_group");
    strcpy(config(sc)->food_group, "swarm");   /* a group that moves */
    assert_int_equal(paths_task.check(config(sc), sc, key, msg), -1);
    assert_non_null(strstr(msg, "moves: false"));
    strcpy(config(sc)->food_group, "nest");
    assert_int_equal(paths_task.check(config(sc), sc, key, msg), -1);
    strcpy(config(sc)->food_group, "food");
    sc->duration = 999.0;
    assert_int_equal(paths_task.check(config(sc), sc, key, msg), -1);
    assert_string_equal(key, "budget");
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------------- random cylinders */

static void cylinders_of(const sim_t *sim, uint32_t first, uint32_t count, float *out)
{
    assert_int_equal(sim_obstacle_count(sim), first + count);
    for (uint32_t k = 0; k < count; k++) {
        const object_def_t *o = sim_object(sim, first + k);
        out[3 * k] = o->x;
        out[3 * k + 1] = o->y;
        out[3 * k + 2] = o->radius;
    }
}

static void test_random_cylinders(void **state)
{
    (void)state;
    enum { COUNT = 30 };
    scenario_t *sc = world(0);
    sc->groups[2].count = 15;   /* 15 robots anywhere, placed after the cylinders */
    sc->groups[2].placement.shape = PLACE_RECTANGLE;
    /* One box of the scenario's own. */
    assert_int_equal(scenario_add_object(sc, &(object_def_t){ .shape = SHAPE_BOX, .x = 0.0f, .y = 1.5f,
                                                             .width = 2.0f, .depth = 0.1f, .height = 0.1f }), 0);
    sc->random_cylinders.count = COUNT;
    sc->random_cylinders.radius_min = 0.05f;
    sc->random_cylinders.radius_max = 0.15f;
    sc->random_cylinders.gap = 0.10f;
    float a[3 * COUNT], b[3 * COUNT], c[3 * COUNT];
    sim_t *sim = fixture_sim(sc, 7);
    cylinders_of(sim, 1, COUNT, a);
    float rmin = 1, rmax = 0;
    for (uint32_t k = 0; k < COUNT; k++) {
        float x = a[3 * k], y = a[3 * k + 1], r = a[3 * k + 2];
        rmin = fminf(rmin, r);
        rmax = fmaxf(rmax, r);
        assert_true(r >= 0.05f && r <= 0.15f);
        assert_true(fabsf(x) + r + 0.1f <= 2.5f + 1e-5f && fabsf(y) + r + 0.1f <= 2.5f + 1e-5f);
        /* Clear of the box (its band y in [1.45, 1.55] for |x| <= 1). */
        if (fabsf(x) <= 1.0f) assert_true(fabsf(y - 1.5f) - 0.05f - r >= 0.1f - 1e-5f);
        for (uint32_t j = 0; j < k; j++) {
            assert_true(hypotf(x - a[3 * j], y - a[3 * j + 1]) - r - a[3 * j + 2] >= 0.1f - 1e-5f);
        }
        for (uint32_t i = 0; i < 2; i++) {   /* the nest and the food */
            double rx, ry, th;
            sim_robot_pose(sim, i, &rx, &ry, &th);
            assert_true(hypot(x - rx, y - ry) - r - EPUCK_BODY_RADIUS_M >= 0.1 - 1e-5);
        }
        for (uint32_t i = 2; i < sim_robot_count(sim); i++) {   /* random robots: not on them */
            double rx, ry, th;
            sim_robot_pose(sim, i, &rx, &ry, &th);
            assert_true(hypot(x - rx, y - ry) - r - EPUCK_BODY_RADIUS_M > 0.0);
        }
    }
    assert_true(rmax - rmin > 0.05f);   /* radii spread over the range */
    sim_destroy(sim);
    /* The same run seed, the same layout; another, another. */
    sim = fixture_sim(sc, 7);
    cylinders_of(sim, 1, COUNT, b);
    assert_memory_equal(a, b, sizeof a);
    sim_destroy(sim);
    sim = fixture_sim(sc, 8);
    cylinders_of(sim, 1, COUNT, b);
    assert_memory_not_equal(a, b, sizeof a);
    sim_destroy(sim);
    /* A layout seed: one layout whatever the run seed. */
    sc->random_cylinders.layout_seed = 5;
    sim = fixture_sim(sc, 7);
    cylinders_of(sim, 1, COUNT, b);
    sim_destroy(sim);
    sim = fixture_sim(sc, 8);
    cylinders_of(sim, 1, COUNT, c);
    assert_memory_equal(b, c, sizeof b);
    sim_destroy(sim);
    /* No room: an error, not a hang. */
    sc->random_cylinders.count = 400;
    sc->random_cylinders.radius_min = sc->random_cylinders.radius_max = 0.3f;
    char err[SIM_ERR_MAX] = "";
    assert_null(sim_create(sc, 1, err));
    assert_non_null(strstr(err, "random_cylinders"));
    scenario_free(sc);
    free(sc);
}

/* ------------------------------------------------------------- scenarios */

/* A shipped scenario as it is (the EAIPP controller and its sources),
 * loaded with `set`. */
static scenario_t *shipped(const char *file, const scenario_override_t *set, size_t n_set)
{
    char path[256];
    snprintf(path, sizeof path, "../sim_host/scenarios/%s", file);
    scenario_t *sc = calloc(1, sizeof *sc);
    char err[SIM_ERR_MAX];
    if (scenario_load(path, set, n_set, sc, err) != 0) fail_msg("%s: %s", file, err);
    return sc;
}

/* The square arena loads, places 30 cylinders, and runs 100 steps. */
static void test_square_scenario(void **state)
{
    (void)state;
    scenario_override_t set[] = { { "random_cylinders.count=30" } };
    scenario_t *sc = shipped("eaipp_square.yaml", set, 1);
    sim_t *sim = fixture_sim(sc, 3);
    assert_int_equal(sim_robot_count(sim), 17);
    assert_int_equal(sim_obstacle_count(sim), 30);
    for (int s = 0; s < 100; s++) sim_step(sim);
    assert_float_equal(fixture_metric(sim, "distance_m"), 3.0, 1e-6);
    assert_float_equal(fixture_metric(sim, "budget_s"), 1000.0, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The half-scale maze: 70 robots fit the waiting area, D = 2.5 sqrt 2 m,
 * and walls hide the food from the nest. */
static void test_maze_scenario(void **state)
{
    (void)state;
    scenario_t *sc = shipped("eaipp_maze.yaml", NULL, 0);
    sim_t *sim = fixture_sim(sc, 1);
    assert_int_equal(sim_robot_count(sim), 72);
    assert_int_equal(sim_obstacle_count(sim), 7);
    for (uint32_t i = 2; i < 72; i++) {
        double x, y, th;
        sim_robot_pose(sim, i, &x, &y, &th);
        assert_true(x < -1.5 && y < -1.5);
    }
    assert_true(sim_segment_blocked(sim, -1.25, -1.75, 1.25, 0.75));
    sim_step(sim);
    assert_float_equal(fixture_metric(sim, "distance_m"), 2.5 * sqrt(2.0), 1e-6);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chain_detection),
        cmocka_unit_test(test_moving_nodes),
        cmocka_unit_test(test_links_need_range_and_sight),
        cmocka_unit_test(test_hold),
        cmocka_unit_test(test_food_perceived),
        cmocka_unit_test(test_failure_at_budget),
        cmocka_unit_test(test_checks),
        cmocka_unit_test(test_random_cylinders),
        cmocka_unit_test(test_square_scenario),
        cmocka_unit_test(test_maze_scenario),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
