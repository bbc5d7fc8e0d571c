/*
 * metrics.c - ground-truth observers.  The obstacle-avoidance count is the
 * robots' own (seed 000 counts OAEs on the robot); everything else comes
 * from the simulator's state.
 */
#include "metrics.h"

#include <math.h>

#include "tasks/foraging/foraging.h"

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
    const foraging_t *f = sim_foraging(sim);
    if (f) {
        put(out, "food_nest", f->food);
        put(out, "food_collected", (double)f->delivered);
        put(out, "waiting", f->waiting);
        put(out, "searching", f->searching);
        put(out, "returning", f->returning);
        put(out, "active", f->searching + f->returning);
    }
}

void metrics_final(const sim_t *sim, metric_list_t *out)
{
    const sim_metrics_t *g = sim_metrics(sim);
    const scenario_t *sc = sim_scenario(sim);
    double n = sim_swarm_count(sim) ? sim_swarm_count(sim) : 1;
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
    const foraging_t *f = sim_foraging(sim);
    if (f) {
        /* Seed 000, section 2.4.  Eq 8: V_f = sum_t |F_d - F(t)| / T over the
         * T control steps.  Eq 9: E_e = E_n / E_T, net food energy over the
         * energy collected; both in tokens x token_energy, so E_e is
         * F(T) / collected (reported as a fraction, the paper prints %).
         * Eq 10: M_v = M_T / N_r, M_T the total OAEs. */
        double steps = (double)sim_step_count(sim);
        put(out, "V_f", steps > 0 ? f->deviation_sum / steps : 0.0);
        put(out, "E_e", f->delivered ? f->food / (double)f->delivered : 0.0);
        put(out, "M_T", (double)sim_oae_total(sim));
        put(out, "M_v", (double)sim_oae_total(sim) / n);
        put(out, "food_collected", (double)f->delivered);
        put(out, "food_net", f->food);
        put(out, "food_dropped", (double)f->dropped);
    }
}
