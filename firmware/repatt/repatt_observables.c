/*
 * repatt_observables.c - what RepAtt shows, for the simulator's telemetry
 * and the e-puck image's alike.  Apart from repatt_def.c so that an image
 * links these strings only, not the parameters' documentation: avr-gcc
 * keeps a file's string literals in RAM, in one section per file.
 */
#include "repatt/repatt.h"

#define Q32_SCALE 2.3283064e-10f   /* 2^-32 */
const observable_t repatt_observables[] = {
    { .name = "state", OBS_FIELD(repatt_t, state, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "0 search, 1 tumble, 2 acquire, 3 pick, 4 home, 5 avoid, 6 avoid_run" },
    { .name = "found", OBS_FIELD(repatt_t, found, uint8_t), .scale = 1.0f, .unit = "targets",
      .doc = "red blobs (targets) in view" },
    { .name = "cap", OBS_FIELD(repatt_t, cap, uint8_t), .scale = 1.0f, .unit = "targets",
      .doc = "targets the robot can still take (Algorithm 1's cap)" },
    { .name = "i_r", OBS_FIELD(repatt_t, level_r, uint32_t), .scale = 1.0f, .unit = "counts",
      .doc = "I_r, mean repulsion level over the queue (eq 5; simulator: 1000 counts = 1 unit)" },
    { .name = "i_a", OBS_FIELD(repatt_t, level_a, uint32_t), .scale = 1.0f, .unit = "counts",
      .doc = "I_a, mean attraction level over the queue (eq 5)" },
    { .name = "d_r", OBS_FIELD(repatt_t, d_r, int8_t), .scale = 1.0f, .unit = "",
      .doc = "sign of dI_r (eq 6): -1, 0, +1" },
    { .name = "d_a", OBS_FIELD(repatt_t, d_a, int8_t), .scale = 1.0f, .unit = "",
      .doc = "sign of dI_a (eq 6): -1, 0, +1" },
    { .name = "p_t", OBS_FIELD(repatt_t, p_t_q32, uint32_t), .scale = Q32_SCALE, .unit = "",
      .doc = "P_t, tumble probability per period (lines 8-21)" },
    { .name = "band", OBS_FIELD(repatt_t, band, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "band broadcast: 0 none, 1 repulsion, 2 attraction" },
    { .name = "odo_x", OBS_FIELD(repatt_t, odo.x_um, int32_t), .scale = 0.001f, .unit = "mm",
      .doc = "odometry: ahead of the start point along the start heading" },
    { .name = "odo_y", OBS_FIELD(repatt_t, odo.y_um, int32_t), .scale = 0.001f, .unit = "mm",
      .doc = "odometry: left of the start point" },
    { .name = "oae", OBS_FIELD(repatt_t, oae_count, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "obstacle avoidances" },
    { .name = "pickups", OBS_FIELD(repatt_t, pickups, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "targets", .doc = "targets the robot counted as carried" },
    { .name = "unloads", OBS_FIELD(repatt_t, unloads, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "trips", .doc = "loads taken home" },
    { .name = "readings", OBS_FIELD(repatt_t, readings, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "readings", .doc = "sound readings taken (periods heard)" },
    OBS_END
};
