/* The calibration image as the simulator runs it: its keys and what it
 * shows (calib.h).  Its commands come from the host link (hal_host_receive). */
#include "calib/calib.h"

#define P calib_params_t
static const param_desc_t calib_params[] = {
    { .key = "window_steps", PARAM_FIELD(P, window_steps, uint8_t), .min = 1, .max = 100,
      .doc = "control periods per window of readings (one window per telemetry message by default)" },
    { .key = "settle_windows", PARAM_FIELD(P, settle_windows, uint8_t), .min = 0, .max = 100,
      .doc = "windows dropped after a command while the robot settles" },
    PARAM_END
};
#undef P

const observable_t calib_observables[] = {
    { .name = "mean0", OBS_FIELD(calib_t, mean[0], float), .scale = 1.0f, .unit = "",
      .doc = "channel 0's mean over the last window (calib.h: per state)" },
    { .name = "mean1", OBS_FIELD(calib_t, mean[1], float), .scale = 1.0f, .unit = "",
      .doc = "channel 1's mean over the last window (calib.h: per state)" },
    { .name = "mean2", OBS_FIELD(calib_t, mean[2], float), .scale = 1.0f, .unit = "",
      .doc = "channel 2's mean over the last window (calib.h: per state)" },
    { .name = "mean3", OBS_FIELD(calib_t, mean[3], float), .scale = 1.0f, .unit = "",
      .doc = "channel 3's mean over the last window (calib.h: per state)" },
    { .name = "mean4", OBS_FIELD(calib_t, mean[4], float), .scale = 1.0f, .unit = "",
      .doc = "channel 4's mean over the last window (calib.h: per state)" },
    { .name = "mean5", OBS_FIELD(calib_t, mean[5], float), .scale = 1.0f, .unit = "",
      .doc = "channel 5's mean over the last window (calib.h: per state)" },
    { .name = "mean6", OBS_FIELD(calib_t, mean[6], float), .scale = 1.0f, .unit = "",
      .doc = "channel 6's mean over the last window (calib.h: per state)" },
    { .name = "mean7", OBS_FIELD(calib_t, mean[7], float), .scale = 1.0f, .unit = "",
      .doc = "channel 7's mean over the last window (calib.h: per state)" },
    { .name = "var0", OBS_FIELD(calib_t, var[0], float), .scale = 1.0f, .unit = "",
      .doc = "channel 0's variance within the last window" },
    { .name = "var1", OBS_FIELD(calib_t, var[1], float), .scale = 1.0f, .unit = "",
      .doc = "channel 1's variance within the last window" },
    { .name = "var2", OBS_FIELD(calib_t, var[2], float), .scale = 1.0f, .unit = "",
      .doc = "channel 2's variance within the last window" },
    { .name = "var3", OBS_FIELD(calib_t, var[3], float), .scale = 1.0f, .unit = "",
      .doc = "channel 3's variance within the last window" },
    { .name = "var4", OBS_FIELD(calib_t, var[4], float), .scale = 1.0f, .unit = "",
      .doc = "channel 4's variance within the last window" },
    { .name = "var5", OBS_FIELD(calib_t, var[5], float), .scale = 1.0f, .unit = "",
      .doc = "channel 5's variance within the last window" },
    { .name = "var6", OBS_FIELD(calib_t, var[6], float), .scale = 1.0f, .unit = "",
      .doc = "channel 6's variance within the last window" },
    { .name = "var7", OBS_FIELD(calib_t, var[7], float), .scale = 1.0f, .unit = "",
      .doc = "channel 7's variance within the last window" },
    OBS_END
};

CONTROLLER_ADAPTERS(calib)

const controller_def_t calib_def = {
    .name = CALIB_NAME,
    .doc = "calibration image: streams raw readings as the host asks (docs: Calibrate the models)",
    CONTROLLER_FUNCS(calib), CONTROLLER_LIVE_PARAMS(calib, params),
    .params = calib_params,
    .observables = calib_observables,
};
