/*
 * sound.c - the sound field (sound.h): seed 002's eqs 1, 2 and 4, every
 * pair exact; with a cutoff, the pairs within it exact and the rest as one
 * aggregate term per band.
 */
#include "sound.h"

#include <math.h>

#include "pool.h"
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

/* cutoff > 0: listener r's sums from the robot grid.  Robots within the
 * cutoff, in id order, as the all-pairs loop meets them (same terms, same
 * draws); every robot beyond it adds only ae to a band (in `none` mode only
 * when it emits in that band), so their m terms ae (1 - noise N_j) sum to
 * m ae - ae noise sqrt(m) N: one draw per band, the same distribution
 * (a sum of independent Gaussians), and work per listener bounded by the
 * robots within the cutoff, not by the swarm. */
static void listen_near(struct sim *sim, sim_scratch_t *ws, uint32_t i, const uint32_t emitters[HAL_SOUND_BANDS])
{
    const scenario_t *sc = sim->sc;
    sim_robot_t *a = &sim->robots[i];
    double cutoff = sc->sound.cutoff;
    float box = (float)cutoff + 0.01f;   /* a little more: the test below is in double */
    uint32_t *near = ws->robots;
    uint32_t n = sim_gather_robots(sim, a->x - box, a->y - box, a->x + box, a->y + box, near, sim->n);
    uint32_t near_emit[HAL_SOUND_BANDS] = { 0 }, n_near = 0;
    grid_sort_ids(near, n);
    for (uint32_t k = 0; k < HAL_SOUND_BANDS; k++) {
        a->sound_acc[k] = 0.0;
    }
    for (uint32_t c = 0; c < n; c++) {
        const sim_robot_t *b = &sim->robots[near[c]];
        if (near[c] == i) {
            continue;
        }
        double dx = (double)a->x - (double)b->x, dy = (double)a->y - (double)b->y;
        double d = sqrt(dx * dx + dy * dy);
        if (d > cutoff) {
            continue;
        }
        n_near++;
        near_emit[b->speaker_played]++;
        double loud = b->speaker_played ? sc->sound.a0 * exp(-sc->sound.alpha * d) + sc->sound.ae : 0.0;
        hear(sc, a, a->sound_acc, b, loud);
    }
    int ambient = sc->sound.silent_robots == SOUND_SILENT_AMBIENT;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        uint32_t m = ambient ? sim->n - 1 - n_near
                             : emitters[k] - near_emit[k] - (a->speaker_played == k ? 1u : 0u);
        if (m == 0) {
            continue;
        }
        double sum = (double)m * sc->sound.ae;
        if (sc->sound.noise > 0.0) {
            sum -= sc->sound.ae * sc->sound.noise * sqrt((double)m) * sim_rand_normal(&a->sound_rand);
        }
        a->sound_acc[k] += sum;
    }
}

typedef struct listeners {
    struct sim *sim;
    uint32_t emitters[HAL_SOUND_BANDS];   /**< robots that played in each band */
} listeners_t;

/* pool_fn: listeners [begin, end), each its own sums and noise stream, so
 * that they are summed side by side. */
static void listen_range(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    listeners_t *l = ctx;
    struct sim *sim = l->sim;
    int masking = sim->sc->sound.self_masking != 0;
    for (uint32_t i = begin; i < end; i++) {
        sim_robot_t *a = &sim->robots[i];
        if (masking && a->speaker_played) {
            for (uint32_t k = 0; k < HAL_SOUND_BANDS; k++) {
                a->sound_acc[k] = 0.0;
            }
        } else {
            listen_near(sim, &sim->scratch[worker], i, l->emitters);
        }
    }
}

/* Listeners take a few microseconds each within a 2 m cutoff. */
#define LISTEN_CHUNK 64u

static void update_with_cutoff(struct sim *sim)
{
    listeners_t l = { .sim = sim };
    for (uint32_t i = 0; i < sim->n; i++) {
        l.emitters[sim->robots[i].speaker_played]++;
    }
    pool_for(sim->pool, sim->n, LISTEN_CHUNK, listen_range, &l);
}

/* cutoff 0: eq 2 as written, every pair exact. */
static void update_all_pairs(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    uint32_t n = sim->n;
    int masking = sc->sound.self_masking != 0;
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
            /* A source's loud term, eq 1 at this pair's distance.  The
             * distance is needed only when one of the two emits. */
            double loud = 0.0;
            if (a->speaker_played || b->speaker_played) {
                double dx = (double)a->x - (double)b->x, dy = (double)a->y - (double)b->y;
                double d = sqrt(dx * dx + dy * dy);
                loud = sc->sound.a0 * exp(-sc->sound.alpha * d) + sc->sound.ae;
            }
            if (a_hears) {
                hear(sc, a, a->sound_acc, b, loud);
            }
            if (b_hears) {
                hear(sc, b, b->sound_acc, a, loud);
            }
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
    if (sc->sound.cutoff > 0.0) {
        update_with_cutoff(sim);
    } else {
        update_all_pairs(sim);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
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
