/*
 * summary.h - a run's summary.json and the aggregate over repetitions:
 * written with their provenance (what ran, how, from which code), and a
 * run's summary read back, so that --resume can count a finished run
 * without running it again.
 *
 * Provenance in every summary: the scenario and its file, every --set
 * override in order, the effective scenario's file name beside it
 * (scenario.yaml) and its hash, the seed(s), each group's controller and
 * policy, the code version and the command line.  Two result folders can
 * be told apart from these files alone.
 */
#ifndef SIM_SUMMARY_H
#define SIM_SUMMARY_H

#include <stdint.h>
#include <stdio.h>

#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"

#define SUMMARY_SCENARIO_COPY "scenario.yaml"
/** Beside a run's summary.json: its metrics exactly, for --resume. */
#define SUMMARY_EXACT_METRICS ".metrics.exact"

typedef struct provenance {
    const char *code_version;        /**< git describe of the build */
    const char *command;             /**< the command line, shell-quoted */
    const scenario_override_t *overrides;
    size_t override_count;
    uint64_t scenario_hash;          /**< FNV-1a of the effective scenario's text */
    const char *control;             /**< a run under --control: control_json's object, or NULL */
} provenance_t;

/** One finished run (`sim`, when given, adds its injected faults). */
void summary_write_run(FILE *f, const scenario_t *sc, const provenance_t *pv, const sim_t *sim,
                       uint64_t seed, uint64_t steps, uint64_t state_hash, const metric_list_t *m);

/** Mean, sd, min and max of each metric over the `done` finished runs of
 *  `reps` asked for (seeds first_seed ..); `complete` is done == reps. */
void summary_write_aggregate(FILE *f, const scenario_t *sc, const provenance_t *pv,
                             uint64_t first_seed, uint32_t reps, uint64_t steps,
                             const metric_list_t *const *done, uint32_t done_count);

/**
 * Reads back a summary this module wrote for `seed`: its steps, state hash
 * and, from the exact copy beside it, the values of the metrics named in
 * `names` (same names, same order; the strings of `names` are kept).  Returns 0, or -1 when the file is
 * missing, is not such a summary, or lacks one of the metrics.
 */
int summary_read_run(const char *path, uint64_t seed, const metric_list_t *names,
                     metric_list_t *out, uint64_t *steps, uint64_t *state_hash);

/** The metrics exactly (hexadecimal floating point), one "name value" a
 *  line: written beside summary.json as SUMMARY_EXACT_METRICS. */
void summary_write_exact(FILE *f, const metric_list_t *m);

/** FNV-1a 64 of a text (the effective scenario's identity). */
uint64_t summary_text_hash(const char *text, size_t len);

#endif
