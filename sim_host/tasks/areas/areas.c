/* The nest and food areas on the floor and the trips between them (areas.h). */
#include "areas.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/ground/ground.h"

enum { AREA_NONE = 0, AREA_NEST = 1, AREA_FOOD = 2 };
/* The areas in pictures (the legend's table sets their colours). */
enum { KEY_NEST, KEY_FOOD, KEY_END };
static const draw_key_t areas_legend[] = {
    [KEY_NEST] = { 0x404040u, "nest area", DRAW_KEY_RING, 0 },
    [KEY_FOOD] = { 0x909090u, "food area", DRAW_KEY_RING, 0 },
    [KEY_END] = { 0 },
};
enum { ROLE_OTHER = 0, ROLE_NEST = 1, ROLE_FOOD = 2 };

typedef struct areas {
    const areas_config_t *cfg;
    uint32_t n;
    uint8_t *role;        /**< per robot */
    uint8_t *last;        /**< per robot: the last area it was in */
    uint8_t *both;        /**< per robot: has been in both */
    uint32_t n_sources;
    float *src_x, *src_y; /**< the areas' centres */
    uint8_t *src_kind;    /**< AREA_NEST or AREA_FOOD */
    uint32_t movers;      /**< robots of neither group */
    uint64_t trips;
} areas_t;

#define AC areas_config_t
static const param_desc_t areas_params[] = {
    { .key = "nest_group", PARAM_STRING_FIELD(AC, nest_group),
      .doc = "the robot group standing on the nest area (moves: false)" },
    { .key = "food_group", PARAM_STRING_FIELD(AC, food_group),
      .doc = "the robot group standing on the food area (moves: false)" },
    { .key = "radius", PARAM_FIELD(AC, radius, float), .min = 0.01, .max = 100,
      .doc = "m: each area's radius (a disc centred on its robot)" },
    { .key = "nest_reflectance", PARAM_FIELD(AC, nest_reflectance, float), .min = 0, .max = 1,
      .doc = "the nest area's IR reflectance (0 black, 1 white)" },
    { .key = "food_reflectance", PARAM_FIELD(AC, food_reflectance, float), .min = 0, .max = 1,
      .doc = "the food area's IR reflectance" },
    PARAM_END
};
#undef AC

static void areas_default_config(void *config)
{
    areas_config_t *c = config;
    memset(c, 0, sizeof *c);
    snprintf(c->nest_group, sizeof c->nest_group, "nest");
    snprintf(c->food_group, sizeof c->food_group, "food");
    c->radius = 0.2f;
    c->nest_reflectance = 0.0f;
    c->food_reflectance = 0.5f;
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

static int areas_check(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX])
{
    const areas_config_t *c = config;
    const char *names[2] = { c->nest_group, c->food_group };
    const char *keys[2] = { "nest_group", "food_group" };
    for (int k = 0; k < 2; k++) {
        int g = group_named(sc, names[k]);
        snprintf(key, 64, "%s", keys[k]);
        if (g < 0) {
            snprintf(msg, SIM_ERR_MAX, "no robot group is named '%s' (name a group of robots[])", names[k]);
            return -1;
        }
        if (sc->groups[g].moves) {
            snprintf(msg, SIM_ERR_MAX, "group '%s' must not move: give it moves: false (its area stays put)",
                     names[k]);
            return -1;
        }
    }
    if (strcmp(c->nest_group, c->food_group) == 0) {
        snprintf(key, 64, "food_group");
        snprintf(msg, SIM_ERR_MAX, "the nest and the food are one group ('%s'): name two groups", c->food_group);
        return -1;
    }
    return 0;
}

static void areas_destroy(void *self)
{
    areas_t *a = self;
    if (a) {
        free(a->role);
        free(a->last);
        free(a->both);
        free(a->src_x);
        free(a->src_y);
        free(a->src_kind);
        free(a);
    }
}

static void *areas_create(sim_t *sim, const void *config, char err[SIM_ERR_MAX])
{
    const areas_config_t *c = config;
    const scenario_t *sc = sim_scenario(sim);
    areas_t *a = calloc(1, sizeof *a);
    uint32_t n = sim_robot_count(sim), n1 = n ? n : 1;
    int gn = group_named(sc, c->nest_group), gf = group_named(sc, c->food_group);
    if (!a || !(a->role = calloc(n1, 1)) || !(a->last = calloc(n1, 1)) || !(a->both = calloc(n1, 1))
        || !(a->src_x = calloc(n1, sizeof *a->src_x)) || !(a->src_y = calloc(n1, sizeof *a->src_y))
        || !(a->src_kind = calloc(n1, 1))) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the areas task");
        areas_destroy(a);
        return NULL;
    }
    a->cfg = c;
    a->n = n;
    for (uint32_t i = 0; i < n; i++) {
        int g = (int)sim_robot_group(sim, i);
        a->role[i] = g == gn ? ROLE_NEST : g == gf ? ROLE_FOOD : ROLE_OTHER;
        if (a->role[i] == ROLE_OTHER) {
            a->movers++;
            continue;
        }
        double x, y, t;
        sim_robot_pose(sim, i, &x, &y, &t);
        ground_region_t disc = { .shape = GROUND_DISC, .x = (float)x, .y = (float)y, .radius = c->radius,
                                 .reflectance = a->role[i] == ROLE_NEST ? c->nest_reflectance
                                                                        : c->food_reflectance };
        if (ground_add_region(sim, &disc) != 0) {
            snprintf(err, SIM_ERR_MAX, "out of memory for the areas task's floor");
            areas_destroy(a);
            return NULL;
        }
        a->src_x[a->n_sources] = (float)x;
        a->src_y[a->n_sources] = (float)y;
        a->src_kind[a->n_sources] = a->role[i] == ROLE_NEST ? AREA_NEST : AREA_FOOD;
        a->n_sources++;
    }
    return a;
}

/* The area robot i's centre is in (the last listed on top, as the floor). */
static uint8_t area_of(const areas_t *a, double x, double y)
{
    double r2 = (double)a->cfg->radius * a->cfg->radius;
    uint8_t area = AREA_NONE;
    for (uint32_t s = 0; s < a->n_sources; s++) {
        double dx = x - a->src_x[s], dy = y - a->src_y[s];
        if (dx * dx + dy * dy <= r2) {
            area = a->src_kind[s];
        }
    }
    return area;
}

static void areas_after_physics(void *self, sim_t *sim)
{
    areas_t *a = self;
    for (uint32_t i = 0; i < a->n; i++) {
        double x, y, t;
        uint8_t area;
        if (a->role[i] != ROLE_OTHER) {
            continue;
        }
        sim_robot_pose(sim, i, &x, &y, &t);
        area = area_of(a, x, y);
        if (area != AREA_NONE && area != a->last[i]) {
            if (a->last[i] != AREA_NONE) {
                a->trips++;
                a->both[i] = 1;
            }
            a->last[i] = area;
        }
    }
}

static const metric_desc_t areas_columns[] = {
    { "trips", "trips", "trips between the nest and food areas so far (all robots)" },
    { NULL, NULL, NULL }
};

static void areas_sample(const void *self, const sim_t *sim, double *v)
{
    (void)sim;
    v[0] = (double)((const areas_t *)self)->trips;
}

static const metric_desc_t areas_summary[] = {
    { "trips_total", "trips", "entries into the area other than the one last visited, all robots" },
    { "trips_per_robot", "trips", "trips_total over the robots of neither source group" },
    { "visited_both", "robots", "robots that have been in both areas" },
    { NULL, NULL, NULL }
};

static void areas_final(const void *self, const sim_t *sim, double *v)
{
    const areas_t *a = self;
    uint32_t both = 0;
    (void)sim;
    for (uint32_t i = 0; i < a->n; i++) {
        both += a->both[i];
    }
    v[0] = (double)a->trips;
    v[1] = a->movers ? (double)a->trips / a->movers : 0.0;
    v[2] = both;
}

static void areas_draw(const void *self, const sim_t *sim, drawing_t *out)
{
    const areas_t *a = self;
    (void)sim;
    for (uint32_t s = 0; s < a->n_sources; s++) {
        draw_shape_t ring = { .kind = DRAW_RING, .layer = DRAW_FLOOR,
                              .rgb = areas_legend[a->src_kind[s] == AREA_NEST ? KEY_NEST : KEY_FOOD].rgb,
                              .x = a->src_x[s], .y = a->src_y[s], .radius = a->cfg->radius, .line = 0.01f };
        drawing_add(out, &ring);
    }
}

static size_t areas_memory(const void *config, const scenario_t *sc)
{
    (void)config;
    return sizeof(areas_t) + scenario_robot_count(sc) * (3 + 2 * sizeof(float) + 1);
}

const task_def_t areas_task = {
    .name = "areas",
    .doc = "seed 003 NNEA: nest and food discs on the floor under the source robots, and the trips between them",
    .config_size = sizeof(areas_config_t),
    .memory = areas_memory,
    .params = areas_params,
    .default_config = areas_default_config,
    .check = areas_check,
    .create = areas_create,
    .destroy = areas_destroy,
    .after_physics = areas_after_physics,
    .columns = areas_columns,
    .sample = areas_sample,
    .summary = areas_summary,
    .final = areas_final,
    .draw = areas_draw,
    .legend = areas_legend,
};
