/*
 * random_walk.h - random walk with IR obstacle avoidance.
 *
 * A controller of its own, and the motion of the controllers that embed it
 * when nothing attracts them, with the obstacle avoidance all three seeds
 * share: seed 000's forager searches with it (its attractor selection model,
 * eq 1 with A(t) = 0), with its own speed and a tumble every 20 s instead of
 * this default 5 s.  The walk is a run-and-tumble: drive straight; each
 * step, with probability `turn_chance`, turn in place by an angle drawn
 * uniformly from (-180, 180] degrees.  When a front IR sensor exceeds
 * `avoid_enter` the robot turns in place away from the more excited side
 * until every front sensor is below `avoid_exit`: one obstacle-avoidance
 * event (OAE) is counted per such avoidance.
 *
 * Other controllers embed this one as their "no attractor" behaviour.
 */
#ifndef FW_RANDOM_WALK_H
#define FW_RANDOM_WALK_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/rng.h"

typedef struct random_walk_params {
    int16_t speed_steps_s;       /**< forward wheel speed, steps/s (500 = 64.4 mm/s) */
    int16_t turn_speed_steps_s;  /**< wheel speed when turning in place, steps/s */
    uint16_t turn_chance;        /**< chance of a tumble per step, /65536 */
    uint16_t avoid_enter;        /**< front proximity that starts avoidance, counts */
    uint16_t avoid_exit;         /**< front proximity that ends it, counts */
} random_walk_params_t;

typedef enum random_walk_state {
    RW_FORWARD = 0,   /**< driving straight */
    RW_TUMBLE = 1,    /**< turning in place by a random angle */
    RW_AVOID = 2      /**< turning away from an obstacle */
} random_walk_state_t;

typedef struct random_walk {
    random_walk_params_t params;
    rng_t rng;
    uint32_t seed;
    uint8_t state;            /**< random_walk_state_t */
    int8_t turn_sign;         /**< +1 counter-clockwise, -1 clockwise */
    int32_t turn_steps_left;  /**< wheel steps left in the current tumble */
    uint32_t oae_count;       /**< obstacle-avoidance events so far */
} random_walk_t;

/* The controller contract (controller.h):
 *   default_params  speed 500 steps/s, tumble chance 2 % per step (mean run
 *                   5 s at 10 Hz), turn speed 300 steps/s, avoidance at 300
 *                   counts (~25 mm) until 150;
 *   init            copies params, keeps seed, resets;
 *   reset           driving forward, OAE count 0, the seeded stream anew;
 *   step            reads the IR sensors and sets the wheel speeds;
 *   state_name      "forward", "tumble", "avoid". */
CONTROLLER_API(random_walk);

/** Largest proximity of the four front sensors (IR0, IR1, IR6, IR7). */
uint16_t random_walk_front_proximity(hal_t *hal);

/** Its registered name, and what it shows (random_walk_def.c): the simulator's
 *  telemetry and the robot image's read the same table. */
#define RANDOM_WALK_NAME "random_walk"
extern const observable_t random_walk_observables[];

/** Its description for the simulator (random_walk_def.c). */
extern const controller_def_t random_walk_def;

/** The walk's tuning keys in params struct T, whose members are reached by
 *  prefix P (empty for random_walk_params_t itself, `walk.` for a
 *  controller embedding one as `walk`).  Its speed is listed by each
 *  controller: the forager's comes from its task.  LIVE (param.h): 1 for
 *  random_walk's own keys; 0 where an embedding controller's state holds
 *  the walk's copy apart from its own (its init copies them there). */
#define RANDOM_WALK_TUNING_PARAMS(T, P, LIVE)                                            \
    { .key = "turn_speed_steps_s", .live = LIVE, PARAM_FIELD(T, P turn_speed_steps_s, int16_t),   \
      .min = 1, .max = 1000, .doc = "wheel speed when turning in place, steps/s" }, \
    { .key = "turn_chance", .live = LIVE, PARAM_FIELD(T, P turn_chance, uint16_t), .min = 0,       \
      .max = 65535, .doc = "random walk: chance of a tumble per step, in 1/65536" }, \
    { .key = "avoid_enter", .live = LIVE, PARAM_FIELD(T, P avoid_enter, uint16_t), .min = 0,       \
      .max = 4095, .doc = "front IR proximity that starts an avoidance (an OAE), counts" }, \
    { .key = "avoid_exit", .live = LIVE, PARAM_FIELD(T, P avoid_exit, uint16_t), .min = 0,         \
      .max = 4095, .doc = "front IR proximity below which avoidance ends, counts" }

#endif
