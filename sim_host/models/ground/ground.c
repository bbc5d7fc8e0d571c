/*
 * ground.c - the ground-sensor module and the floor it reads (ground.h).
 */
#include "ground.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/sim_internal.h"
#include "units.h"

/* ---------------------------------------------------------------- keys */

static const char *const shape_names[] = { "disc", "box", NULL };

#define R ground_region_t
static const param_desc_t region_params[] = {
    { .key = "shape", PARAM_ENUM_FIELD(R, shape, shape_names), .doc = "disc or box" },
    { .key = "x", PARAM_FIELD(R, x, float), .min = -500, .max = 500, .doc = "centre x, m" },
    { .key = "y", PARAM_FIELD(R, y, float), .min = -500, .max = 500, .doc = "centre y, m" },
    { .key = "radius", PARAM_FIELD(R, radius, float), .min = 0, .max = 500, .doc = "disc radius, m (disc: > 0)" },
    { .key = "width", PARAM_FIELD(R, width, float), .min = 0, .max = 1000,
      .doc = "box size along its x, m (box: > 0)" },
    { .key = "depth", PARAM_FIELD(R, depth, float), .min = 0, .max = 1000,
      .doc = "box size along its y, m (box: > 0)" },
    { .key = "angle", PARAM_FIELD(R, angle, float), .min = -360, .max = 360, .doc = "box rotation, deg CCW" },
    { .key = "reflectance", PARAM_FIELD(R, reflectance, float), .min = 0, .max = 1,
      .doc = "IR reflectance: 1 white paper, 0 black (coloured paper reads nearly white)" },
    PARAM_END
};
#undef R

#define G ground_config_t
static const param_desc_t ground_params[] = {
    { .key = "floor", PARAM_FIELD(G, floor, float), .min = 0, .max = 1,
      .doc = "IR reflectance of the bare floor (1 white, 0 black)" },
    { .key = "white", PARAM_FIELD(G, white, float), .min = 0, .max = 4095,
      .doc = "reading over reflectance 1, counts (about 1000 on white paper)" },
    { .key = "black", PARAM_FIELD(G, black, float), .min = 0, .max = 4095,
      .doc = "reading over reflectance 0, counts" },
    { .key = "noise_rel", PARAM_FIELD(G, noise_rel, float), .min = 0, .max = 1,
      .doc = "relative Gaussian sd of a reading (Webots' e-puck model: 0.1)" },
    { .key = "noise_abs", PARAM_FIELD(G, noise_abs, float), .min = 0, .max = 4095,
      .doc = "additive Gaussian sd, counts" },
    PARAM_END
};
#undef G

static const ground_region_t region_default = { GROUND_DISC, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f };

/* A disc needs a radius, a box its sides. */
static int check_region(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
{
    const ground_region_t *r = elem;
    const char *key = r->shape == GROUND_DISC ? (r->radius > 0.0f ? NULL : "radius")
                      : r->width <= 0.0f ? "width" : r->depth <= 0.0f ? "depth" : NULL;
    char p[SCHEMA_PATH_MAX];
    if (key == NULL) {
        return 0;
    }
    schema_join(p, path, key);
    return schema_fail(ld, schema_node_of(item, key), p, "a %s needs %s > 0", shape_names[r->shape], key);
}

static const schema_t region_schema = { region_params, NULL, NULL, NULL };
/* On the heap: a scenario holds the regions its file lists. */
static const seq_desc_t regions_seq = {
    "regions", GROUND_MAX_REGIONS, sizeof(ground_region_t), &region_default, &region_schema,
    offsetof(ground_config_t, regions), offsetof(ground_config_t, region_count), check_region, 1, NULL
};
static const child_t ground_children[] = {
    { "regions", CHILD_SEQUENCE, NULL, &regions_seq, "areas of the floor with their own grey level" },
    CHILD_END
};
MODEL_ONE_SECTION(ground_schema, "ground", ground_params, ground_children,
                  "the floor the ground sensors read (robots[].ground_sensors)");

#define GG ground_group_config_t
static const param_desc_t group_params[] = {
    { .key = "ground_sensors", PARAM_BOOL_FIELD(GG, fitted),
      .doc = "its robots carry the ground-sensor module (hal_ground; section ground)" },
    PARAM_END
};
#undef GG
static const schema_t ground_group_schema = { group_params, NULL, NULL, NULL };

/* A white floor; the module's response: about 1000 counts on white paper,
 * near 0 on black, 10 % noise (docs/models/ground-sensors.md). */
static void ground_defaults(void *config)
{
    ground_config_t *c = config;
    c->floor = 1.0f;
    c->white = 1000.0f;
    c->black = 0.0f;
    c->noise_rel = 0.1f;
    c->noise_abs = 0.0f;
}

static int ground_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    const ground_config_t *c = config;
    for (uint32_t k = 0; k < c->region_count; k++) {
        if (!scenario_inside_arena(sc, c->regions[k].x, c->regions[k].y, 0.0, 0.0)) {
            snprintf(path, SCHEMA_PATH_MAX, "ground.regions.%u.x", k);
            scenario_outside_message(sc, "the region's centre is", msg, SIM_ERR_MAX);
            return -1;
        }
    }
    return 0;
}

static void ground_free_config(void *config)
{
    ground_config_t *c = config;
    free(c->regions);
    c->regions = NULL;
    c->region_count = 0;
}

/* ---------------------------------------------------------------- a run */

/* One robot's module. */
typedef struct ground_robot {
    uint64_t stamp;                /* value is this step's when == the step's stamp */
    uint16_t value[HAL_GROUND_COUNT];
    uint8_t fitted;
    sim_rand_t rand;               /* its noise (sim_rand_purpose("ground")) */
} ground_robot_t;

typedef struct ground {
    const ground_config_t *cfg;
    ground_robot_t *robot;         /* NULL when no group carries the module */
    ground_region_t *regions;      /* the scenario's, then the tasks' */
    uint32_t n, cap;
} ground_t;

static int any_fitted(const scenario_t *sc)
{
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const ground_group_config_t *gc = scenario_group_model_config(&sc->groups[g], SIM_MODEL_ground);
        if (gc->fitted && sc->groups[g].count > 0) {
            return 1;
        }
    }
    return 0;
}

static void ground_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const ground_config_t *c = config;
    if (any_fitted(sc)) {
        out->arrays = 1;
        out->elem_size[0] = sizeof(ground_robot_t);
    }
    out->run_bytes = sizeof(ground_t) + c->region_count * sizeof(ground_region_t);
}

static int ground_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const ground_config_t *c = config;
    ground_t *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the ground sensors");
        return -1;
    }
    *self = m;
    m->cfg = c;
    if (c->region_count > 0) {
        if (!(m->regions = malloc(c->region_count * sizeof *m->regions))) {
            snprintf(err, SIM_ERR_MAX, "out of memory for %u floor regions", c->region_count);
            return -1;
        }
        memcpy(m->regions, c->regions, c->region_count * sizeof *m->regions);
        m->n = m->cap = c->region_count;
    }
    if (!any_fitted(sim->sc)) {
        return 0;
    }
    m->robot = sim_model_array(sim, SIM_MODEL_ground, 0);
    const uint64_t purpose = sim_rand_purpose("ground");
    for (uint32_t i = 0; i < sim->n; i++) {
        const robot_group_t *grp = &sim->sc->groups[sim->robots[i].group];
        const ground_group_config_t *gc = scenario_group_model_config(grp, SIM_MODEL_ground);
        m->robot[i].fitted = gc->fitted;
        sim_rand_seed(&m->robot[i].rand, sim->seed, i, purpose);
    }
    return 0;
}

static void ground_destroy(void *self)
{
    ground_t *m = self;
    if (m) {
        free(m->regions);
        free(m);
    }
}

int ground_add_region(sim_t *sim, const ground_region_t *region)
{
    ground_t *m = sim_model_self(sim, SIM_MODEL_ground);
    if (m->n == m->cap) {
        uint32_t cap = m->cap ? 2 * m->cap : 8;
        ground_region_t *grown = realloc(m->regions, cap * sizeof *grown);
        if (!grown) {
            return -1;
        }
        m->regions = grown;
        m->cap = cap;
    }
    m->regions[m->n++] = *region;
    return 0;
}

static int holds(const ground_region_t *r, float x, float y)
{
    float dx = x - r->x, dy = y - r->y;
    if (r->shape == GROUND_DISC) {
        return dx * dx + dy * dy <= r->radius * r->radius;
    }
    float a = r->angle * (float)UNITS_PI / 180.0f, c = cosf(a), s = sinf(a);
    float u = c * dx + s * dy, v = -s * dx + c * dy;   /* in the box's frame */
    return fabsf(u) <= 0.5f * r->width && fabsf(v) <= 0.5f * r->depth;
}

float ground_reflectance(const sim_t *sim, float x, float y)
{
    const ground_t *m = sim_model_self(sim, SIM_MODEL_ground);
    for (uint32_t k = m->n; k-- > 0;) {   /* the last listed is on top */
        if (holds(&m->regions[k], x, y)) {
            return m->regions[k].reflectance;
        }
    }
    return m->cfg->floor;
}

static void ground_moved(sim_t *sim, void *self, uint32_t robot)
{
    ground_t *m = self;
    (void)sim;
    if (m->robot) {
        m->robot[robot].stamp = 0;
    }
}

/* The three readings of robot i now. */
static void sense(const sim_t *sim, const ground_t *m, uint32_t i, ground_robot_t *g)
{
    const sim_robot_t *r = &sim->robots[i];
    const ground_config_t *cfg = m->cfg;
    float c = cosf(r->theta), s = sinf(r->theta);
    for (uint32_t k = 0; k < HAL_GROUND_COUNT; k++) {
        float ahead = GROUND_SENSOR_AHEAD_M, left = GROUND_SENSOR_SPACING_M * (1.0f - (float)k);
        float x = r->x + c * ahead - s * left, y = r->y + s * ahead + c * left;
        double v = cfg->black + (cfg->white - cfg->black) * ground_reflectance(sim, x, y);
        v += v * cfg->noise_rel * sim_rand_normal(&g->rand);
        v += cfg->noise_abs * sim_rand_normal(&g->rand);
        g->value[k] = v <= 0.0 ? 0 : v >= HAL_RAW_MAX ? HAL_RAW_MAX : (uint16_t)(v + 0.5);
    }
}

hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected)
{
    ground_t *m = sim_model_self(hal->sim, SIM_MODEL_ground);
    *reflected = 0;
    if (index >= HAL_GROUND_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (!m->robot || !m->robot[hal->index].fitted) {
        return HAL_ERR_UNAVAILABLE;
    }
    ground_robot_t *g = &m->robot[hal->index];
    if (g->stamp != sim_hal_stamp(hal)) {
        sense(hal->sim, m, hal->index, g);
        g->stamp = sim_hal_stamp(hal);
    }
    *reflected = g->value[index];
    return HAL_OK;
}

static const char *const ground_hal_calls[] = { "hal_ground", NULL };

static const model_field_t ground_fields[] = {
    { "ground.reflected", "counts", "the ground sensors' readings last taken (GS0 left, GS1, GS2 right)",
      SIM_FIELD_U16, 0, offsetof(ground_robot_t, value), HAL_GROUND_COUNT },
    { "ground.fitted", "", "1 when the robot carries the ground-sensor module", SIM_FIELD_U8, 0,
      offsetof(ground_robot_t, fitted), 1 },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t ground_model = {
    .name = "ground",
    .doc = "the ground-sensor module: three downward IR sensors over the floor's grey levels",
    .config_size = sizeof(ground_config_t),
    .default_config = ground_defaults,
    .schema = &ground_schema,
    .check = ground_check,
    .free_config = ground_free_config,
    .group_config_size = sizeof(ground_group_config_t),
    .group_schema = &ground_group_schema,
    .layout = ground_layout,
    .create = ground_create,
    .destroy = ground_destroy,
    .moved = ground_moved,
    .hal_calls = ground_hal_calls,
    .fields = ground_fields,
};
