/*
 * metrics.c - ground-truth observers.  The obstacle-avoidance count is the
 * robots' own (seed 000 counts OAEs on the robot); everything else comes
 * from the simulator's state.
 */
#include "metrics.h"

#include <math.h>

static void put(metric_list_t *m, const char *name, double value)
{
    if (m->count < METRICS_MAX) {
        m->name[m->count] = name;
        m->value[m->count] = value;
        m->count++;
    }
}

void metrics_sample(const sim_t *sim, metric_list_t *out)
{
    const sim_metrics_t *g = sim_metrics(sim);
    const scenario_t *sc = sim_scenario(sim);
    out->count = 0;
    put(out, "step", (double)sim_step_count(sim));
    put(out, "time_s", (double)sim_step_count(sim) * sc->control_period_ms / 1000.0);
    put(out, "oae_total", (double)sim_oae_total(sim));
    put(out, "robot_contacts", (double)g->robot_contacts);
    put(out, "static_contacts", (double)g->static_contacts);
    put(out, "distance_m", g->distance_m);
}

void metrics_final(const sim_t *sim, metric_list_t *out)
{
    const sim_metrics_t *g = sim_metrics(sim);
    const scenario_t *sc = sim_scenario(sim);
    double n = sim_robot_count(sim) ? sim_robot_count(sim) : 1;
    double t = (double)sim_step_count(sim) * sc->control_period_ms / 1000.0;
    out->count = 0;
    put(out, "oae_total", (double)sim_oae_total(sim));
    put(out, "oae_per_robot", (double)sim_oae_total(sim) / n);
    put(out, "robot_contacts", (double)g->robot_contacts);
    put(out, "static_contacts", (double)g->static_contacts);
    put(out, "distance_per_robot_m", g->distance_m / n);
    put(out, "mean_speed_mm_s", t > 0 ? 1000.0 * g->distance_m / n / t : 0.0);
    put(out, "min_wall_clearance_mm", isfinite(g->min_wall_clearance_m) ? 1000.0 * g->min_wall_clearance_m : 0.0);
    put(out, "escaped", (double)g->escaped);
}
