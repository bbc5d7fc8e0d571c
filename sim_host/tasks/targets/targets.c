/*
 * targets.c - seed 002's targets, nest and pick-up rule as a task plug-in
 * (targets.h).
 */
#include "targets.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "swarmsim/rand.h"
#include "units.h"

/* Rejection sampling: draws per target before the layout is said not to fit. */
#define PLACE_TRIES 100000
/* The layout's random stream: (layout_seed, this index, RAND_TASK), apart
 * from every stream of a run (those are keyed by the run seed). */
#define LAYOUT_STREAM UINT64_C(0x7461726765747300)   /* "targets" */
/* Drawing: the nest's floor, the targets' halo (the paper's purple). */
/* A target's halo in a picture: this many target radii, and at least this
 * share of the layout square (a 1 cm target in a 16 m world is a pixel). */
#define HALO_RADII 3.0f
#define HALO_SIDE_SHARE 0.004f

enum { KEY_MOVING, KEY_PICKING, KEY_NEST, KEY_TARGET, KEY_HALO, KEY_END };
static const draw_key_t targets_legend[] = {
    [KEY_MOVING] = { 0, "other", DRAW_KEY_ROBOT, 0 },
    [KEY_PICKING] = { DRAW_RGB_HL_YELLOW, "waiting on a target", DRAW_KEY_ROBOT, 0 },
    [KEY_NEST] = { 0xB4B4B4u, "nest", DRAW_KEY_AREA, 0 },
    [KEY_TARGET] = { 0, "target", DRAW_KEY_ITEM, HAL_COLOUR_RED },
    [KEY_HALO] = { 0x9040C0u, "target halo", DRAW_KEY_RING, 0 },
    [KEY_END] = { 0 },
};

typedef struct targets {
    const targets_config_t *cfg;
    uint32_t n_robots;
    uint32_t n_targets;
    sim_item_t *items;         /**< what the camera sees; NaN once picked up */
    int32_t *waiting_on;       /**< per robot: the target it waits on, -1 */
    uint32_t *still;           /**< per robot: its consecutive (0, 0) steps at that target */
    uint32_t pick_steps;       /**< pick_time in control steps */
    uint32_t stop_count;
    uint32_t picked;
    uint32_t in_nest;
    double stop_time_s;        /**< NaN until the stop count is reached */
    double period_s;
} targets_t;

/* ---------------------------------------------------------------- config */

#define TC targets_config_t
static const char *const distribution_choices[] = { "one", "two", "four", "half", "uniform", NULL };
static const char *const half_shape_choices[] = { "cluster", "strip", NULL };

static const param_desc_t targets_params[] = {
    { .key = "distribution", PARAM_ENUM_FIELD(TC, distribution, distribution_choices),
      .doc = "the layout (seed 002 Fig 1): one, two or four clusters, half the square, uniform" },
    { .key = "count", PARAM_FIELD(TC, count, uint32_t), .min = 0, .max = 5000,
      .doc = "targets (seed 002: 200)" },
    { .key = "layout_side", PARAM_FIELD(TC, layout_side, float), .min = 0.01, .max = 1000,
      .doc = "m: side of the square, centred on the nest, the layout is drawn in (kept when "
             "the world grows)" },
    { .key = "cluster_radius", PARAM_FIELD(TC, cluster_radius, float), .min = 0.001, .max = 500,
      .doc = "m: radius of each cluster's disc (one, two, four)" },
    { .key = "cluster_offset", PARAM_FIELD(TC, cluster_offset, float), .min = 0, .max = 500,
      .doc = "m: each cluster centre is this far from the nest along x and along y" },
    { .key = "half_shape", PARAM_ENUM_FIELD(TC, half_shape, half_shape_choices),
      .doc = "distribution half: cluster (half the targets in One's disc, half uniform over the "
             "square) or strip (all uniform over the half x >= nest.x)" },
    { .key = "layout_seed", PARAM_FIELD(TC, layout_seed, uint64_t), .min = 0, .max = 9007199254740991.0,
      .doc = "seed of the layout alone: targets are fixed per world, not per run seed" },
    { .key = "target_radius", PARAM_FIELD(TC, target_radius, float), .min = 0.001, .max = 1,
      .doc = "m" },
    { .key = "target_height", PARAM_FIELD(TC, target_height, float), .min = 0.001, .max = 1,
      .doc = "m (the camera's rows, pictures)" },
    { .key = "pick_time", PARAM_FIELD(TC, pick_time, float), .min = 0.001, .max = 3600,
      .doc = "s a robot stands still, wheels commanded (0, 0), to pick up a target within reach "
             "(rounded to whole control periods)" },
    { .key = "pick_reach", PARAM_FIELD(TC, pick_reach, float), .min = 0, .max = 1,
      .doc = "m: within reach = centre distance <= body radius + target radius + this" },
    { .key = "stop_fraction", PARAM_FIELD(TC, stop_fraction, float), .min = 0, .max = 1,
      .doc = "end the run when ceil(this x count) targets are picked up (0: never)" },
    PARAM_END
};

static const param_desc_t nest_params[] = {
    { .key = "x", PARAM_FIELD(TC, nest.x, float), .min = -500, .max = 500, .doc = "nest centre x, m" },
    { .key = "y", PARAM_FIELD(TC, nest.y, float), .min = -500, .max = 500, .doc = "nest centre y, m" },
    { .key = "radius", PARAM_FIELD(TC, nest.radius, float), .min = 0.01, .max = 500,
      .doc = "nest radius, m (a floor region robots drive over, not an obstacle)" },
    PARAM_END
};
#undef TC

static const param_section_t targets_sections[] = {
    { "nest", nest_params, "the nest: a disc on the floor at the layout's centre" },
    { NULL, NULL, NULL }
};

/* The defaults: seed 002's 50 m world at e-puck scale (k = 0.10 / 0.605,
 * docs/notes/i14_targets.md), the One layout. */
static void targets_default_config(void *config)
{
    targets_config_t *c = config;
    c->distribution = TARGETS_ONE;
    c->count = 200;
    c->layout_side = 8.264f;       /* 50 m x k */
    c->cluster_radius = 0.826f;    /* 5 m x k (a reconstruction) */
    c->cluster_offset = 2.479f;    /* 15 m x k (a reconstruction) */
    c->half_shape = TARGETS_HALF_CLUSTER;   /* a reconstruction (docs/notes/i14_targets.md) */
    c->layout_seed = 1;
    c->target_radius = 0.010f;
    c->target_height = 0.020f;
    c->nest.x = 0.0f;
    c->nest.y = 0.0f;
    c->nest.radius = 0.331f;       /* 2 m x k (a choice) */
    c->pick_time = 5.0f;
    c->pick_reach = 0.010f;
    c->stop_fraction = 0.9f;
}

static int clusters_of(int distribution)
{
    return distribution == TARGETS_ONE ? 1 : distribution == TARGETS_TWO ? 2 : distribution == TARGETS_FOUR ? 4 : 0;
}

/* Whether the layout has a cluster disc (half's cluster shape has One's). */
static int has_disc(const targets_config_t *c)
{
    return clusters_of(c->distribution) > 0
           || (c->distribution == TARGETS_HALF && c->half_shape == TARGETS_HALF_CLUSTER);
}

static int targets_check(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX])
{
    const targets_config_t *c = config;
    double half = c->layout_side / 2.0;
    if (!scenario_inside_arena(sc, c->nest.x, c->nest.y, c->nest.radius, c->nest.radius)) {
        snprintf(key, 64, "nest");
        scenario_outside_message(sc, "the nest disc reaches", msg, SIM_ERR_MAX);
        return -1;
    }
    if (!scenario_inside_arena(sc, c->nest.x, c->nest.y, half, half)) {
        snprintf(key, 64, "layout_side");
        scenario_outside_message(sc, "the layout square (centred on the nest) reaches", msg, SIM_ERR_MAX);
        return -1;
    }
    if (c->nest.radius >= half) {
        snprintf(key, 64, "nest.radius");
        snprintf(msg, SIM_ERR_MAX, "the nest (radius %g m) must lie inside the layout square (half side %g m)",
                 c->nest.radius, half);
        return -1;
    }
    if (has_disc(c) && c->cluster_offset + c->cluster_radius > half) {
        snprintf(key, 64, "cluster_offset");
        snprintf(msg, SIM_ERR_MAX, "a cluster reaches out of the layout square: cluster_offset + cluster_radius "
                 "= %g m > layout_side / 2 = %g m", c->cluster_offset + c->cluster_radius, half);
        return -1;
    }
    if (c->pick_time * 1000.0 < sc->control_period_ms * 0.5) {
        snprintf(key, 64, "pick_time");
        snprintf(msg, SIM_ERR_MAX, "%g s is less than half a control period (%u ms): it rounds to no step",
                 c->pick_time, sc->control_period_ms);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- layout */

uint32_t targets_stop_count(const targets_config_t *c)
{
    /* 0.9f x 200 is 179.99999...: the small slack makes it 180, not 181. */
    double n = ceil((double)c->stop_fraction * c->count - 1e-4);
    return c->stop_fraction > 0.0f ? (uint32_t)fmax(n, 0.0) : 0u;
}

/* A candidate for target k of the layout, relative to the nest. */
static void draw_candidate(const targets_config_t *c, sim_rand_t *r, uint32_t k, float *x, float *y)
{
    static const float sx[4] = { 1, -1, -1, 1 }, sy[4] = { 1, -1, 1, -1 };
    float half = c->layout_side / 2.0f;
    int clusters = clusters_of(c->distribution);
    if (c->distribution == TARGETS_HALF && c->half_shape == TARGETS_HALF_CLUSTER) {
        clusters = (k % 2u == 0u) ? 1 : 0;   /* even: One's disc; odd: the square */
    }
    if (clusters > 0) {
        /* One (+,+); two (+,+) and (-,-) on a diagonal; four: every corner. */
        int q = (int)(k % (uint32_t)clusters);
        double rho = c->cluster_radius * sqrt(sim_rand_uniform(r)), phi = 2.0 * UNITS_PI * sim_rand_uniform(r);
        *x = sx[q] * c->cluster_offset + (float)(rho * cos(phi));
        *y = sy[q] * c->cluster_offset + (float)(rho * sin(phi));
    } else if (c->distribution == TARGETS_HALF && c->half_shape == TARGETS_HALF_STRIP) {
        *x = (float)(sim_rand_uniform(r) * half);
        *y = (float)((2.0 * sim_rand_uniform(r) - 1.0) * half);
    } else {
        *x = (float)((2.0 * sim_rand_uniform(r) - 1.0) * half);
        *y = (float)((2.0 * sim_rand_uniform(r) - 1.0) * half);
    }
}

int targets_layout(const targets_config_t *c, float *x, float *y, char err[SIM_ERR_MAX])
{
    sim_rand_t r;
    float tr = c->target_radius, half = c->layout_side / 2.0f - tr;
    float keep_out = c->nest.radius + tr, apart = 2.0f * tr;
    sim_rand_seed(&r, c->layout_seed, LAYOUT_STREAM, RAND_TASK);
    for (uint32_t k = 0; k < c->count; k++) {
        int placed = 0;
        for (int tries = 0; tries < PLACE_TRIES && !placed; tries++) {
            float px, py;
            draw_candidate(c, &r, k, &px, &py);
            placed = fabsf(px) <= half && fabsf(py) <= half && px * px + py * py > keep_out * keep_out;
            for (uint32_t j = 0; placed && j < k; j++) {
                float dx = px - (x[j] - c->nest.x), dy = py - (y[j] - c->nest.y);
                placed = dx * dx + dy * dy >= apart * apart;
            }
            x[k] = c->nest.x + px;
            y[k] = c->nest.y + py;
        }
        if (!placed) {
            snprintf(err, SIM_ERR_MAX, "cannot place target %u of %u: no room left in its region outside the "
                     "nest (targets may not overlap)", k + 1, c->count);
            return -1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- a run */

static void targets_destroy(void *self)
{
    targets_t *t = self;
    if (t) {
        free(t->items);
        free(t->waiting_on);
        free(t->still);
        free(t);
    }
}

static void *targets_create(sim_t *sim, const void *config, char err[SIM_ERR_MAX])
{
    const targets_config_t *c = config;
    const scenario_t *sc = sim_scenario(sim);
    targets_t *t = calloc(1, sizeof *t);
    uint32_t n = sim_robot_count(sim), n1 = n ? n : 1, m1 = c->count ? c->count : 1;
    float *x = malloc(m1 * sizeof *x), *y = malloc(m1 * sizeof *y);
    if (!t || !x || !y || !(t->items = calloc(m1, sizeof *t->items))
        || !(t->waiting_on = malloc(n1 * sizeof *t->waiting_on)) || !(t->still = calloc(n1, sizeof *t->still))) {
        snprintf(err, SIM_ERR_MAX, "out of memory for %u targets", c->count);
        free(x);
        free(y);
        targets_destroy(t);
        return NULL;
    }
    if (targets_layout(c, x, y, err) != 0) {
        free(x);
        free(y);
        targets_destroy(t);
        return NULL;
    }
    t->cfg = c;
    t->n_robots = n;
    t->n_targets = c->count;
    for (uint32_t k = 0; k < c->count; k++) {
        t->items[k] = (sim_item_t){ x[k], y[k], c->target_radius, c->target_height,
                                    targets_legend[KEY_TARGET].colour };
    }
    free(x);
    free(y);
    for (uint32_t i = 0; i < n; i++) {
        t->waiting_on[i] = -1;
    }
    t->period_s = sc->control_period_ms / 1000.0;
    t->pick_steps = (uint32_t)fmax(1.0, floor(c->pick_time / t->period_s + 0.5));
    t->stop_count = targets_stop_count(c);
    t->stop_time_s = NAN;
    return t;
}

static int within_reach(const targets_t *t, double x, double y, uint32_t k)
{
    double reach = EPUCK_BODY_RADIUS_M + t->cfg->target_radius + t->cfg->pick_reach;
    double dx = t->items[k].x - x, dy = t->items[k].y - y;
    return isfinite(t->items[k].x) && dx * dx + dy * dy <= reach * reach;
}

/* The nearest target left within reach of (x, y), or -1. */
static int32_t nearest_within_reach(const targets_t *t, double x, double y)
{
    int32_t best = -1;
    double best_d2 = INFINITY;
    for (uint32_t k = 0; k < t->n_targets; k++) {
        double dx = t->items[k].x - x, dy = t->items[k].y - y, d2 = dx * dx + dy * dy;
        if (within_reach(t, x, y, k) && d2 < best_d2) {
            best = (int32_t)k;
            best_d2 = d2;
        }
    }
    return best;
}

/* After control (task.h, phase 4): the wheels this step were commanded;
 * the poses are the step's start.  Robots in id order. */
static void targets_pick_up(void *self, sim_t *sim)
{
    targets_t *t = self;
    for (uint32_t i = 0; i < t->n_robots; i++) {
        int16_t l, r;
        double x, y, th;
        sim_robot_wheels(sim, i, &l, &r);
        if (l != 0 || r != 0) {   /* moving: any wait starts over */
            t->waiting_on[i] = -1;
            t->still[i] = 0;
            continue;
        }
        sim_robot_pose(sim, i, &x, &y, &th);
        int32_t k = t->waiting_on[i];
        if (k < 0 || !within_reach(t, x, y, (uint32_t)k)) {
            /* Its target was taken, or it was pushed away: a new wait. */
            k = nearest_within_reach(t, x, y);
            t->waiting_on[i] = k;
            t->still[i] = 0;
            if (k < 0) {
                continue;
            }
        }
        if (++t->still[i] < t->pick_steps) {
            continue;
        }
        t->items[k].x = t->items[k].y = NAN;
        t->waiting_on[i] = -1;
        t->still[i] = 0;
        t->picked++;
        sim_event(sim, i, "pickup", "", k);
        if (t->stop_count > 0 && t->picked == t->stop_count) {
            /* This step's end: the time the core's completion_time_s gives. */
            t->stop_time_s = (double)(sim_step_count(sim) + 1) * t->period_s;
        }
    }
}

/* After physics: robots in the nest. */
static void targets_count_nest(void *self, sim_t *sim)
{
    targets_t *t = self;
    double r2 = (double)t->cfg->nest.radius * t->cfg->nest.radius;
    t->in_nest = 0;
    for (uint32_t i = 0; i < t->n_robots; i++) {
        double x, y, th;
        sim_robot_pose(sim, i, &x, &y, &th);
        x -= t->cfg->nest.x;
        y -= t->cfg->nest.y;
        t->in_nest += x * x + y * y <= r2;
    }
}

static uint32_t targets_items(const void *self, const sim_item_t **items)
{
    const targets_t *t = self;
    *items = t->items;
    return t->n_targets;
}

/* ---------------------------------------------------------------- outputs */

static const metric_desc_t targets_columns[] = {
    { "picked", "targets", "targets picked up so far" },
    { "in_nest", "robots", "robots whose centre is in the nest disc" },
    { NULL, NULL, NULL }
};

static void targets_sample(const void *self, const sim_t *sim, double *v)
{
    const targets_t *t = self;
    (void)sim;
    v[0] = t->picked;
    v[1] = t->in_nest;
}

static const metric_desc_t targets_summary[] = {
    { "time_to_stop_s", "s", "when stop_count targets had been picked up (null: not within the run)" },
    { "finished", "", "1 when the stop count was reached within the run's duration" },
    { "time_capped_s", "s", "time_to_stop_s, or the run's length when it did not finish (a censored time)" },
    { "picked", "targets", "targets picked up" },
    { "targets", "targets", "targets at the start" },
    { "stop_count", "targets", "ceil(stop_fraction x targets): tp of seed 002's eq 7" },
    { "robots", "robots", "n: every robot of the run (each can pick up)" },
    { "efficiency", "targets/(robot s)", "eq 7: E_n = tp / (n t_tp), tp = stop_count (null: not finished)" },
    { NULL, NULL, NULL }
};

static void targets_final(const void *self, const sim_t *sim, double *v)
{
    const targets_t *t = self;
    int finished = isfinite(t->stop_time_s);
    v[0] = t->stop_time_s;
    v[1] = finished;
    v[2] = finished ? t->stop_time_s : sim_time_s(sim);
    v[3] = t->picked;
    v[4] = t->n_targets;
    v[5] = t->stop_count;
    v[6] = t->n_robots;
    v[7] = finished && t->n_robots > 0 ? t->stop_count / (t->n_robots * t->stop_time_s) : NAN;
}

static void targets_draw(const void *self, const sim_t *sim, drawing_t *out)
{
    const targets_t *t = self;
    const targets_config_t *c = t->cfg;
    float halo = fmaxf(HALO_RADII * c->target_radius, HALO_SIDE_SHARE * c->layout_side);
    draw_shape_t nest = { .kind = DRAW_DISC, .layer = DRAW_FLOOR, .rgb = targets_legend[KEY_NEST].rgb, .x = c->nest.x,
                          .y = c->nest.y, .radius = c->nest.radius };
    draw_shape_t cross = { .kind = DRAW_LINE, .layer = DRAW_FLOOR, .rgb = 0x000000u, .line = 0.0f };
    draw_shape_t label = { .kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = 0x303030u,
                           .x = c->nest.x - c->nest.radius, .y = c->nest.y + c->nest.radius + 0.03f };
    (void)sim;
    drawing_add(out, &nest);
    /* The paper's black '+' at the nest. */
    cross.x = c->nest.x - c->nest.radius / 3;
    cross.x2 = c->nest.x + c->nest.radius / 3;
    cross.y = cross.y2 = c->nest.y;
    drawing_add(out, &cross);
    cross.x = cross.x2 = c->nest.x;
    cross.y = c->nest.y - c->nest.radius / 3;
    cross.y2 = c->nest.y + c->nest.radius / 3;
    drawing_add(out, &cross);
    for (uint32_t k = 0; k < t->n_targets; k++) {
        if (isfinite(t->items[k].x)) {
            draw_shape_t h = { .kind = DRAW_RING, .layer = DRAW_FLOOR, .rgb = targets_legend[KEY_HALO].rgb,
                               .x = t->items[k].x, .y = t->items[k].y, .radius = halo, .line = 0.0f };
            drawing_add(out, &h);
        }
    }
    snprintf(label.text, sizeof label.text, "PICKED %u/%u", t->picked, t->n_targets);
    drawing_add(out, &label);
    for (uint32_t i = 0; i < t->n_robots && i < out->robot_count; i++) {
        if (t->waiting_on[i] >= 0) {
            out->robot_rgb[i] = targets_legend[KEY_PICKING].rgb;
        }
    }
}

static int targets_done(const void *self, const sim_t *sim)
{
    const targets_t *t = self;
    (void)sim;
    return t->stop_count > 0 && t->picked >= t->stop_count;
}

/* Robots of these controllers need seed 002's world: the RepAtt firmware
 * (its random walk is the same firmware with gains 1). */
static const char *const targets_controllers[] = { "repatt", NULL };

/* What create allocates: per target and per robot. */
static size_t targets_memory(const void *config, const scenario_t *sc)
{
    const targets_config_t *c = config;
    const targets_t *t = NULL;
    return sizeof *t + (size_t)c->count * (sizeof *t->items + 2 * sizeof(float))
           + scenario_robot_count(sc) * (sizeof *t->waiting_on + sizeof *t->still);
}

const task_def_t targets_task = {
    .name = "targets",
    .doc = "seed 002: red targets in Fig 1's layouts, a central nest, 5 s pick-ups, stop at 90 %",
    .config_size = sizeof(targets_config_t),
    .memory = targets_memory,
    .params = targets_params,
    .sections = targets_sections,
    .default_config = targets_default_config,
    .controllers = targets_controllers,
    .check = targets_check,
    .create = targets_create,
    .destroy = targets_destroy,
    .after_control = targets_pick_up,
    .after_physics = targets_count_nest,
    .items = targets_items,
    .columns = targets_columns,
    .sample = targets_sample,
    .summary = targets_summary,
    .final = targets_final,
    .draw = targets_draw,
    .legend = targets_legend,
    .done = targets_done,
};

/* ---------------------------------------------------------------- for tests */

int targets_truth(const sim_t *sim, targets_truth_t *out)
{
    const targets_t *t = sim_task(sim, &targets_task);
    if (!t) {
        return 0;
    }
    out->count = t->n_targets;
    out->picked = t->picked;
    out->in_nest = t->in_nest;
    out->stop_time_s = t->stop_time_s;
    return 1;
}

const sim_item_t *targets_item(const sim_t *sim, uint32_t k)
{
    const targets_t *t = sim_task(sim, &targets_task);
    return t && k < t->n_targets ? &t->items[k] : NULL;
}
