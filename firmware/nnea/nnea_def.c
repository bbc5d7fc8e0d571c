/*
 * nnea_def.c - NNEA (firmware/nnea/nnea.h) as the simulator runs it: its
 * keys (the genome's six arrays, then the sensing constants), its policies
 * (a swarm robot, or the fixed nest or food) and what it shows.
 */
#include "nnea/nnea.h"

static const char *const nnea_roles[] = { "robot", "nest", "food", NULL };

#define NP nnea_params_t
static const param_desc_t nnea_params[] = {
    { .key = "w_in", PARAM_ARRAY_FIELD(NP, w_in, int16_t), .min = -NNEA_WEIGHT_MAX, .max = NNEA_WEIGHT_MAX,
      .doc = "input j to hidden i at [i*14+j], Q8 (1/256): the genome" },
    { .key = "w_rec", PARAM_ARRAY_FIELD(NP, w_rec, int16_t), .min = -NNEA_WEIGHT_MAX, .max = NNEA_WEIGHT_MAX,
      .doc = "hidden j to hidden i at [i*4+j], Q8: the genome" },
    { .key = "b_hidden", PARAM_ARRAY_FIELD(NP, b_hidden, int16_t), .min = -NNEA_WEIGHT_MAX,
      .max = NNEA_WEIGHT_MAX, .doc = "hidden biases, Q8: the genome" },
    { .key = "tau", PARAM_ARRAY_FIELD(NP, tau, uint8_t), .min = 0, .max = 255,
      .doc = "hidden time constants, 1/256 (0: no memory): the genome" },
    { .key = "w_out", PARAM_ARRAY_FIELD(NP, w_out, int16_t), .min = -NNEA_WEIGHT_MAX, .max = NNEA_WEIGHT_MAX,
      .doc = "hidden i to output k at [k*4+i] (left, right, colour), Q8: the genome" },
    { .key = "b_out", PARAM_ARRAY_FIELD(NP, b_out, int16_t), .min = -NNEA_WEIGHT_MAX, .max = NNEA_WEIGHT_MAX,
      .doc = "output biases, Q8: the genome" },
    { .key = "speed_steps_s", PARAM_FIELD(NP, speed_steps_s, uint16_t), .min = 0, .max = 1000,
      .doc = "steps/s: a wheel at output 1 (388: 5 cm/s, seed 003)" },
    { .key = "stop_band", PARAM_FIELD(NP, stop_band, int16_t), .min = 0, .max = 2048,
      .doc = "Q12: a wheel output this close to 1/2 stops the wheel" },
    { .key = "sense_range_mm", PARAM_FIELD(NP, sense_range_mm, uint16_t), .min = 1, .max = 10000,
      .doc = "mm: a neighbour's input falls to 0 at this range (R)" },
    { .key = "ir_full", PARAM_FIELD(NP, ir_full, uint16_t), .min = 1, .max = 4095,
      .doc = "proximity counts that read as input 1" },
    { .key = "ground_dark_max", PARAM_FIELD(NP, ground_dark_max, uint16_t), .min = 0, .max = 4095,
      .doc = "ground counts below this: on the nest's black disc" },
    { .key = "ground_grey_max", PARAM_FIELD(NP, ground_grey_max, uint16_t), .min = 0, .max = 4095,
      .doc = "ground counts below this, not dark: on the food's grey disc" },
    PARAM_END
};
#undef NP

const observable_t nnea_observables[] = {
    { .name = "colour", OBS_FIELD(nnea_t, colour, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "the colour the robot shows (output 2 > 1/2)" },
    { .name = "area", OBS_FIELD(nnea_t, area, uint8_t), .scale = 1.0f, .unit = "",
      .doc = "floor under the robot: 0 bare, 1 nest, 2 food" },
    { .name = "h0", OBS_FIELD(nnea_t, hidden[0], int16_t), .scale = 1.0f / NNEA_ONE, .unit = "",
      .doc = "hidden neuron 0's activation" },
    { .name = "h1", OBS_FIELD(nnea_t, hidden[1], int16_t), .scale = 1.0f / NNEA_ONE, .unit = "",
      .doc = "hidden neuron 1's activation" },
    { .name = "h2", OBS_FIELD(nnea_t, hidden[2], int16_t), .scale = 1.0f / NNEA_ONE, .unit = "",
      .doc = "hidden neuron 2's activation" },
    { .name = "h3", OBS_FIELD(nnea_t, hidden[3], int16_t), .scale = 1.0f / NNEA_ONE, .unit = "",
      .doc = "hidden neuron 3's activation" },
    { .name = "floor_trips", OBS_FIELD(nnea_t, trips, uint32_t), .kind = OBS_COUNTER, .scale = 1.0f,
      .unit = "trips", .doc = "arrivals, by its own ground sensor, in the area other than the last visited" },
    OBS_END
};

static void nnea_set_policy(void *params, uint8_t index)
{
    ((nnea_params_t *)params)->role = index;
}

CONTROLLER_ADAPTERS(nnea)

const controller_def_t nnea_def = {
    .name = NNEA_NAME,
    .doc = "seed 003 baseline NNEA (Sperati, Trianni, Nolfi 2011): an evolved CTRNN, fixed point",
    CONTROLLER_FUNCS(nnea), CONTROLLER_LIVE_PARAMS(nnea, params),
    .params = nnea_params,
    .policies = nnea_roles,
    .set_policy = nnea_set_policy,
    .observables = nnea_observables,
    .ircom_bits = 8,   /* one tag byte: the colour bit */
};
