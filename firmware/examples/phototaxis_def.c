/* The example controller as the simulator runs it: its keys and what it
 * shows.  The build registers it: tools/make/registry.sh finds its line
 * `const controller_def_t phototaxis_def = {`. */
#include "examples/phototaxis.h"

#define P phototaxis_params_t
static const param_desc_t phototaxis_params[] = {
    { .key = "speed_steps_s", .live = 1, PARAM_FIELD(P, speed_steps_s, int16_t), .min = 0, .max = 1000,
      .doc = "forward wheel speed, steps/s" },
    { .key = "steer_gain", .live = 1, PARAM_FIELD(P, steer_gain, int16_t), .min = 0, .max = 2000,
      .doc = "wheel speed difference per rad of the light's bearing, steps/s" },
    { .key = "arrive_level", .live = 1, PARAM_FIELD(P, arrive_level, uint16_t), .min = 0, .max = 4095,
      .doc = "ambient reading below which the robot has arrived, counts" },
    { .key = "leave_level", .live = 1, PARAM_FIELD(P, leave_level, uint16_t), .min = 0, .max = 4095,
      .doc = "ambient reading above which it seeks again, counts" },
    { .key = "avoid_enter", PARAM_FIELD(P, avoid_enter, uint16_t), .min = 0, .max = 4095,
      .doc = "front IR proximity that starts avoiding, counts" },
    { .key = "avoid_exit", PARAM_FIELD(P, avoid_exit, uint16_t), .min = 0, .max = 4095,
      .doc = "front IR proximity that ends it, counts" },
    PARAM_END
};
#undef P

const observable_t phototaxis_observables[] = {
    { .name = "brightest", OBS_FIELD(phototaxis_t, brightest, uint16_t), .scale = 1.0f,
      .unit = "counts", .doc = "the smallest ambient reading (the most light)" },
    { .name = "light_bearing", OBS_FIELD(phototaxis_t, light_bearing_mrad, int16_t), .scale = 0.001f,
      .unit = "rad", .doc = "bearing of the brightest sensor" },
    { .name = "arrivals", OBS_FIELD(phototaxis_t, arrivals, uint32_t), .kind = OBS_COUNTER,
      .scale = 1.0f, .unit = "events", .doc = "times the robot reached the light" },
    OBS_END
};

CONTROLLER_ADAPTERS(phototaxis)

const controller_def_t phototaxis_def = {
    .name = PHOTOTAXIS_NAME,
    .doc = "example: drive to the brightest light and stop under it (docs: Your first controller)",
    CONTROLLER_FUNCS(phototaxis), CONTROLLER_LIVE_PARAMS(phototaxis, params),
    .params = phototaxis_params,
    .observables = phototaxis_observables,
};
