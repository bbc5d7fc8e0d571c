/*
 * scenario.h - a simulation scenario: arena, obstacles, lights, groups of
 * robots (each a controller with its parameters and a placement), the
 * sensor and actuator models, the tasks, duration and seed.
 *
 * Scenario files are YAML with a strict schema (scenario.c has every key,
 * its unit and range; `swarmsim --help` prints them).  Lengths are metres,
 * angles degrees, times seconds unless a key's name says otherwise.
 */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "common/controller.h"
#include "common/param.h"
#include "base.h"


#define SCENARIO_NAME_MAX 64
#define SCENARIO_PATH_MAX 512
#define SCENARIO_MAX_OBJECTS 4096
#define SCENARIO_MAX_LIGHTS 16
#define SCENARIO_MAX_GROUPS 16
#define SCENARIO_MAX_POSES 256
#define SCENARIO_MAX_TASKS 4
#define SCENARIO_CONTROLLER_PARAMS_MAX 512
#define SCENARIO_TASK_CONFIG_MAX 1024
/** The one seed range, [0, 2^53 - 1]: the scenario's `seed`, --seed and every
 *  repetition's seed + r lie in it.  2^53 - 1 is exact as a double (the YAML
 *  loader compares through one), as a JSON number and as a signed 64-bit
 *  integer, so summaries and sweep tables carry seeds without rounding. */
#define SCENARIO_SEED_MAX UINT64_C(9007199254740991)
/** Bytes for every model's config (sim_host/models/model.h), and for every
 *  model's config of one group: each model's struct at its own 16-byte
 *  aligned offset, in list order (scenario_model_config). */
#define SCENARIO_MODEL_CONFIG_BYTES 4096
#define SCENARIO_GROUP_MODEL_CONFIG_BYTES 512

/** A block of plain data aligned for any member type. */
#define SCENARIO_BLOCK(bytes_) union { uint8_t bytes[bytes_]; max_align_t align; }

struct task_def;

typedef enum object_shape { SHAPE_CYLINDER = 0, SHAPE_BOX = 1 } object_shape_t;

/** A static obstacle. */
typedef struct object_def {
    int shape;          /**< object_shape_t: "cylinder" or "box" */
    float x, y;         /**< centre, m (arena centre is 0,0) */
    float radius;       /**< cylinder radius, m */
    float width, depth; /**< box size along its x and y, m */
    float angle;        /**< box rotation, degrees CCW */
    float height;       /**< m (for the camera and pictures) */
    int colour;         /**< hal_colour_t: "none", "red", "green", "blue" */
} object_def_t;

/** A point light (a lamp above the floor). */
typedef struct light_def {
    float x, y;         /**< m */
    float height;       /**< above the floor, m */
    float intensity;    /**< relative: 1 gives irradiance 1 at 1 m */
} light_def_t;

/** Where a group's robots start (placement.c). */
typedef enum placement_shape {
    PLACE_RECTANGLE = 0,  /**< uniform in a rectangle (default: the arena) */
    PLACE_CIRCLE = 1,     /**< uniform in a disc */
    PLACE_RING = 2,       /**< uniform in an annulus */
    PLACE_GRID = 3,       /**< rows and columns over a rectangle, one spot per robot */
    PLACE_POSES = 4       /**< one explicit pose per robot */
} placement_shape_t;

/** Which robot of a group takes which spot (placement.c). */
typedef enum placement_order {
    PLACE_ORDER_DRAWN = 0,  /**< robot k the k-th spot drawn */
    PLACE_ORDER_SPACE = 1   /**< the spots renumbered by space (0.5 m cells, Morton order) */
} placement_order_t;

typedef struct pose_def {
    float x, y;         /**< m */
    float heading;      /**< deg CCW from +x; NaN ("random"): the group's heading */
} pose_def_t;

typedef struct placement_def {
    int shape;                  /**< placement_shape_t */
    int order;                  /**< placement_order_t */
    float x, y;                 /**< centre of the region, m */
    float width, height;        /**< rectangle, grid; 0: the arena's */
    float radius;               /**< circle, m */
    float inner, outer;         /**< ring radii, m */
    uint32_t pose_count;
    pose_def_t poses[SCENARIO_MAX_POSES];
} placement_def_t;

/** A controller's params block (aligned for any member type). */
typedef union scenario_params {
    uint8_t bytes[SCENARIO_CONTROLLER_PARAMS_MAX];
    double align_double;
    uint64_t align_u64;
} scenario_params_t;

/** robot_group_t.first_id's default: a robot's id is its index. */
#define SCENARIO_IDS_BY_INDEX 0xFFFFFFFFu

/** Robots that run one controller with one set of parameters. */
typedef struct robot_group {
    char name[32];              /**< label in outputs (default: the controller's name) */
    uint32_t count;             /**< robots; ids are consecutive, group after group */
    char controller[32];        /**< a controller registered in sim_host/registry.c */
    const controller_def_t *def;/**< the controller (resolved when loading) */
    char policy[16];            /**< one of the controller's policies (default: its first) */
    uint8_t policy_index;
    scenario_params_t params;   /**< the controller's params, defaults then `params:` */
    placement_def_t placement;
    float heading;              /**< start heading, deg; NaN: random */
    float min_spacing;          /**< centre-to-centre distance to every robot placed before, m */
    uint8_t moves;              /**< 0: a static body that nothing pushes (a fixed station, a landmark) */
    /** hal_robot_id of its first robot, the others' following it;
     *  SCENARIO_IDS_BY_INDEX (the default): each robot's index. */
    uint32_t first_id;
    /** The models' keys of this group (model.h: group_schema). */
    SCENARIO_BLOCK(SCENARIO_GROUP_MODEL_CONFIG_BYTES) model_config;
} robot_group_t;

/** A task's section, parsed into the task's own config struct. */
typedef struct task_config {
    const struct task_def *def;
    union {
        uint8_t bytes[SCENARIO_TASK_CONFIG_MAX];
        double align_double;
        uint64_t align_u64;
    } config;
} task_config_t;

typedef struct scenario {
    char name[SCENARIO_NAME_MAX];
    char path[SCENARIO_PATH_MAX];  /**< file it was read from */

    uint64_t seed;                 /**< base seed; repetition r uses seed + r */
    double duration;               /**< simulated time, s */
    uint16_t control_period_ms;    /**< one controller step, ms */
    uint16_t physics_substeps;     /**< Box2D sub-steps per control step */
    uint32_t memory_limit_mb;      /**< the loader refuses a scenario whose run needs more
                                        (sim_memory_estimate), MB of 2^20 bytes */

    struct {
        float width, height;       /**< walled rectangle centred on 0,0, m */
        float wall_thickness;      /**< m */
    } arena;

    uint32_t group_count;
    robot_group_t groups[SCENARIO_MAX_GROUPS];

    uint32_t object_count;
    object_def_t *objects;         /**< object_count of them, on the heap (NULL: none);
                                        scenario_free frees them */

    /** Cylinders drawn at random when a run is built (placement.c), after
     *  `objects` and before the robots: each clears every obstacle, the
     *  walls and every robot of a `poses` group by `gap`; robots placed at
     *  random then avoid them as any obstacle.  Seed 003's obstacle tests
     *  ("a random configuration of obstacle cylinders"). */
    struct {
        uint32_t count;            /**< cylinders (0: none) */
        float radius_min;          /**< m */
        float radius_max;          /**< m; the radius is uniform in [min, max] */
        float height;              /**< m (camera, pictures) */
        float gap;                 /**< least gap to an obstacle, a wall or a fixed robot's body, m */
        uint64_t layout_seed;      /**< 0: each run draws its own layout from its run seed;
                                        else one layout for every run */
    } random_cylinders;

    uint32_t light_count;
    light_def_t lights[SCENARIO_MAX_LIGHTS];

    struct {
        uint32_t timeseries_every; /**< control steps between CSV rows */
    } output;

    uint32_t task_count;
    task_config_t tasks[SCENARIO_MAX_TASKS];  /**< in registry order */

    /** Every model's config (model.h), its defaults unless the file has its
     *  sections; scenario_model_config finds one. */
    SCENARIO_BLOCK(SCENARIO_MODEL_CONFIG_BYTES) model_config;
} scenario_t;

/** One `--set key.path=value` override. */
typedef struct scenario_override {
    const char *text;              /**< "key.path=value" as given */
} scenario_override_t;

/** Frees what a scenario holds on the heap (its objects), not the struct:
 *  after a successful scenario_load, or scenario_add_object.  NULL is a
 *  no-op. */
void scenario_free(scenario_t *sc);

/** Appends an object (code that builds a scenario without a file).
 *  Returns 0, or -1 past SCENARIO_MAX_OBJECTS or out of memory. */
int scenario_add_object(scenario_t *sc, const object_def_t *o);

/** Fills `out` with every default (no file): one group of 20 random
 *  walkers anywhere in a 4 x 4 m arena, no task, no objects (it overwrites
 *  `out` without freeing it). */
void scenario_defaults(scenario_t *out);

/**
 * Reads `path`, applies `overrides` in order, validates, and fills `out`.
 * Returns 0, or -1 with a message in `err` that names the file, the line
 * and the key ("x.yaml:12: robots[0].count: expected an integer, got '2.5'").
 * On error `out` is unspecified but holds nothing on the heap.  The caller
 * owns `out` (allocate it on the heap: about 94 kB) and, after a success,
 * frees what it holds with scenario_free (also before loading into it
 * again: `out` is overwritten, not freed).
 */
int scenario_load(const char *path, const scenario_override_t *overrides,
                  size_t override_count, scenario_t *out,
                  char err[SIM_ERR_MAX]);

/** scenario_load into a scenario of its own on the heap (for bindings,
 *  which do not know its size): the scenario, or NULL with the message in
 *  `err`.  scenario_destroy frees it whole. */
scenario_t *scenario_create(const char *path, const scenario_override_t *overrides,
                            size_t override_count, char err[SIM_ERR_MAX]);
/** Frees what scenario_create made (NULL: a no-op). */
void scenario_destroy(scenario_t *sc);

/**
 * Writes the effective scenario to `out` as YAML: the file's tree with the
 * overrides applied (comments are not kept; absent keys keep meaning their
 * defaults), so that loading it gives what scenario_load gave.  Call it
 * after scenario_load succeeded.  Returns 0, or -1 with a message in `err`.
 */
int scenario_write_effective(const char *path, const scenario_override_t *overrides,
                             size_t override_count, FILE *out, char err[SIM_ERR_MAX]);

/** Every robot of every group. */
uint32_t scenario_robot_count(const scenario_t *sc);

/** The control steps of its `duration` (duration / control period,
 *  rounded): what swarmsim runs without --steps. */
uint64_t scenario_steps(const scenario_t *sc);
/** Its `seed`: the first repetition's without --seed (sc->seed, for
 *  bindings that do not read the struct). */
uint64_t scenario_seed(const scenario_t *sc);

/** Non-zero when a rectangle of half-extents hx, hy (m) centred on (x, y)
 *  lies inside the arena (to 1 um): the check of objects, lights and the
 *  tasks' own regions. */
int scenario_inside_arena(const scenario_t *sc, double x, double y, double hx, double hy);
/** "<what> outside the arena (x in [..], y in [..] m)" in `msg`: the one
 *  wording of that error, for the core and the tasks. */
void scenario_outside_message(const scenario_t *sc, const char *what, char *msg, size_t size);

/** The config of task `def` in `sc`, or NULL when the scenario has no such
 *  section. */
const void *scenario_task_config(const scenario_t *sc, const struct task_def *def);

/** The default memory_limit_mb: a run of 2 GB.  The largest benchmark world
 *  (100,000 robots, full sensing) needs about 0.4 GB; a scenario past the
 *  limit is almost always a count with a zero too many, and a study runs
 *  several runs side by side. */
#define SCENARIO_MEMORY_LIMIT_MB 2048u

/** "3.2 GB", "14 MB", "850 kB": `bytes` for messages. */
void scenario_format_bytes(uint64_t bytes, char *out, size_t len);

/** Writes every key with its default, unit and range to `f` (for --help). */
void scenario_print_schema(FILE *file);

#endif
