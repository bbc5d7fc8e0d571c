/*
 * sim.h - one simulation run: a Box2D world of e-pucks in groups, each
 * robot running its firmware controller through the simulator's hal_t, the
 * sensor and actuator models, and the scenario's tasks around them (task.h
 * and sim_host/models/model.h say how one step runs).
 *
 * The simulator's public API, for tasks, tools, tests and bindings alike:
 *   create    scenario_load (scenario.h: a file and --set overrides, errors
 *             with file and line), then sim_create / sim_create_threads;
 *   step      sim_step, sim_done;
 *   read      robots' poses, wheels, LEDs, controllers' states and
 *             observables (below), every per-robot field as a strided
 *             array (sim_field), the run's ground truth (sim_metrics);
 *   metrics   metrics_sample (time series) and metrics_final (the summary's
 *             metrics, the tasks' included: metrics.h), sim_state_hash;
 *   destroy   sim_destroy, then scenario_free.
 * The internals (sim_host/core/, sim_host/models/) are not part of it.
 *
 * Ownership: the scenario must outlive the sim.  Not thread-safe: one sim
 * is stepped by one thread (which may spread a step over the run's own
 * threads), but different sims run concurrently without sharing anything.
 */
#ifndef SIM_SIM_H
#define SIM_SIM_H

#include <stdint.h>

#include "common/controller.h"
#include "hal.h"
#include "scenario.h"

typedef struct sim sim_t;
struct task_def;
struct sim_rand;

/** Ground-truth observations of a run (never the robots' beliefs). */
typedef struct sim_metrics {
    uint64_t robot_contacts;      /**< robot-robot contacts begun */
    uint64_t static_contacts;     /**< robot-wall/obstacle contacts begun */
    double distance_m;            /**< summed path length of all robots, m */
    double min_wall_clearance_m;  /**< smallest body-to-wall gap seen, m (<0: overlap) */
    uint32_t escaped;             /**< robots ever outside the arena */
} sim_metrics_t;

/** Builds the world for run seed `seed`.  Returns NULL with a message in
 *  `err` (e.g. robots that cannot be placed). */
sim_t *sim_create(const scenario_t *sc, uint64_t seed, char err[SIM_ERR_MAX]);
/** The same run stepped on `threads` threads (1 .. 64): the controllers and
 *  their sensors, IR delivery, the sound field with a cutoff and Box2D's
 *  solver spread over them.  The results are those of sim_create, byte for
 *  byte, at any thread count. */
sim_t *sim_create_threads(const scenario_t *sc, uint64_t seed, uint32_t threads, char err[SIM_ERR_MAX]);
void sim_destroy(sim_t *sim);

/** What a run of a scenario needs, estimated from the scenario alone,
 *  before anything is allocated: the core's arrays and grids, each
 *  model's arrays and run state (model.h), the controllers' states, the
 *  tasks' (task_def_t.memory), and Box2D's bodies and shapes (a measured
 *  constant per body: sim.c).  Within about 25 % of what a run's resident
 *  memory grows by (test_sim).  The loader refuses a scenario whose
 *  estimate passes its `memory_limit_mb`. */
typedef struct sim_memory {
    uint64_t total;            /**< bytes of one run on `threads` threads */
    uint64_t per_robot;        /**< bytes each robot adds, on average */
    uint32_t robots;
} sim_memory_t;
void sim_memory_estimate(const scenario_t *sc, uint32_t threads, sim_memory_t *out);

/** One control period (task.h lists its phases). */
void sim_step(sim_t *sim);

/** Non-zero once a task's stop condition holds (checked after each step). */
int sim_done(const sim_t *sim);

uint64_t sim_step_count(const sim_t *sim);
/** Simulated time, s: steps x control period. */
double sim_time_s(const sim_t *sim);
uint64_t sim_seed(const sim_t *sim);
const scenario_t *sim_scenario(const sim_t *sim);
const sim_metrics_t *sim_metrics(const sim_t *sim);

/* ---------------------------------------------------------------- robots */

/** Every robot; ids 0 .. count-1, group after group. */
uint32_t sim_robot_count(const sim_t *sim);
/** Index into the scenario's groups of robot `i`. */
uint32_t sim_robot_group(const sim_t *sim, uint32_t i);
/** The controller robot `i` runs. */
const controller_def_t *sim_robot_def(const sim_t *sim, uint32_t i);
/** Its controller state (a task may read the state of its seed's own
 *  controllers; tests do).  NULL for a controller without state. */
void *sim_robot_controller(sim_t *sim, uint32_t i);
const void *sim_robot_controller_const(const sim_t *sim, uint32_t i);
/** The current state name of its controller. */
const char *sim_robot_state_name(const sim_t *sim, uint32_t i);
/** The value of observable `name` (the controller's observable.h table:
 *  "threshold", "oae", ...) of robot `i` into *value, scaled as telemetry
 *  reports it: 0, or -1 when its controller declares none of that name. */
int sim_robot_observable(const sim_t *sim, uint32_t i, const char *name, float *value);
/** The hal_t of robot `i`, to drive a robot from a test. */
hal_t *sim_robot_hal(sim_t *sim, uint32_t i);

/** Types of a per-robot field's values (sim_field_t). */
typedef enum sim_field_type {
    SIM_FIELD_U8, SIM_FIELD_I8, SIM_FIELD_U16, SIM_FIELD_I16, SIM_FIELD_U32, SIM_FIELD_I32, SIM_FIELD_U64,
    SIM_FIELD_F32, SIM_FIELD_F64
} sim_field_type_t;

/** A per-robot value of the run, where it lives: robot i's `count` values
 *  of `type` start at (const char *)base + i * stride.  What the core keeps
 *  of every robot ("pose.x", "pose.y", "pose.theta", "leds", "group") and
 *  what each model exposes ("wheels.cmd_left", "sound.level", ...; --help
 *  lists them).  Valid until the sim is destroyed; the values are those of
 *  the current step.  For bindings that read robots as arrays without a
 *  copy per robot (a strided view). */
typedef struct sim_field {
    const char *name;
    const char *unit;       /**< "" when it has none */
    const char *doc;
    sim_field_type_t type;
    const void *base;       /**< robot 0's first value (NULL when the run has no robots) */
    size_t stride;          /**< bytes from one robot's values to the next */
    uint32_t count;         /**< values per robot */
} sim_field_t;

/** The field called `name`: 0, or -1 when the run has none of that name
 *  (a model that allocated nothing for this run, such as sound when off). */
int sim_field(const sim_t *sim, const char *name, sim_field_t *out);
/** The k-th field of the run (0, 1, ...): 0, or -1 past the last. */
int sim_field_at(const sim_t *sim, uint32_t k, sim_field_t *out);

/** Pose of robot `i`: m, m, rad (CCW from +x). */
void sim_robot_pose(const sim_t *sim, uint32_t i, double *x, double *y, double *theta);
/** Teleports robot `i` (tests and placement). */
void sim_set_robot_pose(sim_t *sim, uint32_t i, double x, double y, double theta);
/** Commanded wheel speeds of robot `i`, steps/s. */
void sim_robot_wheels(const sim_t *sim, uint32_t i, int16_t *left, int16_t *right);
/** LED state of robot `i`: bit k = ring LED k; bit 8 body; bit 9 front. */
uint16_t sim_robot_leds(const sim_t *sim, uint32_t i);

/** Puts `msg` in robot `i`'s IR inbox, as if received this step (a task
 *  standing in for a robot, e.g. ideal information).  Returns 0, or -1 when
 *  the inbox is full. */
int sim_ircom_inject(sim_t *sim, uint32_t i, const hal_ircom_msg_t *msg);
/** How far an IR message reaches, centre to centre, m (`ircom.range`). */
float sim_ircom_range_m(const sim_t *sim);

/* ---------------------------------------------------------------- world */

/** Half the arena's width and height, m. */
void sim_arena_half(const sim_t *sim, float *hw, float *hh);
uint32_t sim_obstacle_count(const sim_t *sim);
/** Obstacle `k` (the scenario's objects, then the run's random cylinders),
 *  or NULL past the last. */
const object_def_t *sim_object(const sim_t *sim, uint32_t k);
/** Non-zero when an obstacle cuts the segment from (x0, y0) to (x1, y1), m:
 *  the line-of-sight test of IR messages (ircom.c), robots aside. */
int sim_segment_blocked(sim_t *sim, double x0, double y0, double x1, double y1);
/** Bounding box of obstacle `k`: min x, min y, max x, max y, m. */
void sim_obstacle_bounds(const sim_t *sim, uint32_t k, float out[4]);

/* ---------------------------------------------------------------- tasks */

/** The state of the running task `def` (task_def_t.create's result), or
 *  NULL when the scenario does not run it. */
void *sim_task(const sim_t *sim, const struct task_def *def);

/** Seeds a random stream of task `def` for this run: a pure function of the
 *  run seed, the task and `index` (the task's choice of stream). */
void sim_task_rand_seed(const sim_t *sim, const struct task_def *def, uint64_t index,
                        struct sim_rand *out);

/** Records an event of robot `robot` this step ("pickup", "deposit", ...)
 *  for the telemetry.  `kind` and `detail` must be string literals or
 *  outlive the step. */
void sim_event(sim_t *sim, uint32_t robot, const char *kind, const char *detail, int32_t value);

typedef struct sim_event_rec {
    uint32_t robot;
    const char *kind, *detail;
    int32_t value;
} sim_event_rec_t;

/** The events recorded during the last step. */
uint32_t sim_events(const sim_t *sim, const sim_event_rec_t **events);

struct robot_link;
/** Robot `i`'s telemetry link when the scenario runs the robots' own
 *  telemetry (robot_telemetry.enabled), else NULL. */
const struct robot_link *sim_robot_link(const sim_t *sim, uint32_t i);

/* ---------------------------------------------------------------- camera */

/** Saves robot `robot`'s camera frames from now on as PNG pictures with
 *  the blobs of each drawn on them, in folder `dir` (which must exist):
 *  frame_<step>.png, <step> the control step it was captured at.  With the
 *  geometric model the frame is rendered for the picture only (the blobs
 *  drawn are the model's); results are the same with and without it.
 *  Returns 0, or -1 when `robot` is not a robot or `dir` too long. */
int sim_camera_record(sim_t *sim, uint32_t robot, const char *dir);

/** NULL, or what went wrong in a model during the last step (a camera
 *  renderer that could not be made, a picture that could not be written):
 *  the run must stop. */
const char *sim_error(const sim_t *sim);

/** FNV-1a hash of every robot's pose bits and counters: equal hashes mean
 *  bit-identical runs. */
uint64_t sim_state_hash(const sim_t *sim);

/** Test hook: the order robots step in (phase 2 of task.h).  0 ascending
 *  ids (the default), 1 descending, 2 a shuffle drawn from `key`. */
void sim_set_step_order(sim_t *sim, int order, uint64_t key);

#endif
