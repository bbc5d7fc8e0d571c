/*
 * sim_internal.h - the state shared by the simulator core's modules (world,
 * placement, sensors, IR communication, HAL).  Not a public header: tasks
 * use sim.h.
 */
#ifndef SIM_INTERNAL_H
#define SIM_INTERNAL_H

#include <box2d/box2d.h>

#include "models/model.h"
#include "swarmsim/geometry.h"
#include "swarmsim/grid.h"
#include "items.h"
#include "hal.h"
#include "swarmsim/rand.h"
#include "swarmsim/sim.h"
#include "robot_link.h"
#include "swarmsim/task.h"
#include "telemetry/robot_telemetry.h"

/** What a controller's `hal_t *` points to in the simulator. */
struct hal {
    struct sim *sim;
    uint32_t index;
    uint32_t worker;   /**< the pool worker stepping this robot now (its scratch); 0 outside */
};

typedef struct sim_robot {
    hal_t hal;
    b2BodyId body;
    float x, y, theta;             /**< pose at the start of this control step */
    uint16_t leds;                 /**< bits 0-7 ring, 8 body, 9 front */
    uint32_t group;                /**< index into the scenario's groups */
    const controller_def_t *def;   /**< what runs on this robot */
    void *ctrl;                    /**< controller state, or NULL when it has none */
    /** What steps it: def->step, or its platform binding's (a robot on an
     *  emulated MCU: models/pil/pil.h), which keeps ctrl in step. */
    void (*step)(void *ctrl, hal_t *hal);
    uint8_t own_telemetry;         /**< its image sends its own telemetry bytes (a PIL robot):
                                        the UART model does not run the sender for it */
    uint8_t moves;                 /**< 0: a static body */
    uint8_t escaped;
    uint16_t id;                   /**< hal_robot_id: the index unless set (sim_set_robot_id) */
} sim_robot_t;

/** A robot's body velocity for Box2D this step (world_drive), and how far
 *  it moved in it (world_read_poses), m/s, rad/s, m. */
typedef struct world_velocity {
    b2Vec2 v;
    float w;
    double moved;
} world_velocity_t;

typedef struct obstacle {
    int shape;                     /**< object_shape_t */
    vec2_t c;                      /**< centre */
    float r;                       /**< cylinder radius */
    vec2_t corner[4];              /**< box corners, counter-clockwise */
    float height;
    int colour;
    float aabb[4];
} obstacle_t;

/** One pool worker's working memory (pool.h): what a sensor query, a
 *  delivery or a listener's sum needs while it runs, so that robots are
 *  sensed side by side.  Worker 0 is the thread that steps the run, and
 *  the only one outside the parallel phases (tasks' hooks, tests). */
typedef struct sim_scratch {
    uint32_t *obstacle_mark;       /**< n_obstacles: de-duplicates grid hits per query */
    uint32_t mark_stamp;
    uint32_t *robots;              /**< n: a query's robots (sound, IR delivery) */
    uint32_t *items;               /**< item_index.cap: a query's items (items.h) */
} sim_scratch_t;

/** A counter the run's controllers declare (observable.h), and its keys in
 *  the summary and time series. */
#define SIM_MAX_COUNTERS 16

/** The robot grid's smallest cell side, m (wider when a model reaches
 *  further); placement.order: space numbers robots along cells of it. */
#define SIM_ROBOT_CELL_MIN_M 0.5f
typedef struct sim_counter {
    const char *name;
    const char *unit;
    char total_doc[160];       /**< "summed over the robots that count it: <doc>" */
    char total_key[48];        /**< "<name>_total" */
    char per_robot_key[56];    /**< "<name>_per_robot" */
} sim_counter_t;

/** One counter of a group's controller and the total it adds to. */
typedef struct sim_group_counter {
    const observable_t *obs;
    uint8_t slot;              /**< in sim->counters */
} sim_group_counter_t;

/** A model in a run: its config, its arrays, its scratch per worker and
 *  what its create made. */
typedef struct sim_model_run {
    const model_def_t *def;
    const void *config;            /**< in the scenario */
    void *self;
    model_layout_t layout;
    void *array[MODEL_MAX_ARRAYS]; /**< n elements each */
    uint8_t *scratch;              /**< one block per worker, layout.scratch_size each */
    size_t scratch_stride;
    int created;                   /**< its create ran (destroy is due) */
} sim_model_run_t;

/** Phases of a step that models take part in (sim.c). */
#define SIM_PHASES 5

/** A running task. */
typedef struct sim_task_run {
    const task_def_t *def;
    void *self;
} sim_task_run_t;

struct sim {
    const scenario_t *sc;
    uint64_t seed;
    uint64_t step;
    float dt;                      /**< control period, s */
    float hw, hh;                  /**< half width and height of the arena, m */
    b2WorldId world;
    world_velocity_t *drive;       /**< n: world.c's per-robot results */

    uint32_t n;                    /**< robots */
    sim_robot_t *robots;
    void **ctrl_blocks;            /**< per group: its robots' controller states */
    float *px, *py;                /**< robot centres, for the grid: always equal to robots[i].x
                                        and .y (written together), and where neighbour loops read
                                        them (sim_robot_at): the grid's pass has just brought them into
                                        the cache, 4 B a robot where a record is 72 */
    grid_t robot_grid;
    uint32_t *step_order;          /**< robots in the order they step (phase 2) */

    uint32_t n_obstacles;          /**< the scenario's objects, then its random cylinders */
    object_def_t *objects;         /**< n_obstacles: what each obstacle is (placement_cylinders) */
    obstacle_t *obstacles;
    grid_t obstacle_grid;

    struct pool *pool;             /**< the run's worker threads (pool.h) */
    sim_scratch_t *scratch;        /**< one per pool worker */

    uint32_t n_tasks;
    sim_task_run_t tasks[SCENARIO_MAX_TASKS];
    sim_item_index_t item_index;   /**< the tasks' items for the camera (items.h) */
    int done;                      /**< a task's stop condition held */

    uint32_t n_counters;
    sim_counter_t counters[SIM_MAX_COUNTERS];
    /* Per group, its controller's counters (found once by name, so that
     * counting each step matches no strings). */
    uint8_t n_group_counters[SCENARIO_MAX_GROUPS];
    sim_group_counter_t group_counters[SCENARIO_MAX_GROUPS][SIM_MAX_COUNTERS];


    sim_event_rec_t *events;       /**< of the current step */
    uint32_t n_events, events_cap;


    sim_metrics_t metrics;

    sim_model_run_t models[SIM_MODEL_COUNT];   /**< in list order (models/model_list.h) */
    /* The models that take part in each phase of a step (sim.c's phase_t),
     * that step after each robot, that may halt one: found once, so that
     * a step does not ask every model about every hook. */
    uint8_t n_phase[SIM_PHASES], phase_model[SIM_PHASES][SIM_MODEL_COUNT];
    uint8_t n_after_robot, after_robot[SIM_MODEL_COUNT];
    uint8_t n_halts, halts[SIM_MODEL_COUNT];
};

/** Model `id`'s config for this run. */
static inline const void *sim_model_config(const struct sim *sim, sim_model_id_t id)
{
    return sim->models[id].config;
}

/** Array `k` of model `id`: robot i's element is at i x its elem_size. */
static inline void *sim_model_array(const struct sim *sim, sim_model_id_t id, uint32_t k)
{
    return sim->models[id].array[k];
}

/** Model `id`'s working memory on pool worker `worker` (hal_t.worker). */
static inline void *sim_model_scratch(const struct sim *sim, sim_model_id_t id, uint32_t worker)
{
    return sim->models[id].scratch + (size_t)worker * sim->models[id].scratch_stride;
}

/** What model `id`'s create left in its self (NULL: nothing). */
static inline void *sim_model_self(const struct sim *sim, sim_model_id_t id)
{
    return sim->models[id].self;
}

/** The robot behind a controller's hal_t. */
static inline sim_robot_t *sim_hal_robot(hal_t *hal)
{
    return &hal->sim->robots[hal->index];
}

/** The stamp of sensor readings taken in the current step (0: none yet). */
static inline uint64_t sim_hal_stamp(const hal_t *hal)
{
    return hal->sim->step + 1;
}

/** FNV-1a 64 of `n` bytes folded into `h`: the state hash (sim_state_hash). */
uint64_t sim_hash_bytes(uint64_t h, const void *p, size_t n);

/** Non-zero when a model stops robot i's controller and motors this step. */
int sim_robot_halted(const struct sim *sim, uint32_t i);

/* sim.c */
/** Robot i's commands and sensor summaries as robot_telemetry reports them:
 *  IR and ambient from the readings cached at step stamp `since` or later
 *  (1: any read so far; the current stamp: this step only), else -1. */
void sim_robot_platform(const struct sim *sim, uint32_t i, uint64_t since, robot_telemetry_platform_t *p);
/** Robot i's latest readings as every model holds them (model.h's
 *  model_inspect_t; inspecting reads no sensor). */
void sim_robot_inspect(const struct sim *sim, uint32_t i, struct model_inspect *out);

/* world.c: Box2D bodies */
int world_create(struct sim *sim, char err[SIM_ERR_MAX]);
void world_destroy(struct sim *sim);
void world_drive(struct sim *sim);
void world_advance(struct sim *sim);
void world_read_poses(struct sim *sim);

/* placement.c: start poses of every group */
int placement_run(struct sim *sim, char err[SIM_ERR_MAX]);
/** Draws the scenario's random cylinders into sim->objects after its
 *  objects (placement.c).  Returns 0, or -1 with a message. */
int placement_cylinders(struct sim *sim, char err[SIM_ERR_MAX]);

/** Writes to `out` (at most `max`) the indices of obstacles whose bounding
 *  boxes meet [minx,maxx] x [miny,maxy], each once, in ascending order of
 *  first grid hit; returns how many.  `ws`: the calling worker's scratch. */
uint32_t sim_gather_obstacles(const struct sim *sim, sim_scratch_t *ws, float minx, float miny, float maxx,
                              float maxy, uint32_t *out, uint32_t max);
/** Non-zero when an obstacle cuts the segment from p to q (the first 256
 *  whose boxes meet the segment's: line of sight). */
int sim_obstacles_cut(const struct sim *sim, sim_scratch_t *ws, vec2_t p, vec2_t q);
/** The scratch of the worker stepping robot i now (worker 0's outside the
 *  control phase). */
sim_scratch_t *sim_robot_scratch(const struct sim *sim, uint32_t i);
/** Same for robots whose centres lie in the box. */
uint32_t sim_gather_robots(const struct sim *sim, float minx, float miny, float maxx, float maxy,
                           uint32_t *out, uint32_t max);

/** Robot i's centre, m (the same values as robots[i].x and .y, read from
 *  the compact copies that sim_gather_robots reads). */
static inline vec2_t sim_robot_at(const struct sim *sim, uint32_t i)
{
    return v2(sim->px[i], sim->py[i]);
}

#endif
