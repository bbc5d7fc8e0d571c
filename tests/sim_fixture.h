/*
 * sim_fixture.h - what the simulator's tests share: a run built from a
 * scenario file or an idle one (the test fails with the simulator's message
 * when it cannot be) and a summary metric by name.  Include after <cmocka.h>.
 */
#ifndef TESTS_SIM_FIXTURE_H
#define TESTS_SIM_FIXTURE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "registry.h"

/** A scenario (on the heap: scenario_free, free) of `robots` idle robots
 *  on a grid in a square arena of side `arena` (m), every other key its
 *  default: tests drive the robots through their hal_t. */
static inline scenario_t *fixture_idle_scenario(uint32_t robots, float arena)
{
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    scenario_defaults(sc);
    strcpy(sc->groups[0].controller, "idle");
    strcpy(sc->groups[0].name, "idle");
    sc->groups[0].def = &idle_def;
    sc->groups[0].count = robots;
    sc->groups[0].placement.shape = PLACE_GRID;
    sc->arena.width = sc->arena.height = arena;
    return sc;
}

/** The scenario file at `path` (on the heap: scenario_free, free); fails
 *  the test with the loader's message when it cannot be read. */
static inline scenario_t *fixture_load(const char *path)
{
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    assert_non_null(sc);
    if (scenario_load(path, NULL, 0, sc, err) != 0) fail_msg("%s", err);
    return sc;
}

/** A run of `sc` with `seed`; fails the test when sim_create refuses it. */
static inline sim_t *fixture_sim(const scenario_t *sc, uint64_t seed)
{
    char err[SIM_ERR_MAX] = "";
    sim_t *sim = sim_create(sc, seed, err);
    if (!sim) fail_msg("sim_create: %s", err);
    return sim;
}

/** The summary metric `name` of the run so far; fails the test when the
 *  run has none of that name. */
static inline double fixture_metric(const sim_t *sim, const char *name)
{
    metric_list_t m;
    metrics_final(sim, &m);
    for (unsigned k = 0; k < m.count; k++) {
        if (!strcmp(m.name[k], name)) return m.value[k];
    }
    fail_msg("no metric %s", name);
    return NAN;
}

#endif
