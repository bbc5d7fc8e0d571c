/*
 * task.h - an experiment's world-side logic as a plug-in: the things on the
 * floor, the ledgers and the detectors of an experiment, and its metrics.
 * The seeds' tasks live in sim_host/tasks/<name>/; the core names none.
 *
 * A task has its own scenario section (a mapping named after it, strict
 * like the rest: its keys are descriptor tables), tells the robots of each
 * group what a real robot would be built with (configure), keeps its own
 * state (create/destroy), runs hooks around each control step, adds things
 * the sensors see (items), declares its time-series columns and summary
 * metrics, draws itself as data (drawing.h), and may end a run (done).
 * The build registers it: it finds every `const task_def_t NAME = {` (on
 * one line) in sim_host/tasks/<task>/ (tools/make/registry.sh).
 *
 * How one control step runs (sim_step):
 *   1. before_control of every task, in registry order (serial);
 *   2. every robot's controller steps.  Sensing and stepping read only the
 *      state at the start of the step (poses, items, messages delivered
 *      last step) and write only the robot's own outputs, so robots step
 *      in any order, and side by side on the run's threads (pool.h), with
 *      the same result (tested);
 *   3. IR messages sent in step 2 are delivered, each receiver taking the
 *      senders in turn order (they are readable in the next step);
 *   4. after_control of every task (serial): it may read the commanded
 *      wheel speeds;
 *   5. physics: wheels drive the bodies, Box2D resolves contacts;
 *   6. after_physics of every task (serial): it sees the new poses;
 *   7. the step count advances, then the run asks done().
 * The models (the sensors and actuators, sim_host/models/model.h) take part
 * around these: their sensing in step 2, IR delivery as step 3, the wheels
 * in step 5; model.h lists the phases of both in one order.
 * Hooks may be NULL.
 */
#ifndef SIM_TASK_H
#define SIM_TASK_H

#include <stddef.h>
#include <stdint.h>

#include "common/param.h"
#include "drawing.h"
#include "metrics.h"
#include "scenario.h"
#include "sim.h"

/** Something on the floor that the robots' camera sees (food, a
 *  target).  Items are not rigid: robots drive through them, and the IR
 *  sensors do not see them. */
typedef struct sim_item {
    float x, y;        /**< centre, m; NaN: out of the world */
    float radius;      /**< m */
    float height;      /**< m */
    uint8_t colour;    /**< hal_colour_t; HAL_COLOUR_NONE is not seen */
} sim_item_t;

/** A nested mapping of a task's section, e.g. a `goal:` with its x, y, radius. */
typedef struct param_section {
    const char *key;
    const param_desc_t *params;   /**< offsets from the task's config struct */
    const char *doc;
} param_section_t;

typedef struct task_def {
    const char *name;             /**< its scenario section */
    const char *doc;              /**< one line for --help */
    size_t config_size;           /**< of its config struct (<= SCENARIO_TASK_CONFIG_MAX) */
    const param_desc_t *params;   /**< scalar keys of the section */
    const param_section_t *sections;  /**< nested mappings, {NULL}-terminated, or NULL */
    void (*default_config)(void *config);
    /** Controllers that mean nothing without this task (it is their world:
     *  without it their robots have nothing to do), NULL-terminated, or
     *  NULL.  A scenario with such robots and without the
     *  task is an error. */
    const char *const *controllers;

    /** Cross-checks after loading.  Returns 0, or -1 with the key (relative
     *  to the section, "nest.diameter"; "" for the section) and a message. */
    int (*check)(const void *config, const scenario_t *sc, char key[64], char msg[SIM_ERR_MAX]);

    /** Tells robots of `group` what a real robot would be built with:
     *  fills the task's part of `params`, the group's controller's params
     *  struct (group->def says which controller it is). */
    void (*configure)(const void *config, const scenario_t *sc, const robot_group_t *group,
                      void *params);

    /** About how many bytes its create allocates for a run of `sc`, for
     *  the loader's memory estimate (sim_memory_estimate); NULL: a few. */
    size_t (*memory)(const void *config, const scenario_t *sc);

    /** Its state for one run; NULL with a message in `err` on failure. */
    void *(*create)(sim_t *sim, const void *config, char err[SIM_ERR_MAX]);
    void (*destroy)(void *self);

    void (*before_control)(void *self, sim_t *sim);
    void (*after_control)(void *self, sim_t *sim);
    void (*after_physics)(void *self, sim_t *sim);

    /** What the camera sees of the task now: *items points to `return`
     *  entries that stay valid until the next hook.  Called by robots'
     *  cameras on several threads at once while the controllers step: it
     *  must only read. */
    uint32_t (*items)(const void *self, const sim_item_t **items);

    /** Time-series columns (metric_desc_t, {NULL}-terminated) and the
     *  function that fills their values in that order. */
    const metric_desc_t *columns;
    void (*sample)(const void *self, const sim_t *sim, double *values);

    /** Summary metrics, the same way. */
    const metric_desc_t *summary;
    void (*final)(const void *self, const sim_t *sim, double *values);

    /** For a `liar` fault: the well-formed but false message robot `robot`
     *  sends this step (seed 000: a deposit report every step), or NULL
     *  when the task's controllers cannot lie. */
    uint16_t (*lie)(const void *self, const sim_t *sim, uint32_t robot);

    /** Appends its picture of the current step. */
    void (*draw)(const void *self, const sim_t *sim, drawing_t *out);

    /** Its legend ({0, NULL}-terminated, or NULL): what the robot fills of
     *  `draw` mean, then its floor areas, outlines and items (drawing.h,
     *  draw_key_t).  The PNG frames, the videos and the live page all show
     *  this table; `draw` takes its colours from it. */
    const draw_key_t *legend;

    /** Non-zero when the experiment is over (a stop condition): the run
     *  ends and its summary gives the completion time.  NULL: never. */
    int (*done)(const void *self, const sim_t *sim);
} task_def_t;

#endif
