/*
 * scenario.c - the strict scenario loader: every key's type, range, unit and
 * default as descriptor tables (param_desc_t), and the check of a YAML tree
 * (yaml_tree.c: parsing and --set overrides) against them.
 *
 * Decisions:
 *  - An empty file (or one with only comments, or a null document) gives the
 *    defaults; so does an empty section (`robots:` with nothing after it).
 *  - Integers are decimal with an optional sign: "2.5", "1e3", "0x10", "5m"
 *    and quoted "5" are errors, as is a value outside the key's range or its
 *    C type.  Numbers accept integers, decimals and exponents but not
 *    nan/inf/.inf, hex or trailing garbage.  Booleans are true/false (any
 *    case YAML 1.2 allows), not yes/no/on/off/1/0.
 *  - Strings may be plain or quoted but not empty or null.
 *  - Every object and light must be a mapping; absent keys take the entry
 *    defaults below.  A cylinder needs radius > 0, a box width and depth > 0;
 *    keys of the other shape are ignored.  Objects must lie wholly inside the
 *    arena (the inside of the walls), lights and the nest likewise.
 */
#include "scenario.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "controllers.h"
#include "yaml_tree.h"

#define PATH_BUF 256
#define DEFAULT_CONTROLLER "random_walk"
/* Objects may touch the walls: rounding must not reject them. */
#define ARENA_EPS 1e-6
/* M_PI is not in strict C11/POSIX. */
#define DEG_TO_RAD (3.14159265358979323846 / 180.0)

/* ---------------------------------------------------------------- errors */

typedef struct loader {
    const char *file;
    char *err;  /* SCENARIO_ERROR_MAX bytes */
} loader_t;

/* snprintf that may cut: messages and key paths are bounded on purpose
 * (and, unlike snprintf, GCC does not warn about it). */
__attribute__((format(printf, 3, 4)))
static void format_into(char *buf, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, len, fmt, ap);
    va_end(ap);
}

/* "FILE:LINE: path: message", or "--set TEXT: path: message" for a value
 * that an override wrote.  Always returns -1. */
__attribute__((format(printf, 4, 5)))
static int fail(const loader_t *ld, const ynode_t *node, const char *path, const char *fmt, ...)
{
    char msg[SCENARIO_ERROR_MAX], where[SCENARIO_PATH_MAX + 32];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (node != NULL && node->origin != NULL) {
        format_into(where, sizeof where, "--set %s", node->origin);
    } else if (node != NULL && node->line > 0) {
        format_into(where, sizeof where, "%s:%d", ld->file, node->line);
    } else {
        format_into(where, sizeof where, "%s", ld->file);
    }
    if (path[0] != '\0') {
        format_into(ld->err, SCENARIO_ERROR_MAX, "%s: %s: %s", where, path, msg);
    } else {
        format_into(ld->err, SCENARIO_ERROR_MAX, "%s: %s", where, msg);
    }
    return -1;
}

static int wrong_type(const loader_t *ld, const ynode_t *v, const char *path, const char *expected)
{
    char got[64];
    ytree_describe(v, got, sizeof got);
    return fail(ld, v, path, "expected %s, got %s", expected, got);
}

/* "parent.key" (or "key" at the top level); a long unknown key is cut so
 * that the message stays readable. */
static void join(char out[PATH_BUF], const char *parent, const char *key)
{
    if (parent[0] == '\0') {
        format_into(out, PATH_BUF, "%.64s", key);
    } else {
        format_into(out, PATH_BUF, "%s.%.64s", parent, key);
    }
}

/* Integral values print without a fraction, others with %g. */
static void format_number(double v, char *buf, size_t len)
{
    if (fabs(v) < 1e15 && v == (double)(long long)v) {
        snprintf(buf, len, "%.0f", v);
    } else {
        snprintf(buf, len, "%g", v);
    }
}

static void format_range(const param_desc_t *d, char *buf, size_t len)
{
    char lo[32], hi[32];
    size_t used = 0;
    const char *const *c;
    switch (d->type) {
    case PARAM_BOOL:
        snprintf(buf, len, "true|false");
        return;
    case PARAM_STRING:
        snprintf(buf, len, "<= %zu chars", d->size - 1);
        return;
    case PARAM_ENUM:
        buf[0] = '\0';
        for (c = d->choices; *c != NULL && used < len; c++) {
            used += (size_t)snprintf(buf + used, len - used, "%s%s", c == d->choices ? "" : "|", *c);
        }
        return;
    default:
        format_number(d->min, lo, sizeof lo);
        if (d->type == PARAM_U64 && d->max >= (double)UINT64_MAX) {
            snprintf(hi, sizeof hi, "%" PRIu64, UINT64_MAX);
        } else {
            format_number(d->max, hi, sizeof hi);
        }
        snprintf(buf, len, "[%s, %s]", lo, hi);
    }
}

static int out_of_range(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                        const char *path)
{
    char range[64];
    format_range(d, range, sizeof range);
    return fail(ld, v, path, "%.40s is out of range %s", v->text, range);
}

/* Optimal string alignment distance (typos: one edit or swap is 1). */
static size_t edit_distance(const char *a, const char *b)
{
    unsigned char d[33][33];
    size_t la = strlen(a), lb = strlen(b), i, j;
    if (la > 32 || lb > 32) {
        return 99;
    }
    for (i = 0; i <= la; i++) {
        for (j = 0; j <= lb; j++) {
            size_t best;
            if (i == 0 || j == 0) {
                d[i][j] = (unsigned char)(i + j);
                continue;
            }
            best = (size_t)d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if ((size_t)d[i - 1][j] + 1 < best) best = (size_t)d[i - 1][j] + 1;
            if ((size_t)d[i][j - 1] + 1 < best) best = (size_t)d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                (size_t)d[i - 2][j - 2] + 1 < best) {
                best = (size_t)d[i - 2][j - 2] + 1;
            }
            d[i][j] = (unsigned char)best;
        }
    }
    return d[la][lb];
}

/* Keeps in *best the candidate closest to `word` within distance 2. */
static void consider(const char *word, const char *candidate, const char **best, size_t *dist)
{
    size_t d = edit_distance(word, candidate);
    if (d <= 2 && d < *dist) {
        *best = candidate;
        *dist = d;
    }
}

/* ---------------------------------------------------------------- schema */

typedef struct schema schema_t;
typedef struct seq_desc seq_desc_t;

typedef enum child_kind {
    CHILD_MAPPING,     /* a nested struct of scenario_t */
    CHILD_SEQUENCE,    /* objects, lights */
    CHILD_CONTROLLER,  /* controller: its name decides the params schema */
    CHILD_DEFERRED     /* controller.params: checked by CHILD_CONTROLLER */
} child_kind_t;

/* A key whose value is a mapping or a sequence.  CHILD_SEQUENCE and
 * CHILD_CONTROLLER appear only where the base is the scenario_t itself. */
typedef struct child {
    const char *key;
    child_kind_t kind;
    const schema_t *schema;  /* CHILD_MAPPING, CHILD_CONTROLLER */
    const seq_desc_t *seq;   /* CHILD_SEQUENCE */
    const char *doc;
} child_t;

struct schema {
    const param_desc_t *params;  /* scalar keys, offsets from the base */
    const child_t *children;     /* NULL, or ends with a NULL key */
};

typedef int (*elem_check_fn)(const loader_t *ld, const ynode_t *item, const char *path,
                             const void *elem);

struct seq_desc {
    const char *noun;      /* "objects" */
    size_t max;
    size_t elem_size;
    const void *defaults;  /* one element with every default */
    const schema_t *schema;
    size_t array_offset;   /* of the array in scenario_t */
    size_t count_offset;   /* of its uint32_t count in scenario_t */
    elem_check_fn check;   /* or NULL */
};

#define CHILD_END { NULL, CHILD_MAPPING, NULL, NULL, NULL }
/* offsetof and size of a member, possibly nested ("arena.width"). */
#define SC(m) offsetof(scenario_t, m), sizeof(((scenario_t *)0)->m)
#define OBJ(m) offsetof(object_def_t, m), sizeof(((object_def_t *)0)->m)
#define LIGHT(m) offsetof(light_def_t, m), sizeof(((light_def_t *)0)->m)
/* Positions: the arena is at most 1000 m wide, centred on 0,0. */
#define POS_MIN -500.0
#define POS_MAX 500.0

static const char *const placement_choices[] = { "random", "nest", "grid", NULL };
static const char *const shape_choices[] = { "cylinder", "box", NULL };
static const char *const colour_choices[] = { "none", "red", "green", "blue", NULL };

static const param_desc_t top_params[] = {
    { "name", PARAM_STRING, SC(name), 0, 0, NULL,
      "scenario name (default: the file name without its extension)" },
    { "seed", PARAM_U64, SC(seed), 0, (double)UINT64_MAX, NULL,
      "base random seed; repetition r uses seed + r" },
    { "duration", PARAM_DOUBLE, SC(duration), 0.001, 1e7, NULL, "simulated time, s" },
    { "control_period_ms", PARAM_U16, SC(control_period_ms), 1, 10000, NULL,
      "one controller step, ms" },
    { "physics_substeps", PARAM_U16, SC(physics_substeps), 1, 64, NULL,
      "physics sub-steps per control step" },
    PARAM_END
};

static const param_desc_t arena_params[] = {
    { "width", PARAM_FLOAT, SC(arena.width), 0.1, 1000, NULL,
      "inside size along x of the walled rectangle centred on 0,0, m" },
    { "height", PARAM_FLOAT, SC(arena.height), 0.1, 1000, NULL, "inside size along y, m" },
    { "wall_thickness", PARAM_FLOAT, SC(arena.wall_thickness), 0.001, 10, NULL,
      "wall thickness (outside the width x height), m" },
    PARAM_END
};

static const param_desc_t nest_params[] = {
    { "enabled", PARAM_BOOL, SC(nest.enabled), 0, 1, NULL, "draw the grey nest circle" },
    { "x", PARAM_FLOAT, SC(nest.x), POS_MIN, POS_MAX, NULL, "nest centre x, m" },
    { "y", PARAM_FLOAT, SC(nest.y), POS_MIN, POS_MAX, NULL, "nest centre y, m" },
    { "diameter", PARAM_FLOAT, SC(nest.diameter), 0.01, 1000, NULL, "nest diameter, m" },
    PARAM_END
};

static const param_desc_t robots_params[] = {
    { "count", PARAM_U32, SC(robots.count), 0, 100000, NULL, "number of e-pucks" },
    { "placement", PARAM_ENUM, SC(robots.placement), 0, 0, placement_choices,
      "start positions: anywhere, in the nest, or on a grid" },
    { "min_spacing", PARAM_FLOAT, SC(robots.min_spacing), 0.07, 10, NULL,
      "centre-to-centre distance when placing, m (the body is 0.07 m)" },
    PARAM_END
};

static const param_desc_t object_params[] = {
    { "shape", PARAM_ENUM, OBJ(shape), 0, 0, shape_choices, "obstacle shape" },
    { "x", PARAM_FLOAT, OBJ(x), POS_MIN, POS_MAX, NULL, "centre x, m" },
    { "y", PARAM_FLOAT, OBJ(y), POS_MIN, POS_MAX, NULL, "centre y, m" },
    { "radius", PARAM_FLOAT, OBJ(radius), 0, 500, NULL, "cylinder radius, m (cylinder: > 0)" },
    { "width", PARAM_FLOAT, OBJ(width), 0, 1000, NULL, "box size along its x, m (box: > 0)" },
    { "depth", PARAM_FLOAT, OBJ(depth), 0, 1000, NULL, "box size along its y, m (box: > 0)" },
    { "angle", PARAM_FLOAT, OBJ(angle), -360, 360, NULL, "box rotation, deg counter-clockwise" },
    { "height", PARAM_FLOAT, OBJ(height), 0.001, 100, NULL, "height, m (camera, pictures)" },
    { "colour", PARAM_ENUM, OBJ(colour), 0, 0, colour_choices, "colour the camera sees" },
    PARAM_END
};

static const param_desc_t light_params[] = {
    { "x", PARAM_FLOAT, LIGHT(x), POS_MIN, POS_MAX, NULL, "lamp x, m" },
    { "y", PARAM_FLOAT, LIGHT(y), POS_MIN, POS_MAX, NULL, "lamp y, m" },
    { "height", PARAM_FLOAT, LIGHT(height), 0, 100, NULL, "lamp height above the floor, m" },
    { "intensity", PARAM_FLOAT, LIGHT(intensity), 0, 1e6, NULL,
      "relative: 1 gives irradiance 1 at 1 m" },
    PARAM_END
};

static const param_desc_t controller_params[] = {
    { "name", PARAM_STRING, SC(controller.name), 0, 0, NULL,
      "registered controller (see controller.params below)" },
    { "policy", PARAM_STRING, SC(controller.policy), 0, 0, NULL,
      "variant of the controller (forager: drtm, artm, frtm; default the first)" },
    PARAM_END
};

static const char *const information_choices[] = { "beacon", "global", NULL };

static const param_desc_t foraging_params[] = {
    { "enabled", PARAM_BOOL, SC(foraging.enabled), 0, 1, NULL,
      "seed 000's foraging task: food tokens, nest ledger, energy metrics" },
    { "food_count", PARAM_U32, SC(foraging.food_count), 0, 10000, NULL,
      "N_f, food tokens kept in the arena (one respawns per delivery)" },
    { "token_radius", PARAM_FLOAT, SC(foraging.token_radius), 0.005, 0.5, NULL, "token radius, m" },
    { "token_height", PARAM_FLOAT, SC(foraging.token_height), 0.005, 1, NULL, "token height, m" },
    { "token_energy", PARAM_FLOAT, SC(foraging.token_energy), 1, 1e9, NULL,
      "energy units per food token" },
    { "initial_food", PARAM_FLOAT, SC(foraging.initial_food), -1e6, 1e6, NULL,
      "F(0), food tokens in the nest at the start" },
    { "desired_food", PARAM_FLOAT, SC(foraging.desired_food), -1e6, 1e6, NULL,
      "F_d, desired food tokens in the nest" },
    { "consumption", PARAM_FLOAT, SC(foraging.consumption), 0, 1e6, NULL,
      "C_rate, food the nest consumes, tokens/min" },
    { "move_cost", PARAM_FLOAT, SC(foraging.move_cost), 0, 1e9, NULL,
      "energy units per step per foraging robot" },
    { "oae_energy", PARAM_FLOAT, SC(foraging.oae_energy), 0, 1e9, NULL,
      "E_a, energy units per obstacle-avoidance event" },
    { "robot_speed", PARAM_FLOAT, SC(foraging.robot_speed), 0.001, 0.128, NULL,
      "v, forager speed, m/s (seed 000: 0.05); sets T2 = L/(2v)" },
    { "information", PARAM_ENUM, SC(foraging.information), 0, 0, information_choices,
      "beacon: a nest-beacon e-puck keeps the ledger; global: ideal information" },
    PARAM_END
};

static const param_desc_t ir_params[] = {
    { "aperture", PARAM_FLOAT, SC(ir.aperture), 0.1, 90, NULL,
      "half-angle of the sensing cone, deg" },
    { "range", PARAM_FLOAT, SC(ir.range), 0.001, 1, NULL, "beyond this a sensor reads ~0, m" },
    { "noise_rel", PARAM_FLOAT, SC(ir.noise_rel), 0, 1, NULL,
      "relative Gaussian sd of the value" },
    { "noise_abs", PARAM_FLOAT, SC(ir.noise_abs), 0, 4095, NULL,
      "additive Gaussian sd, raw counts" },
    PARAM_END
};

static const param_desc_t ambient_params[] = {
    { "dark", PARAM_FLOAT, SC(ambient.dark), 0, 4095, NULL, "raw reading in the dark, counts" },
    { "half", PARAM_FLOAT, SC(ambient.half), 1e-6, 1e6, NULL,
      "irradiance at which the reading halves (1 = unit lamp at 1 m)" },
    { "noise_rel", PARAM_FLOAT, SC(ambient.noise_rel), 0, 1, NULL, "relative Gaussian sd" },
    PARAM_END
};

static const param_desc_t camera_params[] = {
    { "fov", PARAM_FLOAT, SC(camera.fov), 1, 179, NULL, "horizontal field of view, deg" },
    { "range", PARAM_FLOAT, SC(camera.range), 0.01, 100, NULL,
      "objects farther away are not seen, m" },
    { "width_px", PARAM_U16, SC(camera.width_px), 1, 640, NULL, "frame width, pixels" },
    { "height_px", PARAM_U16, SC(camera.height_px), 1, 480, NULL, "frame height, pixels" },
    PARAM_END
};

static const param_desc_t ircom_params[] = {
    { "range", PARAM_FLOAT, SC(ircom.range), 0, 10, NULL, "centre-to-centre reach, m" },
    { "loss", PARAM_FLOAT, SC(ircom.loss), 0, 1, NULL, "probability a message is lost" },
    { "bearing_noise", PARAM_FLOAT, SC(ircom.bearing_noise), 0, 180, NULL,
      "Gaussian sd added to the bearing, deg" },
    { "range_noise_rel", PARAM_FLOAT, SC(ircom.range_noise_rel), 0, 1, NULL,
      "relative Gaussian sd of the range" },
    { "quantise_bearing", PARAM_BOOL, SC(ircom.quantise_bearing), 0, 1, NULL,
      "report the receiving sensor's bearing" },
    { "blocked_by_robots", PARAM_BOOL, SC(ircom.blocked_by_robots), 0, 1, NULL,
      "robots also block line of sight" },
    { "payload_bits", PARAM_U8, SC(ircom.payload_bits), 8, 16, NULL,
      "data bits per message: 8 libIrcom, 16 range-and-bearing turret" },
    PARAM_END
};

static const param_desc_t wheels_params[] = {
    { "speed_noise_rel", PARAM_FLOAT, SC(wheels.speed_noise_rel), 0, 1, NULL,
      "per-wheel relative speed noise (sd)" },
    PARAM_END
};

static const param_desc_t output_params[] = {
    { "timeseries_every", PARAM_U32, SC(output.timeseries_every), 1, 1e9, NULL,
      "control steps between time-series CSV rows" },
    PARAM_END
};

static const object_def_t object_default = {
    SHAPE_CYLINDER, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.05f, 0 /* HAL_COLOUR_NONE */
};
static const light_def_t light_default = { 0.0f, 0.0f, 0.1f, 1.0f };

static int check_object(const loader_t *ld, const ynode_t *item, const char *path,
                        const void *elem);

#define MAPPING_SCHEMA(name) static const schema_t name##_schema = { name##_params, NULL }
MAPPING_SCHEMA(arena);
MAPPING_SCHEMA(nest);
MAPPING_SCHEMA(robots);
MAPPING_SCHEMA(object);
MAPPING_SCHEMA(light);
MAPPING_SCHEMA(ir);
MAPPING_SCHEMA(ambient);
MAPPING_SCHEMA(camera);
MAPPING_SCHEMA(ircom);
MAPPING_SCHEMA(wheels);
MAPPING_SCHEMA(output);
MAPPING_SCHEMA(foraging);

static const seq_desc_t objects_seq = {
    "objects", SCENARIO_MAX_OBJECTS, sizeof(object_def_t), &object_default, &object_schema,
    offsetof(scenario_t, objects), offsetof(scenario_t, object_count), check_object
};
static const seq_desc_t lights_seq = {
    "lights", SCENARIO_MAX_LIGHTS, sizeof(light_def_t), &light_default, &light_schema,
    offsetof(scenario_t, lights), offsetof(scenario_t, light_count), NULL
};

static const child_t controller_children[] = {
    { "params", CHILD_DEFERRED, NULL, NULL, "the controller's parameters" },
    CHILD_END
};
static const schema_t controller_schema = { controller_params, controller_children };

static const child_t top_children[] = {
    { "arena", CHILD_MAPPING, &arena_schema, NULL, "walled rectangle" },
    { "nest", CHILD_MAPPING, &nest_schema, NULL, "grey floor circle" },
    { "robots", CHILD_MAPPING, &robots_schema, NULL, "the swarm" },
    { "objects", CHILD_SEQUENCE, NULL, &objects_seq, "static obstacles (at most 4096)" },
    { "lights", CHILD_SEQUENCE, NULL, &lights_seq, "point lights (at most 16)" },
    { "controller", CHILD_CONTROLLER, &controller_schema, NULL, "robot controller" },
    { "ir", CHILD_MAPPING, &ir_schema, NULL, "IR proximity sensors" },
    { "ambient", CHILD_MAPPING, &ambient_schema, NULL, "ambient light sensors" },
    { "camera", CHILD_MAPPING, &camera_schema, NULL, "front camera blobs" },
    { "ircom", CHILD_MAPPING, &ircom_schema, NULL, "IR communication" },
    { "wheels", CHILD_MAPPING, &wheels_schema, NULL, "wheel motors" },
    { "output", CHILD_MAPPING, &output_schema, NULL, "output files" },
    { "foraging", CHILD_MAPPING, &foraging_schema, NULL, "seed 000 foraging task" },
    CHILD_END
};
static const schema_t top_schema = { top_params, top_children };

/* ---------------------------------------------------------------- defaults */

static void controller_defaults(scenario_t *sc, const sim_controller_t *ctrl)
{
    memset(sc->controller.params.bytes, 0, sizeof sc->controller.params.bytes);
    if (ctrl != NULL && ctrl->default_params != NULL &&
        ctrl->params_size <= sizeof sc->controller.params.bytes) {
        ctrl->default_params(sc->controller.params.bytes);
    }
}

void scenario_defaults(scenario_t *out)
{
    memset(out, 0, sizeof *out);
    out->seed = 1;
    out->duration = 60.0;
    out->control_period_ms = 100;
    out->physics_substeps = 4;
    out->arena.width = 4.0f;
    out->arena.height = 4.0f;
    out->arena.wall_thickness = 0.05f;
    out->nest.enabled = 0;
    out->nest.diameter = 0.5f;
    out->robots.count = 20;
    out->robots.placement = PLACE_RANDOM;
    out->robots.min_spacing = 0.08f;
    snprintf(out->controller.name, sizeof out->controller.name, "%s", DEFAULT_CONTROLLER);
    controller_defaults(out, controllers_find(DEFAULT_CONTROLLER));
    out->ir.aperture = 15.0f;
    out->ir.range = 0.1f;
    out->ir.noise_rel = 0.01f;
    out->ir.noise_abs = 5.0f;
    out->ambient.dark = 4000.0f;
    out->ambient.half = 1.0f;
    out->ambient.noise_rel = 0.01f;
    out->camera.fov = 56.0f;
    out->camera.range = 0.6f;
    out->camera.width_px = 40;
    out->camera.height_px = 40;
    out->ircom.range = 0.25f;
    out->ircom.loss = 0.1f;
    out->ircom.bearing_noise = 5.0f;
    out->ircom.range_noise_rel = 0.1f;
    out->ircom.quantise_bearing = 1;
    out->ircom.blocked_by_robots = 0;
    out->ircom.payload_bits = 8;
    out->wheels.speed_noise_rel = 0.0f;
    out->output.timeseries_every = 10;
    out->foraging.enabled = 0;
    out->foraging.food_count = 20;
    out->foraging.token_radius = 0.0175f;
    out->foraging.token_height = 0.042f;
    out->foraging.token_energy = 1500.0f;
    out->foraging.initial_food = 5.0f;
    out->foraging.desired_food = 20.0f;
    out->foraging.consumption = 2.0f;
    out->foraging.move_cost = 1.0f;
    out->foraging.oae_energy = 10.0f;
    out->foraging.robot_speed = 0.05f;
    out->foraging.information = INFO_BEACON;
}

/* ---------------------------------------------------------------- scalars */

static int all_digits(const char *s)
{
    const char *p = s;
    while (*p >= '0' && *p <= '9') {
        p++;
    }
    return p != s && *p == '\0';
}

static int is_plain(const ynode_t *v)
{
    return v != NULL && v->kind == YNODE_SCALAR && !v->quoted;
}

static int fill_bool(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    static const char *const words[] = { "false", "False", "FALSE", "true", "True", "TRUE" };
    size_t i;
    (void)d;
    for (i = 0; is_plain(v) && i < sizeof words / sizeof words[0]; i++) {
        if (strcmp(v->text, words[i]) == 0) {
            uint8_t b = i >= 3;
            memcpy(dst, &b, sizeof b);
            return 0;
        }
    }
    return wrong_type(ld, v, path, "true/false");
}

/* Stores `i` as the C type of `d`; returns -1 if it does not fit. */
static int store_int(const param_desc_t *d, intmax_t i, void *dst)
{
    uint8_t u8 = (uint8_t)i;
    uint16_t u16 = (uint16_t)i;
    int16_t i16 = (int16_t)i;
    uint32_t u32 = (uint32_t)i;
    if (d->type == PARAM_U8 && i >= 0 && i <= UINT8_MAX) {
        memcpy(dst, &u8, sizeof u8);
    } else if (d->type == PARAM_U16 && i >= 0 && i <= UINT16_MAX) {
        memcpy(dst, &u16, sizeof u16);
    } else if (d->type == PARAM_I16 && i >= INT16_MIN && i <= INT16_MAX) {
        memcpy(dst, &i16, sizeof i16);
    } else if (d->type == PARAM_U32 && i >= 0 && i <= (intmax_t)UINT32_MAX) {
        memcpy(dst, &u32, sizeof u32);
    } else {
        return -1;
    }
    return 0;
}

static int fill_u64(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                    const char *path, void *dst)
{
    const char *s = v->text;
    uintmax_t u;
    uint64_t x;
    /* strtoumax accepts "-5" and wraps it; only "-0" is in range. */
    if (s[0] == '-' && strspn(s + 1, "0") != strlen(s + 1)) {
        return out_of_range(ld, d, v, path);
    }
    errno = 0;
    u = strtoumax(s, NULL, 10);
    if (errno == ERANGE || u > UINT64_MAX || (double)u < d->min || (double)u > d->max) {
        return out_of_range(ld, d, v, path);
    }
    x = (uint64_t)u;
    memcpy(dst, &x, sizeof x);
    return 0;
}

static int fill_integer(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                        const char *path, void *dst)
{
    intmax_t i;
    if (!is_plain(v) || !all_digits(v->text + (v->text[0] == '-' || v->text[0] == '+'))) {
        return wrong_type(ld, v, path, "an integer");
    }
    if (d->type == PARAM_U64) {
        return fill_u64(ld, d, v, path, dst);
    }
    errno = 0;
    i = strtoimax(v->text, NULL, 10);
    if (errno == ERANGE || (double)i < d->min || (double)i > d->max ||
        store_int(d, i, dst) != 0) {
        return out_of_range(ld, d, v, path);
    }
    return 0;
}

static int fill_real(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    const char *s = v != NULL ? v->text : NULL;
    char *end;
    double x;
    /* strtod would also take hex, "nan", "inf" and leading blanks. */
    if (!is_plain(v) || strspn(s, "0123456789+-.eE") != strlen(s) ||
        strpbrk(s, "0123456789") == NULL) {
        return wrong_type(ld, v, path, "a number");
    }
    errno = 0;
    x = strtod(s, &end);
    if (*end != '\0') {
        return wrong_type(ld, v, path, "a number");
    }
    if (!isfinite(x) || x < d->min || x > d->max) {
        return out_of_range(ld, d, v, path);
    }
    if (d->type == PARAM_FLOAT) {
        float f = (float)x;
        memcpy(dst, &f, sizeof f);
    } else {
        memcpy(dst, &x, sizeof x);
    }
    return 0;
}

static int fill_string(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                       const char *path, void *dst)
{
    size_t len;
    if (v == NULL || v->kind != YNODE_SCALAR || ytree_is_null(v)) {
        return wrong_type(ld, v, path, "a string");
    }
    len = strlen(v->text);
    if (len == 0) {
        return fail(ld, v, path, "expected a non-empty string");
    }
    if (len >= d->size) {
        return fail(ld, v, path, "'%.40s...' is longer than %zu characters", v->text,
                    d->size - 1);
    }
    memcpy(dst, v->text, len + 1);
    return 0;
}

static int fill_enum(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    char range[120], choices[128], got[64];
    const char *best = NULL;
    size_t dist = 3;
    int i;
    format_range(d, range, sizeof range);
    format_into(choices, sizeof choices, "one of %s", range);
    if (v == NULL || v->kind != YNODE_SCALAR) {
        return wrong_type(ld, v, path, choices);
    }
    for (i = 0; d->choices[i] != NULL; i++) {
        if (strcmp(v->text, d->choices[i]) == 0) {
            memcpy(dst, &i, sizeof i);
            return 0;
        }
        consider(v->text, d->choices[i], &best, &dist);
    }
    ytree_describe(v, got, sizeof got);
    if (best != NULL) {
        return fail(ld, v, path, "expected %s, got %s (did you mean '%s'?)", choices, got, best);
    }
    return fail(ld, v, path, "expected %s, got %s", choices, got);
}

static int fill_scalar(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                       const char *path, void *base)
{
    void *dst = (char *)base + d->offset;
    switch (d->type) {
    case PARAM_BOOL:
        return fill_bool(ld, d, v, path, dst);
    case PARAM_FLOAT:
    case PARAM_DOUBLE:
        return fill_real(ld, d, v, path, dst);
    case PARAM_STRING:
        return fill_string(ld, d, v, path, dst);
    case PARAM_ENUM:
        return fill_enum(ld, d, v, path, dst);
    default:
        return fill_integer(ld, d, v, path, dst);
    }
}

/* ---------------------------------------------------------------- mappings */

static const param_desc_t *find_param(const param_desc_t *d, const char *key)
{
    for (; d != NULL && d->key != NULL; d++) {
        if (strcmp(d->key, key) == 0) {
            return d;
        }
    }
    return NULL;
}

static const child_t *find_child(const child_t *c, const char *key)
{
    for (; c != NULL && c->key != NULL; c++) {
        if (strcmp(c->key, key) == 0) {
            return c;
        }
    }
    return NULL;
}

/* Appends `key` to the list in buf. */
static void list_key(char *buf, size_t len, const char *key)
{
    size_t used = strlen(buf);
    if (used < len) {
        snprintf(buf + used, len - used, "%s%s", used ? ", " : "", key);
    }
}

static int unknown_key(const loader_t *ld, const ynode_t *key, const char *path,
                       const schema_t *schema)
{
    char valid[320] = "";
    const char *best = NULL;
    size_t dist = 3;
    const param_desc_t *d;
    const child_t *c;
    for (d = schema->params; d != NULL && d->key != NULL; d++) {
        consider(key->text, d->key, &best, &dist);
        list_key(valid, sizeof valid, d->key);
    }
    for (c = schema->children; c != NULL && c->key != NULL; c++) {
        consider(key->text, c->key, &best, &dist);
        list_key(valid, sizeof valid, c->key);
    }
    if (best != NULL) {
        return fail(ld, key, path, "unknown key '%.64s' (did you mean '%s'?)", key->text, best);
    }
    if (valid[0] == '\0') {
        return fail(ld, key, path, "unknown key '%.64s' (no keys are allowed here)", key->text);
    }
    return fail(ld, key, path, "unknown key '%.64s' (valid keys: %s)", key->text, valid);
}

static int fill_mapping(const loader_t *ld, const ynode_t *node, const char *path,
                        const schema_t *schema, void *base);
static int fill_sequence(const loader_t *ld, const ynode_t *node, const char *path,
                         const seq_desc_t *seq, void *base);
static int fill_controller(const loader_t *ld, const ynode_t *node, const char *path,
                           scenario_t *sc);

static int fill_entry(const loader_t *ld, const ypair_t *pair, const char *path,
                      const schema_t *schema, void *base)
{
    const param_desc_t *d = find_param(schema->params, pair->key->text);
    const child_t *c;
    if (d != NULL) {
        return fill_scalar(ld, d, pair->value, path, base);
    }
    c = find_child(schema->children, pair->key->text);
    if (c == NULL) {
        return unknown_key(ld, pair->key, path, schema);
    }
    switch (c->kind) {
    case CHILD_MAPPING:
        return fill_mapping(ld, pair->value, path, c->schema, base);
    case CHILD_SEQUENCE:
        return fill_sequence(ld, pair->value, path, c->seq, base);
    case CHILD_CONTROLLER:
        return fill_controller(ld, pair->value, path, base);
    default:
        return 0;
    }
}

static int duplicate_key(const loader_t *ld, const ynode_t *map, size_t i, const char *path)
{
    const ynode_t *key = map->pairs[i].key;
    size_t j;
    for (j = 0; j < i; j++) {
        const ynode_t *first = map->pairs[j].key;
        if (strcmp(first->text, key->text) == 0) {
            if (first->line > 0) {
                return fail(ld, key, path, "duplicate key '%.64s' (first on line %d)", key->text,
                            first->line);
            }
            return fail(ld, key, path, "duplicate key '%.64s'", key->text);
        }
    }
    return 0;
}

/* Fills the keys present in `node`; absent keys keep their value.  A null
 * node (an empty section) changes nothing. */
static int fill_mapping(const loader_t *ld, const ynode_t *node, const char *path,
                        const schema_t *schema, void *base)
{
    size_t i;
    if (ytree_is_null(node)) {
        return 0;
    }
    if (node->kind != YNODE_MAPPING) {
        return wrong_type(ld, node, path, "a mapping");
    }
    for (i = 0; i < node->count; i++) {
        char child[PATH_BUF];
        join(child, path, node->pairs[i].key->text);
        if (duplicate_key(ld, node, i, child) != 0 ||
            fill_entry(ld, &node->pairs[i], child, schema, base) != 0) {
            return -1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- sequences */

static void index_path(char out[PATH_BUF], const char *path, size_t i)
{
    format_into(out, PATH_BUF, "%s[%zu]", path, i);
}

/* A given sequence replaces the default (empty) one; each entry starts from
 * the entry defaults. */
static int fill_sequence(const loader_t *ld, const ynode_t *node, const char *path,
                         const seq_desc_t *seq, void *base)
{
    char *array = (char *)base + seq->array_offset;
    uint32_t count = 0;
    size_t n = 0;
    if (!ytree_is_null(node)) {
        if (node->kind != YNODE_SEQUENCE) {
            return wrong_type(ld, node, path, "a sequence");
        }
        n = node->count;
    }
    for (; count < n; count++) {
        const ynode_t *item = node->items[count];
        void *elem = array + (size_t)count * seq->elem_size;
        char ipath[PATH_BUF];
        index_path(ipath, path, count);
        if (count >= seq->max) {
            return fail(ld, item, ipath, "too many %s (at most %zu)", seq->noun, seq->max);
        }
        if (item == NULL || item->kind != YNODE_MAPPING) {
            return wrong_type(ld, item, ipath, "a mapping");
        }
        memcpy(elem, seq->defaults, seq->elem_size);
        if (fill_mapping(ld, item, ipath, seq->schema, elem) != 0 ||
            (seq->check != NULL && seq->check(ld, item, ipath, elem) != 0)) {
            return -1;
        }
    }
    memcpy((char *)base + seq->count_offset, &count, sizeof count);
    return 0;
}

/* The value node of `key` in `item` if present, else `item` (for the line). */
static const ynode_t *node_of(const ynode_t *item, const char *key)
{
    const ynode_t *v = ytree_get(item, key);
    return v != NULL ? v : item;
}

static int need_positive(const loader_t *ld, const ynode_t *item, const char *path,
                         const char *key, float value, const char *shape)
{
    char p[PATH_BUF];
    if (value > 0.0f) {
        return 0;
    }
    join(p, path, key);
    return fail(ld, node_of(item, key), p, "a %s needs %s > 0", shape, key);
}

static int check_object(const loader_t *ld, const ynode_t *item, const char *path,
                        const void *elem)
{
    const object_def_t *o = elem;
    if (o->shape == SHAPE_CYLINDER) {
        return need_positive(ld, item, path, "radius", o->radius, "cylinder");
    }
    if (need_positive(ld, item, path, "width", o->width, "box") != 0) {
        return -1;
    }
    return need_positive(ld, item, path, "depth", o->depth, "box");
}

/* ---------------------------------------------------------------- controller */

static int fill_params(const loader_t *ld, const ynode_t *node, const char *path,
                       const sim_controller_t *ctrl, scenario_t *sc)
{
    schema_t schema;
    if (ctrl->params_size > sizeof sc->controller.params.bytes) {
        return fail(ld, node, path, "controller '%s' has %zu bytes of parameters (at most %zu)",
                    ctrl->name, ctrl->params_size, sizeof sc->controller.params.bytes);
    }
    controller_defaults(sc, ctrl);
    schema.params = ctrl->params;
    schema.children = NULL;
    return fill_mapping(ld, node, path, &schema, sc->controller.params.bytes);
}

/* controller.policy must be one of the controller's; empty means its first. */
static int check_policy(const loader_t *ld, const ynode_t *node, const char *path,
                        const sim_controller_t *ctrl, scenario_t *sc)
{
    char p[PATH_BUF], valid[256] = "";
    size_t i;
    join(p, path, "policy");
    if (ctrl->policies == NULL || ctrl->policies[0] == NULL) {
        if (sc->controller.policy[0] != '\0') {
            return fail(ld, node_of(node, "policy"), p, "controller '%s' has no policies",
                        ctrl->name);
        }
        return 0;
    }
    if (sc->controller.policy[0] == '\0') {
        snprintf(sc->controller.policy, sizeof sc->controller.policy, "%s", ctrl->policies[0]);
        return 0;
    }
    for (i = 0; ctrl->policies[i] != NULL; i++) {
        if (strcmp(ctrl->policies[i], sc->controller.policy) == 0) {
            return 0;
        }
        list_key(valid, sizeof valid, ctrl->policies[i]);
    }
    return fail(ld, node_of(node, "policy"), p, "unknown policy '%s' for controller '%s' (valid: %s)",
                sc->controller.policy, ctrl->name, valid);
}

/* The keys and the name first (params are deferred), then the params of the
 * named controller over its defaults, whatever order the file uses. */
static int fill_controller(const loader_t *ld, const ynode_t *node, const char *path,
                           scenario_t *sc)
{
    const sim_controller_t *ctrl;
    char p[PATH_BUF];
    if (fill_mapping(ld, node, path, &controller_schema, sc) != 0) {
        return -1;
    }
    ctrl = controllers_find(sc->controller.name);
    if (ctrl == NULL) {
        char valid[256] = "";
        size_t i;
        for (i = 0; controllers_at(i) != NULL; i++) {
            list_key(valid, sizeof valid, controllers_at(i)->name);
        }
        join(p, path, "name");
        return fail(ld, node_of(node, "name"), p, "unknown controller '%s' (valid: %s)",
                    sc->controller.name, valid);
    }
    if (check_policy(ld, node, path, ctrl, sc) != 0) {
        return -1;
    }
    join(p, path, "params");
    return fill_params(ld, ytree_get(node, "params"), p, ctrl, sc);
}

/* ---------------------------------------------------------------- cross checks */

static int inside_arena(const scenario_t *sc, double x, double y, double hx, double hy)
{
    return fabs(x) + hx <= sc->arena.width / 2.0 + ARENA_EPS &&
           fabs(y) + hy <= sc->arena.height / 2.0 + ARENA_EPS;
}

static int outside(const loader_t *ld, const ynode_t *node, const char *path, const char *what,
                   const scenario_t *sc)
{
    return fail(ld, node, path, "%s outside the arena (x in [%g, %g], y in [%g, %g] m)", what,
                -sc->arena.width / 2.0, sc->arena.width / 2.0, -sc->arena.height / 2.0,
                sc->arena.height / 2.0);
}

static int check_objects_inside(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    const ynode_t *seq = ytree_get(root, "objects");
    uint32_t i;
    for (i = 0; i < sc->object_count; i++) {
        const object_def_t *o = &sc->objects[i];
        double hx = o->radius, hy = o->radius;
        char path[PATH_BUF];
        if (o->shape == SHAPE_BOX) {
            /* Half-extents of the rotated box's bounding rectangle. */
            double a = o->angle * DEG_TO_RAD, c = fabs(cos(a)), s = fabs(sin(a));
            hx = (c * o->width + s * o->depth) / 2.0;
            hy = (s * o->width + c * o->depth) / 2.0;
        }
        if (!inside_arena(sc, o->x, o->y, hx, hy)) {
            index_path(path, "objects", i);
            return outside(ld, seq->items[i], path,
                           o->shape == SHAPE_BOX ? "the box reaches" : "the cylinder reaches", sc);
        }
    }
    return 0;
}

static int check_inside(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    const ynode_t *lights = ytree_get(root, "lights");
    uint32_t i;
    if (check_objects_inside(ld, root, sc) != 0) {
        return -1;
    }
    for (i = 0; i < sc->light_count; i++) {
        char path[PATH_BUF];
        if (!inside_arena(sc, sc->lights[i].x, sc->lights[i].y, 0.0, 0.0)) {
            index_path(path, "lights", i);
            return outside(ld, lights->items[i], path, "the light is", sc);
        }
    }
    if (sc->nest.enabled &&
        !inside_arena(sc, sc->nest.x, sc->nest.y, sc->nest.diameter / 2.0,
                      sc->nest.diameter / 2.0)) {
        return outside(ld, ytree_get(root, "nest"), "nest", "the nest circle reaches", sc);
    }
    return 0;
}

static int cross_check(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    const ynode_t *robots = ytree_get(root, "robots");
    if (sc->robots.placement == PLACE_NEST && !sc->nest.enabled) {
        return fail(ld, node_of(robots, "placement"), "robots.placement",
                    "'nest' needs nest.enabled: true");
    }
    if (sc->foraging.enabled && !sc->nest.enabled) {
        const ynode_t *f = ytree_get(root, "foraging");
        return fail(ld, node_of(f, "enabled"), "foraging.enabled",
                    "the foraging task needs a nest (nest.enabled: true)");
    }
    if (sc->duration * 1000.0 < sc->control_period_ms) {
        const ynode_t *d = ytree_get(root, "duration");
        return fail(ld, d != NULL ? d : root, "duration",
                    "%g s is shorter than one control period (%g s)", sc->duration,
                    sc->control_period_ms / 1000.0);
    }
    return check_inside(ld, root, sc);
}

/* ---------------------------------------------------------------- loading */

static int set_path_and_name(const loader_t *ld, const char *path, scenario_t *out)
{
    const char *base = strrchr(path, '/');
    const char *dot;
    size_t len;
    if (strlen(path) >= sizeof out->path) {
        return fail(ld, NULL, "", "path longer than %zu characters", sizeof out->path - 1);
    }
    memcpy(out->path, path, strlen(path) + 1);
    base = base != NULL ? base + 1 : path;
    dot = strrchr(base, '.');
    len = (dot != NULL && dot != base) ? (size_t)(dot - base) : strlen(base);
    if (len >= sizeof out->name) {
        len = sizeof out->name - 1;
    }
    memcpy(out->name, base, len);
    out->name[len] = '\0';
    return 0;
}

/* A file with no document, or a null one, is an empty mapping. */
static int check_root(const loader_t *ld, ynode_t **root)
{
    if (ytree_is_null(*root)) {
        ytree_free(*root);
        *root = ytree_new_mapping(0, NULL);
        return *root != NULL ? 0 : fail(ld, NULL, "", "out of memory");
    }
    if ((*root)->kind != YNODE_MAPPING) {
        return wrong_type(ld, *root, "", "a mapping of keys at the top level");
    }
    return 0;
}

int scenario_load(const char *path, const scenario_override_t *overrides,
                  size_t override_count, scenario_t *out, char err[SCENARIO_ERROR_MAX])
{
    loader_t ld;
    ynode_t *root = NULL;
    size_t i;
    int rc;
    ld.file = path != NULL ? path : "(null)";
    ld.err = err;
    err[0] = '\0';
    scenario_defaults(out);
    if (path == NULL || set_path_and_name(&ld, path, out) != 0) {
        return path == NULL ? fail(&ld, NULL, "", "no scenario file") : -1;
    }
    if (ytree_parse_file(path, &root, err, SCENARIO_ERROR_MAX) != 0) {
        return -1;
    }
    rc = check_root(&ld, &root);
    for (i = 0; rc == 0 && i < override_count; i++) {
        rc = ytree_apply_override(&root, overrides[i].text, err, SCENARIO_ERROR_MAX);
    }
    if (rc == 0) {
        rc = fill_mapping(&ld, root, "", &top_schema, out);
    }
    if (rc == 0) {
        rc = cross_check(&ld, root, out);
    }
    ytree_free(root);
    return rc == 0 ? 0 : -1;
}

/* ---------------------------------------------------------------- --help */

static const char *type_name(param_type_t t)
{
    switch (t) {
    case PARAM_BOOL: return "bool";
    case PARAM_FLOAT:
    case PARAM_DOUBLE: return "number";
    case PARAM_STRING: return "string";
    case PARAM_ENUM: return "enum";
    default: return "int";
    }
}

static void format_value(const param_desc_t *d, const void *base, char *buf, size_t len)
{
    const char *p = (const char *)base + d->offset;
    union { uint8_t u8; uint16_t u16; int16_t i16; uint32_t u32; uint64_t u64; float f;
            double d; int i; } v;
    memcpy(&v, p, d->type == PARAM_STRING ? 0 : d->size);
    switch (d->type) {
    case PARAM_BOOL: snprintf(buf, len, "%s", v.u8 ? "true" : "false"); break;
    case PARAM_U8: snprintf(buf, len, "%u", (unsigned)v.u8); break;
    case PARAM_U16: snprintf(buf, len, "%u", (unsigned)v.u16); break;
    case PARAM_I16: snprintf(buf, len, "%d", (int)v.i16); break;
    case PARAM_U32: snprintf(buf, len, "%" PRIu32, v.u32); break;
    case PARAM_U64: snprintf(buf, len, "%" PRIu64, v.u64); break;
    case PARAM_FLOAT: format_number(v.f, buf, len); break;
    case PARAM_DOUBLE: format_number(v.d, buf, len); break;
    case PARAM_STRING: snprintf(buf, len, "%s", p[0] ? p : "-"); break;
    case PARAM_ENUM: snprintf(buf, len, "%s", d->choices[v.i]); break;
    }
}

static void print_params(FILE *f, const char *prefix, const param_desc_t *d, const void *base)
{
    for (; d != NULL && d->key != NULL; d++) {
        char path[PATH_BUF], def[48], range[128];
        join(path, prefix, d->key);
        format_value(d, base, def, sizeof def);
        format_range(d, range, sizeof range);
        fprintf(f, "  %-34s %-6s %-12s %-22s %s\n", path, type_name(d->type), def, range, d->doc);
    }
}

static void print_controller_params(FILE *f, const char *prefix)
{
    const sim_controller_t *ctrl;
    size_t i;
    for (i = 0; (ctrl = controllers_at(i)) != NULL; i++) {
        union { uint8_t bytes[SCENARIO_CONTROLLER_PARAMS_MAX]; double d; uint64_t u; } buf;
        if (ctrl->params_size > sizeof buf.bytes) {
            continue;
        }
        memset(&buf, 0, sizeof buf);
        if (ctrl->default_params != NULL) {
            ctrl->default_params(buf.bytes);
        }
        if (ctrl->params == NULL || ctrl->params[0].key == NULL) {
            fprintf(f, "  %s: none when controller.name is %s\n", prefix, ctrl->name);
            continue;
        }
        fprintf(f, "  %s when controller.name is %s (%s):\n", prefix, ctrl->name, ctrl->doc);
        print_params(f, prefix, ctrl->params, buf.bytes);
    }
}

static void print_schema(FILE *f, const char *prefix, const schema_t *schema, const void *base)
{
    const child_t *c;
    print_params(f, prefix, schema->params, base);
    for (c = schema->children; c != NULL && c->key != NULL; c++) {
        char path[PATH_BUF], elem[PATH_BUF];
        join(path, prefix, c->key);
        switch (c->kind) {
        case CHILD_SEQUENCE:
            fprintf(f, "  %-34s %-6s %-12s <= %-19zu %s; each entry:\n", path, "list", "empty",
                    c->seq->max, c->doc);
            format_into(elem, sizeof elem, "%s[]", path);
            print_schema(f, elem, c->seq->schema, c->seq->defaults);
            break;
        case CHILD_DEFERRED:
            print_controller_params(f, path);
            break;
        default:
            print_schema(f, path, c->schema, base);
        }
    }
}

void scenario_print_schema(FILE *file)
{
    scenario_t *def = malloc(sizeof *def);
    if (def == NULL) {
        return;
    }
    scenario_defaults(def);
    fprintf(file, "Scenario keys (YAML; lengths in m, angles in deg, times in s; "
                  "the arena is centred on 0,0):\n");
    fprintf(file, "  %-34s %-6s %-12s %-22s %s\n", "key", "type", "default", "range", "meaning");
    print_schema(file, "", &top_schema, def);
    fprintf(file, "Override any key with --set key.path=value "
                  "(e.g. --set robots.count=50 --set objects.0.x=1.5).\n");
    free(def);
}
