/*
 * tsasr_def.c - TSASR (firmware/tsasr/tsasr.h, a reconstruction) as the
 * simulator runs it: its keys, its policies (a swarm robot, or the fixed
 * nest or food robot that broadcasts its role) and what it shows.
 */
#include "tsasr/tsasr.h"

static const char *const tsasr_roles[] = { "robot", "nest", "food", NULL };

#define TP tsasr_params_t
static const param_desc_t tsasr_params[] = {
    { .key = "p_join", .live = 1, PARAM_FIELD(TP, p_join, uint16_t), .min = 0, .max = 65535,
      .doc = "explorer to chain member per step at a tail or chainless nest, /65536 (PFIAS's P_e->c)" },
    { .key = "p_leave", .live = 1, PARAM_FIELD(TP, p_leave, uint16_t), .min = 0, .max = 65535,
      .doc = "PFIAS's P_c->e: a tail member leaves at random per step, /65536 (reconstruction)" },
    { .key = "elim_steps", PARAM_FIELD(TP, elim_steps, uint16_t), .min = 1, .max = 65535,
      .doc = "elimination: steps a tail may go without the target before it retreats (reconstruction)" },
    { .key = "retreat_steps", PARAM_FIELD(TP, retreat_steps, uint16_t), .min = 1, .max = 65535,
      .doc = "elimination: steps a retreating member shows the flag before it leaves (reconstruction)" },
    { .key = "elim_cascade", PARAM_BOOL_FIELD(TP, elim_cascade),
      .doc = "true: a member whose successor left in retreat retreats too (the failed chain goes as a whole)" },
    { .key = "elim_explorer_resets", PARAM_BOOL_FIELD(TP, elim_explorer_resets),
      .doc = "true: a tail's elimination timer restarts while it perceives an explorer (reconstruction)" },
    PFIAS_CHAIN_PARAMS(TP),   /* PFIAS's perception and motion keys */
    { .key = "leave_needs_no_explorer", PARAM_BOOL_FIELD(TP, leave_needs_no_explorer),
      .doc = "true: p_leave applies only when the tail perceives no explorer (as PFIAS)" },
    RANDOM_WALK_TUNING_PARAMS(TP, walk., 0),
    PARAM_END
};
#undef TP

const observable_t tsasr_observables[] = {
    { .name = "colour", OBS_FIELD(tsasr_t, colour, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "chain member's colour: 0 blue, 1 green, 2 red (meaningful in state member)" },
    { .name = "tail", OBS_FIELD(tsasr_t, tail, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while a chain member perceives no successor" },
    { .name = "prey", OBS_FIELD(tsasr_t, prey, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while a chain member perceives (or has perceived) the target" },
    { .name = "retreat", OBS_FIELD(tsasr_t, retreat, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while a chain member is being eliminated" },
    { .name = "joins", OBS_FIELD(tsasr_t, joins, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "times the robot became a chain member" },
    { .name = "leaves", OBS_FIELD(tsasr_t, leaves, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "times the robot left a chain (any reason)" },
    { .name = "eliminations", OBS_FIELD(tsasr_t, eliminations, uint32_t), .kind = OBS_COUNTER,
      .scale = 1.0f, .unit = "events", .doc = "times the robot left a chain by elimination" },
    OBS_END
};

static void tsasr_set_policy(void *params, uint8_t index)
{
    ((tsasr_params_t *)params)->role = index;
}

CONTROLLER_ADAPTERS(tsasr)

const controller_def_t tsasr_def = {
    .name = TSASR_NAME,
    .doc = "seed 003 baseline TSASR (Luo et al. 2020), reconstructed: PFIAS chains plus timed elimination of chains that found nothing",
    CONTROLLER_FUNCS(tsasr), CONTROLLER_LIVE_PARAMS(tsasr, params),
    .params = tsasr_params,
    .policies = tsasr_roles,
    .set_policy = tsasr_set_policy,
    .observables = tsasr_observables,
    .ircom_bits = 16,   /* tsasr_msg frames: the range-and-bearing turret */
};
