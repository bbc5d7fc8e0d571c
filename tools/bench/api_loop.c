/*
 * api_loop.c - the C loop the Python API's overhead is measured against
 * (tools/bench/python_api.py): the public API alone, a scenario with
 * --set-style overrides, then sim_step `steps` times, timed.  Prints one
 * line: "seconds <wall s of the steps> cpu <CPU s of the steps> hash
 * <state hash>" (CPU time: what the comparison uses on a shared machine).
 *
 *   api_loop SCENARIO STEPS SEED [KEY=VALUE ...]
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"

static double now_s(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: api_loop SCENARIO STEPS SEED [KEY=VALUE ...]\n");
        return 2;
    }
    scenario_override_t sets[64];
    size_t n = 0;
    for (int i = 4; i < argc && n < 64; i++) sets[n++].text = argv[i];
    char err[SIM_ERR_MAX];
    scenario_t *sc = scenario_create(argv[1], sets, n, err);
    if (!sc) {
        fprintf(stderr, "api_loop: %s\n", err);
        return 2;
    }
    sim_t *sim = sim_create(sc, strtoull(argv[3], NULL, 10), err);
    if (!sim) {
        fprintf(stderr, "api_loop: %s\n", err);
        scenario_destroy(sc);
        return 1;
    }
    uint64_t steps = strtoull(argv[2], NULL, 10);
    double t0 = now_s(CLOCK_MONOTONIC), c0 = now_s(CLOCK_PROCESS_CPUTIME_ID);
    for (uint64_t s = 0; s < steps && !sim_done(sim); s++) sim_step(sim);
    double t1 = now_s(CLOCK_MONOTONIC), c1 = now_s(CLOCK_PROCESS_CPUTIME_ID);
    printf("seconds %.6f cpu %.6f hash %016" PRIx64 "\n", t1 - t0, c1 - c0, sim_state_hash(sim));
    sim_destroy(sim);
    scenario_destroy(sc);
    return 0;
}
