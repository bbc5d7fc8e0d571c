/*
 * scenario.c - the scenario's schema: every key's type, range, unit and
 * default as descriptor tables, robot groups (whose `params:` follow their
 * controller), the tasks' sections, and the checks across keys.  The strict
 * loading itself is schema.c; parsing and --set are yaml_tree.c.
 *
 * Decisions (besides schema.h's):
 *  - An empty file (or one with only comments, or a null document) gives the
 *    defaults: one group of 20 random walkers, no task.
 *  - Every object, light and group must be a mapping; absent keys take the
 *    entry defaults below.  A cylinder needs radius > 0, a box width and
 *    depth > 0; keys of the other shape are ignored.  Objects and lights
 *    must lie wholly inside the arena (the inside of the walls).
 *  - A group names its controller; its policy defaults to the controller's
 *    first, its name to the controller's (with its index when taken).  A
 *    `poses` placement gives one pose per robot.
 *  - A task runs when its section (named after the task) is present, in
 *    registry order whatever the file's order.
 */
#include "swarmsim/scenario.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/model.h"
#include "registry.h"
#include "swarmsim/sim.h"
#include "schema.h"
#include "swarmsim/task.h"
#include "units.h"
#include "yaml_tree.h"

#define DEFAULT_CONTROLLER "random_walk"
/* Objects may touch the walls: rounding must not reject them. */
#define ARENA_EPS 1e-6
/* Positions: the arena is at most 1000 m wide, centred on 0,0. */
#define POS_MIN -500.0
#define POS_MAX 500.0

/* ---------------------------------------------------------------- tables */

#define SC scenario_t
#define OBJ object_def_t
#define LIGHT light_def_t
#define GRP robot_group_t

static const char *const shape_choices[] = { "cylinder", "box", NULL };
static const char *const colour_choices[] = { "none", "red", "green", "blue", NULL };
static const char *const placement_choices[] = { "rectangle", "circle", "ring", "grid", "poses", NULL };
static const char *const order_choices[] = { "drawn", "space", NULL };

static const param_desc_t top_params[] = {
    { .key = "name", PARAM_STRING_FIELD(SC, name),
      .doc = "scenario name (default: the file name without its extension)" },
    { .key = "seed", PARAM_FIELD(SC, seed, uint64_t), .min = 0, .max = (double)SCENARIO_SEED_MAX,
      .doc = "base random seed; repetition r uses seed + r" },
    { .key = "duration", PARAM_FIELD(SC, duration, double), .min = 0.001, .max = 1e7,
      .doc = "simulated time, s" },
    { .key = "control_period_ms", PARAM_FIELD(SC, control_period_ms, uint16_t), .min = 1,
      .max = 10000, .doc = "one controller step, ms" },
    { .key = "physics_substeps", PARAM_FIELD(SC, physics_substeps, uint16_t), .min = 1, .max = 64,
      .doc = "physics sub-steps per control step" },
    { .key = "memory_limit_mb", PARAM_FIELD(SC, memory_limit_mb, uint32_t), .min = 1, .max = 16777216,
      .doc = "refuse the scenario when a run needs more, MB (the estimate: swarmsim --check)" },
    PARAM_END
};

static const param_desc_t arena_params[] = {
    { .key = "width", PARAM_FIELD(SC, arena.width, float), .min = 0.1, .max = 1000,
      .doc = "inside size along x of the walled rectangle centred on 0,0, m" },
    { .key = "height", PARAM_FIELD(SC, arena.height, float), .min = 0.1, .max = 1000,
      .doc = "inside size along y, m" },
    { .key = "wall_thickness", PARAM_FIELD(SC, arena.wall_thickness, float), .min = 0.001,
      .max = 10, .doc = "wall thickness (outside the width x height), m" },
    PARAM_END
};

static const param_desc_t group_params[] = {
    { .key = "name", PARAM_STRING_FIELD(GRP, name),
      .doc = "label in outputs (default: the controller's name)" },
    { .key = "count", PARAM_FIELD(GRP, count, uint32_t), .min = 0, .max = 100000,
      .doc = "robots in the group" },
    { .key = "controller", PARAM_STRING_FIELD(GRP, controller),
      .doc = "registered controller (swarmsim --help lists them)" },
    { .key = "policy", PARAM_STRING_FIELD(GRP, policy),
      .doc = "variant of the controller (swarmsim --help lists them; default its first)" },
    { .key = "heading", PARAM_ANGLE_FIELD(GRP, heading), .min = -360, .max = 360,
      .doc = "start heading, deg CCW from +x, or random" },
    { .key = "min_spacing", PARAM_FIELD(GRP, min_spacing, float), .min = 0.07, .max = 10,
      .doc = "centre-to-centre distance to robots placed before, m (the body is 0.07 m)" },
    { .key = "moves", PARAM_BOOL_FIELD(GRP, moves),
      .doc = "false: a static body nothing can push (a fixed station, a landmark)" },
    { .key = "first_id", PARAM_FIELD(GRP, first_id, uint32_t), .min = 0, .max = 65535,
      .doc = "hal_robot_id of the group's first robot, the others' following it (default: each robot's index)" },
    PARAM_END
};

static const param_desc_t placement_params[] = {
    { .key = "shape", PARAM_ENUM_FIELD(GRP, placement.shape, placement_choices),
      .doc = "region the robots start in (bodies inside it)" },
    { .key = "x", PARAM_FIELD(GRP, placement.x, float), .min = POS_MIN, .max = POS_MAX,
      .doc = "centre of the region, m" },
    { .key = "y", PARAM_FIELD(GRP, placement.y, float), .min = POS_MIN, .max = POS_MAX,
      .doc = "centre of the region, m" },
    { .key = "width", PARAM_FIELD(GRP, placement.width, float), .min = 0, .max = 1000,
      .doc = "rectangle, grid: size along x, m (0: the arena's)" },
    { .key = "height", PARAM_FIELD(GRP, placement.height, float), .min = 0, .max = 1000,
      .doc = "rectangle, grid: size along y, m (0: the arena's)" },
    { .key = "radius", PARAM_FIELD(GRP, placement.radius, float), .min = 0, .max = 500,
      .doc = "circle: radius, m" },
    { .key = "inner", PARAM_FIELD(GRP, placement.inner, float), .min = 0, .max = 500,
      .doc = "ring: inner radius, m" },
    { .key = "outer", PARAM_FIELD(GRP, placement.outer, float), .min = 0, .max = 500,
      .doc = "ring: outer radius, m" },
    { .key = "order", PARAM_ENUM_FIELD(GRP, placement.order, order_choices),
      .doc = "which robot takes which spot: drawn (robot k the k-th spot drawn) or space (the same "
             "spots renumbered along a Morton curve of 0.5 m cells, so that robots near in id start "
             "near in space and their data shares the caches: a large swarm steps faster; the run "
             "is another sample of the same start, not the drawn one's)" },
    PARAM_END
};

static const param_desc_t pose_params[] = {
    { .key = "x", PARAM_FIELD(pose_def_t, x, float), .min = POS_MIN, .max = POS_MAX, .doc = "m" },
    { .key = "y", PARAM_FIELD(pose_def_t, y, float), .min = POS_MIN, .max = POS_MAX, .doc = "m" },
    { .key = "heading", PARAM_ANGLE_FIELD(pose_def_t, heading), .min = -360, .max = 360,
      .doc = "deg CCW from +x, or random (default: the group's heading)" },
    PARAM_END
};

static const param_desc_t object_params[] = {
    { .key = "shape", PARAM_ENUM_FIELD(OBJ, shape, shape_choices), .doc = "obstacle shape" },
    { .key = "x", PARAM_FIELD(OBJ, x, float), .min = POS_MIN, .max = POS_MAX, .doc = "centre x, m" },
    { .key = "y", PARAM_FIELD(OBJ, y, float), .min = POS_MIN, .max = POS_MAX, .doc = "centre y, m" },
    { .key = "radius", PARAM_FIELD(OBJ, radius, float), .min = 0, .max = 500,
      .doc = "cylinder radius, m (cylinder: > 0)" },
    { .key = "width", PARAM_FIELD(OBJ, width, float), .min = 0, .max = 1000,
      .doc = "box size along its x, m (box: > 0)" },
    { .key = "depth", PARAM_FIELD(OBJ, depth, float), .min = 0, .max = 1000,
      .doc = "box size along its y, m (box: > 0)" },
    { .key = "angle", PARAM_FIELD(OBJ, angle, float), .min = -360, .max = 360,
      .doc = "box rotation, deg counter-clockwise" },
    { .key = "height", PARAM_FIELD(OBJ, height, float), .min = 0.001, .max = 100,
      .doc = "height, m (camera, pictures)" },
    { .key = "colour", PARAM_ENUM_FIELD(OBJ, colour, colour_choices), .doc = "colour the camera sees" },
    PARAM_END
};

static const param_desc_t light_params[] = {
    { .key = "x", PARAM_FIELD(LIGHT, x, float), .min = POS_MIN, .max = POS_MAX, .doc = "lamp x, m" },
    { .key = "y", PARAM_FIELD(LIGHT, y, float), .min = POS_MIN, .max = POS_MAX, .doc = "lamp y, m" },
    { .key = "height", PARAM_FIELD(LIGHT, height, float), .min = 0, .max = 100,
      .doc = "lamp height above the floor, m" },
    { .key = "intensity", PARAM_FIELD(LIGHT, intensity, float), .min = 0, .max = 1e6,
      .doc = "relative: 1 gives irradiance 1 at 1 m" },
    PARAM_END
};

static const param_desc_t random_cylinders_params[] = {
    { .key = "count", PARAM_FIELD(SC, random_cylinders.count, uint32_t), .min = 0, .max = SCENARIO_MAX_OBJECTS,
      .doc = "cylinders drawn at random when each run is built (0: none)" },
    { .key = "radius_min", PARAM_FIELD(SC, random_cylinders.radius_min, float), .min = 0.001, .max = 100,
      .doc = "m: smallest radius (uniform between radius_min and radius_max)" },
    { .key = "radius_max", PARAM_FIELD(SC, random_cylinders.radius_max, float), .min = 0.001, .max = 100,
      .doc = "m: largest radius" },
    { .key = "height", PARAM_FIELD(SC, random_cylinders.height, float), .min = 0.001, .max = 100,
      .doc = "m (camera, pictures)" },
    { .key = "gap", PARAM_FIELD(SC, random_cylinders.gap, float), .min = 0, .max = 100,
      .doc = "m: least gap between a cylinder and another obstacle, a wall or the body of a robot "
             "of a poses group (robots placed at random avoid the cylinders as any obstacle)" },
    { .key = "layout_seed", PARAM_FIELD(SC, random_cylinders.layout_seed, uint64_t), .min = 0,
      .max = (double)SCENARIO_SEED_MAX,
      .doc = "0: each run draws its own layout from its run seed; else this one layout for every run" },
    PARAM_END
};

static const param_desc_t output_params[] = {
    { .key = "timeseries_every", PARAM_FIELD(SC, output.timeseries_every, uint32_t), .min = 1,
      .max = 1e9, .doc = "control steps between time-series CSV rows" },
    PARAM_END
};

#undef SC
#undef OBJ
#undef LIGHT

static const object_def_t object_default = {
    SHAPE_CYLINDER, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.05f, 0 /* HAL_COLOUR_NONE */
};
static const light_def_t light_default = { 0.0f, 0.0f, 0.1f, 1.0f };
static const pose_def_t pose_default = { 0.0f, 0.0f, NAN };
/* A group entry before its keys: one robot anywhere in the arena, random
 * heading; it must name its controller. */
static const robot_group_t group_default = {
    .count = 1, .heading = NAN, .min_spacing = 0.08f, .moves = 1, .first_id = SCENARIO_IDS_BY_INDEX,
    .placement = { .shape = PLACE_RECTANGLE },
};

static int check_object(const loader_t *ld, const ynode_t *item, const char *path, void *elem);
static int check_group(const loader_t *ld, const ynode_t *item, const char *path, void *elem);
static int fill_other(const loader_t *ld, const ypair_t *pair, const char *path, void *base);
static const char *other_key(size_t i);
static int fill_task(const loader_t *ld, const ypair_t *pair, const char *path, void *base);
static const char *task_key(size_t i);

#define MAPPING_SCHEMA(name) static const schema_t name##_schema = { name##_params, NULL, NULL, NULL }
MAPPING_SCHEMA(arena);
MAPPING_SCHEMA(object);
MAPPING_SCHEMA(light);
MAPPING_SCHEMA(pose);
MAPPING_SCHEMA(output);
MAPPING_SCHEMA(random_cylinders);

static const seq_desc_t poses_seq = {
    "poses", SCENARIO_MAX_POSES, sizeof(pose_def_t), &pose_default, &pose_schema,
    offsetof(robot_group_t, placement.poses), offsetof(robot_group_t, placement.pose_count), NULL, 0, NULL
};
static const child_t placement_children[] = {
    { "poses", CHILD_SEQUENCE, NULL, &poses_seq, "poses: one {x, y, heading} per robot" },
    CHILD_END
};
static const schema_t placement_schema = { placement_params, placement_children, NULL, NULL };


static const child_t group_children[] = {
    { "placement", CHILD_MAPPING, &placement_schema, NULL, "where the robots start" },
    { "params", CHILD_DEFERRED, NULL, NULL, "the controller's parameters" },
    CHILD_END
};
static int fill_group_model(const loader_t *ld, const ypair_t *pair, const char *path, void *base);
static const char *group_model_key(size_t i);
static void group_model_defaults(void *group);
static const schema_t group_schema = { group_params, group_children, fill_group_model, group_model_key };

static const seq_desc_t groups_seq = {
    "groups", SCENARIO_MAX_GROUPS, sizeof(robot_group_t), &group_default, &group_schema,
    offsetof(scenario_t, groups), offsetof(scenario_t, group_count), check_group, 0, group_model_defaults
};
/* On the heap: a scenario holds the objects its file lists, not room for
 * SCENARIO_MAX_OBJECTS of them. */
static const seq_desc_t objects_seq = {
    "objects", SCENARIO_MAX_OBJECTS, sizeof(object_def_t), &object_default, &object_schema,
    offsetof(scenario_t, objects), offsetof(scenario_t, object_count), check_object, 1, NULL
};
static const seq_desc_t lights_seq = {
    "lights", SCENARIO_MAX_LIGHTS, sizeof(light_def_t), &light_default, &light_schema,
    offsetof(scenario_t, lights), offsetof(scenario_t, light_count), NULL, 0, NULL
};


static const child_t top_children[] = {
    { "arena", CHILD_MAPPING, &arena_schema, NULL, "walled rectangle" },
    { "robots", CHILD_SEQUENCE, NULL, &groups_seq, "groups of robots (at most 16)" },
    { "objects", CHILD_SEQUENCE, NULL, &objects_seq, "static obstacles (at most 4096)" },
    { "random_cylinders", CHILD_MAPPING, &random_cylinders_schema, NULL,
      "cylinders at random positions, drawn for each run (seed 003's obstacle tests)" },
    { "lights", CHILD_SEQUENCE, NULL, &lights_seq, "point lights (at most 16)" },
    { "output", CHILD_MAPPING, &output_schema, NULL, "output files" },
    CHILD_END
};
static const schema_t top_schema = { top_params, top_children, fill_other, other_key };

/* ---------------------------------------------------------------- defaults */

/* `def`'s default params in `out`, zeroed first; -1 (and zeros) when its
 * params struct does not fit (resolve_controller reports that). */
static int default_params_of(const controller_def_t *def, scenario_params_t *out)
{
    memset(out, 0, sizeof *out);
    if (def->params_size > sizeof out->bytes) {
        return -1;
    }
    if (def->default_params != NULL) {
        def->default_params(out->bytes);
    }
    return 0;
}

static void group_defaults(robot_group_t *g, const controller_def_t *def)
{
    *g = group_default;
    group_model_defaults(g);
    if (def != NULL) {
        snprintf(g->controller, sizeof g->controller, "%s", def->name);
        g->def = def;
        (void)default_params_of(def, &g->params);
    }
}

void scenario_defaults(scenario_t *out)
{
    memset(out, 0, sizeof *out);
    out->seed = 1;
    out->duration = 60.0;
    out->control_period_ms = 100;
    out->physics_substeps = 4;
    out->memory_limit_mb = SCENARIO_MEMORY_LIMIT_MB;
    out->arena.width = 4.0f;
    out->arena.height = 4.0f;
    out->arena.wall_thickness = 0.05f;
    out->group_count = 1;
    group_defaults(&out->groups[0], registry_controller(DEFAULT_CONTROLLER));
    out->groups[0].count = 20;
    snprintf(out->groups[0].name, sizeof out->groups[0].name, "%s", DEFAULT_CONTROLLER);
    out->output.timeseries_every = 10;
    out->random_cylinders.count = 0;
    out->random_cylinders.radius_min = 0.05f;
    out->random_cylinders.radius_max = 0.05f;
    out->random_cylinders.height = 0.1f;
    out->random_cylinders.gap = 0.08f;
    out->random_cylinders.layout_seed = 0;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim_models[id]->default_config != NULL) {
            sim_models[id]->default_config(scenario_model_config_mut(out, (sim_model_id_t)id));
        }
    }
}

uint32_t scenario_robot_count(const scenario_t *sc)
{
    uint32_t n = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        n += sc->groups[g].count;
    }
    return n;
}

const void *scenario_task_config(const scenario_t *sc, const struct task_def *def)
{
    for (uint32_t t = 0; t < sc->task_count; t++) {
        if (sc->tasks[t].def == def) {
            return sc->tasks[t].config.bytes;
        }
    }
    return NULL;
}

/* ---------------------------------------------------------------- groups */

static int need_positive(const loader_t *ld, const ynode_t *item, const char *path,
                         const char *key, float value, const char *shape)
{
    char p[SCHEMA_PATH_MAX];
    if (value > 0.0f) {
        return 0;
    }
    schema_join(p, path, key);
    return schema_fail(ld, schema_node_of(item, key), p, "a %s needs %s > 0", shape, key);
}

static int check_object(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
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

/* The controller a group names, with the list of valid ones if unknown. */
static int resolve_controller(const loader_t *ld, const ynode_t *item, const char *path,
                              robot_group_t *g)
{
    char p[SCHEMA_PATH_MAX], valid[256] = "";
    const controller_def_t *def;
    schema_join(p, path, "controller");
    if (g->controller[0] == '\0') {
        for (size_t i = 0; (def = registry_controller_at(i)) != NULL; i++) {
            schema_list_key(valid, sizeof valid, def->name);
        }
        return schema_fail(ld, item, p, "every group needs a controller (one of %s)", valid);
    }
    def = registry_controller(g->controller);
    if (def == NULL) {
        const char *best = NULL;
        size_t dist = 3;
        for (size_t i = 0; (def = registry_controller_at(i)) != NULL; i++) {
            schema_list_key(valid, sizeof valid, def->name);
            schema_consider(g->controller, def->name, &best, &dist);
        }
        if (best != NULL) {
            return schema_fail(ld, schema_node_of(item, "controller"), p,
                               "unknown controller '%s' (did you mean '%s'?)", g->controller, best);
        }
        return schema_fail(ld, schema_node_of(item, "controller"), p,
                           "unknown controller '%s' (valid: %s)", g->controller, valid);
    }
    if (def->params_size > sizeof g->params.bytes) {
        return schema_fail(ld, schema_node_of(item, "controller"), p,
                           "controller '%s' has %zu bytes of parameters (at most %zu)", def->name,
                           def->params_size, sizeof g->params.bytes);
    }
    g->def = def;
    return 0;
}

/* The group's policy must be one of its controller's; empty means its first. */
static int resolve_policy(const loader_t *ld, const ynode_t *item, const char *path, robot_group_t *g)
{
    char p[SCHEMA_PATH_MAX], valid[256] = "";
    const char *const *pol = g->def->policies;
    schema_join(p, path, "policy");
    if (pol == NULL || pol[0] == NULL) {
        if (g->policy[0] != '\0') {
            return schema_fail(ld, schema_node_of(item, "policy"), p, "controller '%s' has no policies",
                               g->def->name);
        }
        return 0;
    }
    if (g->policy[0] == '\0') {
        snprintf(g->policy, sizeof g->policy, "%s", pol[0]);
    }
    for (uint8_t i = 0; pol[i] != NULL; i++) {
        if (strcmp(pol[i], g->policy) == 0) {
            g->policy_index = i;
            return 0;
        }
        schema_list_key(valid, sizeof valid, pol[i]);
    }
    return schema_fail(ld, schema_node_of(item, "policy"), p,
                       "unknown policy '%s' for controller '%s' (valid: %s)", g->policy, g->def->name,
                       valid);
}

static int check_placement(const loader_t *ld, const ynode_t *item, const char *path,
                           const robot_group_t *g)
{
    const placement_def_t *pl = &g->placement;
    const ynode_t *node = ytree_get(item, "placement");
    char p[SCHEMA_PATH_MAX];
    schema_join(p, path, "placement");
    if (pl->shape == PLACE_CIRCLE) {
        return need_positive(ld, node ? node : item, p, "radius", pl->radius, "circle placement");
    }
    if (pl->shape == PLACE_RING && !(pl->outer > pl->inner)) {
        char q[SCHEMA_PATH_MAX];
        schema_join(q, p, "outer");
        return schema_fail(ld, schema_node_of(node ? node : item, "outer"), q,
                           "a ring placement needs outer > inner (%g <= %g)", (double)pl->outer,
                           (double)pl->inner);
    }
    if (pl->shape == PLACE_POSES && pl->order == PLACE_ORDER_SPACE) {
        char q[SCHEMA_PATH_MAX];
        schema_join(q, p, "order");
        return schema_fail(ld, schema_node_of(node ? node : item, "order"), q,
                           "order: space renumbers the spots drawn, and a poses group gives each "
                           "robot its own pose (leave order out, or place the group at random)");
    }
    if (pl->shape == PLACE_POSES && g->count != 0 && pl->pose_count != g->count) {
        char q[SCHEMA_PATH_MAX];
        schema_join(q, p, "poses");
        return schema_fail(ld, schema_node_of(node ? node : item, "poses"), q,
                           "%u poses for a group of %u robots (give one per robot)",
                           pl->pose_count, g->count);
    }
    return 0;
}

static int check_group(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
{
    robot_group_t *g = elem;
    char p[SCHEMA_PATH_MAX];
    schema_t params_schema = { NULL, NULL, NULL, NULL };
    if (resolve_controller(ld, item, path, g) != 0 || resolve_policy(ld, item, path, g) != 0) {
        return -1;
    }
    (void)default_params_of(g->def, &g->params);   /* it fits: resolve_controller checked */
    params_schema.params = g->def->params;
    schema_join(p, path, "params");
    if (schema_fill_mapping(ld, ytree_get(item, "params"), p, &params_schema, g->params.bytes) != 0) {
        return -1;
    }
    if (g->first_id != SCENARIO_IDS_BY_INDEX && g->count > 0 && g->first_id + (g->count - 1u) > 0xFFFFu) {
        schema_join(p, path, "first_id");
        return schema_fail(ld, schema_node_of(item, "first_id"), p,
                           "ids %u to %u: a robot's id is at most 65535", g->first_id, g->first_id + (g->count - 1u));
    }
    return check_placement(ld, item, path, g);
}

/* Default names: the controller's, or controller_<index> when taken. */
static int name_groups(const loader_t *ld, const ynode_t *root, scenario_t *sc)
{
    const ynode_t *seq = ytree_get(root, "robots");
    for (uint32_t g = 0; g < sc->group_count; g++) {
        robot_group_t *grp = &sc->groups[g];
        int given = grp->name[0] != '\0';
        if (!given) {
            /* Both fields hold at most 31 characters. */
            memcpy(grp->name, grp->controller, sizeof grp->name);
        }
        for (uint32_t h = 0; h < g; h++) {
            if (strcmp(sc->groups[h].name, grp->name) != 0) {
                continue;
            }
            if (given) {
                char p[SCHEMA_PATH_MAX], q[SCHEMA_PATH_MAX];
                schema_index_path(q, "robots", g);
                schema_join(p, q, "name");
                const ynode_t *item = seq && seq->kind == YNODE_SEQUENCE && g < seq->count ? seq->items[g] : root;
                return schema_fail(ld, schema_node_of(item, "name"), p,
                                   "'%s' already names robots[%u]; give each group its own name",
                                   grp->name, h);
            }
            /* A zero-filled buffer, copied whole: a scenario is a function
             * of its file to the last byte (stale stack bytes after the
             * name made two loads differ). */
            char name[sizeof grp->name];
            memset(name, 0, sizeof name);
            snprintf(name, sizeof name, "%.20s_%u", grp->controller, g);
            memcpy(grp->name, name, sizeof name);
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- models */

/* Each model's config (and group config) at its own 16-byte aligned offset
 * of the scenario's block, in list order (model.h). */
static size_t model_offset(sim_model_id_t id, int group)
{
    size_t off = 0;
    for (uint32_t k = 0; k < (uint32_t)id; k++) {
        size_t n = group ? sim_models[k]->group_config_size : sim_models[k]->config_size;
        off += (n + 15u) & ~(size_t)15u;
    }
    SIM_ASSERT(off + (group ? sim_models[id]->group_config_size : sim_models[id]->config_size)
               <= (group ? (size_t)SCENARIO_GROUP_MODEL_CONFIG_BYTES : (size_t)SCENARIO_MODEL_CONFIG_BYTES));
    return off;
}

const void *scenario_model_config(const scenario_t *sc, sim_model_id_t id)
{
    return sc->model_config.bytes + model_offset(id, 0);
}

void *scenario_model_config_mut(scenario_t *sc, sim_model_id_t id)
{
    return sc->model_config.bytes + model_offset(id, 0);
}

const void *scenario_group_model_config(const robot_group_t *g, sim_model_id_t id)
{
    return sim_models[id]->group_config_size ? g->model_config.bytes + model_offset(id, 1) : NULL;
}

void *scenario_group_model_config_mut(robot_group_t *g, sim_model_id_t id)
{
    return sim_models[id]->group_config_size ? g->model_config.bytes + model_offset(id, 1) : NULL;
}

/* A group's model keys take their defaults (seq_desc_t.init). */
static void group_model_defaults(void *group)
{
    robot_group_t *g = group;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim_models[id]->default_group_config != NULL) {
            sim_models[id]->default_group_config(scenario_group_model_config_mut(g, (sim_model_id_t)id));
        }
    }
}

/* A key of a group that a model declares (model_def_t.group_schema). */
static int fill_group_model(const loader_t *ld, const ypair_t *pair, const char *path, void *base)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const model_def_t *m = sim_models[id];
        if (m->group_schema != NULL) {
            int rc = schema_fill_known(ld, pair, path, m->group_schema,
                                       scenario_group_model_config_mut(base, (sim_model_id_t)id));
            if (rc != 0) {
                return rc;
            }
        }
    }
    return 0;
}

static const char *group_model_key(size_t i)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const char *key;
        for (size_t k = 0; sim_models[id]->group_schema != NULL
                           && (key = schema_key_at(sim_models[id]->group_schema, k)) != NULL; k++) {
            if (i-- == 0) {
                return key;
            }
        }
    }
    return NULL;
}

/* A top-level key of a model's (one of its sections), or of a task's. */
static int fill_other(const loader_t *ld, const ypair_t *pair, const char *path, void *base)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        int rc = schema_fill_known(ld, pair, path, sim_models[id]->schema,
                                   scenario_model_config_mut(base, (sim_model_id_t)id));
        if (rc != 0) {
            return rc;
        }
    }
    return fill_task(ld, pair, path, base);
}

static const char *other_key(size_t i)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const char *key;
        for (size_t k = 0; (key = schema_key_at(sim_models[id]->schema, k)) != NULL; k++) {
            if (i-- == 0) {
                return key;
            }
        }
    }
    return task_key(i);
}

/* Every model's cross-checks, in list order. */
static int check_models(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const model_def_t *m = sim_models[id];
        char path[SCHEMA_PATH_MAX] = "", shown[SCHEMA_PATH_MAX], msg[SIM_ERR_MAX] = "";
        if (m->check == NULL || m->check(scenario_model_config(sc, (sim_model_id_t)id), sc, path, msg) == 0) {
            continue;
        }
        schema_display_path(shown, path);
        return schema_fail(ld, schema_find(root, path), shown, "%s", msg);
    }
    return 0;
}

/* ---------------------------------------------------------------- tasks */

static const char *task_key(size_t i)
{
    const task_def_t *t = registry_task_at(i);
    return t != NULL ? t->name : NULL;
}

static size_t task_index(const task_def_t *def)
{
    size_t i = 0;
    while (registry_task_at(i) != NULL && registry_task_at(i) != def) {
        i++;
    }
    return i;
}

/* A task's section: its scalar keys and nested mappings (param_section_t). */
static int fill_task(const loader_t *ld, const ypair_t *pair, const char *path, void *base)
{
    scenario_t *sc = base;
    const task_def_t *def = registry_task(pair->key->text);
    child_t children[9];
    schema_t sections[8];
    schema_t schema = { NULL, children, NULL, NULL };
    size_t n = 0;
    if (def == NULL) {
        return 0;
    }
    for (uint32_t t = 0; t < sc->task_count; t++) {
        if (sc->tasks[t].def == def) {
            return schema_fail(ld, pair->key, path, "the task appears twice");
        }
    }
    if (sc->task_count == SCENARIO_MAX_TASKS) {
        return schema_fail(ld, pair->key, path, "more than %d tasks", SCENARIO_MAX_TASKS);
    }
    if (def->config_size > SCENARIO_TASK_CONFIG_MAX) {
        return schema_fail(ld, pair->key, path, "task '%s' has %zu bytes of config (at most %d)",
                           def->name, def->config_size, SCENARIO_TASK_CONFIG_MAX);
    }
    task_config_t *tc = &sc->tasks[sc->task_count++];
    memset(tc, 0, sizeof *tc);
    tc->def = def;
    if (def->default_config != NULL) {
        def->default_config(tc->config.bytes);
    }
    schema.params = def->params;
    for (const param_section_t *s = def->sections; s != NULL && s->key != NULL && n < 8; s++, n++) {
        sections[n] = (schema_t){ s->params, NULL, NULL, NULL };
        children[n] = (child_t){ s->key, CHILD_MAPPING, &sections[n], NULL, s->doc };
    }
    children[n] = (child_t)CHILD_END;
    return schema_fill_mapping(ld, pair->value, path, &schema, tc->config.bytes) == 0 ? 1 : -1;
}

/* Registry order, whatever the file's. */
static void order_tasks(scenario_t *sc)
{
    for (uint32_t i = 1; i < sc->task_count; i++) {
        for (uint32_t j = i; j > 0 && task_index(sc->tasks[j - 1].def) > task_index(sc->tasks[j].def); j--) {
            task_config_t tmp = sc->tasks[j - 1];
            sc->tasks[j - 1] = sc->tasks[j];
            sc->tasks[j] = tmp;
        }
    }
}

static int check_tasks(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    for (uint32_t t = 0; t < sc->task_count; t++) {
        const task_def_t *def = sc->tasks[t].def;
        char key[64] = "", msg[256] = "", path[SCHEMA_PATH_MAX];
        if (def->check == NULL || def->check(sc->tasks[t].config.bytes, sc, key, msg) == 0) {
            continue;
        }
        if (key[0] != '\0') {
            schema_join(path, def->name, key);
        } else {
            snprintf(path, sizeof path, "%s", def->name);
        }
        return schema_fail(ld, schema_find(root, path), path, "%s", msg);
    }
    return 0;
}

/* ---------------------------------------------------------------- cross checks */

int scenario_inside_arena(const scenario_t *sc, double x, double y, double hx, double hy)
{
    return fabs(x) + hx <= sc->arena.width / 2.0 + ARENA_EPS &&
           fabs(y) + hy <= sc->arena.height / 2.0 + ARENA_EPS;
}

void scenario_outside_message(const scenario_t *sc, const char *what, char *msg, size_t size)
{
    snprintf(msg, size, "%s outside the arena (x in [%g, %g], y in [%g, %g] m)", what,
             -sc->arena.width / 2.0, sc->arena.width / 2.0, -sc->arena.height / 2.0, sc->arena.height / 2.0);
}

static int outside(const loader_t *ld, const ynode_t *node, const char *path, const char *what,
                   const scenario_t *sc)
{
    char msg[160];
    scenario_outside_message(sc, what, msg, sizeof msg);
    return schema_fail(ld, node, path, "%s", msg);
}

static int check_inside(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    const ynode_t *seq = ytree_get(root, "objects"), *lights = ytree_get(root, "lights");
    char path[SCHEMA_PATH_MAX];
    for (uint32_t i = 0; i < sc->object_count; i++) {
        const object_def_t *o = &sc->objects[i];
        double hx = o->radius, hy = o->radius;
        if (o->shape == SHAPE_BOX) {
            /* Half-extents of the rotated box's bounding rectangle. */
            double a = o->angle * UNITS_PI / 180.0, c = fabs(cos(a)), s = fabs(sin(a));
            hx = (c * o->width + s * o->depth) / 2.0;
            hy = (s * o->width + c * o->depth) / 2.0;
        }
        if (!scenario_inside_arena(sc, o->x, o->y, hx, hy)) {
            schema_index_path(path, "objects", i);
            return outside(ld, seq->items[i], path,
                           o->shape == SHAPE_BOX ? "the box reaches" : "the cylinder reaches", sc);
        }
    }
    if (sc->random_cylinders.count > 0) {
        const ynode_t *rc = ytree_get(root, "random_cylinders");
        if (sc->random_cylinders.radius_min > sc->random_cylinders.radius_max) {
            return schema_fail(ld, rc != NULL ? rc : root, "random_cylinders.radius_min",
                               "%g m is larger than radius_max (%g m)", sc->random_cylinders.radius_min,
                               sc->random_cylinders.radius_max);
        }
        if (sc->random_cylinders.count > SCENARIO_MAX_OBJECTS - sc->object_count) {
            return schema_fail(ld, rc != NULL ? rc : root, "random_cylinders.count",
                               "%u cylinders and %u objects pass the %u obstacles a world holds",
                               sc->random_cylinders.count, sc->object_count, SCENARIO_MAX_OBJECTS);
        }
    }
    for (uint32_t i = 0; i < sc->light_count; i++) {
        if (!scenario_inside_arena(sc, sc->lights[i].x, sc->lights[i].y, 0.0, 0.0)) {
            schema_index_path(path, "lights", i);
            return outside(ld, lights->items[i], path, "the light is", sc);
        }
    }
    return 0;
}

static int has_task(const scenario_t *sc, const task_def_t *def)
{
    for (uint32_t t = 0; t < sc->task_count; t++) {
        if (sc->tasks[t].def == def) return 1;
    }
    return 0;
}

static int check_needs(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        const task_def_t *world = registry_task_for_controller(grp->def->name);
        if (grp->count > 0 && world != NULL && !has_task(sc, world)) {
            char path[SCHEMA_PATH_MAX], at[SCHEMA_PATH_MAX];
            snprintf(path, sizeof path, "robots.%u.controller", g);
            const ynode_t *node = schema_find(root, path);
            schema_index_path(at, "robots", g);
            schema_join(path, at, "controller");
            return schema_fail(ld, node, path,
                               "controller '%s' needs the %s task, its world (without it the robots "
                               "have nothing to do): add a `%s:` section (swarmsim --help lists its keys)",
                               grp->def->name, world->name, world->name);
        }
    }
    return 0;
}

void scenario_format_bytes(uint64_t bytes, char *out, size_t len)
{
    if (bytes >= UINT64_C(1000000000)) {
        snprintf(out, len, "%.1f GB", (double)bytes / 1e9);
    } else if (bytes >= UINT64_C(1000000)) {
        snprintf(out, len, "%.0f MB", (double)bytes / 1e6);
    } else {
        snprintf(out, len, bytes < 10000u ? "%.1f kB" : "%.0f kB", (double)bytes / 1e3);
    }
}

/* Before anything is allocated: a run must fit memory_limit_mb. */
static int check_memory(const loader_t *ld, const ynode_t *root, const scenario_t *sc)
{
    sim_memory_t m;
    sim_memory_estimate(sc, 1, &m);
    if (m.total <= (uint64_t)sc->memory_limit_mb << 20) {
        return 0;
    }
    char total[32], each[32];
    scenario_format_bytes(m.total, total, sizeof total);
    scenario_format_bytes(m.per_robot, each, sizeof each);
    const ynode_t *limit = ytree_get(root, "memory_limit_mb"), *robots = ytree_get(root, "robots");
    return schema_fail(ld, limit != NULL ? limit : robots != NULL ? robots : root,
                       limit != NULL ? "memory_limit_mb" : "robots",
                       "a run of this scenario needs about %s (%u robots at about %s each), more than "
                       "memory_limit_mb %u: fewer robots, or a larger limit (--set memory_limit_mb=%llu)",
                       total, m.robots, each, sc->memory_limit_mb,
                       (unsigned long long)((m.total >> 20) * 5 / 4 + 1));
}

static int cross_check(const loader_t *ld, const ynode_t *root, scenario_t *sc)
{
    if (sc->duration * 1000.0 < sc->control_period_ms) {
        const ynode_t *d = ytree_get(root, "duration");
        return schema_fail(ld, d != NULL ? d : root, "duration",
                           "%g s is shorter than one control period (%g s)", sc->duration,
                           sc->control_period_ms / 1000.0);
    }
    if (name_groups(ld, root, sc) != 0 || check_needs(ld, root, sc) != 0
        || check_inside(ld, root, sc) != 0
        || check_models(ld, root, sc) != 0) {
        return -1;
    }
    order_tasks(sc);
    return check_tasks(ld, root, sc) != 0 ? -1 : check_memory(ld, root, sc);
}

/* ---------------------------------------------------------------- loading */

static int set_path_and_name(const loader_t *ld, const char *path, scenario_t *out)
{
    const char *base = strrchr(path, '/');
    const char *dot;
    size_t len;
    if (strlen(path) >= sizeof out->path) {
        return schema_fail(ld, NULL, "", "path longer than %zu characters", sizeof out->path - 1);
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

/* A file with no document, or a null one, is an empty mapping when
 * overrides follow; alone it says nothing to run, so it is an error. */
static int check_root(const loader_t *ld, ynode_t **root, size_t override_count)
{
    if (ytree_is_null(*root) && override_count == 0) {
        return schema_fail(ld, NULL, "", "empty scenario: it sets nothing (a wrong or truncated "
                           "file?); write at least its robots, e.g. robots: [{count: 20, "
                           "controller: random_walk}]");
    }
    if (ytree_is_null(*root)) {
        ytree_free(*root);
        *root = ytree_new_mapping(0, NULL);
        return *root != NULL ? 0 : schema_fail(ld, NULL, "", "out of memory");
    }
    if ((*root)->kind != YNODE_MAPPING) {
        return schema_wrong_type(ld, *root, "", "a mapping of keys at the top level");
    }
    return 0;
}

/* Keys of the scenario format before robot groups: say what replaced them. */
static int old_syntax(const loader_t *ld, const ynode_t *root)
{
    static const char *const moved[][2] = {
        { "controller", "robots are groups now: robots: [{count: 20, controller: NAME, policy: P, "
                        "params: {...}, placement: {...}}]" },
        { "nest", "a nest is no longer a core key: a task that has one declares it in its own "
                  "section (swarmsim --help lists the tasks' keys)" },
    };
    for (size_t i = 0; i < sizeof moved / sizeof moved[0]; i++) {
        const ynode_t *v = ytree_get(root, moved[i][0]);
        if (v != NULL) {
            for (size_t k = 0; k < root->count; k++) {
                if (root->pairs[k].value == v) {
                    return schema_fail(ld, root->pairs[k].key, moved[i][0], "unknown key '%s': %s",
                                       moved[i][0], moved[i][1]);
                }
            }
        }
    }
    const ynode_t *robots = ytree_get(root, "robots");
    if (robots != NULL && robots->kind == YNODE_MAPPING) {
        return schema_fail(ld, robots, "robots", "expected a sequence of groups, got a mapping "
                           "(robots: [{count: 20, controller: random_walk}])");
    }
    return 0;
}

int scenario_load(const char *path, const scenario_override_t *overrides,
                  size_t override_count, scenario_t *out, char err[SIM_ERR_MAX])
{
    loader_t ld = { path != NULL ? path : "(null)", err, SIM_ERR_MAX };
    ynode_t *root = NULL;
    int rc;
    err[0] = '\0';
    scenario_defaults(out);
    if (path == NULL || set_path_and_name(&ld, path, out) != 0) {
        return path == NULL ? schema_fail(&ld, NULL, "", "no scenario file") : -1;
    }
    if (ytree_parse_file(path, &root, err, SIM_ERR_MAX) != 0) {
        return -1;
    }
    rc = check_root(&ld, &root, override_count);
    for (size_t i = 0; rc == 0 && i < override_count; i++) {
        rc = ytree_apply_override(&root, overrides[i].text, err, SIM_ERR_MAX);
    }
    if (rc == 0) {
        rc = old_syntax(&ld, root);
    }
    if (rc == 0) {
        rc = schema_fill_mapping(&ld, root, "", &top_schema, out);
    }
    if (rc == 0) {
        rc = cross_check(&ld, root, out);
    }
    ytree_free(root);
    if (rc != 0) {
        scenario_free(out);   /* a refused scenario holds nothing */
    }
    return rc == 0 ? 0 : -1;
}

void scenario_free(scenario_t *sc)
{
    if (sc != NULL) {
        free(sc->objects);
        sc->objects = NULL;
        sc->object_count = 0;
        for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
            if (sim_models[id]->free_config != NULL) {
                sim_models[id]->free_config(scenario_model_config_mut(sc, (sim_model_id_t)id));
            }
        }
    }
}

int scenario_add_object(scenario_t *sc, const object_def_t *o)
{
    if (sc->object_count >= SCENARIO_MAX_OBJECTS) {
        return -1;
    }
    object_def_t *grown = realloc(sc->objects, (sc->object_count + 1u) * sizeof *grown);
    if (grown == NULL) {
        return -1;
    }
    sc->objects = grown;
    grown[sc->object_count++] = *o;
    return 0;
}

int scenario_write_effective(const char *path, const scenario_override_t *overrides,
                             size_t override_count, FILE *out, char err[SIM_ERR_MAX])
{
    loader_t ld = { path, err, SIM_ERR_MAX };
    ynode_t *root = NULL;
    if (ytree_parse_file(path, &root, err, SIM_ERR_MAX) != 0) {
        return -1;
    }
    int rc = check_root(&ld, &root, override_count);
    for (size_t i = 0; rc == 0 && i < override_count; i++) {
        rc = ytree_apply_override(&root, overrides[i].text, err, SIM_ERR_MAX);
    }
    if (rc == 0) {
        rc = ytree_write(out, root, err, SIM_ERR_MAX);
    }
    ytree_free(root);
    return rc == 0 ? 0 : -1;
}

/* ---------------------------------------------------------------- --help */

static void print_group_params(FILE *f, const char *prefix)
{
    const controller_def_t *def;
    /* The models' keys of a group first: "robots[]", the prefix without ".params". */
    char group[SCHEMA_PATH_MAX];
    snprintf(group, sizeof group, "%.*s", (int)(strlen(prefix) > 7 ? strlen(prefix) - 7 : 0), prefix);
    robot_group_t *g = calloc(1, sizeof *g);
    for (uint32_t id = 0; g != NULL && id < SIM_MODEL_COUNT; id++) {
        if (sim_models[id]->group_schema != NULL) {
            group_model_defaults(g);
            schema_print(f, group, sim_models[id]->group_schema, scenario_group_model_config(g, (sim_model_id_t)id),
                         NULL);
        }
    }
    free(g);
    for (size_t i = 0; (def = registry_controller_at(i)) != NULL; i++) {
        scenario_params_t buf;
        if (default_params_of(def, &buf) != 0) {
            continue;
        }
        if (def->params == NULL || def->params[0].key == NULL) {
            fprintf(f, "  %s: none when controller is %s\n", prefix, def->name);
            continue;
        }
        fprintf(f, "  %s when controller is %s (%s):\n", prefix, def->name, def->doc);
        schema_print_params(f, prefix, def->params, buf.bytes);
    }
}

void scenario_print_schema(FILE *file)
{
    scenario_t *def = malloc(sizeof *def);
    const task_def_t *task;
    if (def == NULL) {
        return;
    }
    scenario_defaults(def);
    fprintf(file, "Scenario keys (YAML; lengths in m, angles in deg, times in s; "
                  "the arena is centred on 0,0):\n");
    fprintf(file, "  %-34s %-6s %-12s %-22s %s\n", "key", "type", "default", "range", "meaning");
    schema_print(file, "", &top_schema, def, print_group_params);
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        schema_print(file, "", sim_models[id]->schema, scenario_model_config(def, (sim_model_id_t)id), NULL);
    }
    for (size_t i = 0; (task = registry_task_at(i)) != NULL; i++) {
        union { uint8_t bytes[SCENARIO_TASK_CONFIG_MAX]; double d; uint64_t u; } cfg;
        memset(&cfg, 0, sizeof cfg);
        if (task->config_size > sizeof cfg.bytes) {
            continue;
        }
        if (task->default_config != NULL) {
            task->default_config(cfg.bytes);
        }
        fprintf(file, "  %-34s %-6s %-12s %-22s task: %s (runs when the section is present)\n",
                task->name, "map", "-", "", task->doc);
        schema_print_params(file, task->name, task->params, cfg.bytes);
        for (const param_section_t *s = task->sections; s != NULL && s->key != NULL; s++) {
            char prefix[SCHEMA_PATH_MAX];
            schema_join(prefix, task->name, s->key);
            schema_print_params(file, prefix, s->params, cfg.bytes);
        }
    }
    fprintf(file, "Override any key with --set key.path=value "
                  "(e.g. --set robots.0.count=50 --set objects.0.x=1.5).\n");
    free(def);
}
