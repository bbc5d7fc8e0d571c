/*
 * noise_draws.h - how a model draws the Gaussian noise of a reading that
 * is a sum of independently noisy terms (`noise_draws`, a key of the IR
 * and sound sections).
 *
 * per_term (the default) draws one normal for every term, as the models'
 * equations write the noise: seed 002's eq 4 per pair of robots, the IR
 * sensors' relative and additive parts apart.  summed draws one normal
 * for the whole sum, scaled by the square root of the sum of the terms'
 * variances: a sum of independent Gaussians is the Gaussian of that
 * variance, so every reading has the same distribution, and readings of
 * different robots, sensors and bands stay independent as before; only the
 * values drawn differ (another sample of the same run).  It is for speed
 * (docs/development/benchmarks.md): the full-sensing benchmark's sound
 * field draws three normals per listener instead of three per neighbour.
 * It moves every result of a run that sets it, so no shipped scenario does.
 */
#ifndef SIM_MODELS_NOISE_DRAWS_H
#define SIM_MODELS_NOISE_DRAWS_H

/** `noise_draws`: one draw per noisy term, or one per sum of them. */
typedef enum noise_draws {
    NOISE_DRAWS_PER_TERM = 0,   /**< as the equations write it (the default) */
    NOISE_DRAWS_SUMMED = 1      /**< one draw of the sum's sd: the same distribution */
} noise_draws_t;

/* noise_draws_t's names, in its order (PARAM_ENUM_FIELD). */
static const char *const noise_draws_names[] = { "per_term", "summed", NULL };

#endif
