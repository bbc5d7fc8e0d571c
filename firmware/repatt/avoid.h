/*
 * avoid.h - seed 002's obstacle avoidance (Obute et al. 2020, Algorithm 1
 * lines 3-4) and the counted turns and runs it is made of, shared by RepAtt
 * (firmware/repatt/repatt.c, whose tumbles are such turns too) and the ALNS
 * route follower (firmware/waypoint/):
 *   - an obstacle is an IR proximity above avoid_enter: in front (IR0,
 *     IR7), else on the right (IR1, IR2) or the left (IR5, IR6), the side
 *     with the larger reading (the right on a tie);
 *   - in front: a turn in place by an angle uniform in (90, 180] deg, its
 *     direction drawn at random; on a side: a turn of side_turn_mrad away
 *     from it;
 *   - then a straight run of a length uniform in [0, oa_run_max_mm].
 * Turns and runs are measured on the wheel step counters (no pose needed):
 * the caller gives each period's counter changes (avoid_count), and the
 * last period's speed is cut so as not to overshoot.
 */
#ifndef FW_REPATT_AVOID_H
#define FW_REPATT_AVOID_H

#include <stdint.h>

#include "hal.h"
#include "common/rng.h"

/** Where an obstacle is (avoid_obstacle). */
typedef enum avoid_where {
    AVOID_NONE = 0,
    AVOID_FRONT = 1,
    AVOID_RIGHT = 2,
    AVOID_LEFT = 3
} avoid_where_t;

/** What the wheel counters are measuring. */
typedef enum avoid_phase {
    AVOID_IDLE = 0,
    AVOID_TURNING = 1,
    AVOID_RUNNING = 2
} avoid_phase_t;

/** A turn in place or a straight run, counted on the wheel steps. */
typedef struct avoid {
    int32_t target2;        /**< turn or run length x 2, wheel steps */
    int32_t done2;          /**< progress x 2, wheel steps */
    int8_t turn_sign;       /**< +1 CCW, -1 CW */
} avoid_t;

/** Nothing to measure. */
void avoid_reset(avoid_t *a);

/** Adds one period's counter changes (steps, odo_counter_delta's) to the
 *  turn (AVOID_TURNING) or run (AVOID_RUNNING) in progress. */
void avoid_count(avoid_t *a, uint8_t phase, int32_t d_left, int32_t d_right);

/** Where an obstacle is this period (avoid_where_t). */
uint8_t avoid_obstacle(hal_t *hal, uint16_t avoid_enter);

/** Starts a turn in place by `mrad` (CCW positive, wrapped). */
void avoid_turn_by(avoid_t *a, int32_t mrad);

/** Starts the turn away from an obstacle at `where` (not AVOID_NONE). */
void avoid_start_turn(avoid_t *a, rng_t *rng, uint8_t where, uint16_t side_turn_mrad);

/** Starts the straight run after a turn: uniform in [0, oa_run_max_mm]. */
void avoid_start_run(avoid_t *a, rng_t *rng, uint16_t oa_run_max_mm);

/** Starts a straight run of `mm` (>= 0). */
void avoid_start_run_mm(avoid_t *a, int32_t mm);

/** Turning: sets the wheels and returns 1 while some of the turn is left;
 *  0 when it is done (wheels untouched). */
uint8_t avoid_turn_step(avoid_t *a, hal_t *hal, int16_t turn_speed_steps_s);

/** Running: as avoid_turn_step, straight ahead. */
uint8_t avoid_run_step(avoid_t *a, hal_t *hal, int16_t speed_steps_s);

#endif
