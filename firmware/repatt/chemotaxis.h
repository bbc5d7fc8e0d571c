/*
 * chemotaxis.h - seed 002's signal filter and tumble-probability gains
 * (RepAtt, Obute et al. 2020): the averaging queue of eq 5, the change of
 * eq 6 and lines 8-21 of Algorithm 1, in integers.
 *
 * The filter of one band keeps the last 2y readings (level counts of
 * hal_mic_level) in a ring the caller provides, and two running sums:
 *   sum_new = the latest y readings        (y I(t),   eq 5)
 *   sum_old = the y readings before them   (y I(t-y))
 * so that the sign of eq 6's I(t) - I(t-y) is the sign of
 * sum_new - sum_old: exact, with no division and no rounding.  The sums
 * are 64-bit: 120 readings of up to 2^32 - 1 counts each cannot overflow
 * them, so any reading a platform returns is taken as it is.  Until 2y
 * readings have been taken the change is 0 (no gradient yet: gains 1).
 * The queue counts readings, not control periods: a robot that listens
 * only in silent periods (slotted listening) fills it more slowly.
 *
 * The ring is the caller's because its size is the image's choice: the
 * simulator's robots keep 2 x 120 readings per band (the paper's largest
 * queue, Q120), the e-puck image 2 x 40 (Q40) so that its RAM stays within
 * the 2 KB gate.  No static storage.
 *
 * Probabilities are Q32: p * 2^32 in a uint32_t (UINT32_MAX stands for 1).
 * P_b = 0.0025 is 10,737,418; the smallest P_t of the paper's gain grid,
 * 0.0025 / (1000 x 1000), is 10.7 (about 5 % resolution there).
 */
#ifndef FW_CHEMOTAXIS_H
#define FW_CHEMOTAXIS_H

#include <stdint.h>

/** Largest gain (a_m, a_d, r_m, r_d): the paper's grid goes to 1000.
 *  Larger values are taken as this, 0 as 1. */
#define CHEMO_GAIN_MAX 1000u

/** Largest queue size y the filter takes (larger is taken as this): 2y
 *  must fit a 16-bit int.  The ring the caller gives bounds y further. */
#define CHEMO_Y_MAX 16000u

/** The averaging queue of one band. */
typedef struct chemo_filter {
    uint64_t sum_new;   /**< sum of the latest y readings, counts */
    uint64_t sum_old;   /**< sum of the y readings before those, counts */
    uint16_t y;         /**< queue size y, readings (>= 1) */
    uint16_t count;     /**< readings held, 0..2y */
    uint16_t head;      /**< ring index the next reading goes to */
} chemo_filter_t;

/** Empties the filter and sets its queue size y (0 is taken as 1, above
 *  CHEMO_Y_MAX as CHEMO_Y_MAX). */
void chemo_filter_init(chemo_filter_t *f, uint16_t y);

/** Adds one reading.  `ring` holds 2y readings (this band's own), or is
 *  NULL: then nothing is stored and the change stays 0. */
void chemo_filter_push(chemo_filter_t *f, uint32_t *ring, uint32_t reading);

/** Eq 6's sign: +1 if I(t) > I(t-y), -1 if less, 0 if equal or if fewer
 *  than 2y readings have been taken. */
int8_t chemo_filter_sign(const chemo_filter_t *f);

/** Eq 5's I(t), counts: the mean of the latest y readings (of those held
 *  while fewer than y); 0 when empty. */
uint32_t chemo_filter_level(const chemo_filter_t *f);

/** The gains of Algorithm 1 (all >= 1; the random walk: all 1). */
typedef struct chemo_gains {
    uint16_t a_m;   /**< attraction multiplier: G_a when attraction falls */
    uint16_t a_d;   /**< attraction divisor: G_a = 1 / a_d when it rises */
    uint16_t r_m;   /**< repulsion multiplier: G_r when repulsion rises */
    uint16_t r_d;   /**< repulsion divisor: G_r = 1 / r_d when it falls */
} chemo_gains_t;

/** Lines 8-21: G_r = G_a = 1; dI_r > 0: G_r = r_m, < 0: 1 / r_d;
 *  dI_a > 0: G_a = 1 / a_d, < 0: a_m; P_t = P_b x G_r x G_a, Q32,
 *  rounded down, at most UINT32_MAX (probability 1). */
uint32_t chemo_tumble_q32(uint32_t p_b_q32, const chemo_gains_t *g, int8_t d_repulsion, int8_t d_attraction);

/** A probability in [0, 1] as Q32 (1 and above: UINT32_MAX; NaN and
 *  below 0: 0).  Float: for parameters, once at start-up. */
uint32_t chemo_probability_q32(float p);

#endif
