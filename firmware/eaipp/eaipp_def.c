/*
 * eaipp_def.c - EAIPP as the simulator runs it: its keys and what it shows.
 * Registration: one controller `eaipp`; the nest and food robots are
 * groups of it with `role: nest` / `role: food`.
 */
#include "eaipp/eaipp.h"

#define EP eaipp_params_t

static const char *const eaipp_roles[] = { "robot", "nest", "food", 0 };
static const char *const eaipp_a_distances[] = { "inverse", "linear", 0 };

static const param_desc_t eaipp_param_descs[] = {
    { .key = "role", PARAM_ENUM_U8_FIELD(EP, role, eaipp_roles),
      .doc = "robot (Lost/Explorer/Node), nest or food (fixed gradient sources)" },
    { .key = "speed", PARAM_FIELD(EP, speed_steps_s, uint16_t), .min = 0, .max = 1000,
      .doc = "wheel speed of Algorithm 3, steps/s (388 = 5 cm/s)" },
    { .key = "b_ul", PARAM_FIELD(EP, b_ul_mm, uint16_t), .min = 0, .max = 5000,
      .doc = "B_UL of Algorithm 4: an explorer becomes a node when its one node is farther, mm (0.75 R)" },
    { .key = "b_ul_max", PARAM_FIELD(EP, b_ul_max_mm, uint16_t), .min = 0, .max = 5000,
      .doc = "0: no upper bound (as printed); else the one node must also be no farther, mm" },
    { .key = "period_time_1", PARAM_FIELD(EP, period1_steps, uint16_t), .min = 1, .max = 60000,
      .doc = "PERIOD_TIME_1: a branch end with no explorer near leaves, steps (reconstructed)" },
    { .key = "period_time_2", PARAM_FIELD(EP, period2_steps, uint16_t), .min = 1, .max = 60000,
      .doc = "PERIOD_TIME_2: explorers near an end but no child: contract, steps (reconstructed)" },
    { .key = "timeout", PARAM_FIELD(EP, timeout_steps, uint8_t), .min = 1, .max = 255,
      .doc = "a neighbour not heard for this long is forgotten, steps" },
    { .key = "w_nodes", PARAM_FIELD(EP, w_nodes, float), .min = 0, .max = 100,
      .doc = "eq 1 weight of the gradient term" },
    { .key = "w_obstacles", PARAM_FIELD(EP, w_obstacles, float), .min = 0, .max = 100,
      .doc = "eq 1 weight of the obstacle term" },
    { .key = "prox_full", PARAM_FIELD(EP, prox_full, uint16_t), .min = 1, .max = 4095,
      .doc = "proximity counts read as eq 1's 1" },
    { .key = "lost_turn_prox", PARAM_FIELD(EP, lost_turn_prox, uint16_t), .min = 0, .max = 4095,
      .doc = "Robot_Lost turns away above this proximity, counts" },
    { .key = "a_distance", PARAM_ENUM_U8_FIELD(EP, a_distance, eaipp_a_distances),
      .doc = "eq 1's node term weighs neighbour i by 1/D_i (inverse) or D_i (linear: the vector to it)" },
    { .key = "ext_strict", PARAM_BOOL_FIELD(EP, ext_strict),
      .doc = "Algorithm 4 waits for every neighbour's STATE and takes only this period's range (off)" },
    { .key = "turn_hold", PARAM_FIELD(EP, turn_hold_mrad, uint16_t), .min = 0, .max = 3141,
      .doc = "Algorithm 3: a direction within this of straight behind keeps the last turn's side, mrad (0: off)" },
    { .key = "lj_exit", PARAM_BOOL_FIELD(EP, lj_exit),
      .doc = "section 5.1: leave the waiting area in the exiting state (Lennard-Jones) before searching" },
    { .key = "lj_sigma", PARAM_FIELD(EP, lj_sigma_mm, uint16_t), .min = 10, .max = 2000,
      .doc = "LJ sigma between exiting robots, mm (they settle 2^(1/6) sigma apart)" },
    { .key = "lj_weight", PARAM_FIELD(EP, lj_weight, float), .min = 0, .max = 100,
      .doc = "weight of the LJ term against the pull to the nest" },
    { .key = "exit_near", PARAM_FIELD(EP, exit_near_mm, uint16_t), .min = 0, .max = 5000,
      .doc = "an exiting robot this near the nest has left the waiting area: explorer, mm" },
    { .key = "food_source", PARAM_BOOL_FIELD(EP, food_source),
      .doc = "the food is a second gradient source and root (default false: the printed Algorithm 4"
             " and eq 1, the food is the target only, as in the maze rule)" },
    { .key = "same_source", PARAM_BOOL_FIELD(EP, same_source),
      .doc = "with food_source: an explorer counts only holders of its own Source_Type (the nest's if"
             " heard) in Algorithm 4 and eq 1, so two networks can merge (a reading; default false)" },
    PARAM_END
};

const observable_t eaipp_observables[] = {
    { .name = "gradient", OBS_FIELD(eaipp_t, gradient, uint8_t), .scale = 1.0f, .unit = "hops",
      .doc = "own gradient value (63: none)" },
    { .name = "source", OBS_FIELD(eaipp_t, source, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "Source_Type: 0 nest, 1 food" },
    { .name = "root", OBS_FIELD(eaipp_t, root, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "Root_ID" },
    { .name = "contraction", OBS_FIELD(eaipp_t, contraction, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "Flag_Contraction" },
    { .name = "neighbours", OBS_FIELD(eaipp_t, nb.count, uint8_t), .scale = 1.0f, .unit = "robots",
      .doc = "robots in the neighbour table" },
    { .name = "joins", .kind = OBS_COUNTER, OBS_FIELD(eaipp_t, joins, uint32_t), .scale = 1.0f,
      .unit = "events", .doc = "explorer -> node" },
    { .name = "leaves", .kind = OBS_COUNTER, OBS_FIELD(eaipp_t, leaves, uint32_t), .scale = 1.0f,
      .unit = "events", .doc = "node -> lost or explorer" },
    OBS_END
};

CONTROLLER_ADAPTERS(eaipp)

const controller_def_t eaipp_def = {
    .name = EAIPP_NAME,
    .doc = "seed 003 EAIPP path formation (role: robot, nest or food)",
    CONTROLLER_FUNCS(eaipp), CONTROLLER_LIVE_PARAMS(eaipp, p),
    .params = eaipp_param_descs,
    .observables = eaipp_observables,
    .ircom_bits = 16,
};
