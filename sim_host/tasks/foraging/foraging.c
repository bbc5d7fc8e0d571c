/*
 * foraging.c - food tokens, the passive gripper, deliveries and the
 * ground-truth nest ledger of seed 000 (foraging.h), as a task plug-in.
 */
#include "foraging.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "swarmsim/geometry.h"
#include "swarmsim/grid.h"
#include "swarmsim/rand.h"
#include "foraging/forager.h"
#include "foraging/forager_sense_all.h"
#include "foraging/nest_beacon.h"
#include "foraging/nest_link.h"
#include "units.h"

/* The gripper takes a token whose centre comes within its radius plus this
 * of the robot's front point, and holds it this far ahead of the lens. */
#define GRASP_TOLERANCE 0.025f
#define CARRY_GAP 0.005f
#define PLACE_TRIES 100000
/* Drawing: robots by task state, the grey nest floor, the red food (the
 * legend's table is the one place their colours are set). */
enum { KEY_WAITING, KEY_SEARCHING, KEY_RETURNING, KEY_BEACON, KEY_NEST, KEY_FOOD, KEY_END };
static const draw_key_t foraging_legend[] = {
    [KEY_WAITING] = { 0, "waiting", DRAW_KEY_ROBOT, 0 },
    [KEY_SEARCHING] = { DRAW_RGB_HL_GREEN, "searching", DRAW_KEY_ROBOT, 0 },
    [KEY_RETURNING] = { DRAW_RGB_HL_YELLOW, "returning", DRAW_KEY_ROBOT, 0 },
    [KEY_BEACON] = { DRAW_RGB_HL_BLUE, "beacon", DRAW_KEY_ROBOT, 0 },
    [KEY_NEST] = { 0xB4B4B4u, "nest", DRAW_KEY_AREA, 0 },
    [KEY_FOOD] = { 0, "food", DRAW_KEY_ITEM, HAL_COLOUR_RED },
    [KEY_END] = { 0 },
};

typedef struct foraging {
    const foraging_config_t *cfg;
    uint32_t n_robots;
    uint8_t *is_forager;     /**< per robot: runs the forager (has the gripper) */
    uint32_t n_foragers;     /**< N_r */
    int64_t beacon;          /**< the nest beacon's robot index, -1 without one */
    int64_t *leave_step;     /**< per robot: step it chose S_S inside the nest, -1 otherwise */
    uint64_t exit_steps, exits;   /**< steps from that choice to out of the nest, summed; how many */
    double beacon_error_sum, beacon_error_max;   /**< |F_beacon - F| over the steps */
    char *task;              /**< per robot: last task state 'W', 'S', 'R' (foragers) */

    uint32_t n_tokens;
    sim_item_t *tokens;      /**< what the camera sees */
    int32_t *carrier;        /**< per token: robot index, or -1 on the floor */
    int32_t *carried;        /**< per robot: token index or -1 */
    sim_rand_t rand;         /**< token placement */
    /* The grasp's index: tokens on the floor binned once a step, so that a
     * gripper looks at the tokens near it, not at every token. */
    grid_t token_grid;
    float *floor_x, *floor_y;   /**< per token: its centre, NaN when carried or out of play */
    uint32_t *near;          /**< per token: grid_gather's working memory */

    uint64_t delivered;      /**< tokens deposited in the nest */
    uint64_t dropped;        /**< tokens let go outside the nest */
    uint64_t forage_steps;   /**< robot-steps spent in S_S or S_R */
    uint64_t search_steps;   /**< of them, in S_S */
    uint64_t oae_at_nest;    /**< OAEs counted by foragers at the nest (nest_reach) */
    uint32_t *last_oae;      /**< per robot: its OAE count after the last step */
    double wait_radius_sum;  /**< sum over steps and waiting foragers of their distance from
                                  the nest centre, m */
    uint64_t wait_steps;     /**< robot-steps in S_W */
    uint64_t oae_seen;       /**< OAEs already charged */
    double nest_units;       /**< energy the nest consumed, units */
    double food;             /**< F(t), tokens */
    double deviation_sum;    /**< sum over steps of |F_d - F(t)| */
    uint32_t waiting, searching, returning;   /**< foragers by task state now */
    uint32_t *oae_window;    /**< the foragers' OAEs per step over the last T2 (global info) */
    uint32_t window_len, window_pos;
    uint64_t window_sum;
} foraging_t;

/* ---------------------------------------------------------------- config */

#define FC foraging_config_t
static const char *const information_choices[] = { "beacon", "global", NULL };

static const param_desc_t foraging_params[] = {
    { .key = "food_count", PARAM_FIELD(FC, food_count, uint32_t), .min = 0, .max = 1000000,
      .doc = "N_f, food tokens kept in the arena (one respawns per delivery)" },
    { .key = "token_radius", PARAM_FIELD(FC, token_radius, float), .min = 0.005, .max = 0.5,
      .doc = "token radius, m" },
    { .key = "token_height", PARAM_FIELD(FC, token_height, float), .min = 0.005, .max = 1,
      .doc = "token height, m" },
    { .key = "token_energy", PARAM_FIELD(FC, token_energy, float), .min = 1, .max = 1e9,
      .doc = "energy units per food token" },
    { .key = "initial_food", PARAM_FIELD(FC, initial_food, float), .min = -1e6, .max = 1e6,
      .doc = "F(0), food tokens in the nest at the start" },
    { .key = "desired_food", PARAM_FIELD(FC, desired_food, float), .min = -1e6, .max = 1e6,
      .doc = "F_d, desired food tokens in the nest" },
    { .key = "consumption", PARAM_FIELD(FC, consumption, float), .min = 0, .max = 1e6,
      .doc = "C_rate, food the nest consumes, tokens/min" },
    { .key = "move_cost", PARAM_FIELD(FC, move_cost, float), .min = 0, .max = 1e9,
      .doc = "energy units per step per foraging robot" },
    { .key = "oae_energy", PARAM_FIELD(FC, oae_energy, float), .min = 0, .max = 1e9,
      .doc = "E_a, energy units per obstacle-avoidance event" },
    { .key = "robot_speed", PARAM_FIELD(FC, robot_speed, float), .min = 0.001, .max = 0.128,
      .doc = "v, forager speed, m/s (seed 000: 0.05); sets T2 = L/(2v)" },
    { .key = "information", PARAM_ENUM_FIELD(FC, information, information_choices),
      .doc = "beacon: a nest_beacon group keeps the ledger; global: ideal information" },
    PARAM_END
};

static const param_desc_t nest_params[] = {
    { .key = "x", PARAM_FIELD(FC, nest.x, float), .min = -500, .max = 500, .doc = "nest centre x, m" },
    { .key = "y", PARAM_FIELD(FC, nest.y, float), .min = -500, .max = 500, .doc = "nest centre y, m" },
    { .key = "diameter", PARAM_FIELD(FC, nest.diameter, float), .min = 0.01, .max = 1000,
      .doc = "d, nest diameter, m" },
    PARAM_END
};
#undef FC

static const param_section_t foraging_sections[] = {
    { "nest", nest_params, "the nest: a grey floor circle" },
    { NULL, NULL, NULL }
};

static void foraging_default_config(void *config)
{
    foraging_config_t *c = config;
    c->nest.x = 0.0f;
    c->nest.y = 0.0f;
    c->nest.diameter = 1.5f;
    c->food_count = 20;
    c->token_radius = 0.0175f;
    c->token_height = 0.042f;
    c->token_energy = 1500.0f;
    c->initial_food = 5.0f;
    c->desired_food = 20.0f;
    c->consumption = 2.0f;
    c->move_cost = 1.0f;
    c->oae_energy = 10.0f;
    c->robot_speed = 0.05f;
    c->information = FORAGING_INFO_BEACON;
}

/* The full-sensing benchmark's forager is a forager to the task (its state
 * begins with a forager_t, forager_sense_all.h). */
static int runs_forager(const controller_def_t *def)
{
    return def == &forager_def || def == &forager_sense_all_def;
}

static uint32_t robots_running(const scenario_t *sc, const controller_def_t *def)
{
    uint32_t n = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const controller_def_t *d = sc->groups[g].def;
        n += (d == def || (def == &forager_def && runs_forager(d))) ? sc->groups[g].count : 0;
    }
    return n;
}

static int foraging_check(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX])
{
    const foraging_config_t *c = config;
    double r = c->nest.diameter / 2.0;
    uint32_t beacons = robots_running(sc, &nest_beacon_def);
    if (!scenario_inside_arena(sc, c->nest.x, c->nest.y, r, r)) {
        snprintf(key, 64, "nest");
        scenario_outside_message(sc, "the nest circle reaches", msg, SIM_ERR_MAX);
        return -1;
    }
    if (c->information == FORAGING_INFO_BEACON && beacons != 1) {
        snprintf(key, 64, "information");
        snprintf(msg, SIM_ERR_MAX, "'beacon' needs one robot running nest_beacon at the nest (the scenario "
                 "has %u); add a group {count: 1, controller: nest_beacon, moves: false} or use "
                 "'global'", beacons);
        return -1;
    }
    if (c->information == FORAGING_INFO_GLOBAL && beacons != 0) {
        snprintf(key, 64, "information");
        snprintf(msg, SIM_ERR_MAX, "'global' replaces the nest beacon by the simulator: remove the "
                 "nest_beacon group (or set its count to 0)");
        return -1;
    }
    /* The beacon keeps its ledger in whole energy units (uint16 constants)
     * and the consumption in 1/1000 token per minute: a value it cannot
     * hold would make its ledger and the ground truth differ silently. */
    const struct { const char *key; double v, scale; } held[] = {
        { "token_energy", c->token_energy, 1.0 }, { "move_cost", c->move_cost, 1.0 },
        { "oae_energy", c->oae_energy, 1.0 }, { "consumption", c->consumption, 1000.0 },
    };
    for (size_t i = 0; c->information == FORAGING_INFO_BEACON && i < sizeof held / sizeof held[0]; i++) {
        double u = held[i].v * held[i].scale;
        if (fabs(u - round(u)) > 1e-6 * fmax(1.0, fabs(u)) || u > 65535.0) {
            snprintf(key, 64, "%s", held[i].key);
            snprintf(msg, SIM_ERR_MAX, "%g is not what the nest beacon can count: it holds %s up to %g (use "
                     "such a value, or information: global)", held[i].v,
                     held[i].scale > 1.0 ? "multiples of 0.001 token/min" : "whole energy units",
                     65535.0 / held[i].scale);
            return -1;
        }
    }
    return 0;
}

/* The arena's side L for eq 4 (k = active / L^2) and T2 = L / (2 v): the
 * side of the square of the same area, so that a rectangle's L^2 is its
 * area (seed 000's arenas are square; its robot arena is 1.2 x 1.5 m). */
static double arena_side(const scenario_t *sc)
{
    return sqrt((double)sc->arena.width * (double)sc->arena.height);
}

/* T2 = L / (2 v) (seed 000, eq 5), s: the window of M_A. */
static double t2_s(const scenario_t *sc, const foraging_config_t *c)
{
    return arena_side(sc) / (2.0 * c->robot_speed);
}

/* What a robot is built with (seed 000): the forager knows F_d, N_r, L, the
 * nest radius and its speed; the beacon the ledger's constants and T2. */
static void foraging_configure(const void *config, const scenario_t *sc, const robot_group_t *group,
                               void *params)
{
    const foraging_config_t *c = config;
    if (runs_forager(group->def)) {
        forager_params_t *p = params;
        p->f_d_tokens = c->desired_food;
        p->n_robots = (uint16_t)robots_running(sc, &forager_def);
        p->arena_l_mm = (uint16_t)lround(fmin(arena_side(sc), 65.535) * 1000.0);
        p->nest_radius_mm = (uint16_t)lround(fmin(c->nest.diameter / 2.0, 65.535) * 1000.0);
        p->speed_steps_s = (int16_t)lround(fmin(c->robot_speed / EPUCK_STEP_M, 1000.0));
        p->walk.speed_steps_s = p->speed_steps_s;
    } else if (group->def == &nest_beacon_def) {
        nest_beacon_params_t *p = params;
        p->n_robots = (uint16_t)robots_running(sc, &forager_def);
        p->f0_tokens = (int16_t)lround(c->initial_food);
        p->token_energy = (uint16_t)lround(fmin(c->token_energy, 65535.0));
        p->c_rate_milli_tokens_per_min = (uint16_t)lround(fmin(c->consumption * 1000.0, 65535.0));
        p->move_cost = (uint16_t)lround(fmin(c->move_cost, 65535.0));
        p->e_a = (uint16_t)lround(fmin(c->oae_energy, 65535.0));
        p->t2_steps = (uint16_t)lround(fmin(t2_s(sc, c) * 1000.0 / sc->control_period_ms, 65535.0));
    }
}

/* ---------------------------------------------------------------- tokens */

static float nest_radius(const foraging_t *f) { return f->cfg->nest.diameter / 2.0f; }

static int in_nest(const foraging_t *f, float x, float y)
{
    float dx = x - f->cfg->nest.x, dy = y - f->cfg->nest.y, r = nest_radius(f);
    return dx * dx + dy * dy < r * r;
}

/* An OAE counts as at the nest when the robot's centre is within this of
 * the nest's rim or inside it (a robot avoiding another at the rim from
 * outside is a body length out), m. */
#define NEST_REACH 0.1f

static double nest_distance(const foraging_t *f, double x, double y)
{
    return hypot(x - f->cfg->nest.x, y - f->cfg->nest.y);
}

/* nest_distance(f, x, y) < reach, as that comparison decides, with hypot
 * called only within a hair of the rim: the squared distance decides the
 * rest (hypot is within an ulp of the exact root and the square within
 * two ulps of the exact square, so a relative margin of 1e-12 leaves no case
 * the two answer differently; NaN falls through to hypot).  Every robot
 * is tested every step: hypot was 2 % of full sensing at 10,000 robots,
 * all of it on the stepping thread. */
static int near_nest(const foraging_t *f, double x, double y, double reach)
{
    double dx = x - f->cfg->nest.x, dy = y - f->cfg->nest.y;
    double d2 = dx * dx + dy * dy, r2 = reach * reach;
    if (d2 < r2 * (1.0 - 1e-12)) {
        return 1;
    }
    if (d2 > r2 * (1.0 + 1e-12)) {
        return 0;
    }
    return hypot(dx, dy) < reach;
}

/* A free spot for token k: inside the walls, outside the nest, off the
 * obstacles.  Returns 0, or -1 when the arena has no room. */
static int place_token(foraging_t *f, const sim_t *sim, uint32_t k)
{
    float r = f->cfg->token_radius, margin = r + 0.01f, hw, hh;
    sim_arena_half(sim, &hw, &hh);
    for (int tries = 0; tries < PLACE_TRIES; tries++) {
        float x = (float)((2 * sim_rand_uniform(&f->rand) - 1) * (hw - margin));
        float y = (float)((2 * sim_rand_uniform(&f->rand) - 1) * (hh - margin));
        float dx = x - f->cfg->nest.x, dy = y - f->cfg->nest.y, nr = nest_radius(f) + r;
        int ok = dx * dx + dy * dy > nr * nr;
        for (uint32_t o = 0; ok && o < sim_obstacle_count(sim); o++) {
            float b[4];
            sim_obstacle_bounds(sim, o, b);
            ok = x < b[0] - r || x > b[2] + r || y < b[1] - r || y > b[3] + r;
        }
        if (ok) {
            f->tokens[k].x = x;
            f->tokens[k].y = y;
            f->carrier[k] = -1;
            return 0;
        }
    }
    return -1;
}

static void foraging_destroy(void *self)
{
    foraging_t *f = self;
    if (!f) {
        return;
    }
    free(f->is_forager);
    free(f->task);
    free(f->leave_step);
    free(f->last_oae);
    free(f->tokens);
    free(f->carrier);
    free(f->carried);
    free(f->oae_window);
    free(f->floor_x);
    free(f->floor_y);
    free(f->near);
    grid_free(&f->token_grid);
    free(f);
}

static void *foraging_create(sim_t *sim, const void *config, char err[SIM_ERR_MAX])
{
    const foraging_config_t *c = config;
    const scenario_t *sc = sim_scenario(sim);
    foraging_t *f = calloc(1, sizeof *f);
    uint32_t n = sim_robot_count(sim), n1 = n ? n : 1;
    if (!f) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the foraging task");
        return NULL;
    }
    f->cfg = c;
    f->n_robots = n;
    f->n_tokens = c->food_count;
    f->is_forager = calloc(n1, 1);
    f->task = calloc(n1, 1);
    f->leave_step = malloc(n1 * sizeof *f->leave_step);
    f->last_oae = calloc(n1, sizeof *f->last_oae);
    f->tokens = calloc(f->n_tokens ? f->n_tokens : 1, sizeof *f->tokens);
    f->carrier = calloc(f->n_tokens ? f->n_tokens : 1, sizeof *f->carrier);
    f->carried = malloc(n1 * sizeof *f->carried);
    /* T2 in control steps. */
    f->window_len = (uint32_t)fmax(1.0, floor(t2_s(sc, c) * 1000.0 / sc->control_period_ms + 0.5));
    f->oae_window = calloc(f->window_len, sizeof *f->oae_window);
    size_t nt = f->n_tokens ? f->n_tokens : 1;
    f->floor_x = malloc(nt * sizeof *f->floor_x);
    f->floor_y = malloc(nt * sizeof *f->floor_y);
    f->near = malloc(nt * sizeof *f->near);
    float hw, hh;
    sim_arena_half(sim, &hw, &hh);
    /* Cells of 0.5 m: a grasp's reach (a few cm) meets at most 4 of them,
     * and at seed 000's density (20 tokens on 16 m^2) a cell holds ~0.3. */
    int grid_bad = grid_init(&f->token_grid, -hw, -hh, 2 * hw, 2 * hh, 0.5f) != 0
                   || grid_reserve(&f->token_grid, nt) != 0;
    if (!f->is_forager || !f->task || !f->leave_step || !f->last_oae || !f->tokens || !f->carrier || !f->carried
        || !f->oae_window || !f->floor_x || !f->floor_y || !f->near || grid_bad) {
        snprintf(err, SIM_ERR_MAX, "out of memory for %u food tokens", f->n_tokens);
        foraging_destroy(f);
        return NULL;
    }
    f->beacon = -1;
    for (uint32_t i = 0; i < n; i++) {
        f->carried[i] = -1;
        f->leave_step[i] = -1;
        f->is_forager[i] = (uint8_t)runs_forager(sim_robot_def(sim, i));
        if (sim_robot_def(sim, i) == &nest_beacon_def) {
            f->beacon = (int64_t)i;
        }
        f->n_foragers += f->is_forager[i];
        f->task[i] = f->is_forager[i] ? 'W' : 0;
    }
    sim_task_rand_seed(sim, &foraging_task, 0, &f->rand);
    for (uint32_t k = 0; k < f->n_tokens; k++) {
        f->tokens[k].radius = c->token_radius;
        f->tokens[k].height = c->token_height;
        f->tokens[k].colour = foraging_legend[KEY_FOOD].colour;
        if (place_token(f, sim, k) != 0) {
            snprintf(err, SIM_ERR_MAX, "cannot place food token %u of %u outside the nest and obstacles",
                     k + 1, f->n_tokens);
            foraging_destroy(f);
            return NULL;
        }
    }
    f->food = c->initial_food;
    return f;
}

static int backing(const sim_t *sim, uint32_t i)
{
    int16_t l, r;
    sim_robot_wheels(sim, i, &l, &r);
    return l < 0 && r < 0;
}

/* Before physics: foragers backing up let go of their tokens. */
static void foraging_release(void *self, sim_t *sim)
{
    foraging_t *f = self;
    for (uint32_t i = 0; i < f->n_robots; i++) {
        int32_t k = f->carried[i];
        if (k < 0 || !backing(sim, i)) {
            continue;
        }
        f->carried[i] = -1;
        f->carrier[k] = -1;
        if (in_nest(f, f->tokens[k].x, f->tokens[k].y)) {
            f->delivered++;
            sim_event(sim, i, "deposit", "", k);
            /* A new token appears at random; if none fits, the delivered one
             * stays out of play. */
            if (place_token(f, sim, (uint32_t)k) != 0) {
                f->tokens[k].x = f->tokens[k].y = NAN;
            }
        } else {
            f->dropped++;
            sim_event(sim, i, "token_dropped", "let go outside the nest", k);
        }
    }
}

/* The first token by index (as a scan of every token would find it) on the
 * floor within reach of the front point (fx, fy), or -1. */
static int32_t token_in_reach(const foraging_t *f, float fx, float fy, float reach)
{
    /* The box is a little larger than the reach: binning and this test
     * round differently. */
    float m = reach + 0.01f;
    uint32_t n = grid_gather(&f->token_grid, fx - m, fy - m, fx + m, fy + m, f->near, f->n_tokens);
    int32_t best = -1;
    for (uint32_t c = 0; c < n; c++) {
        uint32_t k = f->near[c];
        float dx = f->tokens[k].x - fx, dy = f->tokens[k].y - fy;
        if (f->carrier[k] < 0 && dx * dx + dy * dy < reach * reach && (best < 0 || k < (uint32_t)best)) {
            best = (int32_t)k;
        }
    }
    return best;
}

static void carry_and_grasp(foraging_t *f, sim_t *sim)
{
    float tr = f->cfg->token_radius, reach = tr + GRASP_TOLERANCE;
    /* Tokens on the floor do not move during the loop (a token picked up
     * is then skipped by its carrier), so one binning serves every robot. */
    for (uint32_t k = 0; k < f->n_tokens; k++) {
        int floor = f->carrier[k] < 0;
        f->floor_x[k] = floor ? f->tokens[k].x : NAN;
        f->floor_y[k] = floor ? f->tokens[k].y : NAN;
    }
    if (grid_build_points(&f->token_grid, f->floor_x, f->floor_y, f->n_tokens) != 0) {
        sim_out_of_memory("the foraging task's token grid");
    }
    for (uint32_t i = 0; i < f->n_robots; i++) {
        double px, py, pt;
        if (!f->is_forager[i]) {
            continue;
        }
        sim_robot_pose(sim, i, &px, &py, &pt);
        float x = (float)px, y = (float)py, theta = (float)pt;
        float c = cosf(theta), s = sinf(theta);
        if (f->carried[i] < 0 && !backing(sim, i)) {
            float fx = x + EPUCK_BODY_RADIUS_M * c, fy = y + EPUCK_BODY_RADIUS_M * s;
            int32_t k = token_in_reach(f, fx, fy, reach);
            if (k >= 0) {
                f->carrier[k] = (int32_t)i;
                f->carried[i] = k;
                sim_event(sim, i, "pickup", "", k);
            }
        }
        if (f->carried[i] >= 0) {
            sim_item_t *t = &f->tokens[f->carried[i]];
            float ahead = EPUCK_BODY_RADIUS_M + tr + CARRY_GAP;
            t->x = x + ahead * c;
            t->y = y + ahead * s;
        }
    }
}

static double balance(const foraging_t *f)
{
    const foraging_config_t *c = f->cfg;
    double spent = f->nest_units + c->move_cost * (double)f->forage_steps + c->oae_energy * (double)f->oae_seen;
    return c->initial_food + (double)f->delivered - spent / c->token_energy;
}

/* After physics: carried tokens follow, grippers pick up, energy is charged. */
static void foraging_update(void *self, sim_t *sim)
{
    foraging_t *f = self;
    const foraging_config_t *c = f->cfg;
    carry_and_grasp(f, sim);

    uint64_t oae = 0;   /* the foragers' OAEs so far */
    f->waiting = f->searching = f->returning = 0;
    for (uint32_t i = 0; i < f->n_robots; i++) {
        if (!f->is_forager[i]) {
            continue;
        }
        const forager_t *fs = sim_robot_controller(sim, i);
        char st = forager_paper_state(fs->state);
        double x, y, th;
        sim_robot_pose(sim, i, &x, &y, &th);
        oae += fs->walk.oae_count;
        /* A waiting robot's distance is summed anyway: one hypot serves
         * both; the others need only which side of the rim they are. */
        int waiting = st == 'W';
        double reach = nest_radius(f) + NEST_REACH, d = waiting ? nest_distance(f, x, y) : 0.0;
        int at_nest = waiting ? d < reach : near_nest(f, x, y, reach);
        if (at_nest) {
            f->oae_at_nest += fs->walk.oae_count - f->last_oae[i];
        }
        f->last_oae[i] = fs->walk.oae_count;
        if (waiting) {
            f->wait_radius_sum += d;
            f->wait_steps++;
        }
        f->waiting += st == 'W';
        f->searching += st == 'S';
        f->returning += st == 'R';
        if (f->task[i] == 'R' && st == 'S') {
            sim_event(sim, i, "token_lost", "the forager gave up its token", 0);
        }
        /* Leaving the nest: from choosing S_S inside it to the body's
         * centre outside the nest disk (or to the next state change). */
        if (f->task[i] == 'W' && st == 'S' && in_nest(f, (float)x, (float)y)) {
            f->leave_step[i] = (int64_t)sim_step_count(sim);
        } else if (f->leave_step[i] >= 0 && (st != 'S' || !in_nest(f, (float)x, (float)y))) {
            if (st == 'S') {
                f->exit_steps += sim_step_count(sim) - (uint64_t)f->leave_step[i];
                f->exits++;
            }
            f->leave_step[i] = -1;
        }
        f->task[i] = st;
    }
    /* One unit per step per robot in S_S or S_R (seed 000, 3.1). */
    f->forage_steps += f->searching + f->returning;
    f->search_steps += f->searching;

    uint32_t new_oae = (uint32_t)(oae - f->oae_seen);
    f->oae_seen = oae;
    if (c->information == FORAGING_INFO_GLOBAL) {   /* M_A for the broadcast; the beacon keeps its own */
        f->window_sum += new_oae;
        f->window_sum -= f->oae_window[f->window_pos];
        f->oae_window[f->window_pos] = new_oae;
        f->window_pos = (f->window_pos + 1) % f->window_len;
    }

    double minutes = (double)(sim_step_count(sim) + 1) * sim_scenario(sim)->control_period_ms / 60000.0;
    f->nest_units = c->consumption * c->token_energy * minutes;
    f->food = balance(f);
    f->deviation_sum += fabs(c->desired_food - f->food);
    if (f->beacon >= 0) {   /* how far the beacon's belief is from the truth */
        const nest_beacon_t *b = sim_robot_controller_const(sim, (uint32_t)f->beacon);
        double err = fabs((double)b->food_q4 / NL_FOOD_PER_TOKEN - f->food);
        f->beacon_error_sum += err;
        f->beacon_error_max = fmax(f->beacon_error_max, err);
    }
}

/* Ideal global information: the true nest state, in the frames a nest
 * beacon sends, one per step in turn, to every forager within IR range of
 * the nest centre. */
static void foraging_broadcast_truth(void *self, sim_t *sim)
{
    foraging_t *f = self;
    uint16_t frame;
    if (f->cfg->information != FORAGING_INFO_GLOBAL) {
        return;
    }
    switch (sim_step_count(sim) % NL_KIND_COUNT) {
    case NL_KIND_FOOD:
        frame = nest_link_encode_food((int32_t)lround(f->food * NL_FOOD_PER_TOKEN));
        break;
    case NL_KIND_WAITING:
        frame = nest_link_encode_waiting((uint16_t)f->waiting);
        break;
    default:
        frame = nest_link_encode_mean_oae(
            f->n_foragers ? (uint32_t)lround((double)NL_MEAN_OAE_PER_UNIT * (double)f->window_sum / f->n_foragers) : 0u);
        break;
    }
    for (uint32_t i = 0; i < f->n_robots; i++) {
        double px, py, pt;
        if (!f->is_forager[i]) {
            continue;
        }
        sim_robot_pose(sim, i, &px, &py, &pt);
        float dx = f->cfg->nest.x - (float)px, dy = f->cfg->nest.y - (float)py;
        float d = sqrtf(dx * dx + dy * dy);
        if (d > sim_ircom_range_m(sim)) {
            continue;
        }
        hal_ircom_msg_t m;
        m.value = frame;
        m.bearing_mrad = (int16_t)lroundf(1000.0f * geom_wrap(atan2f(dy, dx) - (float)pt));
        m.sensor = 0;
        m.range_mm = (uint16_t)fminf(d * 1000.0f + 0.5f, 65535.0f);
        (void)sim_ircom_inject(sim, i, &m);   /* a full inbox drops it, as a robot's would */
    }
}

static uint32_t foraging_items(const void *self, const sim_item_t **items)
{
    const foraging_t *f = self;
    *items = f->tokens;
    return f->n_tokens;
}

/* ---------------------------------------------------------------- outputs */

static const metric_desc_t foraging_columns[] = {
    { "food_nest", "tokens", "F(t), the nest's food by the ground-truth ledger" },
    { "food_collected", "tokens", "tokens delivered to the nest so far" },
    { "waiting", "robots", "foragers in S_W" },
    { "searching", "robots", "foragers in S_S" },
    { "returning", "robots", "foragers in S_R" },
    { "active", "robots", "foragers in S_S or S_R" },
    { "food_beacon", "tokens", "F(t) as the beacon's ledger has it (what it broadcasts; none with "
      "global information)" },
    { NULL, NULL, NULL }
};

static void foraging_sample(const void *self, const sim_t *sim, double *v)
{
    const foraging_t *f = self;
    v[0] = f->food;
    v[1] = (double)f->delivered;
    v[2] = f->waiting;
    v[3] = f->searching;
    v[4] = f->returning;
    v[5] = f->searching + f->returning;
    v[6] = f->beacon >= 0
           ? (double)((const nest_beacon_t *)sim_robot_controller_const(sim, (uint32_t)f->beacon))->food_q4
                 / NL_FOOD_PER_TOKEN
           : NAN;
}

static const metric_desc_t foraging_summary[] = {
    { "V_f", "tokens", "eq 8: mean |F_d - F(t)| over the steps" },
    { "E_e", "", "eq 9: E_n / E_T = F(T) / collected (a fraction; the paper prints %)" },
    { "food_collected", "tokens", "tokens delivered" },
    { "food_net", "tokens", "F(T)" },
    { "food_dropped", "tokens", "tokens let go outside the nest" },
    { "exit_time_s", "s", "mean time from choosing to forage in the nest to leaving its disk" },
    { "beacon_error_mean", "tokens", "mean |F_beacon - F| over the steps (none with global information)" },
    { "beacon_error_max", "tokens", "largest |F_beacon - F|" },
    { "tau_s", "s", "robot-seconds of foraging (S_S or S_R) per token delivered" },
    { "tau_search_s", "s", "of tau_s, the robot-seconds in S_S (leaving the nest included)" },
    { "active_mean", "robots", "mean number of foragers in S_S or S_R over the steps" },
    { "oae_at_nest", "events", "OAEs of foragers whose centre was in the nest or within 0.1 m of its rim" },
    { "wait_radius_m", "m", "mean distance of the waiting foragers (S_W) from the nest centre" },
    { NULL, NULL, NULL }
};

/* Seed 000, section 2.4. */
static void foraging_final(const void *self, const sim_t *sim, double *v)
{
    const foraging_t *f = self;
    double steps = (double)sim_step_count(sim);
    double dt = sim_scenario(sim)->control_period_ms / 1000.0;
    double per_token = f->delivered ? dt / (double)f->delivered : NAN;
    v[0] = steps > 0 ? f->deviation_sum / steps : 0.0;
    v[1] = f->delivered ? f->food / (double)f->delivered : 0.0;
    v[2] = (double)f->delivered;
    v[3] = f->food;
    v[4] = (double)f->dropped;
    v[5] = f->exits ? (double)f->exit_steps / (double)f->exits * dt : NAN;
    v[6] = f->beacon >= 0 && steps > 0 ? f->beacon_error_sum / steps : NAN;
    v[7] = f->beacon >= 0 ? f->beacon_error_max : NAN;
    v[8] = (double)f->forage_steps * per_token;
    v[9] = (double)f->search_steps * per_token;
    v[10] = steps > 0 ? (double)f->forage_steps / steps : NAN;
    v[11] = (double)f->oae_at_nest;
    v[12] = f->wait_steps ? f->wait_radius_sum / (double)f->wait_steps : NAN;
}

static void foraging_draw(const void *self, const sim_t *sim, drawing_t *out)
{
    const foraging_t *f = self;
    draw_shape_t nest = { .kind = DRAW_DISC, .layer = DRAW_FLOOR, .rgb = foraging_legend[KEY_NEST].rgb,
                          .x = f->cfg->nest.x, .y = f->cfg->nest.y, .radius = nest_radius(f) };
    draw_shape_t label = { .kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = 0x303030u,
                           .x = f->cfg->nest.x - nest_radius(f), .y = f->cfg->nest.y + nest_radius(f) };
    drawing_add(out, &nest);
    snprintf(label.text, sizeof label.text, "F=%.1f COLLECTED %llu", f->food, (unsigned long long)f->delivered);
    drawing_add(out, &label);
    for (uint32_t i = 0; i < f->n_robots && i < out->robot_count; i++) {
        if (sim_robot_def(sim, i) == &nest_beacon_def) {
            out->robot_rgb[i] = foraging_legend[KEY_BEACON].rgb;
        } else if (f->task[i] == 'S') {   /* task[] is 0 for robots that are not foragers */
            out->robot_rgb[i] = foraging_legend[KEY_SEARCHING].rgb;
        } else if (f->task[i] == 'R') {
            out->robot_rgb[i] = foraging_legend[KEY_RETURNING].rgb;
        }   /* waiting: the default body, KEY_WAITING (another task may fill it) */
    }
}

/* A lying forager (fault `liar`): a deposit report every step, its
 * cumulative total rising by one a step, well-formed for the beacon. */
static uint16_t foraging_lie(const void *self, const sim_t *sim, uint32_t robot)
{
    (void)self;
    return nest_link_encode_deposits((uint16_t)robot, (uint32_t)sim_step_count(sim) + 1u);
}

/* Robots of these controllers need the foraging world to do anything. */
static const char *const foraging_controllers[] = { "forager", "forager_sense_all", "nest_beacon", NULL };

/* What create allocates: per robot and per token, and the T2 window. */
static size_t foraging_memory(const void *config, const scenario_t *sc)
{
    const foraging_config_t *c = config;
    const foraging_t *f = NULL;
    size_t n = scenario_robot_count(sc), nt = c->food_count;
    size_t window = (size_t)fmax(1.0, floor(t2_s(sc, c) * 1000.0 / sc->control_period_ms + 0.5));
    return sizeof *f + n * (sizeof *f->is_forager + sizeof *f->task + sizeof *f->leave_step + sizeof *f->carried)
           + nt * (sizeof *f->tokens + sizeof *f->carrier + sizeof *f->floor_x + sizeof *f->floor_y
                   + sizeof *f->near + sizeof(uint32_t))
           + window * sizeof *f->oae_window;
}

const task_def_t foraging_task = {
    .name = "foraging",
    .doc = "seed 000: food tokens, the nest and its ground-truth energy ledger",
    .config_size = sizeof(foraging_config_t),
    .memory = foraging_memory,
    .params = foraging_params,
    .sections = foraging_sections,
    .default_config = foraging_default_config,
    .controllers = foraging_controllers,
    .check = foraging_check,
    .configure = foraging_configure,
    .create = foraging_create,
    .destroy = foraging_destroy,
    .before_control = foraging_broadcast_truth,
    .after_control = foraging_release,
    .after_physics = foraging_update,
    .items = foraging_items,
    .columns = foraging_columns,
    .sample = foraging_sample,
    .summary = foraging_summary,
    .final = foraging_final,
    .draw = foraging_draw,
    .lie = foraging_lie,
    .legend = foraging_legend,
};

/* ---------------------------------------------------------------- for tests */

int foraging_truth(const sim_t *sim, foraging_truth_t *out)
{
    const foraging_t *f = sim_task(sim, &foraging_task);
    if (!f) {
        return 0;
    }
    out->delivered = f->delivered;
    out->dropped = f->dropped;
    out->food = f->food;
    out->waiting = f->waiting;
    out->searching = f->searching;
    out->returning = f->returning;
    return 1;
}

int32_t foraging_carried(const sim_t *sim, uint32_t i)
{
    const foraging_t *f = sim_task(sim, &foraging_task);
    return f && i < f->n_robots ? f->carried[i] : -1;
}

int foraging_drop(sim_t *sim, uint32_t i)
{
    foraging_t *f = sim_task(sim, &foraging_task);
    double x, y, theta;
    if (!f || i >= f->n_robots || f->carried[i] < 0) {
        return 0;
    }
    int32_t k = f->carried[i];
    sim_robot_pose(sim, i, &x, &y, &theta);
    /* Left on the floor a little ahead, out of the gripper's reach. */
    f->tokens[k].x += 0.1f * cosf((float)theta);
    f->tokens[k].y += 0.1f * sinf((float)theta);
    f->carrier[k] = -1;
    f->carried[i] = -1;
    f->dropped++;
    sim_event(sim, i, "token_dropped", "dropped by a test", k);
    return 1;
}

double foraging_balance(const sim_t *sim)
{
    const foraging_t *f = sim_task(sim, &foraging_task);
    return f ? balance(f) : 0.0;
}
