/*
 * paths.c - seed 003's path-formation task as a plug-in (paths.h): who is
 * a node, the nest's and the food's networks, the chain that merges them,
 * and the food's first perception.
 */
#include "paths.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Pictures: the nest's network blue, the food's orange, the chain green
 * (colours set in the legend's table). */
#define CHAIN_LINE_M 0.02f
/* A time is within the budget up to rounding of steps x period. */
#define BUDGET_EPS_S 1e-9

enum { ROLE_OTHER = 0, ROLE_NEST = 1, ROLE_FOOD = 2 };
/* BFS marks: not reached; a root (a source robot). */
#define UNREACHED (-2)
#define ROOT (-1)

enum { KEY_OTHER, KEY_NODE, KEY_CHAIN, KEY_NEST, KEY_FOOD, KEY_LINK, KEY_END };
static const draw_key_t paths_legend[] = {
    [KEY_OTHER] = { 0, "moving, or a source", DRAW_KEY_ROBOT, 0 },
    [KEY_NODE] = { DRAW_RGB_HL_YELLOW, "standing still (a node)", DRAW_KEY_ROBOT, 0 },
    [KEY_CHAIN] = { DRAW_RGB_HL_GREEN, "on the chain nest-food", DRAW_KEY_ROBOT, 0 },
    [KEY_NEST] = { 0x2878C8u, "nest range, network", DRAW_KEY_RING, 0 },
    [KEY_FOOD] = { 0xE08020u, "food range, network", DRAW_KEY_RING, 0 },
    [KEY_LINK] = { 0x20A040u, "the chain", DRAW_KEY_LINE, 0 },
    [KEY_END] = { 0 },
};

typedef struct paths {
    const paths_config_t *cfg;
    uint32_t n;                /**< robots */
    uint8_t *role;             /**< per robot: ROLE_* */
    uint8_t *node;             /**< per robot: a node this step */
    int32_t *from_nest;        /**< per robot: BFS parent from the nest side, ROOT, UNREACHED */
    int32_t *from_food;        /**< the same from the food side */
    int32_t *chain_pos;        /**< per robot: its place on the chain, or -1 */
    uint32_t *queue;           /**< BFS work list */
    uint32_t *chain;           /**< the chain, nest robot first, food robot last */
    uint32_t chain_len;        /**< robots on it (0: no chain) */
    uint32_t nodes, nest_side, food_side, perceivers;
    double period_s;
    uint64_t hold_steps;
    int64_t linked_since;      /**< first step of the current run of linked steps, -1 */
    double since_time_s;       /**< its end, s */
    uint32_t since_chain_nodes;
    int merged;                /**< the merge is confirmed (within the budget) */
    double merge_time_s;       /**< NaN until merged */
    uint32_t merge_chain_nodes;
    double food_time_s;        /**< NaN until perceived */
    double distance_m;         /**< least nest-food centre distance at the start */
} paths_t;

/* ---------------------------------------------------------------- config */

static const char *const nodes_choices[] = { "still", "any", NULL };

#define PC paths_config_t
static const param_desc_t paths_params[] = {
    { .key = "nest_group", PARAM_STRING_FIELD(PC, nest_group),
      .doc = "the robot group of Robot_Nest (moves: false)" },
    { .key = "food_group", PARAM_STRING_FIELD(PC, food_group),
      .doc = "the robot group of Robot_Food (moves: false)" },
    { .key = "range", PARAM_FIELD(PC, range, float), .min = 0.01, .max = 100,
      .doc = "m: R, the longest link of a chain and the food's perception range (seed 003: 0.6)" },
    { .key = "budget", PARAM_FIELD(PC, budget, float), .min = 0.001, .max = 1e7,
      .doc = "s: merges and perceptions count up to it; a run without a merge is recorded at it "
             "(seed 003: 1000 s = 10,000 steps)" },
    { .key = "hold", PARAM_FIELD(PC, hold, float), .min = 0, .max = 3600,
      .doc = "s: a chain nest-food must stand this long past its first step to count "
             "(rounded to control periods; 0: one step)" },
    { .key = "nodes", PARAM_ENUM_FIELD(PC, nodes, nodes_choices),
      .doc = "still: a chain's nodes are robots whose wheels are commanded (0, 0), EAIPP's Robot_Node "
             "(the default, seed 003's criterion); any: every robot of neither source group, moving or "
             "not (a path of robots travelling in a line, as NNEA's evolved robots make)" },
    PARAM_END
};
#undef PC

static void paths_default_config(void *config)
{
    paths_config_t *c = config;
    memset(c, 0, sizeof *c);
    snprintf(c->nest_group, sizeof c->nest_group, "nest");
    snprintf(c->food_group, sizeof c->food_group, "food");
    c->range = 0.6f;
    c->budget = 1000.0f;
    c->hold = 1.0f;
}

static int group_named(const scenario_t *sc, const char *name)
{
    for (uint32_t g = 0; g < sc->group_count; g++) {
        if (strcmp(sc->groups[g].name, name) == 0) {
            return (int)g;
        }
    }
    return -1;
}

static int check_group(const scenario_t *sc, const char *name, const char *key, const char *what,
                       char k[64], char msg[SIM_ERR_MAX])
{
    int g = group_named(sc, name);
    snprintf(k, 64, "%s", key);
    if (g < 0) {
        snprintf(msg, SIM_ERR_MAX, "no robot group is named '%s' (%s: name a group of robots[])", name, what);
        return -1;
    }
    if (sc->groups[g].count == 0) {
        snprintf(msg, SIM_ERR_MAX, "group '%s' (%s) has no robot", name, what);
        return -1;
    }
    if (sc->groups[g].moves) {
        snprintf(msg, SIM_ERR_MAX, "group '%s' (%s) must not move: give it moves: false (a fixed source)", name, what);
        return -1;
    }
    return 0;
}

static int paths_check(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX])
{
    const paths_config_t *c = config;
    if (check_group(sc, c->nest_group, "nest_group", "the nest", key, msg) != 0
        || check_group(sc, c->food_group, "food_group", "the food", key, msg) != 0) {
        return -1;
    }
    if (strcmp(c->nest_group, c->food_group) == 0) {
        snprintf(key, 64, "food_group");
        snprintf(msg, SIM_ERR_MAX, "the nest and the food are one group ('%s'): name two groups", c->food_group);
        return -1;
    }
    if (sc->duration + BUDGET_EPS_S < c->budget) {
        snprintf(key, 64, "budget");
        snprintf(msg, SIM_ERR_MAX, "%g s is longer than the run (duration %g s): a run must last its budget",
                 c->budget, sc->duration);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- a run */

static void paths_destroy(void *self)
{
    paths_t *p = self;
    if (p) {
        free(p->role);
        free(p->node);
        free(p->from_nest);
        free(p->from_food);
        free(p->chain_pos);
        free(p->queue);
        free(p->chain);
        free(p);
    }
}

static void *paths_create(sim_t *sim, const void *config, char err[SIM_ERR_MAX])
{
    const paths_config_t *c = config;
    const scenario_t *sc = sim_scenario(sim);
    paths_t *p = calloc(1, sizeof *p);
    uint32_t n = sim_robot_count(sim), n1 = n ? n : 1;
    if (!p || !(p->role = calloc(n1, 1)) || !(p->node = calloc(n1, 1))
        || !(p->from_nest = calloc(n1, sizeof *p->from_nest)) || !(p->from_food = calloc(n1, sizeof *p->from_food))
        || !(p->chain_pos = calloc(n1, sizeof *p->chain_pos)) || !(p->queue = calloc(n1, sizeof *p->queue))
        || !(p->chain = calloc(n1, sizeof *p->chain))) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the paths task");
        paths_destroy(p);
        return NULL;
    }
    p->cfg = c;
    p->n = n;
    int gn = group_named(sc, c->nest_group), gf = group_named(sc, c->food_group);
    for (uint32_t i = 0; i < n; i++) {
        int g = (int)sim_robot_group(sim, i);
        p->role[i] = g == gn ? ROLE_NEST : g == gf ? ROLE_FOOD : ROLE_OTHER;
        p->chain_pos[i] = -1;
        p->from_nest[i] = p->from_food[i] = UNREACHED;   /* no network drawn before the first step */
    }
    p->distance_m = INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        for (uint32_t j = 0; j < n && p->role[i] == ROLE_NEST; j++) {
            if (p->role[j] == ROLE_FOOD) {
                double xi, yi, ti, xj, yj, tj;
                sim_robot_pose(sim, i, &xi, &yi, &ti);
                sim_robot_pose(sim, j, &xj, &yj, &tj);
                p->distance_m = fmin(p->distance_m, hypot(xi - xj, yi - yj));
            }
        }
    }
    p->period_s = sc->control_period_ms / 1000.0;
    p->hold_steps = (uint64_t)floor(c->hold / p->period_s + 0.5);
    p->linked_since = -1;
    p->merge_time_s = NAN;
    p->food_time_s = NAN;
    return p;
}

/* Robots i and j can talk: centres within range, no obstacle between. */
static int linked(sim_t *sim, double range, uint32_t i, uint32_t j)
{
    double xi, yi, ti, xj, yj, tj;
    sim_robot_pose(sim, i, &xi, &yi, &ti);
    sim_robot_pose(sim, j, &xj, &yj, &tj);
    double dx = xi - xj, dy = yi - yj;
    return dx * dx + dy * dy <= range * range && !sim_segment_blocked(sim, xi, yi, xj, yj);
}

/* Breadth-first from every robot of role `root` through nodes; a robot of
 * the other source role is reached but not gone through.  Fills parent[],
 * returns the first robot of the other role reached (the end of a shortest
 * chain, in links), or -1; *side counts the nodes reached. */
static int32_t spread(paths_t *p, sim_t *sim, uint8_t root, int32_t *parent, uint32_t *side)
{
    uint32_t head = 0, tail = 0;
    int32_t end = -1;
    *side = 0;
    for (uint32_t i = 0; i < p->n; i++) {
        parent[i] = p->role[i] == root ? ROOT : UNREACHED;
        if (p->role[i] == root) {
            p->queue[tail++] = i;
        }
    }
    while (head < tail) {
        uint32_t u = p->queue[head++];
        if (p->role[u] != root && p->role[u] != ROLE_OTHER) {
            continue;   /* the other source: an end, not a relay */
        }
        for (uint32_t v = 0; v < p->n; v++) {
            if (parent[v] != UNREACHED || (p->role[v] == ROLE_OTHER && !p->node[v])
                || !linked(sim, p->cfg->range, u, v)) {
                continue;
            }
            parent[v] = (int32_t)u;
            p->queue[tail++] = v;
            if (p->role[v] == ROLE_OTHER) {
                (*side)++;
            } else if (end < 0) {
                end = (int32_t)v;
            }
        }
    }
    return end;
}

/* After physics (task.h, phase 6): the poses at the step's end, the wheels
 * commanded in it. */
static void paths_after_physics(void *self, sim_t *sim)
{
    paths_t *p = self;
    uint64_t step = sim_step_count(sim);
    double t_end = (double)(step + 1) * p->period_s;
    int within = t_end <= p->cfg->budget + BUDGET_EPS_S;
    p->nodes = 0;
    for (uint32_t i = 0; i < p->n; i++) {
        int16_t l, r;
        sim_robot_wheels(sim, i, &l, &r);
        p->node[i] = p->role[i] == ROLE_OTHER
                     && (p->cfg->nodes == PATHS_NODES_ANY || (l == 0 && r == 0));
        p->nodes += p->node[i];
        p->chain_pos[i] = -1;
    }
    int32_t end = spread(p, sim, ROLE_NEST, p->from_nest, &p->nest_side);
    (void)spread(p, sim, ROLE_FOOD, p->from_food, &p->food_side);
    /* The chain: from the food robot back to the nest, then reversed. */
    p->chain_len = 0;
    for (int32_t v = end; v >= 0; v = p->from_nest[v]) {
        p->chain[p->chain_len++] = (uint32_t)v;
    }
    for (uint32_t k = 0; k < p->chain_len / 2; k++) {
        uint32_t tmp = p->chain[k];
        p->chain[k] = p->chain[p->chain_len - 1 - k];
        p->chain[p->chain_len - 1 - k] = tmp;
    }
    for (uint32_t k = 0; k < p->chain_len; k++) {
        p->chain_pos[p->chain[k]] = (int32_t)k;
    }
    /* Perception: any robot of neither source within range of the food. */
    p->perceivers = 0;
    uint32_t first = 0;
    for (uint32_t i = 0; i < p->n; i++) {
        int sees = 0;
        for (uint32_t j = 0; j < p->n && !sees && p->role[i] == ROLE_OTHER; j++) {
            sees = p->role[j] == ROLE_FOOD && linked(sim, p->cfg->range, i, j);
        }
        first = sees && p->perceivers == 0 ? i : first;
        p->perceivers += sees;
    }
    if (p->perceivers > 0 && isnan(p->food_time_s) && within) {
        p->food_time_s = t_end;
        sim_event(sim, first, "food_perceived", "", (int32_t)p->perceivers);
    }
    if (p->merged) {
        return;
    }
    if (p->chain_len == 0) {
        p->linked_since = -1;
        return;
    }
    if (p->linked_since < 0) {
        p->linked_since = (int64_t)step;
        p->since_time_s = t_end;
        p->since_chain_nodes = p->chain_len - 2;
    }
    if (step - (uint64_t)p->linked_since >= p->hold_steps && within) {
        p->merged = 1;
        p->merge_time_s = p->since_time_s;
        p->merge_chain_nodes = p->since_chain_nodes;
        sim_event(sim, p->chain[p->chain_len - 1], "merged", "", (int32_t)p->merge_chain_nodes);
    }
}

/* ---------------------------------------------------------------- outputs */

static const metric_desc_t paths_columns[] = {
    { "nodes", "robots", "robots standing still (wheels commanded 0, 0), the sources aside" },
    { "nest_side", "robots", "nodes linked to the nest through nodes" },
    { "food_side", "robots", "nodes linked to the food through nodes" },
    { "linked", "", "1 when a chain of nodes links nest and food this step" },
    { "perceivers", "robots", "robots within range of the food (line of sight clear)" },
    { NULL, NULL, NULL }
};

static void paths_sample(const void *self, const sim_t *sim, double *v)
{
    const paths_t *p = self;
    (void)sim;
    v[0] = p->nodes;
    v[1] = p->nest_side;
    v[2] = p->food_side;
    v[3] = p->chain_len > 0;
    v[4] = p->perceivers;
}

static const metric_desc_t paths_summary[] = {
    { "success", "", "1 when the nest's and the food's networks merged within the budget (section 4.3)" },
    { "merge_time_s", "s", "when they merged: the first step of a chain that held (null: never)" },
    { "merge_time_capped_s", "s", "merge_time_s, or the budget for a failure (the paper's Figure 11)" },
    { "merge_steps_capped", "steps", "merge_time_capped_s in control steps (10,000 for a failure)" },
    { "food_perceived", "", "1 when a robot perceived the food within the budget (section 5.2)" },
    { "food_time_s", "s", "when a robot first came within range of the food (null: never)" },
    { "food_time_capped_s", "s", "food_time_s, or the budget" },
    { "chain_nodes", "robots", "nodes on the chain that merged the networks (null: none)" },
    { "nodes_end", "robots", "robots standing still at the end" },
    { "distance_m", "m", "D: nest-food centre distance" },
    { "budget_s", "s", "the budget" },
    { NULL, NULL, NULL }
};

static void paths_final(const void *self, const sim_t *sim, double *v)
{
    const paths_t *p = self;
    double budget = p->cfg->budget, merge = p->merged ? p->merge_time_s : budget;
    int perceived = !isnan(p->food_time_s);
    (void)sim;
    v[0] = p->merged;
    v[1] = p->merge_time_s;
    v[2] = merge;
    v[3] = floor(merge / p->period_s + 0.5);
    v[4] = perceived;
    v[5] = p->food_time_s;
    v[6] = perceived ? p->food_time_s : budget;
    v[7] = p->merged ? (double)p->merge_chain_nodes : NAN;
    v[8] = p->nodes;
    v[9] = p->distance_m;
    v[10] = budget;
}

static void add_line(drawing_t *out, const sim_t *sim, uint32_t a, uint32_t b, uint32_t rgb, float width)
{
    double xa, ya, ta, xb, yb, tb;
    sim_robot_pose(sim, a, &xa, &ya, &ta);
    sim_robot_pose(sim, b, &xb, &yb, &tb);
    draw_shape_t l = { .kind = DRAW_LINE, .layer = DRAW_FLOOR, .rgb = rgb, .x = (float)xa, .y = (float)ya,
                       .x2 = (float)xb, .y2 = (float)yb, .line = width };
    drawing_add(out, &l);
}

static void paths_draw(const void *self, const sim_t *sim, drawing_t *out)
{
    const paths_t *p = self;
    /* The sources, each with its range ring and its name. */
    for (uint32_t i = 0; i < p->n; i++) {
        if (p->role[i] == ROLE_OTHER) {
            continue;
        }
        double x, y, t;
        sim_robot_pose(sim, i, &x, &y, &t);
        uint32_t rgb = paths_legend[p->role[i] == ROLE_NEST ? KEY_NEST : KEY_FOOD].rgb;
        draw_shape_t ring = { .kind = DRAW_RING, .layer = DRAW_FLOOR, .rgb = rgb, .x = (float)x, .y = (float)y,
                              .radius = p->cfg->range, .line = 0.0f };
        draw_shape_t label = { .kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = rgb, .x = (float)x + 0.05f,
                               .y = (float)y + 0.05f };
        snprintf(label.text, sizeof label.text, p->role[i] == ROLE_NEST ? "NEST" : "FOOD");
        drawing_add(out, &ring);
        drawing_add(out, &label);
    }
    /* Each network's links (its breadth-first tree), then the chain. */
    for (uint32_t v = 0; v < p->n; v++) {
        if (p->role[v] == ROLE_OTHER && p->from_nest[v] >= 0) {
            add_line(out, sim, v, (uint32_t)p->from_nest[v], paths_legend[KEY_NEST].rgb, 0.0f);
        }
        if (p->role[v] == ROLE_OTHER && p->from_food[v] >= 0) {
            add_line(out, sim, v, (uint32_t)p->from_food[v], paths_legend[KEY_FOOD].rgb, 0.0f);
        }
    }
    for (uint32_t k = 1; k < p->chain_len; k++) {
        add_line(out, sim, p->chain[k - 1], p->chain[k], paths_legend[KEY_LINK].rgb, CHAIN_LINE_M);
    }
    for (uint32_t i = 0; i < p->n && i < out->robot_count; i++) {
        if (p->chain_pos[i] >= 0 && p->role[i] == ROLE_OTHER) {
            out->robot_rgb[i] = paths_legend[KEY_CHAIN].rgb;
        } else if (p->node[i]) {
            out->robot_rgb[i] = paths_legend[KEY_NODE].rgb;
        }
    }
    draw_shape_t label = { .kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = 0x303030u };
    float hw, hh;
    sim_arena_half(sim, &hw, &hh);
    label.x = -hw + 0.05f;
    label.y = hh - 0.15f;
    if (p->merged) {
        snprintf(label.text, sizeof label.text, "MERGED %.1f s, %u NODES", p->merge_time_s, p->merge_chain_nodes);
    } else {
        snprintf(label.text, sizeof label.text, "NODES %u NEST %u FOOD %u", p->nodes, p->nest_side, p->food_side);
    }
    drawing_add(out, &label);
}

/* The stop condition: the networks merged (a failure runs to the end). */
static int paths_done(const void *self, const sim_t *sim)
{
    (void)sim;
    return ((const paths_t *)self)->merged;
}

/* What create allocates: per robot. */
static size_t paths_memory(const void *config, const scenario_t *sc)
{
    const paths_t *p = NULL;
    (void)config;
    return sizeof *p + scenario_robot_count(sc) * (sizeof *p->role + sizeof *p->node + sizeof *p->from_nest
                                                   + sizeof *p->from_food + sizeof *p->chain_pos + sizeof *p->queue
                                                   + sizeof *p->chain);
}

const task_def_t paths_task = {
    .name = "paths",
    .doc = "seed 003: link a fixed nest and food robot by a chain of still robots within range R",
    .config_size = sizeof(paths_config_t),
    .memory = paths_memory,
    .params = paths_params,
    .default_config = paths_default_config,
    .check = paths_check,
    .create = paths_create,
    .destroy = paths_destroy,
    .after_physics = paths_after_physics,
    .columns = paths_columns,
    .sample = paths_sample,
    .summary = paths_summary,
    .final = paths_final,
    .draw = paths_draw,
    .legend = paths_legend,
    .done = paths_done,
};

/* ---------------------------------------------------------------- for tests */

int paths_truth(const sim_t *sim, paths_truth_t *out)
{
    const paths_t *p = sim_task(sim, &paths_task);
    if (!p) {
        return 0;
    }
    out->nodes = p->nodes;
    out->nest_side = p->nest_side;
    out->food_side = p->food_side;
    out->linked = p->chain_len > 0;
    out->chain_nodes = p->chain_len > 0 ? p->chain_len - 2 : 0;
    out->perceivers = p->perceivers;
    out->merge_time_s = p->merge_time_s;
    out->food_time_s = p->food_time_s;
    return 1;
}

int32_t paths_chain_index(const sim_t *sim, uint32_t i)
{
    const paths_t *p = sim_task(sim, &paths_task);
    return p && i < p->n ? p->chain_pos[i] : -1;
}
