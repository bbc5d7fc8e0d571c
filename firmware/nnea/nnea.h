/*
 * nnea.h - seed 003's baseline NNEA: Sperati, Trianni and Nolfi's evolved
 * path formation (Swarm Intelligence 5, 2011).  Every robot runs the same
 * small continuous-time recurrent network whose weights, biases and time
 * constants are evolved (tools/swarmtools/evolve, studies/nnea_evolve.yaml);
 * the robots have no explicit rules: the behaviour is the genome.
 *
 * The network (docs/studies/nnea.md says what is the paper's and what is
 * reconstructed):
 *
 *   14 inputs   4 obstacle sectors (IR proximity: front, right, back, left),
 *               2 floor areas (ground sensor: on the nest's black disc, on
 *               the food's grey one), 8 neighbour sectors (front-left,
 *               back-left, back-right, front-right, each for the two colours
 *               a neighbour can show: its signal output as a 1-bit IR
 *               message, the paper's blue/red LEDs; strength 1 - range/R)
 *    4 hidden   leaky integrators, fully recurrent:
 *               h_i <- tau_i h_i + (1 - tau_i) sigma(b_i + sum_j w_in[i,j] x_j
 *                                               + sum_j w_rec[i,j] h_j)
 *    3 outputs  sigma(b_k + sum_i w_out h_i): the left and right wheels
 *               ((2 o - 1) of the top speed) and the colour shown (o > 1/2)
 *
 * Fixed point (the e-puck1's dsPIC has no FPU): activations and inputs in
 * Q12 (1/4096 steps, 0..4096), weights and biases int16 Q8 (1/256, within
 * +-8), time constants uint8 in 1/256 (0..255/256); sums in int32 (at most
 * 18 x 2048 x 4096 < 2^28).  The logistic is a 65-point table over [-8, 8]
 * interpolated linearly: off by at most 3e-4 (about one Q12 step), far
 * below the sensors' noise.  Q8 weights resolve 0.004, finer than the GA's
 * 8-bit genes over the same range (0.06).
 */
#ifndef FW_NNEA_H
#define FW_NNEA_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"

#define NNEA_INPUTS 14u
#define NNEA_HIDDEN 4u
#define NNEA_OUTPUTS 3u
/** Genes: every weight, bias and time constant. */
#define NNEA_GENES (NNEA_INPUTS * NNEA_HIDDEN + NNEA_HIDDEN * NNEA_HIDDEN + NNEA_HIDDEN + \
                    NNEA_HIDDEN + NNEA_HIDDEN * NNEA_OUTPUTS + NNEA_OUTPUTS)
/** One in Q12 (activations, inputs). */
#define NNEA_ONE 4096
/** Weights' and biases' bound, Q8: +-8.0. */
#define NNEA_WEIGHT_MAX 2047

/** A robot of the swarm, or the fixed nest or food (still, silent, LEDs on). */
typedef enum nnea_role { NNEA_ROLE_ROBOT = 0, NNEA_ROLE_NEST = 1, NNEA_ROLE_FOOD = 2 } nnea_role_t;

/** The 1-bit message a robot sends every period: NNEA_MSG_TAG | colour. */
#define NNEA_MSG_TAG 0xA4u
#define NNEA_MSG_MASK 0xFEu

typedef struct nnea_params {
    int16_t w_in[NNEA_HIDDEN * NNEA_INPUTS];    /**< input j to hidden i at [i * INPUTS + j], Q8 */
    int16_t w_rec[NNEA_HIDDEN * NNEA_HIDDEN];   /**< hidden j to hidden i at [i * HIDDEN + j], Q8 */
    int16_t b_hidden[NNEA_HIDDEN];              /**< hidden biases, Q8 */
    uint8_t tau[NNEA_HIDDEN];                   /**< hidden time constants, 1/256 */
    int16_t w_out[NNEA_OUTPUTS * NNEA_HIDDEN];  /**< hidden i to output k at [k * HIDDEN + i], Q8 */
    int16_t b_out[NNEA_OUTPUTS];                /**< output biases, Q8 */
    uint16_t speed_steps_s;   /**< top wheel speed, steps/s (388: 5 cm/s) */
    int16_t stop_band;        /**< a wheel output within this of 1/2 stops the wheel, Q12 */
    uint16_t sense_range_mm;  /**< neighbour strength reaches 0 here, mm */
    uint16_t ir_full;         /**< proximity counts that read as 1 */
    uint16_t ground_dark_max; /**< ground counts below this: the nest's black disc */
    uint16_t ground_grey_max; /**< below this (and not dark): the food's grey disc */
    uint8_t role;             /**< nnea_role_t */
} nnea_params_t;

typedef enum nnea_state { NNEA_RUN = 0, NNEA_SOURCE = 1 } nnea_state_t;

typedef struct nnea {
    nnea_params_t params;
    uint32_t seed;
    uint8_t state;                     /**< nnea_state_t */
    uint8_t colour;                    /**< the colour shown (output 2 > 1/2) */
    uint8_t area;                      /**< 0 none, 1 nest, 2 food (this step's floor) */
    uint8_t last_area;                 /**< the last area visited (1 nest, 2 food, 0 none yet) */
    int16_t input[NNEA_INPUTS];        /**< the last step's, Q12 */
    int16_t hidden[NNEA_HIDDEN];       /**< Q12 */
    int16_t output[NNEA_OUTPUTS];      /**< Q12 */
    uint32_t trips;                    /**< nest to food or food to nest, on the robot's own floor reading */
} nnea_t;

/* The controller contract (controller.h); state names "run", "source". */
CONTROLLER_API(nnea);

/** sigma(x) for x in Q12, in Q12 (the table; exported for its test). */
int16_t nnea_sigmoid(int32_t x_q12);

#define NNEA_NAME "nnea"
extern const observable_t nnea_observables[];
extern const controller_def_t nnea_def;

#endif
