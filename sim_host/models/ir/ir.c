/*
 * ir.c - the eight IR sensors' proximity and ambient light (ir.h).
 */
#include "ir.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "core/sim_internal.h"
#include "models/faults/faults.h"
#include "models/noise_draws.h"
#include "models/per_robot.h"
#include "units.h"

/* Where the sensors are: hal/units.h. */
#define IR_MOUNT_RADIUS EPUCK_IR_MOUNT_RADIUS_M
#define SENSOR_HEIGHT EPUCK_IR_HEIGHT_M

/* ---- per sensor and per robot (the calibration kit's fragment) */
#define S ir_sensor_cal_t
static const param_desc_t sensor_params[] = {
    { .key = "gain", PARAM_FIELD(S, gain, float), .min = 0, .max = 100,
      .doc = "times the table's proximity value" },
    { .key = "offset", PARAM_FIELD(S, offset, float), .min = -4095, .max = 4095,
      .doc = "added to it, counts (the reading with nothing in range)" },
    PARAM_END
};
#undef S
static const schema_t sensor_schema = { sensor_params, NULL, NULL, NULL };
static const ir_sensor_cal_t sensor_default = { 1.0f, 0.0f };

#define RC ir_robot_cal_t
static const param_desc_t robot_params[] = {
    { .key = "id", PARAM_FIELD(RC, id, uint16_t), .min = 0, .max = 65535,
      .doc = "the robot's hal_robot_id" },
    { .key = "noise_rel", PARAM_FIELD(RC, noise_rel, float), .min = 0, .max = 1,
      .doc = "its relative Gaussian sd (absent: the section's)" },
    { .key = "noise_abs", PARAM_FIELD(RC, noise_abs, float), .min = 0, .max = 4095,
      .doc = "its additive Gaussian sd, raw counts (absent: the section's)" },
    PARAM_END
};
static const seq_desc_t robot_sensors_seq = {
    "sensors", HAL_IR_COUNT, sizeof(ir_sensor_cal_t), &sensor_default, &sensor_schema,
    offsetof(RC, sensor), offsetof(RC, sensor_count), NULL, 0, NULL
};
#undef RC
static const child_t robot_children[] = {
    { "sensors", CHILD_SEQUENCE, NULL, &robot_sensors_seq, "its 8 sensors' gain and offset, IR0 first "
      "(absent: the section's)" },
    CHILD_END
};
static const schema_t robot_schema = { robot_params, robot_children, NULL, NULL };

/* An entry's sensors: none (the section's) or all eight. */
static int check_sensor_count(const loader_t *ld, const ynode_t *item, const char *path, uint32_t n)
{
    char p[SCHEMA_PATH_MAX];
    if (n == 0 || n == HAL_IR_COUNT) {
        return 0;
    }
    schema_join(p, path, "sensors");
    return schema_fail(ld, schema_node_of(item, "sensors"), p, "lists %u sensors: give all %u (IR0 first) or none",
                       (unsigned)n, (unsigned)HAL_IR_COUNT);
}

static int check_robot(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
{
    return check_sensor_count(ld, item, path, ((const ir_robot_cal_t *)elem)->sensor_count);
}

static void robot_init(void *elem)
{
    ir_robot_cal_t *e = elem;
    e->noise_rel = e->noise_abs = NAN;
}

static const ir_robot_cal_t robot_default = { 0, 0.0f, 0.0f, 0, { { 1.0f, 0.0f } } };

#define C ir_config_t
static const seq_desc_t sensors_seq = {
    "sensors", HAL_IR_COUNT, sizeof(ir_sensor_cal_t), &sensor_default, &sensor_schema,
    offsetof(C, sensor), offsetof(C, sensor_count), NULL, 0, NULL
};
static const seq_desc_t robots_seq = {
    "robots", PER_ROBOT_MAX, sizeof(ir_robot_cal_t), &robot_default, &robot_schema,
    offsetof(C, robots), offsetof(C, robot_count), check_robot, 1, robot_init
};

#define A ambient_robot_cal_t
static const param_desc_t ambient_robot_params[] = {
    { .key = "id", PARAM_FIELD(A, id, uint16_t), .min = 0, .max = 65535,
      .doc = "the robot's hal_robot_id" },
    { .key = "dark", PARAM_FIELD(A, dark, float), .min = 0, .max = 4095,
      .doc = "its reading in the dark, counts (absent: the section's)" },
    { .key = "half", PARAM_FIELD(A, half, float), .min = 1e-6, .max = 1e6,
      .doc = "the irradiance at which its reading halves (absent: the section's)" },
    { .key = "noise_rel", PARAM_FIELD(A, noise_rel, float), .min = 0, .max = 1,
      .doc = "its relative Gaussian sd (absent: the section's)" },
    PARAM_END
};
#undef A
static const schema_t ambient_robot_schema = { ambient_robot_params, NULL, NULL, NULL };
static void ambient_robot_init(void *elem)
{
    ambient_robot_cal_t *e = elem;
    e->dark = e->half = e->noise_rel = NAN;
}
static const ambient_robot_cal_t ambient_robot_default = { 0, 0.0f, 0.0f, 0.0f };
static const seq_desc_t ambient_robots_seq = {
    "robots", PER_ROBOT_MAX, sizeof(ambient_robot_cal_t), &ambient_robot_default, &ambient_robot_schema,
    offsetof(C, ambient.robots), offsetof(C, ambient.robot_count), NULL, 1, ambient_robot_init
};

static const param_desc_t ir_params[] = {
    { .key = "aperture", PARAM_FIELD(C, aperture, float), .min = 0.1, .max = 90,
      .doc = "half-angle of the sensing cone, deg" },
    { .key = "range", PARAM_FIELD(C, range, float), .min = 0.001, .max = 1,
      .doc = "beyond this a sensor reads ~0, m" },
    { .key = "noise_rel", PARAM_FIELD(C, noise_rel, float), .min = 0, .max = 1,
      .doc = "relative Gaussian sd of the value" },
    { .key = "noise_abs", PARAM_FIELD(C, noise_abs, float), .min = 0, .max = 4095,
      .doc = "additive Gaussian sd, raw counts" },
    { .key = "noise_draws", PARAM_ENUM_FIELD(C, noise_draws, noise_draws_names),
      .doc = "the relative and additive noise drawn apart (per_term) or as one (summed: the same distribution)" },
    PARAM_END
};

static const param_desc_t ambient_params[] = {
    { .key = "dark", PARAM_FIELD(C, ambient.dark, float), .min = 0, .max = 4095,
      .doc = "raw reading in the dark, counts" },
    { .key = "half", PARAM_FIELD(C, ambient.half, float), .min = 1e-6, .max = 1e6,
      .doc = "irradiance at which the reading halves (1 = unit lamp at 1 m)" },
    { .key = "noise_rel", PARAM_FIELD(C, ambient.noise_rel, float), .min = 0, .max = 1,
      .doc = "relative Gaussian sd" },
    PARAM_END
};
#undef C

static const child_t ir_children[] = {
    { "sensors", CHILD_SEQUENCE, NULL, &sensors_seq, "the 8 sensors' gain and offset, IR0 first (a lab's "
      "average; absent: gain 1, offset 0)" },
    { "robots", CHILD_SEQUENCE, NULL, &robots_seq, "parameters fitted to one robot id (the calibration kit)" },
    CHILD_END
};
static const child_t ambient_children[] = {
    { "robots", CHILD_SEQUENCE, NULL, &ambient_robots_seq, "parameters fitted to one robot id" },
    CHILD_END
};
static const schema_t ir_section = { ir_params, ir_children, NULL, NULL };
static const schema_t ambient_section = { ambient_params, ambient_children, NULL, NULL };
static const child_t sections[] = {
    { "ir", CHILD_MAPPING, &ir_section, NULL, "IR proximity sensors" },
    { "ambient", CHILD_MAPPING, &ambient_section, NULL, "ambient light sensors" },
    CHILD_END
};
static const schema_t ir_schema = { NULL, sections, NULL, NULL };

/* About 1 % noise (Webots' calibration), 10 cm of reach, a 15 deg cone. */
static void ir_defaults(void *config)
{
    ir_config_t *c = config;
    c->aperture = 15.0f;
    c->range = 0.1f;
    c->noise_rel = 0.01f;
    c->noise_abs = 5.0f;
    c->noise_draws = NOISE_DRAWS_PER_TERM;
    c->ambient.dark = 4000.0f;
    c->ambient.half = 1.0f;
    c->ambient.noise_rel = 0.01f;
}

static int ir_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    const ir_config_t *c = config;
    (void)sc;
    if (c->sensor_count != 0 && c->sensor_count != HAL_IR_COUNT) {
        snprintf(path, SCHEMA_PATH_MAX, "ir.sensors");
        snprintf(msg, SIM_ERR_MAX, "lists %u sensors: give all %u (IR0 first) or none", (unsigned)c->sensor_count,
                 (unsigned)HAL_IR_COUNT);
        return -1;
    }
    int32_t k = per_robot_duplicate(c->robots, c->robot_count, sizeof *c->robots, offsetof(ir_robot_cal_t, id));
    const char *sec = "ir";
    if (k < 0) {
        k = per_robot_duplicate(c->ambient.robots, c->ambient.robot_count, sizeof *c->ambient.robots,
                                offsetof(ambient_robot_cal_t, id));
        sec = "ambient";
    }
    if (k >= 0) {
        snprintf(path, SCHEMA_PATH_MAX, "%s.robots.%d.id", sec, (int)k);
        snprintf(msg, SIM_ERR_MAX, "robot id listed twice: one entry per robot");
        return -1;
    }
    return 0;
}

static void ir_free_config(void *config)
{
    ir_config_t *c = config;
    free(c->robots);
    free(c->ambient.robots);
    c->robots = NULL;
    c->ambient.robots = NULL;
    c->robot_count = c->ambient.robot_count = 0;
}

/* One robot's readings, valid when their stamp is the step's (sim_hal_stamp). */
typedef struct ir_robot {
    uint64_t prox_stamp, ambient_stamp;
    uint16_t prox[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    sim_rand_t noise;              /* both readings' (RAND_SENSORS) */
} ir_robot_t;

/* Which `robots` entries a robot takes (an array only when the scenario
 * lists some: other runs pay nothing). */
typedef struct ir_cal_cache {
    per_robot_cache_t prox, ambient;
} ir_cal_cache_t;

typedef struct ir {
    const ir_config_t *cfg;
    ir_robot_t *robot;
    ir_cal_cache_t *cal;           /* NULL: no `robots` entries */
    vec2_t dir[HAL_IR_COUNT];      /* the sensors' bearings as unit vectors, robot frame */
    float half, cos_half, sin_half;   /* the cone's half-angle, rad, its cosine and sine */
} ir_t;

static void ir_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const ir_config_t *c = config;
    (void)sc;
    out->arrays = (c->robot_count > 0 || c->ambient.robot_count > 0) ? 2 : 1;
    out->elem_size[0] = sizeof(ir_robot_t);
    out->elem_size[1] = sizeof(ir_cal_cache_t);
    out->run_bytes = sizeof(ir_t);
    /* A proximity query looks this far around a robot's body. */
    out->neighbour_reach_m = c->range;
}

static int ir_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    /* From the one table of bearings (units.h). */
    static const int deg[HAL_IR_COUNT] = EPUCK_IR_BEARINGS_DEG;
    ir_t *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the IR sensors");
        return -1;
    }
    *self = m;
    m->cfg = config;
    m->robot = sim_model_array(sim, SIM_MODEL_ir, 0);
    for (uint32_t s = 0; s < HAL_IR_COUNT; s++) {
        m->dir[s] = v2((float)cos(deg[s] * UNITS_PI / 180.0), (float)sin(deg[s] * UNITS_PI / 180.0));
    }
    m->half = m->cfg->aperture * (float)UNITS_PI / 180.0f;
    m->cos_half = cosf(m->half);
    m->sin_half = sinf(m->half);
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&m->robot[i].noise, sim->seed, i, RAND_SENSORS);
    }
    if (m->cfg->robot_count > 0 || m->cfg->ambient.robot_count > 0) {
        m->cal = sim_model_array(sim, SIM_MODEL_ir, 1);
        for (uint32_t i = 0; i < sim->n; i++) {
            m->cal[i].prox.id = m->cal[i].ambient.id = -1;
        }
    }
    return 0;
}

static void ir_destroy(void *self) { free(self); }

/* Proximity (raw counts) against distance from the sensor to a surface,
 * measured on a real e-puck (the calibration of Webots' e-puck
 * model, taken on the robot). */
static const float ir_table_m[] = { 0.000f, 0.005f, 0.010f, 0.015f, 0.020f,
                                    0.030f, 0.040f, 0.050f, 0.060f, 0.070f };
static const float ir_table_v[] = { 4095, 2133, 1466, 601, 384, 235, 158, 120, 104, 67 };
#define IR_TABLE_N (sizeof ir_table_m / sizeof ir_table_m[0])

/** Calibrated proximity without noise at distance d (m).  Beyond the last
 *  measured point (70 mm: 67) the value fades linearly to 0 at `range`:
 *  an assumption, documented in docs/models/ir-proximity.md. */
float ir_curve(float d, float range)
{
    if (d <= 0.0f) {
        return ir_table_v[0];
    }
    for (size_t k = 1; k < IR_TABLE_N; k++) {
        if (d <= ir_table_m[k]) {
            float u = (d - ir_table_m[k - 1]) / (ir_table_m[k] - ir_table_m[k - 1]);
            return ir_table_v[k - 1] + u * (ir_table_v[k] - ir_table_v[k - 1]);
        }
    }
    float last = ir_table_m[IR_TABLE_N - 1];
    if (d >= range || range <= last) {
        return 0.0f;
    }
    return ir_table_v[IR_TABLE_N - 1] * (range - d) / (range - last);
}

/* Rounded and clamped to 0..HAL_RAW_MAX, the clamp on the integer (no
 * branch: a lone sensor's reading is its noise alone, negative half the
 * time, and a branch on its sign would be mispredicted as often).  The
 * same as clamping v first: v + 0.5 truncates to 0 or less for v <= 0, to
 * HAL_RAW_MAX or more for v >= HAL_RAW_MAX; |v| stays far below 2^62 (a
 * reading of at most 4095 and noise of a few sd). */
static uint16_t to_raw(double v)
{
    int64_t k = (int64_t)(v + 0.5);
    k = k < 0 ? 0 : k;
    k = k > HAL_RAW_MAX ? HAL_RAW_MAX : k;
    return (uint16_t)k;
}

/* The smaller of two distances: fminf without its call (the distances
 * here are never NaN; of two zeros the reading is the same). */
static inline float nearer(float d, float e) { return e < d ? e : d; }

static float nearest_obstacle(const obstacle_t *o, const cone_t *k)
{
    if (o->shape == SHAPE_CYLINDER) {
        return geom_cone_circle(k, o->c, o->r);
    }
    float d = INFINITY;
    for (int e = 0; e < 4; e++) {
        d = nearer(d, geom_cone_segment(k, o->corner[e], o->corner[(e + 1) & 3]));
    }
    return d;
}

#define IR_MAX_NEAR 64

/* An arena wall's inner face: the segment, and the unit normal towards it
 * from inside along `axis` (0: x, 1: y) with `sign`, at coordinate `at`. */
typedef struct wall {
    vec2_t a, b;
    int axis;
    float sign, at;
} wall_t;

/* Margin for the tests that skip a wall (m): far above float rounding. */
#define WALL_SKIP_MARGIN 1e-3f

/* Non-zero when wall w cannot be nearer than `range` to any point in cone
 * k, so that leaving it out leaves the sensor's reading as it was (only a
 * distance below `range` counts): the cone's apex lies at least `range`
 * from the wall's line, or inside the arena and looking away from the
 * wall (neither edge has a component towards it; a cone narrower than a
 * half-plane lies between its edges).  geom_cone_segment would return
 * INFINITY or a distance of at least `range` then: the cheap test saves
 * it. */
static int wall_out_of_reach(const wall_t *w, const cone_t *k, float range, float half)
{
    float apex = w->axis ? k->p.y : k->p.x;
    float gap = w->sign * (w->at - apex);
    if (gap >= range + WALL_SKIP_MARGIN) {
        return 1;
    }
    float e1 = w->sign * (w->axis ? k->e1.y : k->e1.x), e2 = w->sign * (w->axis ? k->e2.y : k->e2.x);
    return gap >= WALL_SKIP_MARGIN && half < 1.55f && e1 <= 0.0f && e2 <= 0.0f;
}

static void sense_proximity(struct sim *sim, const ir_t *m, uint32_t i, uint16_t out[HAL_IR_COUNT])
{
    const sim_robot_t *r = &sim->robots[i];
    const ir_config_t *cfg = m->cfg;
    sim_rand_t *noise = &m->robot[i].noise;
    float range = cfg->range;
    float reach = IR_MOUNT_RADIUS + range;
    uint32_t near_robot[IR_MAX_NEAR], near_obst[IR_MAX_NEAR];
    float R = reach + EPUCK_BODY_RADIUS_M;
    uint32_t nr = sim_gather_robots(sim, r->x - R, r->y - R, r->x + R, r->y + R, near_robot, IR_MAX_NEAR);
    uint32_t no = sim_gather_obstacles(sim, sim_robot_scratch(sim, i), r->x - reach, r->y - reach, r->x + reach,
                                       r->y + reach, near_obst, IR_MAX_NEAR);
    /* Inner faces of the walls within reach. */
    wall_t wall[4];
    int nw = 0;
    float hw = sim->hw, hh = sim->hh;
    if (r->x + reach > hw) wall[nw++] = (wall_t){ v2(hw, -hh), v2(hw, hh), 0, 1.0f, hw };
    if (r->x - reach < -hw) wall[nw++] = (wall_t){ v2(-hw, -hh), v2(-hw, hh), 0, -1.0f, -hw };
    if (r->y + reach > hh) wall[nw++] = (wall_t){ v2(-hw, hh), v2(hw, hh), 1, 1.0f, hh };
    if (r->y - reach < -hh) wall[nw++] = (wall_t){ v2(-hw, -hh), v2(hw, -hh), 1, -1.0f, -hh };

    const ir_robot_cal_t *e = NULL;
    if (m->cal != NULL) {
        e = per_robot_entry(&m->cal[i].prox, cfg->robots, cfg->robot_count, sizeof *cfg->robots,
                            offsetof(ir_robot_cal_t, id), r->id);
    }
    const ir_sensor_cal_t *gains = (e != NULL && e->sensor_count) ? e->sensor
                                   : (cfg->sensor_count ? cfg->sensor : NULL);
    float noise_rel = (e != NULL && !isnan(e->noise_rel)) ? e->noise_rel : cfg->noise_rel;
    float noise_abs = (e != NULL && !isnan(e->noise_abs)) ? e->noise_abs : cfg->noise_abs;
    float ch = cosf(r->theta), sh = sinf(r->theta);
    float half = m->half, cos_half = m->cos_half, sin_half = m->sin_half;
    /* Each sensor's two draws (relative, then absolute), in sensor order;
     * summed: one each (models/noise_draws.h). */
    int summed = cfg->noise_draws == NOISE_DRAWS_SUMMED;
    double n[2 * HAL_IR_COUNT];
    sim_rand_normals(noise, n, summed ? HAL_IR_COUNT : 2 * HAL_IR_COUNT);
    for (uint32_t s = 0; s < HAL_IR_COUNT; s++) {
        float d = INFINITY;
        if (nr > 1 || no > 0 || nw > 0) {
            vec2_t a = v2_rot(m->dir[s], ch, sh);
            vec2_t p = v2(r->x + IR_MOUNT_RADIUS * a.x, r->y + IR_MOUNT_RADIUS * a.y);
            cone_t k = geom_cone_dir(p, a, half, cos_half, sin_half);
            for (uint32_t j = 0; j < nr; j++) {
                if (near_robot[j] != i) {
                    d = nearer(d, geom_cone_circle(&k, sim_robot_at(sim, near_robot[j]), EPUCK_BODY_RADIUS_M));
                }
            }
            for (uint32_t j = 0; j < no; j++) {
                d = nearer(d, nearest_obstacle(&sim->obstacles[near_obst[j]], &k));
            }
            for (int w = 0; w < nw; w++) {
                if (!wall_out_of_reach(&wall[w], &k, range, half)) {
                    d = nearer(d, geom_cone_segment(&k, wall[w].a, wall[w].b));
                }
            }
        }
        double v = (d < range) ? ir_curve(d, range) : 0.0f;
        if (gains != NULL) {
            v = gains[s].gain * v + gains[s].offset;
        }
        if (summed) {
            /* v (1 + rel N1) + abs N2 is, in distribution,
             * v + sqrt((v rel)^2 + abs^2) N. */
            double rel = v * noise_rel;
            v += sqrt(rel * rel + (double)noise_abs * noise_abs) * n[s];
        } else {
            v += v * noise_rel * n[2 * s];
            v += noise_abs * n[2 * s + 1];
        }
        out[s] = to_raw(v);
    }
}

static void sense_ambient(struct sim *sim, const ir_t *m, uint32_t i, uint16_t out[HAL_IR_COUNT])
{
    const sim_robot_t *r = &sim->robots[i];
    const scenario_t *sc = sim->sc;
    const ir_config_t *cfg = m->cfg;
    sim_rand_t *noise = &m->robot[i].noise;
    const ambient_robot_cal_t *e = NULL;
    if (m->cal != NULL) {
        e = per_robot_entry(&m->cal[i].ambient, cfg->ambient.robots, cfg->ambient.robot_count,
                            sizeof *cfg->ambient.robots, offsetof(ambient_robot_cal_t, id), r->id);
    }
    float dark = (e != NULL && !isnan(e->dark)) ? e->dark : cfg->ambient.dark;
    float halfe = (e != NULL && !isnan(e->half)) ? e->half : cfg->ambient.half;
    float noise_rel = (e != NULL && !isnan(e->noise_rel)) ? e->noise_rel : cfg->ambient.noise_rel;
    float ch = cosf(r->theta), sh = sinf(r->theta);
    double n[HAL_IR_COUNT];
    sim_rand_normals(noise, n, HAL_IR_COUNT);
    for (uint32_t s = 0; s < HAL_IR_COUNT; s++) {
        vec2_t a = v2_rot(m->dir[s], ch, sh);
        vec2_t p = v2(r->x + IR_MOUNT_RADIUS * a.x, r->y + IR_MOUNT_RADIUS * a.y);
        /* Irradiance on the sensor: intensity * cos(incidence) / d^2 from
         * each lamp, in 3D (lamps hang above the floor).  Shadows cast by
         * robots and obstacles are not modelled. */
        double irr = 0.0;
        for (uint32_t l = 0; l < sc->light_count; l++) {
            const light_def_t *L = &sc->lights[l];
            double hx = L->x - p.x, hy = L->y - p.y, dz = L->height - SENSOR_HEIGHT;
            double d2 = hx * hx + hy * hy + dz * dz, facing = hx * a.x + hy * a.y;
            /* A lamp behind the sensor (facing <= 0) adds nothing: its square
             * root and two divisions are skipped, the sum as it was. */
            if (facing > 0.0 && d2 > 1e-12) {
                double along = facing / sqrt(d2);
                if (along > 0.0) {
                    irr += L->intensity * along / d2;
                }
            }
        }
        /* The raw value falls as light rises: dark at irr = 0, dark/2 at
         * irr = half, towards 0 for bright light. */
        double v = dark * halfe / (halfe + irr);
        v += v * noise_rel * n[s];
        out[s] = to_raw(v);
    }
}


static void ir_moved(sim_t *sim, void *self, uint32_t robot)
{
    ir_t *m = self;
    (void)sim;
    m->robot[robot].prox_stamp = m->robot[robot].ambient_stamp = 0;
}

/* The largest proximity and the lowest ambient reading the robot took at
 * stamp `since` or later (telemetry's summary). */
static void ir_platform(const sim_t *sim, const void *self, uint32_t robot, uint64_t since,
                        robot_telemetry_platform_t *p)
{
    const ir_robot_t *r = &((const ir_t *)self)->robot[robot];
    (void)sim;
    if (r->prox_stamp != 0 && r->prox_stamp >= since) {
        uint16_t best = 0;
        uint8_t at = 0;
        for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
            if (r->prox[k] > best) {
                best = r->prox[k];
                at = k;
            }
        }
        p->ir_max = (int16_t)best;
        p->ir_max_index = (int8_t)at;
    }
    if (r->ambient_stamp != 0 && r->ambient_stamp >= since) {
        uint16_t low = HAL_RAW_MAX;
        for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
            low = r->ambient[k] < low ? r->ambient[k] : low;
        }
        p->ambient_min = (int16_t)low;
    }
}

/* The latest readings of both kinds, and the sensors' bearings. */
static void ir_inspect(const sim_t *sim, const void *self, uint32_t robot, model_inspect_t *out)
{
    const ir_t *m = self;
    const ir_robot_t *r = &m->robot[robot];
    (void)sim;
    out->prox_known = r->prox_stamp != 0;
    out->ambient_known = r->ambient_stamp != 0;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        out->prox[k] = r->prox[k];
        out->ambient[k] = r->ambient[k];
        out->ir_bearing_mrad[k] = (int16_t)lround(1000.0 * atan2(m->dir[k].y, m->dir[k].x));
    }
}

/* ---------------------------------------------------------------- HAL */

uint16_t hal_ir_proximity(hal_t *hal, uint8_t index)
{
    ir_t *m = sim_model_self(hal->sim, SIM_MODEL_ir);
    ir_robot_t *r = &m->robot[hal->index];
    if (index >= HAL_IR_COUNT) {
        return 0;
    }
    if (r->prox_stamp != sim_hal_stamp(hal)) {
        sense_proximity(hal->sim, m, hal->index, r->prox);
        faults_ir(hal->sim, hal->index, r->prox);
        r->prox_stamp = sim_hal_stamp(hal);
    }
    return r->prox[index];
}

uint16_t hal_ir_ambient(hal_t *hal, uint8_t index)
{
    ir_t *m = sim_model_self(hal->sim, SIM_MODEL_ir);
    ir_robot_t *r = &m->robot[hal->index];
    if (index >= HAL_IR_COUNT) {
        return HAL_RAW_MAX;
    }
    if (r->ambient_stamp != sim_hal_stamp(hal)) {
        sense_ambient(hal->sim, m, hal->index, r->ambient);
        r->ambient_stamp = sim_hal_stamp(hal);
    }
    return r->ambient[index];
}

static const char *const ir_hal_calls[] = { "hal_ir_proximity", "hal_ir_ambient", NULL };

static const model_field_t ir_fields[] = {
    { "ir.proximity", "counts", "the proximity readings last taken (0..4095, larger is closer)", SIM_FIELD_U16, 0,
      offsetof(ir_robot_t, prox), HAL_IR_COUNT },
    { "ir.ambient", "counts", "the ambient readings last taken (0..4095, falls as light rises)", SIM_FIELD_U16, 0,
      offsetof(ir_robot_t, ambient), HAL_IR_COUNT },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t ir_model = {
    .name = "ir",
    .doc = "the eight IR sensors: proximity (Webots' measured curve) and ambient light",
    .config_size = sizeof(ir_config_t),
    .default_config = ir_defaults,
    .schema = &ir_schema,
    .check = ir_check,
    .free_config = ir_free_config,
    .layout = ir_layout,
    .create = ir_create,
    .destroy = ir_destroy,
    .moved = ir_moved,
    .platform = ir_platform,
    .inspect = ir_inspect,
    .hal_calls = ir_hal_calls,
    .fields = ir_fields,
};
