/*
 * model.h - a simulator model as a plug-in: one of the e-puck's sensors or
 * actuators (IR proximity and ambient light, the camera, the microphones
 * and speaker, IR communication, the wheels, the ground sensors), a
 * device around it (an overhead tracker, the host link, the UART of the
 * robot's own telemetry) or a fault injector, in the shape tasks have
 * (task.h).  The core names no model: it allocates what a model asks for
 * and calls its hooks in the phases of a step.
 *
 * A model has
 *  - its scenario sections: top-level mappings of the scenario file,
 *    described by descriptor tables (schema.h: strict, every key with its
 *    type, range, unit and default, errors naming file, line and key),
 *    parsed into its own config struct that scenario_t keeps for it
 *    (scenario_model_config), checked across keys by its `check`;
 *    optionally keys of every robot group (a group's `faults:`, whether its
 *    robots carry the ground-sensor module), parsed into a per-group
 *    config struct (scenario_group_model_config);
 *  - its per-robot state: arrays the core allocates for it, each with one
 *    element per robot, in the layout the model asks for (`layout`): one
 *    array of structures, or several arrays (structures of arrays);
 *    zero-filled, 64-byte aligned, found with sim_model_array;
 *  - working memory per pool worker (`layout`'s scratch), for what it
 *    computes while robots are stepped side by side;
 *  - its state for one run (create/destroy), when arrays are not enough;
 *  - the phases of a step it takes part in (hooks; NULL when it takes no
 *    part), in the order below;
 *  - the HAL calls it serves: it defines those functions of hal.h in its
 *    own files, and names them in `hal_calls` (tests/cli/hal_served.sh
 *    checks that each function of hal.h is served exactly once);
 *  - what it reports: per-robot fields readable through sim_field (the
 *    Python binding's arrays), its part of the robots' telemetry summary,
 *    summary metrics, its part of the state hash.
 *
 * The models are listed once, in sim_host/models/model_list.h; that order
 * is the order of their sections in --help and of their hooks within each
 * phase.
 *
 * One control step (sim_step), models' and tasks' hooks together:
 *   1. begin_step of every model (faults begin and end);
 *   2. before_control of every task (task.h);
 *   3. before_control of every model (the sound field, the UART budgets);
 *   4. every robot's controller steps, side by side on the run's threads
 *      unless a model's `serial` says otherwise: a robot whose controller a
 *      model `halts` is skipped; after each robot's step, after_robot of
 *      every model (on the thread that stepped it; it may touch that
 *      robot's state only);
 *   5. after_control of every model (faulty robots' messages, then IR
 *      delivery);
 *   6. after_control of every task;
 *   7. drive of every model (the wheels: each robot's body velocity),
 *      then Box2D resolves contacts and the core reads the new poses;
 *   8. after_physics of every task;
 *   9. end_step of every model (what the speakers play next);
 *  10. the step count advances and the tasks' done() are asked.
 * Between steps (tests, the Python binding) a HAL call computes what the
 * next step's controllers would read.
 *
 * Randomness: a model draws only from its own streams (rand.h: per robot
 * and purpose), so models neither disturb each other nor depend on the
 * thread count.
 */
#ifndef SIM_MODEL_H
#define SIM_MODEL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "core/schema.h"
#include "swarmsim/base.h"
#include "swarmsim/metrics.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "telemetry/robot_telemetry.h"

/** Most per-robot arrays a model asks for. */
#define MODEL_MAX_ARRAYS 8

/** What a model asks the core to allocate for a run (`layout`). */
/** Most waiting IR messages an inspection lists. */
#define MODEL_INSPECT_HEARD 16u

/** One robot's latest readings as the models hold them, for inspecting
 *  the robot of a run under control (control.h): never taken by reading a
 *  sensor, which would change the run's noise.  *_known 0 / counts 0: the
 *  model has nothing (not read yet, not in the run). */
typedef struct model_inspect {
    uint8_t prox_known, ambient_known;
    uint16_t prox[HAL_IR_COUNT];          /**< counts */
    uint16_t ambient[HAL_IR_COUNT];       /**< counts, lower is brighter */
    int16_t ir_bearing_mrad[HAL_IR_COUNT];
    int8_t n_blobs;                       /**< -1: the camera was not read */
    hal_blob_t blobs[HAL_MAX_BLOBS];
    float camera_fov_rad, camera_range_m; /**< 0: no camera */
    uint8_t n_bands;                      /**< bands 1 .. n_bands in mic[] */
    float mic[HAL_SOUND_BANDS];           /**< counts per band, mic[0] unused */
    uint8_t n_heard;
    hal_ircom_msg_t heard[MODEL_INSPECT_HEARD];   /**< waiting in its inbox, oldest first */
    float ircom_range_m;                  /**< 0: no IR communication */
} model_inspect_t;

typedef struct model_layout {
    uint32_t arrays;                     /**< per-robot arrays, <= MODEL_MAX_ARRAYS */
    size_t elem_size[MODEL_MAX_ARRAYS];  /**< bytes per robot of each */
    size_t scratch_size;                 /**< bytes of working memory per pool worker */
    size_t run_bytes;                    /**< what its create allocates besides (renderers,
                                              schedules): for the memory estimate only */
    float neighbour_reach_m;             /**< how far beyond a robot's body its queries of the
                                              robot grid look each step (the grid's cells are
                                              sized for the largest); 0: no say */
} model_layout_t;

/** A per-robot value a model exposes (sim_field): `count` values of
 *  `type` at `offset` in each element of its array `array`. */
typedef struct model_field {
    const char *name;     /**< "<model>.<what>", e.g. "wheels.cmd_left" */
    const char *unit;     /**< "" when it has none */
    const char *doc;      /**< one line */
    sim_field_type_t type;
    uint32_t array;       /**< which of the model's arrays */
    size_t offset;        /**< in that array's element */
    uint32_t count;       /**< values per robot (8: one per IR sensor) */
} model_field_t;

typedef struct model_def {
    const char *name;     /**< the model's name (its main section's) */
    const char *doc;      /**< one line for --help */

    /* ---- the scenario: its sections, as a task's (task.h) */
    size_t config_size;                   /**< of its config struct */
    void (*default_config)(void *config);
    /** Its top-level keys: `children` are its sections (CHILD_MAPPING),
     *  with offsets from its config struct; `params` is NULL. */
    const schema_t *schema;
    /** Cross-checks after loading (every section read, the groups' too).
     *  Returns 0, or -1 with the dotted path of the key at fault from the
     *  top ("ircom.tx_per_period", "robots.0.controller") and a message. */
    int (*check)(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX],
                 char msg[SIM_ERR_MAX]);
    /** Frees what its config holds on the heap (an on_heap sequence), or NULL. */
    void (*free_config)(void *config);
    /** Keys of each robot group, with offsets from its per-group config. */
    size_t group_config_size;
    void (*default_group_config)(void *group_config);
    const schema_t *group_schema;

    /* ---- one run */
    /** The arrays and scratch it needs for scenario `sc` (NULL: none). */
    void (*layout)(const void *config, const scenario_t *sc, model_layout_t *out);
    /** Sets up a run once its robots (placed), obstacles and arrays exist,
     *  before the world and the tasks: seeds its streams, fills its arrays,
     *  and may make run state in *self (NULL until then; its hooks get it).
     *  Returns 0, or -1 with a message ("out of memory for ..."); destroy
     *  is called either way.  NULL: nothing to set up. */
    int (*create)(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX]);
    /** Frees *self's run state (NULL: none). */
    void (*destroy)(void *self);

    /* ---- the phases of a step (above) */
    void (*begin_step)(sim_t *sim, void *self);
    void (*before_control)(sim_t *sim, void *self);
    /** Non-zero when robot `robot`'s controller and motors are stopped. */
    int (*halts)(const sim_t *sim, const void *self, uint32_t robot);
    void (*after_robot)(sim_t *sim, void *self, uint32_t robot);
    void (*after_control)(sim_t *sim, void *self);
    /** Writes the body velocity of every robot that moves (sim_drive). */
    void (*drive)(sim_t *sim, void *self);
    void (*end_step)(sim_t *sim, void *self);
    /** Non-zero when the robots must step on one thread now (the rendered
     *  camera: one GL context per run). */
    int (*serial)(const sim_t *sim, const void *self);
    /** Robot `robot` was moved by hand (sim_set_robot_pose): what it
     *  computed from the old pose this step is stale. */
    void (*moved)(sim_t *sim, void *self, uint32_t robot);

    /* ---- what it serves and reports */
    /** The hal.h functions it defines, NULL-terminated. */
    const char *const *hal_calls;
    /** Per-robot fields, {NULL}-terminated, or NULL. */
    const model_field_t *fields;
    /** Its part of robot `robot`'s telemetry summary: what it read at step
     *  stamp `since` or later (sim_robot_platform). */
    void (*platform)(const sim_t *sim, const void *self, uint32_t robot, uint64_t since,
                     robot_telemetry_platform_t *p);
    /** Its part of robot `robot`'s latest readings (model_inspect_t), from
     *  what it already holds.  NULL: it has none to show. */
    void (*inspect)(const sim_t *sim, const void *self, uint32_t robot, model_inspect_t *out);
    /** Appends its summary metrics (after the core's, before the tasks'). */
    void (*final)(const sim_t *sim, const void *self, metric_list_t *out);
    /** Writes its lines of summary.json (before "seed"), or nothing. */
    void (*write_json)(const sim_t *sim, const void *self, FILE *f);
    /** Folds robot `robot`'s state into the state hash (after its pose). */
    uint64_t (*hash)(const sim_t *sim, const void *self, uint32_t robot, uint64_t h);
    /** NULL, or what went wrong in it (a renderer that could not be made):
     *  the run must stop (sim_error). */
    const char *(*error)(const sim_t *sim, const void *self);
} model_def_t;

/* The list: an id per model (SIM_MODEL_<name>), in list order. */
#define SIM_MODEL(name) SIM_MODEL_##name,
typedef enum sim_model_id {
#include "models/model_list.h"
    SIM_MODEL_COUNT
} sim_model_id_t;
#undef SIM_MODEL

#define SIM_MODEL(name) extern const model_def_t name##_model;
#include "models/model_list.h"
#undef SIM_MODEL

/** Every model, in list order (registry.c). */
extern const model_def_t *const sim_models[SIM_MODEL_COUNT];

/** Model `id`'s config in `sc`: its defaults when the file has none of its
 *  sections (scenario.c).  The run's copy: sim_model_config (sim_internal.h). */
const void *scenario_model_config(const scenario_t *sc, sim_model_id_t id);
void *scenario_model_config_mut(scenario_t *sc, sim_model_id_t id);
/** Model `id`'s config of group `g` (NULL when the model has no group keys). */
const void *scenario_group_model_config(const robot_group_t *g, sim_model_id_t id);
void *scenario_group_model_config_mut(robot_group_t *g, sim_model_id_t id);

/** The schema of a model with one top-level section `key` (its scalar keys
 *  `params`, its nested `children` or NULL, one line of `doc`): defines
 *  `static const schema_t var`, for model_def_t.schema. */
#define MODEL_ONE_SECTION(var, key, params, children, doc)                                \
    static const schema_t var##_section = { params, children, NULL, NULL };               \
    static const child_t var##_sections[] = {                                            \
        { key, CHILD_MAPPING, &var##_section, NULL, doc }, CHILD_END                      \
    };                                                                                    \
    static const schema_t var = { NULL, var##_sections, NULL, NULL }

/** Typed accessors of a model's config in a scenario, for its header:
 *  NAME_config(sc) and NAME_config_mut(sc) (tests and tools that set a
 *  model's keys in code). */
#define MODEL_CONFIG_ACCESSORS(name, type)                                                \
    static inline const type *name##_config(const scenario_t *sc)                         \
    {                                                                                     \
        return (const type *)scenario_model_config(sc, SIM_MODEL_##name);                 \
    }                                                                                     \
    static inline type *name##_config_mut(scenario_t *sc)                                 \
    {                                                                                     \
        return (type *)scenario_model_config_mut(sc, SIM_MODEL_##name);                   \
    }

#endif
