/*
 * metrics.h - what a run reports: named ground-truth values for the
 * summary and the time series, computed by observers of the simulation.
 */
#ifndef SIM_METRICS_H
#define SIM_METRICS_H

#include <stdio.h>

#include "sim.h"

#define METRICS_MAX 32

typedef struct metric_list {
    unsigned count;
    const char *name[METRICS_MAX];
    double value[METRICS_MAX];
} metric_list_t;

/** Columns of the time series, sampled at the current step. */
void metrics_sample(const sim_t *sim, metric_list_t *out);

/** Final metrics of a finished run. */
void metrics_final(const sim_t *sim, metric_list_t *out);

#endif
