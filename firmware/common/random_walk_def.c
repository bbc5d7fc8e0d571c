/* random_walk as the simulator runs it: its keys and what it shows. */
#include "common/random_walk.h"

static const param_desc_t random_walk_params[] = {
    { .key = "speed_steps_s", .live = 1, PARAM_FIELD(random_walk_params_t, speed_steps_s, int16_t),
      .min = 0, .max = 1000, .doc = "forward wheel speed, steps/s (500 = 64.4 mm/s)" },
    RANDOM_WALK_TUNING_PARAMS(random_walk_params_t, , 1),
    PARAM_END
};

const observable_t random_walk_observables[] = {
    { .name = "oae", OBS_FIELD(random_walk_t, oae_count, uint32_t), .kind = OBS_COUNTER,
      .scale = 1.0f, .unit = "events", .doc = "obstacle-avoidance events so far" },
    OBS_END
};

CONTROLLER_ADAPTERS(random_walk)

const controller_def_t random_walk_def = {
    .name = RANDOM_WALK_NAME,
    .doc = "run-and-tumble random walk with IR obstacle avoidance (a tumble every 5 s by default; "
           "seed 000's forager searches with it every 20 s)",
    CONTROLLER_FUNCS(random_walk), CONTROLLER_LIVE_PARAMS(random_walk, params),
    .params = random_walk_params,
    .observables = random_walk_observables,
};
