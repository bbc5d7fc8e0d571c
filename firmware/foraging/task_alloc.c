#include "task_alloc.h"

float ta_stimulus(float F_d_tokens, float F_tokens)
{
    return F_d_tokens - F_tokens;
}

float ta_traffic_density(uint16_t N_r, uint16_t N_W, float L_m)
{
    /* More robots reported waiting than exist (a stale or foreign report)
     * means none is foraging, not a negative density. */
    if (N_W >= N_r || !(L_m > 0.0f)) {
        return 0.0f;
    }
    return (float)(uint16_t)(N_r - N_W) / (L_m * L_m);
}

float ta_mean_oae(uint32_t M_T2, uint16_t N_r)
{
    if (N_r == 0u) {
        return 0.0f;
    }
    return (float)M_T2 / (float)N_r;
}

float ta_drtm_threshold(float alpha, float beta, float k, float M_A)
{
    return alpha * k + beta * M_A;
}

float ta_drtm_theta(uint8_t mode, float alpha, float beta, float k, float M_A, float theta0, float theta_min,
                    float theta_max)
{
    float theta = ta_drtm_threshold(alpha, beta, k, M_A);
    if (mode == TA_THETA_RAW) {
        return theta;
    }
    if (mode == TA_THETA_OFFSET) {
        theta += theta0;
    }
    if (theta < theta_min) {
        theta = theta_min;
    }
    if (theta > theta_max) {
        theta = theta_max;
    }
    return theta;
}

/* r^n by repeated multiplication (n is small: 2..9 in seed 000). */
static float power(float r, uint8_t n)
{
    float x = 1.0f;
    uint8_t i;
    for (i = 0; i < n; i++) {
        x *= r;
    }
    return x;
}

float ta_probability(float S, float theta, uint8_t n)
{
    float r;
    float rn;
    if (!(S > 0.0f)) {
        return 0.0f;
    }
    if (!(theta > 0.0f)) {
        return 1.0f;
    }
    /* Divide through by the larger of S^n and theta^n so the power is of a
     * ratio <= 1: S^n / (S^n + theta^n) overflows a float for S ~ 1e5, n 9. */
    if (theta <= S) {
        r = theta / S;
        return 1.0f / (1.0f + power(r, n));
    }
    r = S / theta;
    rn = power(r, n);
    return rn / (1.0f + rn);
}

uint8_t ta_roulette(rng_t *rng, float p)
{
    uint32_t limit;
    if (!(p > 0.0f)) {
        return 0u;
    }
    if (p >= 1.0f) {
        return 1u;
    }
    /* p * 2^24 < 2^24 is exact in a float's 24-bit mantissa. */
    limit = (uint32_t)(p * 16777216.0f);
    return (uint8_t)((rng_next(rng) >> 8) < limit);
}

float ta_artm_update(float theta, float S, float S_prev, float delta,
                     float theta_min, float theta_max)
{
    /* A rising stimulus (the nest is emptying) lowers the threshold so that
     * more robots go foraging; a falling one raises it. */
    if (S > S_prev) {
        theta -= delta;
    } else if (S < S_prev) {
        theta += delta;
    }
    if (theta < theta_min) {
        theta = theta_min;
    }
    if (theta > theta_max) {
        theta = theta_max;
    }
    return theta;
}

const char *const ta_policy_names[TA_POLICY_COUNT + 1] = { TA_POLICY_NAMES, 0 };
