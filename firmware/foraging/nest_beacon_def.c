/*
 * nest_beacon_def.c - seed 000's nest beacon as the simulator runs it.  Its
 * constants (N_r, F(0), the ledger's costs, T2) come from the foraging
 * task's section, as a real beacon is built with them; its one key is how
 * long a robot's report keeps it counted as waiting.
 */
#include "foraging/nest_beacon.h"

#define BP nest_beacon_params_t
static const param_desc_t nest_beacon_params[] = {
    { .key = "wait_timeout_steps", PARAM_FIELD(BP, wait_timeout_steps, uint8_t), .min = 1, .max = 254,
      .doc = "a robot counts as waiting this many steps after its last deposit report" },
    PARAM_END
};
#undef BP

const observable_t nest_beacon_observables[] = {
    { .name = "nest_food", OBS_FIELD(nest_beacon_t, food_q4, int32_t), .scale = 1.0f / (float)NL_FOOD_PER_TOKEN,
      .unit = "tokens", .doc = "F(t) by the beacon's ledger (what it broadcasts)" },
    { .name = "waiting", OBS_FIELD(nest_beacon_t, n_waiting, uint16_t), .scale = 1.0f,
      .unit = "robots", .doc = "N_W, robots heard waiting in the nest" },
    { .name = "oae_window", OBS_FIELD(nest_beacon_t, m_t2, uint32_t), .scale = 1.0f,
      .unit = "events", .doc = "M_T2, OAEs reported over the last T2" },
    { .name = "deposits_reported", OBS_FIELD(nest_beacon_t, deposits_total, uint32_t),
      .scale = 1.0f, .unit = "tokens", .doc = "deposits the foragers reported" },
    { .name = "oaes_reported", OBS_FIELD(nest_beacon_t, oae_total, uint32_t), .scale = 1.0f,
      .unit = "events", .doc = "OAEs the foragers reported" },
    OBS_END
};

CONTROLLER_ADAPTERS(nest_beacon)

const controller_def_t nest_beacon_def = {
    .name = NEST_BEACON_NAME,
    .doc = "seed 000 nest beacon: keeps the nest ledger, broadcasts F(t), N_W, M_A",
    CONTROLLER_FUNCS(nest_beacon), CONTROLLER_LIVE_PARAMS(nest_beacon, params),
    .params = nest_beacon_params,
    .observables = nest_beacon_observables,
    .ircom_bits = 16,
};
