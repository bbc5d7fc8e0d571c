/*
 * forager_def.c - seed 000's forager as the simulator runs it: the keys a
 * scenario may set, its policies, and what it shows.  What the robot is told
 * about its task (F_d, N_r, L, the nest radius, its speed) is not a key: the
 * foraging task sets it from its own section (sim_host/tasks/foraging/),
 * as a real robot is built with it.
 */
#include "foraging/forager.h"
#include "foraging/nest_link.h"

/* ta_theta_mode_t's names, in its order. */
static const char *const drtm_theta_modes[] = { "offset", "clip", "raw", NULL };

#define FP forager_params_t
static const param_desc_t forager_params[] = {
    { .key = "alpha", .live = 1, PARAM_FIELD(FP, alpha, float), .min = 0, .max = 1000,
      .doc = "DRTM eq 6 weight of k, per robot/m^2" },
    { .key = "beta", .live = 1, PARAM_FIELD(FP, beta, float), .min = 0, .max = 1000,
      .doc = "DRTM eq 6 weight of M_A, per OAE" },
    { .key = "T1", PARAM_FIELD(FP, t1_steps, uint16_t), .min = 1, .max = 60000,
      .doc = "T1, steps between decisions in the nest" },
    { .key = "n_min", PARAM_FIELD(FP, n_min, uint8_t), .min = 1, .max = 20,
      .doc = "eq 7 exponent n: per robot, uniform in [n_min, n_max]" },
    { .key = "n_max", PARAM_FIELD(FP, n_max, uint8_t), .min = 1, .max = 20, .doc = "largest n" },
    { .key = "theta0", PARAM_FIELD(FP, theta0, float), .min = 0, .max = 1000,
      .doc = "ARTM start and FRTM fixed threshold, tokens" },
    { .key = "theta_min", PARAM_FIELD(FP, theta_min, float), .min = 0, .max = 1000,
      .doc = "ARTM lower bound of theta, tokens" },
    { .key = "theta_max", PARAM_FIELD(FP, theta_max, float), .min = 0, .max = 1000,
      .doc = "ARTM upper bound of theta, tokens" },
    { .key = "artm_delta", .live = 1, PARAM_FIELD(FP, artm_delta, float), .min = 0, .max = 1000,
      .doc = "ARTM step of theta per decision, tokens (our reconstruction)" },
    { .key = "steer_gain", .live = 1, PARAM_FIELD(FP, steer_gain, int16_t), .min = 0, .max = 10000,
      .doc = "wheel speed difference per rad of bearing, steps/s" },
    { .key = "grasp_width_mrad", PARAM_FIELD(FP, grasp_width_mrad, uint16_t), .min = 1, .max = 3142,
      .doc = "a red blob this wide means a token is held, mrad" },
    { .key = "near_width_mrad", PARAM_FIELD(FP, near_width_mrad, uint16_t), .min = 1, .max = 3142,
      .doc = "a centred red blob this wide is about to be grasped, mrad" },
    { .key = "lost_steps", PARAM_FIELD(FP, lost_steps, uint8_t), .min = 1, .max = 255,
      .doc = "steps without the token before searching again" },
    { .key = "nest_margin_mm", PARAM_FIELD(FP, nest_margin_mm, uint16_t), .min = 0, .max = 10000,
      .doc = "beacon range must be this far inside the nest radius, mm" },
    { .key = "nest_confirm", PARAM_FIELD(FP, nest_confirm, uint8_t), .min = 1, .max = 255,
      .doc = "beacon frames in a row inside the nest that mean arrival" },
    { .key = "light_detect", PARAM_FIELD(FP, light_detect, uint16_t), .min = 0, .max = 4095,
      .doc = "ambient below this means the nest light is seen, counts" },
    { .key = "deposit_steps", PARAM_FIELD(FP, deposit_steps, uint8_t), .min = 1, .max = 255,
      .doc = "steps of backing out of a deposited token" },
    { .key = "drtm_theta", PARAM_ENUM_U8_FIELD(FP, drtm_theta, drtm_theta_modes),
      .doc = "DRTM threshold: offset = theta0 + eq 6 in [theta_min, theta_max]; clip = eq 6 in the "
             "bounds; raw = eq 6 (docs: studies, DRTM)" },
    { .key = "decide_each_step", PARAM_BOOL_FIELD(FP, decide_each_step),
      .doc = "true: once T1 has passed, draw every step (T1 a minimum wait); false: every T1" },
    { .key = "leave_nest", PARAM_BOOL_FIELD(FP, leave_nest),
      .doc = "true: leaving the nest, turn away from the lamp until out of the nest" },
    { .key = "leave_max_steps", PARAM_FIELD(FP, leave_max_steps, uint16_t), .min = 1, .max = 60000,
      .doc = "stop turning away from the lamp after this many steps" },
    { .key = "grasp_confirm", PARAM_FIELD(FP, grasp_confirm, uint8_t), .min = 1, .max = 255,
      .doc = "steps a wide red blob must stay centred after an approach to count as grasped" },
    { .key = "park_steps", PARAM_FIELD(FP, park_steps, uint16_t), .min = 0, .max = 60000,
      .doc = "after arriving in the nest, steps of driving on toward the lamp before depositing "
             "and resting (ARGoS's foraging example: 50)" },
    { .key = "report_steps", PARAM_FIELD(FP, report_steps, uint8_t), .min = 1, .max = 50,
      .doc = "in the nest, a report to the beacon every this many steps, staggered by id" },
    RANDOM_WALK_TUNING_PARAMS(FP, walk., 0),
    PARAM_END
};
#undef FP

const observable_t forager_observables[] = {
    { .name = "oae", OBS_FIELD(forager_t, walk.oae_count, uint32_t), .kind = OBS_COUNTER,
      .scale = 1.0f, .unit = "events", .doc = "obstacle-avoidance events counted by the robot" },
    { .name = "deposits", OBS_FIELD(forager_t, deposits, uint32_t), .kind = OBS_COUNTER,
      .scale = 1.0f, .unit = "tokens", .doc = "tokens the robot believes it deposited" },
    { .name = "threshold", OBS_FIELD(forager_t, theta, float), .scale = 1.0f, .unit = "tokens",
      .doc = "theta of the last decision (eq 6; ARTM, FRTM: their own)" },
    { .name = "probability", OBS_FIELD(forager_t, P_s, float), .scale = 1.0f, .unit = "",
      .doc = "P_s, probability of leaving the nest at the last decision (eq 7)" },
    { .name = "stimulus", OBS_FIELD(forager_t, S, float), .scale = 1.0f, .unit = "tokens",
      .doc = "S = F_d - F at the last decision (eq 2)" },
    { .name = "density", OBS_FIELD(forager_t, k, float), .scale = 1.0f, .unit = "robots/m^2",
      .doc = "traffic flow density k at the last decision (eq 4)" },
    { .name = "mean_oae", OBS_FIELD(forager_t, M_A, float), .scale = 1.0f, .unit = "events/robot",
      .doc = "M_A, mean OAEs per robot over T2 at the last decision (eq 5)" },
    { .name = "n", OBS_FIELD(forager_t, n, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "eq 7 exponent drawn by this robot" },
    { .name = "nest_food", OBS_FIELD(forager_t, beacon_food_q4, int16_t), .scale = 1.0f / (float)NL_FOOD_PER_TOKEN,
      .unit = "tokens", .doc = "F(t) as last heard from the nest beacon" },
    { .name = "carrying", OBS_FIELD(forager_t, carrying, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while the robot sees a token in its gripper" },
    OBS_END
};

void forager_set_policy(void *params, uint8_t index)
{
    ((forager_params_t *)params)->policy = (ta_policy_t)index;
}

CONTROLLER_ADAPTERS(forager)

const controller_def_t forager_def = {
    .name = FORAGER_NAME,
    .doc = "seed 000 forager: S_W/S_S/S_R with DRTM, ARTM or FRTM task allocation",
    CONTROLLER_FUNCS(forager), CONTROLLER_LIVE_PARAMS(forager, params),
    .params = forager_params,
    .policies = ta_policy_names,
    .set_policy = forager_set_policy,
    .observables = forager_observables,
    .ircom_bits = 16,   /* nest_link frames: the range-and-bearing turret */
};
