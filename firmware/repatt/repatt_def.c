/*
 * repatt_def.c - seed 002's RepAtt as the simulator runs it: the keys a
 * scenario may set, its policies (the same firmware with the paper's best
 * gains, with all gains 1, or with the gains the params give), and what it
 * shows (repatt_observables.c).  The simulator's robots keep queues for y
 * up to REPATT_QUEUE_MAX (repatt_host_t).
 */
#include "repatt/repatt.h"

/* repatt_policy_t's names, in its order; the first is the default. */
static const char *const repatt_policies[] = { "repatt", "random_walk", "custom", NULL };
/* repatt_listening_t's names, in its order. */
static const char *const repatt_listening_modes[] = { "duplex", "slotted", NULL };

#define RP repatt_params_t
static const param_desc_t repatt_params[] = {
    { .key = "p_b", PARAM_FIELD(RP, p_b, float), .min = 0, .max = 1,
      .doc = "P_b, tumble probability per control period (0.0025 per 25 ms step)" },
    { .key = "a_m", PARAM_FIELD(RP, gains.a_m, uint16_t), .min = 1, .max = 1000,
      .doc = "attraction multiplier: G_a when attraction falls (policy custom; repatt sets 4)" },
    { .key = "a_d", PARAM_FIELD(RP, gains.a_d, uint16_t), .min = 1, .max = 1000,
      .doc = "attraction divisor: G_a = 1/a_d when attraction rises (policy custom; repatt sets 100)" },
    { .key = "r_m", PARAM_FIELD(RP, gains.r_m, uint16_t), .min = 1, .max = 1000,
      .doc = "repulsion multiplier: G_r when repulsion rises (policy custom; repatt sets 1)" },
    { .key = "r_d", PARAM_FIELD(RP, gains.r_d, uint16_t), .min = 1, .max = 1000,
      .doc = "repulsion divisor: G_r = 1/r_d when repulsion falls (policy custom; repatt sets 10)" },
    { .key = "queue_size", PARAM_FIELD(RP, queue_size, uint16_t), .min = 1, .max = REPATT_QUEUE_MAX,
      .doc = "y, readings averaged per band (eq 5) and eq 6's lag, in readings" },
    { .key = "listening", PARAM_ENUM_U8_FIELD(RP, listening, repatt_listening_modes),
      .doc = "duplex: emit and listen every period (needs sound.self_masking false); slotted: "
             "emit in a random half of the periods, listen in the silent ones" },
    { .key = "capacity", PARAM_FIELD(RP, capacity, uint8_t), .min = 1, .max = 255,
      .doc = "targets carried before homing" },
    { .key = "speed_steps_s", PARAM_FIELD(RP, speed_steps_s, int16_t), .min = 1, .max = 1000,
      .doc = "forward speed, steps/s (776 = 0.10 m/s)" },
    { .key = "turn_speed_steps_s", PARAM_FIELD(RP, turn_speed_steps_s, int16_t), .min = 1, .max = 1000,
      .doc = "wheel speed when turning in place, steps/s" },
    { .key = "steer_gain", PARAM_FIELD(RP, steer_gain, int16_t), .min = 0, .max = 10000,
      .doc = "wheel speed difference per rad of bearing to a target or home, steps/s" },
    { .key = "tumble_mean_mrad", PARAM_FIELD(RP, tumble_mean_mrad, uint16_t), .min = 0, .max = 6283,
      .doc = "mu of the tumble angle, mrad (3142 = 180 deg)" },
    { .key = "tumble_sd_mrad", PARAM_FIELD(RP, tumble_sd_mrad, uint16_t), .min = 0, .max = 6283,
      .doc = "sigma of the tumble angle, mrad (1571 = 90 deg)" },
    { .key = "avoid_enter", PARAM_FIELD(RP, avoid_enter, uint16_t), .min = 0, .max = 4095,
      .doc = "IR proximity above which an obstacle is met, counts" },
    { .key = "side_turn_mrad", PARAM_FIELD(RP, side_turn_mrad, uint16_t), .min = 0, .max = 3142,
      .doc = "turn away from an obstacle on a side, mrad (785 = 45 deg)" },
    { .key = "oa_run_max_mm", PARAM_FIELD(RP, oa_run_max_mm, uint16_t), .min = 0, .max = 60000,
      .doc = "longest straight run after an avoidance turn, mm (uniform from 0; 165 = 1 m scaled)" },
    { .key = "pick_time_ms", PARAM_FIELD(RP, pick_time_ms, uint16_t), .min = 0, .max = 60000,
      .doc = "stationary time at each target, ms" },
    { .key = "reach_width_mrad", PARAM_FIELD(RP, reach_width_mrad, uint16_t), .min = 1, .max = 6283,
      .doc = "a red blob this wide is near: stop and pick it up (approach_mm 0), or go on "
             "approach_mm first, mrad (330: the e-puck's front camera)" },
    { .key = "approach_mm", PARAM_FIELD(RP, approach_mm, uint16_t), .min = 0, .max = 1000,
      .doc = "after a blob reach_width_mrad wide within 100 mrad of ahead, straight on this far "
             "(step counters) before stopping, mm (46: the front camera; 0: stop at once)" },
    { .key = "give_up_ms", PARAM_FIELD(RP, give_up_ms, uint16_t), .min = 0, .max = 60000,
      .doc = "after a pick-up that failed (the target stayed), targets are ignored this long, ms" },
    { .key = "home_radius_mm", PARAM_FIELD(RP, home_radius_mm, uint16_t), .min = 1, .max = 30000,
      .doc = "unload when odometry puts the start point this close, mm" },
    PARAM_END
};
#undef RP

void repatt_set_policy(void *params, uint8_t index)
{
    repatt_apply_policy((repatt_params_t *)params, index);
}

/* The simulator's robots: a repatt_host_t each, its queues attached. */
static void repatt_def_default_params(void *params) { repatt_default_params((repatt_params_t *)params); }
static void repatt_def_init(void *self, const void *params, uint32_t seed)
{
    repatt_host_t *h = (repatt_host_t *)self;
    repatt_attach_queue(&h->ctrl, h->queue, (uint16_t)REPATT_QUEUE_MAX);
    repatt_init(&h->ctrl, (const repatt_params_t *)params, seed);
}
static void repatt_def_reset(void *self) { repatt_reset(&((repatt_host_t *)self)->ctrl); }
static void repatt_def_step(void *self, hal_t *hal) { repatt_step(&((repatt_host_t *)self)->ctrl, hal); }
static const char *repatt_def_state_name(const void *self)
{
    return repatt_state_name(&((const repatt_host_t *)self)->ctrl);
}

const controller_def_t repatt_def = {
    .name = REPATT_NAME,
    .doc = "seed 002 RepAtt: search/acquire/home/avoid with sound repulsion and attraction "
           "(policy random_walk: all gains 1)",
    .state_size = sizeof(repatt_host_t), .params_size = sizeof(repatt_params_t),
    .default_params = repatt_def_default_params, .init = repatt_def_init,
    .reset = repatt_def_reset, .step = repatt_def_step, .state_name = repatt_def_state_name,
    .params = repatt_params,
    .policies = repatt_policies,
    .set_policy = repatt_set_policy,
    .observables = repatt_observables,
    .ircom_bits = 0,   /* no IR messages: sound only */
};
