#include "rng.h"

void rng_seed(rng_t *rng, uint32_t seed)
{
    /* Scramble so that neighbouring seeds (robot ids) give unrelated
     * streams: one round of a 32-bit integer hash (lowbias32). */
    uint32_t x = seed;
    x ^= x >> 16;
    x *= UINT32_C(0x7feb352d);
    x ^= x >> 15;
    x *= UINT32_C(0x846ca68b);
    x ^= x >> 16;
    rng->s = (x != 0u) ? x : UINT32_C(0x9e3779b9);
}

uint32_t rng_next(rng_t *rng)
{
    uint32_t x = rng->s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    rng->s = x;
    return x;
}

uint32_t rng_below(rng_t *rng, uint32_t n)
{
    /* Multiply-shift: the bias is below n / 2^32, negligible here. */
    return (uint32_t)(((uint64_t)rng_next(rng) * n) >> 32);
}

int32_t rng_range(rng_t *rng, int32_t lo, int32_t hi)
{
    uint32_t span = (uint32_t)(hi - lo) + 1u;
    if (span == 0u) { /* the full 32-bit range */
        return (int32_t)rng_next(rng);
    }
    return lo + (int32_t)rng_below(rng, span);
}

uint8_t rng_chance(rng_t *rng, uint16_t p_per_65536)
{
    return (uint8_t)((rng_next(rng) >> 16) < (uint32_t)p_per_65536);
}
