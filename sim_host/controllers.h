/*
 * controllers.h - the registry of firmware controllers the simulator can run.
 *
 * Each entry adapts one firmware controller (firmware/<name>.h: a state
 * struct, *_default_params, *_init, *_step) to the simulator, with the
 * descriptor table of its params struct so that scenarios can set them.
 */
#ifndef SIM_CONTROLLERS_H
#define SIM_CONTROLLERS_H

#include <stddef.h>
#include <stdint.h>

#include "hal.h"
#include "core/param.h"
#include "core/scenario.h"

typedef struct sim_controller {
    const char *name;            /**< scenario `controller.name` */
    const char *doc;             /**< one line for --help */
    size_t state_size;           /**< bytes of the state struct */
    size_t params_size;          /**< bytes of the params struct */
    const param_desc_t *params;  /**< keys of `controller.params` */
    const char *const *policies; /**< `controller.policy` values, NULL-terminated,
                                      the first is the default; NULL if none */
    void (*default_params)(void *params);
    void (*init)(void *state, const void *params, uint32_t seed);
    void (*step)(void *state, hal_t *hal);
    /** Obstacle-avoidance events the robot has counted so far. */
    uint32_t (*oae_count)(const void *state);
    /** Name of the current state of the controller's state machine. */
    const char *(*state_name)(const void *state);
    /** Copies what the robot is told about its task from the scenario
     *  (policy, task constants) into its params; NULL if nothing. */
    void (*configure)(void *params, const scenario_t *sc);
    /** Seed 000's task state: 'W' waiting, 'S' searching, 'R' returning,
     *  or 0 for controllers without one; NULL means always 0. */
    char (*task_state)(const void *state);
} sim_controller_t;

/** The random walk's tuning keys, for every controller that embeds a
 *  random_walk_params_t: FIELD(f) gives the offset and size of its member
 *  f in the controller's params struct.  (Its speed is listed by each
 *  controller: the forager sets it from the task.) */
#define RANDOM_WALK_TUNING_DESCS(FIELD)                                          \
    { "turn_speed_steps_s", PARAM_I16, FIELD(turn_speed_steps_s), 1, 1000, NULL, \
      "wheel speed when turning in place, steps/s" },                           \
    { "turn_chance", PARAM_U16, FIELD(turn_chance), 0, 65535, NULL,              \
      "random walk: chance of a tumble per step, in 1/65536" },                 \
    { "avoid_enter", PARAM_U16, FIELD(avoid_enter), 0, 4095, NULL,               \
      "front IR proximity that starts an avoidance (an OAE), counts" },         \
    { "avoid_exit", PARAM_U16, FIELD(avoid_exit), 0, 4095, NULL,                 \
      "front IR proximity below which avoidance ends, counts" }

/** Seed 000's forager and nest beacon (controllers_foraging.c). */
extern const sim_controller_t controller_forager;
extern const sim_controller_t controller_nest_beacon;

/** The controller called `name`, or NULL. */
const sim_controller_t *controllers_find(const char *name);

/** The i-th registered controller, or NULL past the end. */
const sim_controller_t *controllers_at(size_t i);

#endif
