/*
 * test_areas.c - the areas task (sim_host/tasks/areas/, seed 003's NNEA):
 * the nest's and the food's discs are laid on the floor where their robots
 * stand (the ground model reads them), trips are counted from poses when a
 * robot enters the area other than the one it was last in, and the
 * section's checks.  Idle robots posed by the test.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "models/ground/ground.h"
#include "registry.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "tasks/areas/areas.h"

/* Groups: 0 the nest at (-0.8, 0.3), 1 the food at (0.9, -0.2), 2 `swarm`
 * idle robots in a row at y = -2. */
static scenario_t *world(uint32_t swarm)
{
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    sc->arena.width = sc->arena.height = 5.0f;
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
            grp->placement.poses[k] = (pose_def_t){ g == 2 ? -2.0f + 0.2f * (float)k : (g == 0 ? -0.8f : 0.9f),
                                                    g == 2 ? -2.0f : (g == 0 ? 0.3f : -0.2f), NAN };
        }
    }
    sc->task_count = 1;
    sc->tasks[0].def = &areas_task;
    areas_task.default_config(sc->tasks[0].config.bytes);
    return sc;
}

static void free_world(scenario_t *sc)
{
    scenario_free(sc);
    free(sc);
}

static void test_discs_follow_the_sources(void **state)
{
    scenario_t *sc = world(1);
    sim_t *sim;
    (void)state;
    sc->groups[1].placement.poses[0].x = 1.3f;   /* a sweep moved the food */
    sim = fixture_sim(sc, 1);
    assert_float_equal(ground_reflectance(sim, -0.8f, 0.3f), 0.0f, 1e-6);     /* the nest: black */
    assert_float_equal(ground_reflectance(sim, -0.8f + 0.19f, 0.3f), 0.0f, 1e-6);
    assert_float_equal(ground_reflectance(sim, -0.8f + 0.21f, 0.3f), 1.0f, 1e-6);  /* radius 0.2 m */
    assert_float_equal(ground_reflectance(sim, 1.3f, -0.2f), 0.5f, 1e-6);      /* the food: grey, moved */
    assert_float_equal(ground_reflectance(sim, 0.9f, -0.2f), 1.0f, 1e-6);      /* not where it was */
    sim_destroy(sim);
    free_world(sc);
}

static void test_trips_from_poses(void **state)
{
    /* Robot 0 of the swarm: bare, nest, bare, nest, food, food, bare, nest. */
    static const double path[][2] = { { 0, 1 }, { -0.8, 0.3 }, { 0, 1 }, { -0.7, 0.3 }, { 0.9, -0.1 },
                                      { 0.95, -0.2 }, { 0, 1 }, { -0.8, 0.35 } };
    static const double trips[] = { 0, 0, 0, 0, 1, 1, 1, 2 };
    scenario_t *sc = world(2);
    sim_t *sim = fixture_sim(sc, 1);
    (void)state;
    for (size_t i = 0; i < sizeof path / sizeof path[0]; i++) {
        sim_set_robot_pose(sim, 2, path[i][0], path[i][1], 0.0);
        sim_step(sim);
        assert_float_equal(fixture_metric(sim, "trips_total"), trips[i], 0.0);
    }
    assert_float_equal(fixture_metric(sim, "trips_per_robot"), 1.0, 1e-12);   /* 2 trips, 2 robots */
    assert_float_equal(fixture_metric(sim, "visited_both"), 1.0, 0.0);
    sim_destroy(sim);
    free_world(sc);
}

static void test_checks(void **state)
{
    scenario_t *sc = world(1);
    areas_config_t *c = (areas_config_t *)sc->tasks[0].config.bytes;
    char key[64], msg[SIM_ERR_MAX];
    (void)state;
    assert_int_equal(areas_task.check(c, sc, key, msg), 0);
    strcpy(c->food_group, "fod");
    assert_int_equal(areas_task.check(c, sc, key, msg), -1);
    assert_string_equal(key, "food_group");
    assert_non_null(strstr(msg, "no robot group is named 'fod'"));
    strcpy(c->food_group, "swarm");
    assert_int_equal(areas_task.check(c, sc, key, msg), -1);
    assert_non_null(strstr(msg, "must not move"));
    strcpy(c->food_group, "nest");
    sc->groups[0].moves = 0;
    assert_int_equal(areas_task.check(c, sc, key, msg), -1);
    assert_non_null(strstr(msg, "one group"));
    free_world(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_discs_follow_the_sources),
        cmocka_unit_test(test_trips_from_poses),
        cmocka_unit_test(test_checks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
