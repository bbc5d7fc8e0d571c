/*
 * waypoint.h - a robot that follows a planned route (issue 16: seed 002's
 * ALNS baseline, Obute et al. 2020 section III.C: "Robots used the
 * optimized ALNS routes as waypoints when foraging").
 *
 * A planner on a PC gives each robot its route as a host message
 * (route_msg.h): up to 6 targets to pick up, in order, then the drop-off
 * point (the nest centre).  The robot knows where it is from an overhead
 * tracker (hal_pose, arena frame, heading CCW from +x).
 *
 *   WAIT_ROUTE  still, until a route message comes.
 *   GO          to the current target: a turn in place while the bearing
 *               error is above turn_in_place_mrad, else forward at
 *               speed_steps_s with a wheel difference of steer_gain per
 *               rad of error.  Within arrive_mm of it: PICK; also,
 *               when reach_mm is not 0, within reach_mm when an obstacle
 *               blocks the way (a target by a wall): it is picked up from
 *               there rather than turned away from.
 *   PICK        wheels (0, 0) for exactly pick_time_ms (rounded up to
 *               whole periods): the pick-up rule of seed 002's targets
 *               (the simulator's targets task takes a target in reach of a
 *               robot that stands still that long); then the next target,
 *               or HOME after the last.
 *   HOME        to the drop-off point as GO; within home_radius_mm: DONE.
 *   DONE        still, the route delivered.
 *   AVOID       an obstacle met in GO, HOME or AVOID_RUN (IR proximity
 *               above avoid_enter): RepAtt's turn away from it (repatt/avoid.h);
 *   AVOID_RUN   then its straight run; then GO or HOME again, whichever
 *               the route is at.  A robot that stands still (WAIT_ROUTE,
 *               PICK, DONE) does not avoid, as RepAtt's PICK.
 *
 * Messages: every period the robot takes one host message.  A route
 * message starts its route from the first target, in any state: a new
 * route replaces the current one at once (a pick in progress is
 * abandoned; an avoidance in progress is finished first, the obstacle
 * being still there).  A route equal to the current one is a resend and
 * changes nothing (a host resends routes: a frame longer than the e-puck's
 * UART ring can be lost, docs/host_link.md).  A malformed message (route_msg_decode refuses it)
 * is counted and ignored: the route goes on.
 *
 * Pose: GO and HOME need a fix; without one (HAL_ERR_UNAVAILABLE, or a fix
 * older than pose_max_age_ms) the robot stops where it is and waits,
 * counting the periods.  Avoidance needs none (it counts wheel steps).
 *
 * Everything is in the HAL's units (mm, mrad, ms, steps); times become
 * periods of hal_control_period_ms.  Defaults: RepAtt's (repatt.h: seed
 * 002 at the e-puck scale of the plan) where RepAtt has the parameter;
 * waypoint.c says where the others come from.
 */
#ifndef FW_WAYPOINT_H
#define FW_WAYPOINT_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/rng.h"
#include "repatt/avoid.h"
#include "route_msg.h"

typedef struct waypoint_params {
    int16_t speed_steps_s;        /**< forward speed, steps/s (776 = 0.10 m/s) */
    int16_t turn_speed_steps_s;   /**< wheel speed turning in place, steps/s (776) */
    int16_t steer_gain;           /**< wheel speed difference per rad of bearing error, steps/s (1000) */
    uint16_t turn_in_place_mrad;  /**< bearing error above which it turns in place, mrad (1571 = 90 deg) */
    uint16_t arrive_mm;           /**< at a target this close to it, mm (30) */
    uint16_t reach_mm;            /**< at a target this close to it when blocked, mm (0: never) */
    uint16_t home_radius_mm;      /**< delivered this close to the drop-off point, mm (100) */
    uint16_t pose_max_age_ms;     /**< an older fix is no fix, ms (300) */
    uint16_t avoid_enter;         /**< IR proximity that means an obstacle, counts (300) */
    uint16_t side_turn_mrad;      /**< turn away from a side obstacle, mrad (785 = 45 deg) */
    uint16_t oa_run_max_mm;       /**< longest straight run after a turn, mm (165) */
    uint16_t pick_time_ms;        /**< stationary time per target, ms (5000) */
} waypoint_params_t;

typedef enum waypoint_state {
    WAYPOINT_WAIT_ROUTE = 0,   /**< still, no route yet */
    WAYPOINT_GO = 1,           /**< to the current target */
    WAYPOINT_PICK = 2,         /**< still at a target */
    WAYPOINT_HOME = 3,         /**< to the drop-off point */
    WAYPOINT_DONE = 4,         /**< still, the route delivered */
    WAYPOINT_AVOID = 5,        /**< obstacle: turning away */
    WAYPOINT_AVOID_RUN = 6     /**< obstacle: the straight run after the turn */
} waypoint_state_t;

typedef struct waypoint {
    waypoint_params_t params;
    rng_t rng;
    uint32_t seed;
    route_t route;
    avoid_t avoid;
    int16_t last_left;      /**< wheel counters at the last step */
    int16_t last_right;
    uint8_t primed;         /**< the counters have been read once */
    uint8_t state;          /**< waypoint_state_t */
    uint8_t index;          /**< the route's current point: targets 0..n-1, n the drop-off */
    uint16_t timer;         /**< PICK: periods stood still so far */
    int16_t bearing_mrad;   /**< bearing error to the current point at the last fix, mrad */
    uint8_t has_pose;       /**< 1 if this period's navigation had a fix */

    /* Counts since reset. */
    uint32_t routes;        /**< route messages taken */
    uint32_t picks;         /**< pick-up waits completed */
    uint32_t deliveries;    /**< routes ended at the drop-off point */
    uint32_t no_pose;       /**< periods GO or HOME stood for want of a fix */
    uint32_t bad_msgs;      /**< host messages refused (malformed) */
    uint32_t oae_count;     /**< obstacle avoidances */
} waypoint_t;

/* The controller contract (controller.h):
 *   default_params  waypoint_params_t's comments;
 *   init            copies params, keeps seed, resets;
 *   reset           WAIT_ROUTE without a route, counts 0, the seeded
 *                   stream anew;
 *   step            one control period (above);
 *   state_name      "wait_route", "go", "pick", "home", "done", "avoid",
 *                   "avoid_run". */
CONTROLLER_API(waypoint);

#define WAYPOINT_NAME "waypoint"
extern const observable_t waypoint_observables[];   /* waypoint_observables.c */
extern const controller_def_t waypoint_def;

#endif
