/*
 * sound.c - the sound field (sound.h): seed 002's eqs 1, 2 and 4, every
 * pair exact.
 */
#include "sound.h"

#include <math.h>

#include "sim_internal.h"

double sound_term(const scenario_t *sc, double d_m, int emits)
{
    if (!emits) {
        return sc->sound.silent_robots == SOUND_SILENT_AMBIENT ? sc->sound.ae : 0.0;
    }
    if (sc->sound.cutoff > 0.0 && d_m > sc->sound.cutoff) {
        return sc->sound.ae;
    }
    return sc->sound.a0 * exp(-sc->sound.alpha * d_m) + sc->sound.ae;
}

uint32_t sound_counts(double units)
{
    double c = 1000.0 * units;
    if (!(c > 0.0)) {
        return 0;
    }
    if (c >= 4294967295.0) {
        return UINT32_MAX;
    }
    return (uint32_t)floor(c + 0.5);
}

/* One term of listener r's sum in band k, with its eq 4 noise drawn from
 * r's own stream. */
static void add_term(sim_robot_t *r, double sum[HAL_SOUND_BANDS], uint8_t k, double a, double noise)
{
    sum[k] += noise > 0.0 ? a * (1.0 - noise * sim_rand_normal(&r->sound_rand)) : a;
}

/* What source `src` at distance d adds to every band of listener `dst`:
 * per band, a term when the source is in that band's sum. */
static void hear(const scenario_t *sc, sim_robot_t *dst, double sum[HAL_SOUND_BANDS],
                 const sim_robot_t *src, double loud)
{
    int ambient = sc->sound.silent_robots == SOUND_SILENT_AMBIENT;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        if (src->speaker_played == k) {
            add_term(dst, sum, k, loud, sc->sound.noise);
        } else if (ambient) {
            add_term(dst, sum, k, sc->sound.ae, sc->sound.noise);
        }
    }
}

void sound_update(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    if (!sc->sound.enabled || sim->sound_stamp == sim->step + 1) {
        return;
    }
    sim->sound_stamp = sim->step + 1;
    uint32_t n = sim->n;
    int masking = sc->sound.self_masking != 0;
    double cutoff = sc->sound.cutoff;
    /* Every unordered pair once (one distance and at most one exponential
     * for both directions), listener i's sum in sound_acc.  Listener m
     * meets its sources in id order: j < m at the outer loop's earlier
     * rounds, then j > m at its own, so its draws and its sum's order are
     * those of a plain loop over j. */
    for (uint32_t i = 0; i < n; i++) {
        for (uint8_t k = 0; k < HAL_SOUND_BANDS; k++) {
            sim->robots[i].sound_acc[k] = 0.0;
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        sim_robot_t *a = &sim->robots[i];
        int a_hears = !(masking && a->speaker_played);
        for (uint32_t j = i + 1; j < n; j++) {
            sim_robot_t *b = &sim->robots[j];
            int b_hears = !(masking && b->speaker_played);
            if (!a_hears && !b_hears) {
                continue;
            }
            /* A source's loud term: eq 1 at this pair's distance (only ae
             * beyond the cutoff).  The distance is needed only when one
             * of the two emits. */
            double loud = 0.0;
            if (a->speaker_played || b->speaker_played) {
                double dx = (double)a->x - (double)b->x, dy = (double)a->y - (double)b->y;
                double d = sqrt(dx * dx + dy * dy);
                double e = cutoff > 0.0 && d > cutoff ? 0.0 : sc->sound.a0 * exp(-sc->sound.alpha * d);
                loud = e + sc->sound.ae;
            }
            if (a_hears) {
                hear(sc, a, a->sound_acc, b, loud);
            }
            if (b_hears) {
                hear(sc, b, b->sound_acc, a, loud);
            }
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        sim_robot_t *r = &sim->robots[i];
        r->sound_level[0] = 0;
        for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
            r->sound_level[k] = sound_counts(r->sound_acc[k]);
        }
    }
}

void sound_end_step(struct sim *sim)
{
    if (!sim->sc->sound.enabled) {
        return;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim->robots[i].speaker_played = sim->robots[i].speaker_set;
    }
}
