/*
 * sound.c - the sound field (sound.h): seed 002's eqs 1, 2 and 4, every
 * pair exact; with a cutoff, the pairs within it exact and the rest as one
 * aggregate term per band.
 *
 * Per robot, as arrays (one each): the band its speaker was set to this
 * step, the band that played during the last period, its levels, the sums
 * being made, its noise stream.  The field's loops read every robot's
 * `played` and write only the listener's own sums.
 */
#include "sound.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/pool.h"
#include "core/sim_internal.h"
#include "models/noise_draws.h"
#include "models/per_robot.h"

/* The names of sound_silent_t, in its order. */
static const char *const silent_names[] = { "ambient", "none", NULL };

#define S sound_config_t
static const param_desc_t sound_params[] = {
    { .key = "enabled", PARAM_BOOL_FIELD(S, enabled),
      .doc = "robots hear each other's speakers (hal_mic_level, hal_speaker_set)" },
    { .key = "a0", PARAM_FIELD(S, a0, double), .min = 0, .max = 1e6,
      .doc = "eq 1: level of a source at 0 m, units (1 unit = 1000 level counts)" },
    { .key = "alpha", PARAM_FIELD(S, alpha, double), .min = 0, .max = 1000,
      .doc = "eq 1: attenuation, 1/m (paper 0.12; e-puck scale 0.12/k = 0.726)" },
    { .key = "ae", PARAM_FIELD(S, ae, double), .min = 0, .max = 1e6,
      .doc = "eq 1: ambient term, units, once per robot in the sum" },
    { .key = "noise", PARAM_FIELD(S, noise, double), .min = 0, .max = 1,
      .doc = "eq 4: relative Gaussian sd of each pair's term (0.06 = N100, 0 = N0)" },
    { .key = "silent_robots", PARAM_ENUM_FIELD(S, silent_robots, silent_names),
      .doc = "a robot silent in a band adds its ambient term (ambient) or nothing (none)" },
    { .key = "self_masking", PARAM_BOOL_FIELD(S, self_masking),
      .doc = "a robot whose speaker played hears nothing that period (false: full duplex)" },
    { .key = "cutoff", PARAM_FIELD(S, cutoff, double), .min = 0, .max = 1e6,
      .doc = "m; > 0: sources farther away add only ae (error <= a0 e^(-alpha cutoff) each)" },
    { .key = "noise_draws", PARAM_ENUM_FIELD(S, noise_draws, noise_draws_names),
      .doc = "eq 4 drawn per pair (per_term) or once per band's sum (summed: the same distribution, faster)" },
    PARAM_END
};
#undef S

#define RC sound_robot_cal_t
static const param_desc_t robot_params[] = {
    { .key = "id", PARAM_FIELD(RC, id, uint16_t), .min = 0, .max = 65535, .doc = "the robot's hal_robot_id" },
    { .key = "gain1", PARAM_FIELD(RC, gain[1], float), .min = 0, .max = 1000,
      .doc = "its microphones' gain in band 1 (absent: 1)" },
    { .key = "gain2", PARAM_FIELD(RC, gain[2], float), .min = 0, .max = 1000,
      .doc = "its microphones' gain in band 2 (absent: 1)" },
    { .key = "gain3", PARAM_FIELD(RC, gain[3], float), .min = 0, .max = 1000,
      .doc = "its microphones' gain in band 3 (absent: 1)" },
    PARAM_END
};
#undef RC
static const schema_t robot_schema = { robot_params, NULL, NULL, NULL };
static const sound_robot_cal_t robot_default = { 0, { 1.0f, 1.0f, 1.0f, 1.0f } };
static const seq_desc_t robots_seq = {
    "robots", PER_ROBOT_MAX, sizeof(sound_robot_cal_t), &robot_default, &robot_schema,
    offsetof(sound_config_t, robots), offsetof(sound_config_t, robot_count), NULL, 1, NULL
};
static const child_t sound_children[] = {
    { "robots", CHILD_SEQUENCE, NULL, &robots_seq, "microphone gains fitted to one robot id (the calibration kit)" },
    CHILD_END
};

MODEL_ONE_SECTION(sound_schema, "sound", sound_params, sound_children,
                  "speakers and microphones (seed 002's model)");

static int sound_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX],
                       char msg[SIM_ERR_MAX])
{
    const sound_config_t *c = config;
    (void)sc;
    int32_t k = per_robot_duplicate(c->robots, c->robot_count, sizeof *c->robots, offsetof(sound_robot_cal_t, id));
    if (k >= 0) {
        snprintf(path, SCHEMA_PATH_MAX, "sound.robots.%d.id", (int)k);
        snprintf(msg, SIM_ERR_MAX, "robot id listed twice: one entry per robot");
        return -1;
    }
    return 0;
}

static void sound_free_config(void *config)
{
    sound_config_t *c = config;
    free(c->robots);
    c->robots = NULL;
    c->robot_count = 0;
}

/* Seed 002's values (DESIGN.md): A0, alpha, Ae, N100's noise. */
static void sound_defaults(void *config)
{
    sound_config_t *c = config;
    c->enabled = 0;
    c->a0 = 299.18;
    c->alpha = 0.12;
    c->ae = 48.18;
    c->noise = 0.06;
    c->silent_robots = SOUND_SILENT_AMBIENT;
    c->self_masking = 1;
    c->cutoff = 0.0;
    c->noise_draws = NOISE_DRAWS_PER_TERM;
    c->robot_count = 0;
    c->robots = NULL;
}

/* Eq 1: an emitter's term at d_m, the one place it is written. */
static inline double eq1(const sound_config_t *cfg, double d_m)
{
    return cfg->a0 * exp(-cfg->alpha * d_m) + cfg->ae;
}

double sound_term(const sound_config_t *cfg, double d_m, int emits)
{
    if (!emits) {
        return cfg->silent_robots == SOUND_SILENT_AMBIENT ? cfg->ae : 0.0;
    }
    if (cfg->cutoff > 0.0 && d_m > cfg->cutoff) {
        return cfg->ae;
    }
    return eq1(cfg, d_m);
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

/* ---------------------------------------------------------------- state */

enum { SET, PLAYED, LEVEL, ACC, RAND, CAL, SQ, ARRAYS };

typedef uint32_t levels_t[HAL_SOUND_BANDS];   /* counts per band ([0] unused) */
typedef double sums_t[HAL_SOUND_BANDS];       /* sound_update's sums, units */

/* The run: the step the field is of, and the arrays. */
typedef struct sound {
    const sound_config_t *cfg;
    uint64_t stamp;          /* the field is this step's when == step + 1 */
    uint8_t *set;            /* band set this step (0: silence) */
    uint8_t *played;         /* band that played during the last period */
    levels_t *level;
    sums_t *acc;
    sums_t *sq;              /* noise_draws: summed, all pairs: the sums of the squared terms */
    sim_rand_t *rand;        /* RAND_SOUND: eq 4's noise of every pair the robot hears */
    per_robot_cache_t *cal;  /* which `robots` entry each robot takes (NULL: none listed) */
} sound_t;

/* noise_draws: summed over all pairs: the pair loop adds both listeners'
 * squared terms as it goes, so it keeps them per robot (with a cutoff each
 * listener sums its own on the stack). */
static int keeps_squares(const sound_config_t *c)
{
    return c->noise_draws == NOISE_DRAWS_SUMMED && c->cutoff <= 0.0;
}

/* Only when enabled: a run without sound holds nothing of it. */
static void sound_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const sound_config_t *c = config;
    (void)sc;
    if (c->enabled) {
        /* The entries' cache only when some are listed, the squares only
         * when kept (they come last, after the cache). */
        out->arrays = keeps_squares(c) ? ARRAYS : (c->robot_count > 0 ? CAL + 1 : CAL);
        out->elem_size[SET] = sizeof(uint8_t);
        out->elem_size[PLAYED] = sizeof(uint8_t);
        out->elem_size[LEVEL] = sizeof(levels_t);
        out->elem_size[ACC] = sizeof(sums_t);
        out->elem_size[RAND] = sizeof(sim_rand_t);
        out->elem_size[CAL] = sizeof(per_robot_cache_t);
        out->elem_size[SQ] = sizeof(sums_t);
        out->run_bytes = sizeof(sound_t);
    }
}

static int sound_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const sound_config_t *c = config;
    if (!c->enabled) {
        return 0;
    }
    sound_t *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the sound field");
        return -1;
    }
    s->cfg = c;
    s->set = sim_model_array(sim, SIM_MODEL_sound, SET);
    s->played = sim_model_array(sim, SIM_MODEL_sound, PLAYED);
    s->level = sim_model_array(sim, SIM_MODEL_sound, LEVEL);
    s->acc = sim_model_array(sim, SIM_MODEL_sound, ACC);
    s->rand = sim_model_array(sim, SIM_MODEL_sound, RAND);
    if (keeps_squares(c)) {
        s->sq = sim_model_array(sim, SIM_MODEL_sound, SQ);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&s->rand[i], sim->seed, i, RAND_SOUND);
    }
    if (c->robot_count > 0) {
        s->cal = sim_model_array(sim, SIM_MODEL_sound, CAL);
        for (uint32_t i = 0; i < sim->n; i++) {
            s->cal[i].id = -1;
        }
    }
    *self = s;
    return 0;
}

static void sound_destroy(void *self) { free(self); }

/* ---------------------------------------------------------------- the field */

/* How many eq 4 draws listener terms from source `src` take: one per band
 * it adds a term to (hear), none without noise. */
static uint32_t draws_of(const sound_t *s, uint32_t src)
{
    if (!(s->cfg->noise > 0.0)) {
        return 0;
    }
    return s->cfg->silent_robots == SOUND_SILENT_AMBIENT ? HAL_SOUND_BANDS - 1u : (s->played[src] ? 1u : 0u);
}

/* One term of a listener's sum (*acc), with its eq 4 noise: the next of
 * the listener's own draws (*z, taken from its stream in order). */
static void add_term(double *acc, double a, double noise, const double **z)
{
    *acc += noise > 0.0 ? a * (1.0 - noise * *(*z)++) : a;
}

/* What source `src` adds to every band of a listener's sums `acc`: per
 * band, a term when the source is in that band's sum (`loud`: its eq 1
 * term); `z`: the draws_of(src) draws of the listener's stream for them. */
static void hear(const sound_t *s, sums_t acc, uint32_t src, double loud, const double **z)
{
    const sound_config_t *cfg = s->cfg;
    int ambient = cfg->silent_robots == SOUND_SILENT_AMBIENT;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        if (s->played[src] == k) {
            add_term(&acc[k], loud, cfg->noise, z);
        } else if (ambient) {
            add_term(&acc[k], cfg->ae, cfg->noise, z);
        }
    }
}

/* Draws are taken this many at a time (sim_rand_normals). */
#define SOUND_DRAW_BLOCK 96u

/* Source j's eq 1 term at listener i, 0 when it is silent. */
static inline double loud_of(const struct sim *sim, const sound_t *s, uint32_t i, uint32_t j)
{
    if (!s->played[j]) {
        return 0.0;
    }
    const sim_robot_t *a = &sim->robots[i];
    vec2_t b = sim_robot_at(sim, j);
    double dx = (double)a->x - (double)b.x, dy = (double)a->y - (double)b.y;
    return eq1(s->cfg, sqrt(dx * dx + dy * dy));
}

/* The near sources' terms in listener i's sums `acc`, in the order of
 * near[] (hear() for each, its draws taken in blocks). */
static void near_terms(struct sim *sim, sound_t *s, uint32_t i, const uint32_t *near, uint32_t n_near, sums_t acc)
{
    double z[SOUND_DRAW_BLOCK];
    for (uint32_t c = 0; c < n_near;) {
        uint32_t end = c, draws = 0;
        while (end < n_near && draws + draws_of(s, near[end]) <= SOUND_DRAW_BLOCK) {
            draws += draws_of(s, near[end++]);
        }
        sim_rand_normals(&s->rand[i], z, draws);
        const double *next = z;
        for (; c < end; c++) {
            hear(s, acc, near[c], loud_of(sim, s, i, near[c]), &next);
        }
    }
}

/* The same for the common case, `silent_robots: ambient` with noise: every
 * source adds a term to every band (its own band its eq 1 term, the others
 * ae) with a draw each, so that the sums stay in registers.  The same
 * terms, added in the same order, as near_terms. */
_Static_assert(HAL_SOUND_BANDS == 4, "near_terms_ambient sums bands 1 to 3");
static void near_terms_ambient(struct sim *sim, sound_t *s, uint32_t i, const uint32_t *near, uint32_t n_near,
                               sums_t acc)
{
    enum { PER = HAL_SOUND_BANDS - 1, BLOCK = SOUND_DRAW_BLOCK / PER };
    const double noise = s->cfg->noise, ae = s->cfg->ae;
    const uint8_t *played = s->played;
    double s1 = acc[1], s2 = acc[2], s3 = acc[3];
    double z[BLOCK * PER];
    for (uint32_t c = 0; c < n_near;) {
        uint32_t end = n_near - c > BLOCK ? c + BLOCK : n_near;
        sim_rand_normals(&s->rand[i], z, (end - c) * PER);
        const double *next = z;
        for (; c < end; c++, next += PER) {
            uint8_t p = played[near[c]];
            double loud = loud_of(sim, s, i, near[c]);
            s1 += (p == 1 ? loud : ae) * (1.0 - noise * next[0]);
            s2 += (p == 2 ? loud : ae) * (1.0 - noise * next[1]);
            s3 += (p == 3 ? loud : ae) * (1.0 - noise * next[2]);
        }
    }
    acc[1] = s1;
    acc[2] = s2;
    acc[3] = s3;
}

/* noise_draws: summed.  What source `src` adds to a listener's sums `acc`
 * and to the sums of its squared terms `sq`: the terms of hear(), without
 * their noise. */
static void moments(const sound_t *s, sums_t acc, sums_t sq, uint32_t src, double loud)
{
    int ambient = s->cfg->silent_robots == SOUND_SILENT_AMBIENT;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        double a = s->played[src] == k ? loud : (ambient ? s->cfg->ae : 0.0);
        acc[k] += a;
        sq[k] += a * a;
    }
}

/* noise_draws: summed, cutoff > 0.  The near sources' terms in listener
 * i's sums `acc` and their squares in `sq`.  No draw per source, so no
 * order to keep (the grid's), and only emitters to visit: under
 * silent_robots: ambient every other near source adds ae to a band, and
 * near_emit[k] says how many do not. */
static void near_moments(struct sim *sim, sound_t *s, uint32_t i, const uint32_t *near, uint32_t n_near,
                         const uint32_t near_emit[HAL_SOUND_BANDS], sums_t acc, sums_t sq)
{
    const double ae = s->cfg->ae;
    for (uint32_t c = 0; c < n_near; c++) {
        uint8_t p = s->played[near[c]];
        if (p) {
            double loud = loud_of(sim, s, i, near[c]);
            acc[p] += loud;
            sq[p] += loud * loud;
        }
    }
    for (uint8_t k = 1; s->cfg->silent_robots == SOUND_SILENT_AMBIENT && k < HAL_SOUND_BANDS; k++) {
        double others = (double)(n_near - near_emit[k]);
        acc[k] += others * ae;
        sq[k] += others * ae * ae;
    }
}

/* noise_draws: summed.  Eq 4's noise of listener i's whole sum in each
 * band: sum_j A_j (1 - noise N_j) is sum_j A_j - noise sqrt(sum_j A_j^2) N
 * in distribution; one draw per band, from the listener's stream. */
static void summed_noise(sound_t *s, uint32_t i, sums_t acc, const sums_t sq)
{
    double z[HAL_SOUND_BANDS - 1];
    sim_rand_normals(&s->rand[i], z, HAL_SOUND_BANDS - 1);
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        acc[k] -= s->cfg->noise * sqrt(sq[k]) * z[k - 1];
    }
}

/* cutoff > 0: listener i's sums from the robot grid.  Robots within the
 * cutoff, in id order, as the all-pairs loop meets them (same terms, same
 * draws); every robot beyond it adds only ae to a band (in `none` mode only
 * when it emits in that band), so their m terms ae (1 - noise N_j) sum to
 * m ae - ae noise sqrt(m) N: one draw per band, the same distribution
 * (a sum of independent Gaussians), and work per listener bounded by the
 * robots within the cutoff, not by the swarm.  The near ones are found
 * first (then sorted: fewer to sort), so that their draws are taken in
 * blocks, exactly as many as the terms use.  noise_draws: summed takes
 * none of that order: near_moments, and one draw per band for the whole
 * sum, far terms included. */
static void listen_near(struct sim *sim, sound_t *s, sim_scratch_t *ws, uint32_t i,
                        const uint32_t emitters[HAL_SOUND_BANDS])
{
    const sound_config_t *cfg = s->cfg;
    const sim_robot_t *a = &sim->robots[i];
    double cutoff = cfg->cutoff;
    float box = (float)cutoff + 0.01f;   /* a little more: the test below is in double */
    uint32_t *near = ws->robots;
    uint32_t n = sim_gather_robots(sim, a->x - box, a->y - box, a->x + box, a->y + box, near, sim->n);
    uint32_t near_emit[HAL_SOUND_BANDS] = { 0 }, n_near = 0;
    /* d > cutoff as the all-pairs loop tests it (sqrt in double), the
     * square root taken only within a hair of the cutoff. */
    double in2 = cutoff * cutoff * (1.0 - 1e-9), out2 = cutoff * cutoff * (1.0 + 1e-9);
    for (uint32_t c = 0; c < n; c++) {
        vec2_t b = sim_robot_at(sim, near[c]);
        double dx = (double)a->x - (double)b.x, dy = (double)a->y - (double)b.y, d2 = dx * dx + dy * dy;
        if (near[c] == i || d2 > out2 || (d2 >= in2 && sqrt(d2) > cutoff)) {
            continue;
        }
        near_emit[s->played[near[c]]]++;
        near[n_near++] = near[c];
    }
    sums_t acc = { 0.0 }, sq = { 0.0 };
    int ambient = cfg->silent_robots == SOUND_SILENT_AMBIENT;
    int summed = cfg->noise_draws == NOISE_DRAWS_SUMMED;
    if (summed) {
        near_moments(sim, s, i, near, n_near, near_emit, acc, sq);
    } else {
        grid_sort_ids(near, n_near);
        if (ambient && cfg->noise > 0.0) {
            near_terms_ambient(sim, s, i, near, n_near, acc);
        } else {
            near_terms(sim, s, i, near, n_near, acc);
        }
    }
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        uint32_t m = ambient ? sim->n - 1 - n_near
                             : emitters[k] - near_emit[k] - (s->played[i] == k ? 1u : 0u);
        if (m == 0) {
            continue;
        }
        double sum = (double)m * cfg->ae;
        if (summed) {
            sq[k] += (double)m * cfg->ae * cfg->ae;
        } else if (cfg->noise > 0.0) {
            sum -= cfg->ae * cfg->noise * sqrt((double)m) * sim_rand_normal(&s->rand[i]);
        }
        acc[k] += sum;
    }
    if (summed && cfg->noise > 0.0) {
        summed_noise(s, i, acc, sq);
    }
    for (uint32_t k = 0; k < HAL_SOUND_BANDS; k++) {
        s->acc[i][k] = acc[k];
    }
}

typedef struct listeners {
    struct sim *sim;
    sound_t *s;
    uint32_t emitters[HAL_SOUND_BANDS];   /**< robots that played in each band */
} listeners_t;

/* Listener i's sums as the counts its microphones read. */
static void levels_of(sound_t *s, uint32_t i)
{
    s->level[i][0] = 0;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        s->level[i][k] = sound_counts(s->acc[i][k]);
    }
}

/* pool_fn: listeners [begin, end), each its own sums and noise stream, so
 * that they are summed side by side. */
static void listen_range(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    listeners_t *l = ctx;
    sound_t *s = l->s;
    int masking = s->cfg->self_masking != 0;
    for (uint32_t i = begin; i < end; i++) {
        if (masking && s->played[i]) {
            for (uint32_t k = 0; k < HAL_SOUND_BANDS; k++) {
                s->acc[i][k] = 0.0;
            }
        } else {
            listen_near(l->sim, s, &l->sim->scratch[worker], i, l->emitters);
        }
        levels_of(s, i);   /* here, on the pool, not after it on one thread */
    }
}

/* Listeners take a few microseconds each within a 2 m cutoff. */
#define LISTEN_CHUNK 64u

static void update_with_cutoff(struct sim *sim, sound_t *s)
{
    listeners_t l = { .sim = sim, .s = s };
    for (uint32_t i = 0; i < sim->n; i++) {
        l.emitters[s->played[i]]++;
    }
    pool_for(sim->pool, sim->n, LISTEN_CHUNK, listen_range, &l);
}

/* cutoff 0: eq 2 as written, every pair exact. */
static void update_all_pairs(struct sim *sim, sound_t *s)
{
    const sound_config_t *cfg = s->cfg;
    uint32_t n = sim->n;
    int masking = cfg->self_masking != 0;
    /* Every unordered pair once (one distance and at most one exponential
     * for both directions), listener i's sum in acc.  Listener m meets its
     * sources in id order: j < m at the outer loop's earlier rounds, then
     * j > m at its own, so its draws and its sum's order are those of a
     * plain loop over j. */
    int summed = s->sq != NULL;   /* keeps_squares */
    for (uint32_t i = 0; i < n; i++) {
        for (uint8_t k = 0; k < HAL_SOUND_BANDS; k++) {
            s->acc[i][k] = 0.0;
            if (summed) {
                s->sq[i][k] = 0.0;
            }
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        const sim_robot_t *a = &sim->robots[i];
        int a_hears = !(masking && s->played[i]);
        for (uint32_t j = i + 1; j < n; j++) {
            const sim_robot_t *b = &sim->robots[j];
            int b_hears = !(masking && s->played[j]);
            if (!a_hears && !b_hears) {
                continue;
            }
            /* A source's loud term, eq 1 at this pair's distance.  The
             * distance is needed only when one of the two emits. */
            double loud = 0.0;
            if (s->played[i] || s->played[j]) {
                double dx = (double)a->x - (double)b->x, dy = (double)a->y - (double)b->y;
                loud = eq1(cfg, sqrt(dx * dx + dy * dy));
            }
            if (summed) {
                if (a_hears) {
                    moments(s, s->acc[i], s->sq[i], j, loud);
                }
                if (b_hears) {
                    moments(s, s->acc[j], s->sq[j], i, loud);
                }
                continue;
            }
            double z[HAL_SOUND_BANDS];
            const double *next = z;
            if (a_hears) {
                sim_rand_normals(&s->rand[i], z, draws_of(s, j));
                hear(s, s->acc[i], j, loud, &next);
            }
            next = z;
            if (b_hears) {
                sim_rand_normals(&s->rand[j], z, draws_of(s, i));
                hear(s, s->acc[j], i, loud, &next);
            }
        }
    }
    for (uint32_t i = 0; summed && cfg->noise > 0.0 && i < n; i++) {
        if (!(masking && s->played[i])) {
            summed_noise(s, i, s->acc[i], s->sq[i]);
        }
    }
}

/* Every robot's levels for the period just ended, unless already computed
 * for this step. */
static void sound_update(struct sim *sim, sound_t *s)
{
    if (s == NULL || s->stamp == sim->step + 1) {
        return;
    }
    s->stamp = sim->step + 1;
    if (s->cfg->cutoff > 0.0) {
        update_with_cutoff(sim, s);   /* levels included */
        return;
    }
    update_all_pairs(sim, s);
    for (uint32_t i = 0; i < sim->n; i++) {
        levels_of(s, i);
    }
}

/* Whole, before any controller reads it. */
static void sound_before_control(sim_t *sim, void *self)
{
    sound_update(sim, self);
}

/* What each robot set this step is what plays during the period that
 * follows. */
static void sound_end_step(sim_t *sim, void *self)
{
    sound_t *s = self;
    for (uint32_t i = 0; s && i < sim->n; i++) {
        s->played[i] = s->set[i];
    }
}

/* A robot moved by hand: the field must be made again from the new pose. */
static void sound_moved(sim_t *sim, void *self, uint32_t robot)
{
    sound_t *s = self;
    (void)sim;
    (void)robot;
    if (s) {
        s->stamp = 0;
    }
}

/* ---------------------------------------------------------------- HAL */

/* The field is computed before the controllers step; here only read.  Read
 * between steps (tests), it is computed then: the field the next step's
 * controllers will see. */
hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level)
{
    sound_t *s = sim_model_self(hal->sim, SIM_MODEL_sound);
    *level = 0;
    if (mic >= HAL_MIC_COUNT || band == 0u || band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (s == NULL) {
        return HAL_ERR_UNAVAILABLE;
    }
    sound_update(hal->sim, s);
    if (s->cfg->self_masking && s->played[hal->index] != 0u) {
        return HAL_ERR_BUSY;
    }
    /* The three microphones hear the same (sound.h). */
    *level = s->level[hal->index][band];
    if (s->cal != NULL) {
        const sound_robot_cal_t *e = per_robot_entry(&s->cal[hal->index], s->cfg->robots, s->cfg->robot_count,
                                                     sizeof *s->cfg->robots, offsetof(sound_robot_cal_t, id),
                                                     hal_robot_id(hal));
        if (e != NULL && !isnan(e->gain[band])) {
            *level = sound_counts(*level * (double)e->gain[band] / 1000.0);
        }
    }
    return HAL_OK;
}

/* Plays from the next period on: the step's end makes it what played. */
hal_status_t hal_speaker_set(hal_t *hal, uint8_t band)
{
    sound_t *s = sim_model_self(hal->sim, SIM_MODEL_sound);
    if (band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (s == NULL) {
        return HAL_ERR_UNAVAILABLE;
    }
    s->set[hal->index] = band;
    return HAL_OK;
}

static const char *const sound_hal_calls[] = { "hal_mic_level", "hal_speaker_set", NULL };

static const model_field_t sound_fields[] = {
    { "sound.played", "", "band its speaker played during the last period (0: silence)", SIM_FIELD_U8, PLAYED, 0, 1 },
    { "sound.level", "counts", "level per band over the last period (index 0 unused)", SIM_FIELD_U32, LEVEL, 0,
      HAL_SOUND_BANDS },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

/* Its levels per band over the last period, once the field was summed. */
static void sound_inspect(const sim_t *sim, const void *self, uint32_t robot, model_inspect_t *out)
{
    const sound_t *s = self;
    (void)sim;
    if (s == NULL || s->stamp == 0) {
        return;
    }
    out->n_bands = HAL_SOUND_BANDS - 1u;
    for (uint8_t k = 1; k < HAL_SOUND_BANDS; k++) {
        out->mic[k] = (float)s->level[robot][k];
    }
}

const model_def_t sound_model = {
    .name = "sound",
    .doc = "speakers and microphones: seed 002's sound field (eqs 1-4)",
    .config_size = sizeof(sound_config_t),
    .default_config = sound_defaults,
    .schema = &sound_schema,
    .check = sound_check,
    .free_config = sound_free_config,
    .layout = sound_layout,
    .create = sound_create,
    .destroy = sound_destroy,
    .before_control = sound_before_control,
    .end_step = sound_end_step,
    .moved = sound_moved,
    .inspect = sound_inspect,
    .hal_calls = sound_hal_calls,
    .fields = sound_fields,
};
