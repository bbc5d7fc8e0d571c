/*
 * test_examples.c - the README's walkthrough example: the phototaxis
 * controller (firmware/examples/) and the gather task
 * (sim_host/tasks/gather/) on their scenario: the robots gather, the run
 * stops on the task's condition, its summary says when; no stop without
 * one; the task's own load error.  The controller alone on a fake HAL is
 * test_phototaxis.c.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "examples/phototaxis.h"
#include "tasks/gather/gather.h"

#define SCENARIO "../sim_host/scenarios/phototaxis_gather.yaml"

static scenario_t *load(const char *const *sets, size_t n)
{
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    scenario_override_t o[8];
    assert_non_null(sc);
    for (size_t k = 0; k < n; k++) o[k].text = sets[k];
    if (scenario_load(SCENARIO, o, n, sc, err) != 0) fail_msg("%s", err);
    return sc;
}

static double metric(const metric_list_t *m, const char *name)
{
    for (unsigned k = 0; k < m->count; k++) {
        if (strcmp(m->name[k], name) == 0) return m->value[k];
    }
    fail_msg("no metric %s", name);
    return NAN;
}

/* The robots reach the lamp; the run ends when three quarters are in the
 * goal, and the summary says when. */
static void test_walkthrough_scenario_gathers(void **state)
{
    (void)state;
    scenario_t *sc = load(NULL, 0);
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 1, err);
    if (!sim) fail_msg("%s", err);
    uint64_t steps = 0;
    while (steps < 3000 && !sim_done(sim)) {
        sim_step(sim);
        steps++;
    }
    assert_true(sim_done(sim));
    assert_true(steps < 3000);
    metric_list_t m, row;
    metrics_final(sim, &m);
    metrics_sample(sim, &row);
    assert_true(metric(&m, "completed") == 1.0);
    assert_true(fabs(metric(&m, "completion_time_s") - steps * 0.1) < 1e-9);
    assert_true(metric(&row, "in_goal") >= 9.0);        /* 0.75 x 12 */
    assert_true(metric(&m, "max_in_goal") >= 9.0);
    uint32_t arrivals = 0, arrived = 0;
    for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
        const phototaxis_t *p = sim_robot_controller(sim, i);
        arrivals += p->arrivals;
        arrived += strcmp(sim_robot_state_name(sim, i), "arrived") == 0;
    }
    assert_true(arrivals >= 1 && arrived >= 1);
    assert_true(metric(&m, "arrivals_total") == (double)arrivals);   /* its counter, totalled */
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Without a stop fraction the run goes on, and reports no completion. */
static void test_no_stop_condition(void **state)
{
    (void)state;
    const char *sets[] = { "gather.stop_fraction=0" };
    scenario_t *sc = load(sets, 1);
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 1, err);
    if (!sim) fail_msg("%s", err);
    for (int k = 0; k < 1000; k++) sim_step(sim);
    assert_false(sim_done(sim));
    metric_list_t m;
    metrics_final(sim, &m);
    assert_true(metric(&m, "completed") == 0.0);
    assert_true(isnan(metric(&m, "completion_time_s")));
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A goal outside the arena is the task's own load error. */
static void test_task_check(void **state)
{
    (void)state;
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    scenario_override_t o[1] = { { "gather.goal.x=9" } };
    assert_int_equal(scenario_load(SCENARIO, o, 1, sc, err), -1);
    assert_non_null(strstr(err, "--set gather.goal.x=9: gather.goal.x: the goal's centre is outside the arena (x in [-1.5, 1.5]"));
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_walkthrough_scenario_gathers),
        cmocka_unit_test(test_no_stop_condition),
        cmocka_unit_test(test_task_check),
    };
    return cmocka_run_group_tests_name("examples", tests, NULL, NULL);
}
