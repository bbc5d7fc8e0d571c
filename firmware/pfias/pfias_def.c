/*
 * pfias_def.c - PFIAS (firmware/pfias/pfias.h) as the simulator runs it:
 * its keys, its policies (a swarm robot, or the fixed nest or food robot
 * that broadcasts its role) and what it shows.
 */
#include "pfias/pfias.h"

static const char *const pfias_roles[] = { "robot", "nest", "food", NULL };

#define PP pfias_params_t
static const param_desc_t pfias_params[] = {
    { .key = "p_join", .live = 1, PARAM_FIELD(PP, p_join, uint16_t), .min = 0, .max = 65535,
      .doc = "P_e->c, explorer to chain member per step at a tail or chainless nest, /65536" },
    { .key = "p_leave", .live = 1, PARAM_FIELD(PP, p_leave, uint16_t), .min = 0, .max = 65535,
      .doc = "P_c->e, tail member to explorer per step, /65536 (reconstruction)" },
    PFIAS_CHAIN_PARAMS(PP),
    { .key = "leave_needs_no_explorer", PARAM_BOOL_FIELD(PP, leave_needs_no_explorer),
      .doc = "true: a tail member leaves only when it perceives no explorer (reconstruction)" },
    RANDOM_WALK_TUNING_PARAMS(PP, walk., 0),
    PARAM_END
};
#undef PP

const observable_t pfias_observables[] = {
    { .name = "colour", OBS_FIELD(pfias_t, colour, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "chain member's colour: 0 blue, 1 green, 2 red (meaningful in state member)" },
    { .name = "tail", OBS_FIELD(pfias_t, tail, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while a chain member perceives no successor" },
    { .name = "prey", OBS_FIELD(pfias_t, prey, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "1 while a chain member perceives (or has perceived) the food" },
    { .name = "joins", OBS_FIELD(pfias_t, joins, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "times the robot became a chain member" },
    { .name = "leaves", OBS_FIELD(pfias_t, leaves, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "events", .doc = "times the robot left a chain" },
    OBS_END
};

static void pfias_set_policy(void *params, uint8_t index)
{
    ((pfias_params_t *)params)->role = index;
}

CONTROLLER_ADAPTERS(pfias)

const controller_def_t pfias_def = {
    .name = PFIAS_NAME,
    .doc = "seed 003 baseline PFIAS (Nouyan, Campo, Dorigo 2008): chains with a 3-colour pattern over the turret",
    CONTROLLER_FUNCS(pfias), CONTROLLER_LIVE_PARAMS(pfias, params),
    .params = pfias_params,
    .policies = pfias_roles,
    .set_policy = pfias_set_policy,
    .observables = pfias_observables,
    .ircom_bits = 16,   /* pfias_msg frames: the range-and-bearing turret */
};
