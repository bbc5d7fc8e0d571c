/* The tutorial's example task (gather.h; docs/tutorials/first-task.md). */
#include "gather.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Robots by where they are, and the goal (the legend's table sets their
 * colours). */
enum { KEY_OUTSIDE, KEY_INSIDE, KEY_GOAL, KEY_END };
static const draw_key_t gather_legend[] = {
    [KEY_OUTSIDE] = { 0, "outside", DRAW_KEY_ROBOT, 0 },
    [KEY_INSIDE] = { DRAW_RGB_HL_GREEN, "in goal", DRAW_KEY_ROBOT, 0 },
    [KEY_GOAL] = { 0x2878C8u, "goal", DRAW_KEY_RING, 0 },
    [KEY_END] = { 0 },
};

typedef struct gather {
    const gather_config_t *cfg;
    uint32_t n;                /**< robots */
    uint8_t *inside;           /**< per robot, this step */
    uint32_t in_goal;          /**< robots inside now */
    uint32_t max_in_goal;
    double sum_in_goal;        /**< over the steps, for the mean */
} gather_t;

#define GC gather_config_t
static const param_desc_t gather_params[] = {
    { .key = "stop_fraction", PARAM_FIELD(GC, stop_fraction, float), .min = 0, .max = 1,
      .doc = "end the run when this share of the robots is in the goal (0: never)" },
    PARAM_END
};
static const param_desc_t goal_params[] = {
    { .key = "x", PARAM_FIELD(GC, goal.x, float), .min = -500, .max = 500, .doc = "goal centre x, m" },
    { .key = "y", PARAM_FIELD(GC, goal.y, float), .min = -500, .max = 500, .doc = "goal centre y, m" },
    { .key = "radius", PARAM_FIELD(GC, goal.radius, float), .min = 0.01, .max = 500,
      .doc = "goal radius, m (a robot is in when its centre is)" },
    PARAM_END
};
#undef GC

static const param_section_t gather_sections[] = {
    { "goal", goal_params, "the goal circle" },
    { NULL, NULL, NULL }
};

static void gather_default_config(void *config)
{
    gather_config_t *c = config;
    c->goal.x = 0.0f;
    c->goal.y = 0.0f;
    c->goal.radius = 0.5f;
    c->stop_fraction = 0.0f;
}

static int gather_check(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX])
{
    const gather_config_t *c = config;
    int x_out = fabsf(c->goal.x) > sc->arena.width / 2, y_out = fabsf(c->goal.y) > sc->arena.height / 2;
    if (x_out || y_out) {
        snprintf(key, 64, x_out ? "goal.x" : "goal.y");
        scenario_outside_message(sc, "the goal's centre is", msg, SIM_ERR_MAX);
        return -1;
    }
    return 0;
}

static void gather_destroy(void *self)
{
    gather_t *g = self;
    if (g) {
        free(g->inside);
        free(g);
    }
}

static void *gather_create(sim_t *sim, const void *config, char err[SIM_ERR_MAX])
{
    gather_t *g = calloc(1, sizeof *g);
    uint32_t n = sim_robot_count(sim);
    if (!g || !(g->inside = calloc(n ? n : 1, 1))) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the gather task");
        gather_destroy(g);
        return NULL;
    }
    g->cfg = config;
    g->n = n;
    return g;
}

/* After physics: who is in the goal now. */
static void gather_after_physics(void *self, sim_t *sim)
{
    gather_t *g = self;
    double r2 = (double)g->cfg->goal.radius * g->cfg->goal.radius;
    g->in_goal = 0;
    for (uint32_t i = 0; i < g->n; i++) {
        double x, y, t;
        sim_robot_pose(sim, i, &x, &y, &t);
        x -= g->cfg->goal.x;
        y -= g->cfg->goal.y;
        g->inside[i] = x * x + y * y <= r2;
        g->in_goal += g->inside[i];
    }
    g->max_in_goal = g->in_goal > g->max_in_goal ? g->in_goal : g->max_in_goal;
    g->sum_in_goal += g->in_goal;
}

static const metric_desc_t gather_columns[] = {
    { "in_goal", "robots", "robots whose centre is in the goal circle" },
    { NULL, NULL, NULL }
};

static void gather_sample(const void *self, const sim_t *sim, double *v)
{
    (void)sim;
    v[0] = ((const gather_t *)self)->in_goal;
}

static const metric_desc_t gather_summary[] = {
    { "max_in_goal", "robots", "most robots in the goal at once" },
    { "mean_in_goal", "robots", "robots in the goal, mean over the steps" },
    { NULL, NULL, NULL }
};

static void gather_final(const void *self, const sim_t *sim, double *v)
{
    const gather_t *g = self;
    uint64_t steps = sim_step_count(sim);   /* after_physics ran once in each */
    v[0] = g->max_in_goal;
    v[1] = steps ? g->sum_in_goal / (double)steps : 0.0;
}

static void gather_draw(const void *self, const sim_t *sim, drawing_t *out)
{
    const gather_t *g = self;
    draw_shape_t ring = { .kind = DRAW_RING, .layer = DRAW_FLOOR, .rgb = gather_legend[KEY_GOAL].rgb, .x = g->cfg->goal.x,
                          .y = g->cfg->goal.y, .radius = g->cfg->goal.radius, .line = 0.01f };
    draw_shape_t label = { .kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = gather_legend[KEY_GOAL].rgb,
                           .x = g->cfg->goal.x - g->cfg->goal.radius,
                           .y = g->cfg->goal.y + g->cfg->goal.radius + 0.03f };
    (void)sim;
    drawing_add(out, &ring);
    snprintf(label.text, sizeof label.text, "IN GOAL %u/%u", g->in_goal, g->n);
    drawing_add(out, &label);
    for (uint32_t i = 0; i < g->n && i < out->robot_count; i++) {
        if (g->inside[i]) {   /* outside: the default body, KEY_OUTSIDE */
            out->robot_rgb[i] = gather_legend[KEY_INSIDE].rgb;
        }
    }
}

/* The stop condition: enough robots gathered. */
static int gather_done(const void *self, const sim_t *sim)
{
    const gather_t *g = self;
    (void)sim;
    return g->cfg->stop_fraction > 0.0f && g->n > 0
           && (double)g->in_goal >= (double)g->cfg->stop_fraction * g->n;
}

/* What create allocates: a flag per robot. */
static size_t gather_memory(const void *config, const scenario_t *sc)
{
    const gather_t *g = NULL;
    (void)config;
    return sizeof *g + scenario_robot_count(sc) * sizeof *g->inside;
}

const task_def_t gather_task = {
    .name = "gather",
    .doc = "example: robots in a goal circle; ends the run when enough are in (docs: Your first task)",
    .config_size = sizeof(gather_config_t),
    .memory = gather_memory,
    .params = gather_params,
    .sections = gather_sections,
    .default_config = gather_default_config,
    .check = gather_check,
    .create = gather_create,
    .destroy = gather_destroy,
    .after_physics = gather_after_physics,
    .columns = gather_columns,
    .sample = gather_sample,
    .summary = gather_summary,
    .final = gather_final,
    .draw = gather_draw,
    .legend = gather_legend,
    .done = gather_done,
};
