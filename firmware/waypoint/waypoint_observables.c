/*
 * waypoint_observables.c - what the route follower shows, for the
 * simulator's telemetry and the e-puck image's alike.  Apart from
 * waypoint_def.c so that an image links these strings only, not the
 * parameters' documentation (avr-gcc keeps a file's string literals in
 * RAM, in one section per file; repatt_observables.c says the same).
 */
#include "waypoint/waypoint.h"

const observable_t waypoint_observables[] = {
    { .name = "state", OBS_FIELD(waypoint_t, state, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "0 wait_route, 1 go, 2 pick, 3 home, 4 done, 5 avoid, 6 avoid_run" },
    { .name = "wp", OBS_FIELD(waypoint_t, index, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "the route's current point: targets 0..n-1, n the drop-off point" },
    { .name = "route_n", OBS_FIELD(waypoint_t, route.n, uint8_t), .scale = 1.0f, .unit = "targets",
      .doc = "targets in the current route (0: none yet)" },
    { .name = "err", OBS_FIELD(waypoint_t, bearing_mrad, int16_t), .scale = 1.0f, .unit = "mrad",
      .doc = "bearing error to the current point at the last fix, CCW positive" },
    { .name = "pose_ok", OBS_FIELD(waypoint_t, has_pose, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 if the last period that needed the tracker's fix had a fresh one" },
    { .name = "routes", OBS_FIELD(waypoint_t, routes, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "messages", .doc = "route messages taken" },
    { .name = "picks", OBS_FIELD(waypoint_t, picks, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "targets", .doc = "pick-up waits completed at targets" },
    { .name = "deliveries", OBS_FIELD(waypoint_t, deliveries, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "routes", .doc = "routes ended at the drop-off point" },
    { .name = "no_pose", OBS_FIELD(waypoint_t, no_pose, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "periods", .doc = "control periods stopped for want of a fresh tracker fix" },
    { .name = "bad_msgs", OBS_FIELD(waypoint_t, bad_msgs, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "messages", .doc = "host messages refused as malformed" },
    { .name = "oae", OBS_FIELD(waypoint_t, oae_count, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "obstacle avoidances" },
    OBS_END
};
