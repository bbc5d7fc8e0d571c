/*
 * random_walk.h - random walk with IR obstacle avoidance.
 *
 * The searching motion of seed 000's attractor selection model (eq 1 with
 * A(t) = 0: the noise term drives the robot) and the obstacle avoidance all
 * three seeds share.  The walk is a run-and-tumble: drive straight; each
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
#include "rng.h"

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

/** speed 500 steps/s, tumble chance 2 % per step (mean run 5 s at 10 Hz),
 *  turn speed 300 steps/s, avoidance at 300 counts (~25 mm) until 150. */
void random_walk_default_params(random_walk_params_t *params);

/** Copies `params`, keeps `seed`, and resets. */
void random_walk_init(random_walk_t *self, const random_walk_params_t *params, uint32_t seed);

/** Back to driving forward with the OAE count at 0 and the seeded stream. */
void random_walk_reset(random_walk_t *self);

/** One control step: reads the IR sensors and sets the wheel speeds. */
void random_walk_step(random_walk_t *self, hal_t *hal);

/** Largest proximity of the four front sensors (IR0, IR1, IR6, IR7). */
uint16_t random_walk_front_proximity(hal_t *hal);

/** Name of a random_walk_state_t. */
const char *random_walk_state_name(uint8_t state);

#endif
