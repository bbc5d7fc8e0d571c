/*
 * metrics.h - what a run reports: named ground-truth values for the summary
 * and the time series.  The core observes the world (contacts, distance,
 * clearance, escapes) and totals the controllers' counters (observable.h);
 * each task adds the values it declares (task.h).
 */
#ifndef SIM_METRICS_H
#define SIM_METRICS_H

#include <stdio.h>

#include "sim.h"

#define METRICS_MAX 64

/** A named value a task or the core declares: a time-series column or a
 *  summary metric. */
typedef struct metric_desc {
    const char *name;   /**< CSV column / JSON key */
    const char *unit;   /**< "" when it has none */
    const char *doc;    /**< one line */
} metric_desc_t;

typedef struct metric_list {
    unsigned count;
    const char *name[METRICS_MAX];
    const char *unit[METRICS_MAX];
    const char *doc[METRICS_MAX];
    double value[METRICS_MAX];
} metric_list_t;

/** Appends one value (dropped past METRICS_MAX).  The strings must outlive
 *  the list (literals, tables, the sim's own). */
void metrics_put(metric_list_t *m, const char *name, const char *unit, const char *doc, double value);

/** Columns of the time series, sampled at the current step. */
void metrics_sample(const sim_t *sim, metric_list_t *out);

/** Final metrics of a finished run. */
void metrics_final(const sim_t *sim, metric_list_t *out);

#endif
