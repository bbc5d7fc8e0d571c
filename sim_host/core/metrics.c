/*
 * metrics.c - ground-truth observers of the core, the controllers' own
 * counters (observable.h: obstacle-avoidance events are counted on the
 * robot, as seed 000 does), and what each task declares.
 */
#include "swarmsim/metrics.h"

#include <math.h>

#include "sim_internal.h"

void metrics_put(metric_list_t *m, const char *name, const char *unit, const char *doc, double value)
{
    if (m->count < METRICS_MAX) {
        m->name[m->count] = name;
        m->unit[m->count] = unit;
        m->doc[m->count] = doc;
        m->value[m->count] = value;
        m->count++;
    }
}

/* Entries of a {NULL}-terminated metric_desc_t table. */
static unsigned metric_desc_count(const metric_desc_t *table)
{
    unsigned n = 0;
    while (table && table[n].name) {
        n++;
    }
    return n;
}

/* Totals of each counter (sim->counters) over the robots that count it. */
static void count(const struct sim *sim, double *total, uint32_t *robots)
{
    for (uint32_t k = 0; k < sim->n_counters; k++) {
        total[k] = 0.0;
        robots[k] = 0;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        const sim_robot_t *r = &sim->robots[i];
        const sim_group_counter_t *c = sim->group_counters[r->group];
        for (uint32_t k = 0; r->ctrl && k < sim->n_group_counters[r->group]; k++) {
            total[c[k].slot] += (double)observable_read(c[k].obs, r->ctrl);
            robots[c[k].slot]++;
        }
    }
}

/* Robots that can move: the "per robot" of distance and speed. */
static uint32_t moving_robots(const struct sim *sim)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        n += sim->robots[i].moves != 0;
    }
    return n;
}

void metrics_sample(const sim_t *simp, metric_list_t *out)
{
    const struct sim *sim = simp;
    const sim_metrics_t *g = &sim->metrics;
    double total[SIM_MAX_COUNTERS];
    uint32_t robots[SIM_MAX_COUNTERS];
    out->count = 0;
    metrics_put(out, "step", "", "control steps done", (double)sim->step);
    metrics_put(out, "time_s", "s", "simulated time", sim_time_s(simp));
    count(sim, total, robots);
    for (uint32_t k = 0; k < sim->n_counters; k++) {
        metrics_put(out, sim->counters[k].total_key, sim->counters[k].unit, sim->counters[k].total_doc, total[k]);
    }
    metrics_put(out, "robot_contacts", "", "robot-robot contacts begun", (double)g->robot_contacts);
    metrics_put(out, "static_contacts", "", "robot-wall and robot-obstacle contacts begun",
                (double)g->static_contacts);
    metrics_put(out, "distance_m", "m", "path length of all robots", g->distance_m);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const task_def_t *def = sim->tasks[t].def;
        unsigned n = metric_desc_count(def->columns);
        double v[METRICS_MAX];
        if (!def->sample || n == 0) {
            continue;
        }
        def->sample(sim->tasks[t].self, simp, v);
        for (unsigned k = 0; k < n && k < METRICS_MAX; k++) {
            metrics_put(out, def->columns[k].name, def->columns[k].unit, def->columns[k].doc, v[k]);
        }
    }
}

void metrics_final(const sim_t *simp, metric_list_t *out)
{
    const struct sim *sim = simp;
    const sim_metrics_t *g = &sim->metrics;
    double total[SIM_MAX_COUNTERS];
    uint32_t robots[SIM_MAX_COUNTERS];
    uint32_t moving = moving_robots(sim);
    double n = moving ? moving : 1;
    double t = sim_time_s(simp);
    out->count = 0;
    count(sim, total, robots);
    for (uint32_t k = 0; k < sim->n_counters; k++) {
        metrics_put(out, sim->counters[k].total_key, sim->counters[k].unit, sim->counters[k].total_doc, total[k]);
        metrics_put(out, sim->counters[k].per_robot_key, sim->counters[k].unit,
                    "the total over the robots that count it, per robot",
                    robots[k] ? total[k] / robots[k] : 0.0);
    }
    metrics_put(out, "robot_contacts", "", "robot-robot contacts begun", (double)g->robot_contacts);
    metrics_put(out, "static_contacts", "", "robot-wall and robot-obstacle contacts begun",
                (double)g->static_contacts);
    metrics_put(out, "distance_per_robot_m", "m", "path length per robot that can move", g->distance_m / n);
    metrics_put(out, "mean_speed_mm_s", "mm/s", "mean ground speed of the robots that can move",
                t > 0 ? 1000.0 * g->distance_m / n / t : 0.0);
    metrics_put(out, "min_wall_clearance_mm", "mm", "smallest body-to-wall gap (negative: overlap)",
                isfinite(g->min_wall_clearance_m) ? 1000.0 * g->min_wall_clearance_m : 0.0);
    metrics_put(out, "escaped", "robots", "robots that ever left the arena", (double)g->escaped);
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim->models[id].def->final) {
            sim->models[id].def->final(sim, sim->models[id].self, out);
        }
    }
    int stops = 0;
    for (uint32_t k = 0; k < sim->n_tasks; k++) {
        const task_def_t *def = sim->tasks[k].def;
        unsigned m = metric_desc_count(def->summary);
        double v[METRICS_MAX];
        stops |= def->done != NULL;
        if (!def->final || m == 0) {
            continue;
        }
        def->final(sim->tasks[k].self, simp, v);
        for (unsigned j = 0; j < m && j < METRICS_MAX; j++) {
            metrics_put(out, def->summary[j].name, def->summary[j].unit, def->summary[j].doc, v[j]);
        }
    }
    if (stops) {
        /* A run that ends on a task's stop condition: when (NaN if it
         * never did, within the run's steps). */
        metrics_put(out, "completed", "", "1 when a task's stop condition ended the run", sim->done ? 1.0 : 0.0);
        metrics_put(out, "completion_time_s", "s", "when it did (null: never)", sim->done ? t : NAN);
    }
}
