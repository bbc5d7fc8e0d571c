#include "rand.h"

#include <math.h>

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

void sim_rand_seed(sim_rand_t *r, uint64_t seed, uint64_t index, uint64_t purpose)
{
    uint64_t x = seed ^ (index * UINT64_C(0xd1342543de82ef95)) ^ (purpose << 56);
    r->s[0] = splitmix64(&x);
    r->s[1] = splitmix64(&x);
    if (r->s[0] == 0 && r->s[1] == 0) {
        r->s[0] = 1;
    }
    r->has_spare = 0;
    r->spare = 0.0;
}

uint32_t sim_rand_seed32(uint64_t seed, uint64_t index, uint64_t purpose)
{
    sim_rand_t r;
    sim_rand_seed(&r, seed, index, purpose);
    return (uint32_t)(sim_rand_u64(&r) >> 32);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t sim_rand_u64(sim_rand_t *r)
{
    /* xoroshiro128+ */
    uint64_t s0 = r->s[0], s1 = r->s[1];
    uint64_t result = s0 + s1;
    s1 ^= s0;
    r->s[0] = rotl(s0, 24) ^ s1 ^ (s1 << 16);
    r->s[1] = rotl(s1, 37);
    return result;
}

double sim_rand_uniform(sim_rand_t *r)
{
    return (double)(sim_rand_u64(r) >> 11) * 0x1.0p-53;
}

double sim_rand_normal(sim_rand_t *r)
{
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    double u, v, s;
    do {
        u = 2.0 * sim_rand_uniform(r) - 1.0;
        v = 2.0 * sim_rand_uniform(r) - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    double m = sqrt(-2.0 * log(s) / s);
    r->spare = v * m;
    r->has_spare = 1;
    return u * m;
}
