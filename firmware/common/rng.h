/*
 * rng.h - a small per-robot pseudo-random generator (xorshift32).
 *
 * Each controller owns one in its state; the platform provides the seed
 * (scenario seed and robot id in the simulator).  32-bit arithmetic only,
 * so it is cheap on the 16-bit dsPIC.
 */
#ifndef FW_RNG_H
#define FW_RNG_H

#include <stdint.h>

typedef struct rng {
    uint32_t s;   /**< never 0 */
} rng_t;

/** Seeds the generator; any seed is valid (0 is mapped to a fixed state). */
void rng_seed(rng_t *rng, uint32_t seed);

/** Next 32 uniformly distributed bits. */
uint32_t rng_next(rng_t *rng);

/** Uniform integer in [0, n); returns 0 when n is 0. */
uint32_t rng_below(rng_t *rng, uint32_t n);

/** Uniform integer in [lo, hi] (inclusive); lo <= hi. */
int32_t rng_range(rng_t *rng, int32_t lo, int32_t hi);

/** 1 with probability p / 65536, else 0. */
uint8_t rng_chance(rng_t *rng, uint16_t p_per_65536);

#endif
