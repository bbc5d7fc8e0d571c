/*
 * waypoint_def.c - the route follower (issue 16, seed 002's ALNS baseline)
 * as the simulator runs it: the keys a scenario may set and what it shows
 * (waypoint_observables.c).  Its route comes from the scenario's host
 * messages (hal_host_receive), its pose from the tracker (hal_pose).
 */
#include "waypoint/waypoint.h"

#define WP waypoint_params_t
static const param_desc_t waypoint_params[] = {
    { .key = "speed_steps_s", .live = 1, PARAM_FIELD(WP, speed_steps_s, int16_t), .min = 1, .max = 1000,
      .doc = "forward speed, steps/s (776 = 0.10 m/s, RepAtt's)" },
    { .key = "turn_speed_steps_s", .live = 1, PARAM_FIELD(WP, turn_speed_steps_s, int16_t), .min = 1, .max = 1000,
      .doc = "wheel speed when turning in place (toward a waypoint, avoiding), steps/s" },
    { .key = "steer_gain", .live = 1, PARAM_FIELD(WP, steer_gain, int16_t), .min = 0, .max = 10000,
      .doc = "wheel speed difference per rad of bearing error to the waypoint, steps/s" },
    { .key = "turn_in_place_mrad", PARAM_FIELD(WP, turn_in_place_mrad, uint16_t), .min = 0, .max = 3142,
      .doc = "bearing error above which the robot turns in place rather than drives, mrad "
             "(1571 = 90 deg)" },
    { .key = "arrive_mm", PARAM_FIELD(WP, arrive_mm, uint16_t), .min = 1, .max = 30000,
      .doc = "at a target when the tracker puts it this close, mm (the targets task reaches "
             "55 mm between centres by default)" },
    { .key = "reach_mm", PARAM_FIELD(WP, reach_mm, uint16_t), .min = 0, .max = 30000,
      .doc = "at a target this close when an obstacle blocks the way (a target by a wall), mm "
             "(0: never; among clustered targets it picks a neighbour's)" },
    { .key = "home_radius_mm", PARAM_FIELD(WP, home_radius_mm, uint16_t), .min = 1, .max = 30000,
      .doc = "the route is delivered this close to the drop-off point, mm" },
    { .key = "pose_max_age_ms", PARAM_FIELD(WP, pose_max_age_ms, uint16_t), .min = 0, .max = 60000,
      .doc = "a tracker fix older than this counts as none: the robot stops, ms (the HAL gives "
             "none older than 1000)" },
    { .key = "avoid_enter", PARAM_FIELD(WP, avoid_enter, uint16_t), .min = 0, .max = 4095,
      .doc = "IR proximity above which an obstacle is met, counts" },
    { .key = "side_turn_mrad", PARAM_FIELD(WP, side_turn_mrad, uint16_t), .min = 0, .max = 3142,
      .doc = "turn away from an obstacle on a side, mrad (785 = 45 deg)" },
    { .key = "oa_run_max_mm", PARAM_FIELD(WP, oa_run_max_mm, uint16_t), .min = 0, .max = 60000,
      .doc = "longest straight run after an avoidance turn, mm (uniform from 0; 165 = 1 m scaled)" },
    { .key = "pick_time_ms", PARAM_FIELD(WP, pick_time_ms, uint16_t), .min = 0, .max = 60000,
      .doc = "stationary time at each target, wheels (0, 0), ms" },
    PARAM_END
};
#undef WP

CONTROLLER_ADAPTERS(waypoint)

const controller_def_t waypoint_def = {
    .name = WAYPOINT_NAME,
    .doc = "seed 002 ALNS baseline: follows a planned route (host message) with the tracker's pose: "
           "targets in order, a pick-up wait at each, then the drop-off point",
    CONTROLLER_FUNCS(waypoint), CONTROLLER_LIVE_PARAMS(waypoint, params),
    .params = waypoint_params,
    .observables = waypoint_observables,
    .ircom_bits = 0,   /* no IR messages */
};
