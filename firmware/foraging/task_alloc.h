/*
 * task_alloc.h - response-threshold task allocation as pure functions.
 *
 * The equations of seed 000 (Pang et al. 2023, "Dynamic Response Threshold
 * Model ...", Appl. Sci. 13:9107), numbered as there, and the two models it
 * is compared with.  No HAL: a forager calls these when its waiting timer
 * expires (t1 >= T1) and draws the leave decision with `ta_roulette`.
 *
 *   eq 2  S(t)  = F_d - F(t)                      stimulus, tokens
 *   eq 4  k     = (N_r - N_W) / (L * L)           traffic flow density, robots/m^2
 *   eq 5  M_A   = M_T2 / N_r                      mean OAEs per robot over T2
 *   eq 6  theta = alpha * k + beta * M_A          DRTM threshold
 *   eq 7  P_s   = S^n / (S^n + theta^n) if S > 0, else 0
 *
 * Policies (the threshold fed to eq 7):
 *   - DRTM (seed 000): eq 6, raw.  It is NOT clipped: with every robot in
 *     the nest and no OAE yet, theta = 0 and P_s = 1 for any S > 0.
 *   - ARTM (Castello et al., seed refs [17, 27, 28]): an adaptive theta that
 *     falls when the stimulus rises and rises when it falls.  The published
 *     update rule could not be found (papers paywalled); `ta_artm_update` is
 *     OUR RECONSTRUCTION, a discretised attractor selection between
 *     theta_min and theta_max (docs/studies/drtm.md, the ARTM policy):
 *         theta <- clip(theta - delta * sign(S - S_prev), theta_min, theta_max)
 *     applied at each of the robot's decisions, S_prev being the stimulus at
 *     its previous decision.
 *   - FRTM (Bonabeau et al., seed refs [22, 23]): a fixed theta = theta0 in
 *     eq 7, i.e. ARTM with delta = 0.
 *
 * Floats are 32-bit (software float on the dsPIC); eq 7's integer power is a
 * loop, so no math library is needed.
 */
#ifndef FW_TASK_ALLOC_H
#define FW_TASK_ALLOC_H

#include <stdint.h>

#include "common/rng.h"

/** Which threshold a forager uses in eq 7. */
typedef enum { TA_DRTM = 0, TA_ARTM = 1, TA_FRTM = 2, TA_POLICY_COUNT = 3 } ta_policy_t;

/** The policies' names, in ta_policy_t order: the one list (the forager's
 *  `policy:` values in a scenario, its telemetry, `make firmware
 *  FORAGER_POLICY=`, which reads this line). */
#define TA_POLICY_NAMES "drtm", "artm", "frtm"

/** TA_POLICY_NAMES and a NULL. */
extern const char *const ta_policy_names[TA_POLICY_COUNT + 1];

/** Eq 2: stimulus S = F_d - F, in tokens (positive: the nest lacks food). */
float ta_stimulus(float F_d_tokens, float F_tokens);

/** Eq 4: traffic flow density k = (N_r - N_W) / (L * L), robots per m^2,
 *  for a square arena of side `L_m` metres.  0 when N_W >= N_r or L <= 0. */
float ta_traffic_density(uint16_t N_r, uint16_t N_W, float L_m);

/** Eq 5: mean obstacle-avoidance events per robot M_A = M_T2 / N_r, where
 *  M_T2 is the swarm's OAE count over the last T2.  0 when N_r is 0. */
float ta_mean_oae(uint32_t M_T2, uint16_t N_r);

/** Eq 6: DRTM threshold theta = alpha * k + beta * M_A (not clipped). */
float ta_drtm_threshold(float alpha, float beta, float k, float M_A);

/** How theta0 and the bounds [theta_min, theta_max] enter DRTM's eq 6; seed
 *  000 gives eq 6 alone and, "following the ARTM", theta_t0 = 3.3 with
 *  1 <= theta <= 10, and says theta "is 3.3" at the start and "becomes
 *  larger" as robots forage, while eq 6 is 0 there (k = M_A = 0). */
typedef enum {
    TA_THETA_OFFSET = 0,   /**< theta0 + eq 6, clipped to the bounds: 3.3 at the start, rising */
    TA_THETA_CLIP = 1,     /**< eq 6 clipped to the bounds: 1 at the start */
    TA_THETA_RAW = 2       /**< eq 6 as written (the real-robot section's theta = 0 at the start) */
} ta_theta_mode_t;

/** DRTM's threshold under `mode`. */
float ta_drtm_theta(uint8_t mode, float alpha, float beta, float k, float M_A, float theta0, float theta_min,
                    float theta_max);

/** Eq 7: probability of leaving the nest, S^n / (S^n + theta^n).
 *  0 when S <= 0; 1 when theta <= 0 (and S > 0).  Computed as
 *  1 / (1 + (theta/S)^n) or r^n / (1 + r^n) with r = S/theta, whichever
 *  keeps the ratio <= 1, so it neither overflows nor loses precision for
 *  any n.  Seed 000 draws n per robot from 2..9; n = 0 gives 0.5. */
float ta_probability(float S, float theta, uint8_t n);

/** Roulette-wheel draw: 1 with probability `p`, else 0.  Compares 24 random
 *  bits with p * 2^24 (p <= 0 never, p >= 1 always). */
uint8_t ta_roulette(rng_t *rng, float p);

/** ARTM threshold update (our reconstruction, see above): theta moves by
 *  `delta` against the trend of the stimulus (S > S_prev: theta - delta;
 *  S < S_prev: theta + delta; equal: unchanged), then is clipped to
 *  [theta_min, theta_max] (theta_min <= theta_max). */
float ta_artm_update(float theta, float S, float S_prev, float delta,
                     float theta_min, float theta_max);

#endif
