/*
 * avoid.h - seed 002's obstacle avoidance (Obute et al. 2020, Algorithm 1
 * lines 3-4) for the waypoint controller: RepAtt's rule, re-implemented.
 *
 * RepAtt (firmware/repatt/repatt.c) keeps this rule in static functions of
 * its own file, and its behaviour is pinned by golden hashes; sharing the
 * code would mean changing repatt.c, so the rule is written out again here
 * with the same parameter names, defaults and random draws:
 *   - an obstacle is an IR proximity above avoid_enter: in front (IR0,
 *     IR7), else on the right (IR1, IR2) or the left (IR5, IR6), the side
 *     with the larger reading (the right on a tie);
 *   - in front: a turn in place by an angle uniform in (90, 180] deg, its
 *     direction drawn at random; on a side: a turn of side_turn_mrad away
 *     from it;
 *   - then a straight run of a length uniform in [0, oa_run_max_mm].
 * Turns and runs are measured on the wheel step counters (no pose needed),
 * and the last period's speed is cut so as not to overshoot them.
 */
#ifndef FW_WAYPOINT_AVOID_H
#define FW_WAYPOINT_AVOID_H

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

typedef struct avoid {
    int32_t target2;        /**< turn or run length x 2, wheel steps */
    int32_t done2;          /**< progress x 2, wheel steps */
    int16_t last_left;      /**< counters at the last avoid_track */
    int16_t last_right;
    int8_t turn_sign;       /**< +1 CCW, -1 CW */
    uint8_t primed;         /**< the counters have been read once */
} avoid_t;

/** Nothing measured; the next avoid_track only reads the counters. */
void avoid_reset(avoid_t *a);

/** Reads the wheel counters (every period, so that a manoeuvre starts from
 *  the right count) and adds their change to a turn or a run in progress. */
void avoid_track(avoid_t *a, hal_t *hal, uint8_t phase);

/** Where an obstacle is this period (avoid_where_t). */
uint8_t avoid_obstacle(hal_t *hal, uint16_t avoid_enter);

/** Starts the turn away from an obstacle at `where` (not AVOID_NONE). */
void avoid_start_turn(avoid_t *a, rng_t *rng, uint8_t where, uint16_t side_turn_mrad);

/** Starts the straight run after a turn: uniform in [0, oa_run_max_mm]. */
void avoid_start_run(avoid_t *a, rng_t *rng, uint16_t oa_run_max_mm);

/** Turning: sets the wheels and returns 1 while some of the turn is left;
 *  0 when it is done (wheels untouched). */
uint8_t avoid_turn_step(avoid_t *a, hal_t *hal, int16_t turn_speed_steps_s);

/** Running: as avoid_turn_step, straight ahead. */
uint8_t avoid_run_step(avoid_t *a, hal_t *hal, int16_t speed_steps_s);

#endif
