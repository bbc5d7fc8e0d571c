/*
 * forager.h - seed 000's foraging robot (Figure 1, Table 1) with its task
 * allocation policy: DRTM, ARTM or FRTM (task_alloc.h).
 *
 * States (paper names in brackets):
 *   WAIT    [S_W]  in the nest, wheels stopped.  Reads the nest beacon's
 *                  frames (nest_link.h: F(t), N_W, M_A and its range) and
 *                  sends one report per step, alternating its deposit total
 *                  and its OAE total.  After T1 steps it decides (eqs 2-7):
 *                  P_s from the policy's threshold and its own n, then a
 *                  roulette draw: SEARCH, or wait; with decide_each_step
 *                  (T1 is the paper's "minimum waiting time") it draws
 *                  again every step, else after another T1.  The threshold
 *                  moves (ARTM's update) once per T1 in either case.  Without every
 *                  beacon quantity heard at least once, P_s = 0.
 *   SEARCH [S_S]  Leaving the nest first (leave_nest): it turns away from
 *                  the lamp (the brightest ambient sensor) and drives out,
 *                  avoiding obstacles, until nest_confirm beacon frames in
 *                  a row come from beyond the nest radius (or the light is
 *                  lost, or leave_max_steps pass); tokens are not in the
 *                  nest, so it ignores red blobs meanwhile (another robot's
 *                  carried token is not its food).  Then A(t) = 0: random
 *                  walk (random_walk.h).  A(t) = 1 when a red blob (a
 *                  token) is seen: steer toward it, proportional to its
 *                  bearing.  A red blob at least grasp_width_mrad wide and
 *                  centred for grasp_confirm steps in a row, right after an
 *                  approach to it (or for 20 steps without one: a token
 *                  taken in passing), is a token held by the passive gripper
 *                  in front of the lens: RETURN.  (A token another robot
 *                  carries past is wide for a moment, not centred and held.)
 *   RETURN [S_R]  A(t) = 0: random walk; A(t) = 1 when the nest light is
 *                  seen (some ambient reading below light_detect): steer to
 *                  the brightest sensor, turning in place when it is behind.
 *                  A beacon frame from closer than nest_radius - nest_margin
 *                  means the nest: DEPOSIT.  No wide red blob for lost_steps
 *                  steps means the token was lost: SEARCH.
 *   DEPOSIT [S_R] backs straight out at -speed for deposit_steps steps: a
 *                  passive gripper lets go when the robot backs off (the
 *                  simulator releases a carried token when both wheels are
 *                  commanded backward).  Then, once no wide red blob is seen,
 *                  the deposit counts and the robot WAITs.  If the token is
 *                  still in view after another deposit_steps of backing, it
 *                  WAITs without counting: the token probably did not let
 *                  go, and a deposit the beacon never gets is better than an
 *                  invented one (the camera check in SEARCH finds it again).
 * Obstacle avoidance (and its OAE count) is the embedded random walk's in
 * every moving state; the forager's OAE total is walk.oae_count.
 *
 * Needs hal_ircom_payload_bits() == 16 (range-and-bearing turret): over 8
 * bits every frame decodes as invalid and the robot never leaves the nest.
 * The IR inbox is drained every step in every state, so that a frame heard
 * long ago is never taken for the nest.
 */
#ifndef FW_FORAGER_H
#define FW_FORAGER_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/random_walk.h"
#include "common/rng.h"
#include "task_alloc.h"

typedef struct forager_params {
    ta_policy_t policy;          /**< TA_DRTM, TA_ARTM or TA_FRTM */
    float alpha;                 /**< eq 6 weight of k, per (robots/m^2) (3.0) */
    float beta;                  /**< eq 6 weight of M_A, per OAE (2.0) */
    uint16_t t1_steps;           /**< T1, steps between decisions in the nest (50 = 5 s) */
    uint8_t n_min;               /**< eq 7 exponent n, per robot uniform in [n_min, n_max] (2) */
    uint8_t n_max;               /**< (9) */
    float theta0;                /**< ARTM start and FRTM fixed threshold, tokens (3.3) */
    float theta_min;             /**< ARTM clip, tokens (1.0) */
    float theta_max;             /**< ARTM clip, tokens (10.0) */
    float artm_delta;            /**< ARTM step per decision, tokens (0.5) */
    float f_d_tokens;            /**< F_d, desired nest food, tokens (20) */
    uint16_t n_robots;           /**< N_r, robots in the swarm (20) */
    uint16_t arena_l_mm;         /**< L, arena side, mm (4000) */
    int16_t speed_steps_s;       /**< forward speed, steps/s (388 = 0.05 m/s); also the walk's */
    int16_t steer_gain;          /**< wheel speed difference per bearing, steps/s per rad (800) */
    /* A held token fills the 977 mrad view; one on the floor stays below
     * about 850 mrad (forager_default_params). */
    uint16_t grasp_width_mrad;   /**< red blob this wide = token held, mrad (900) */
    uint16_t near_width_mrad;    /**< red blob this wide and centred = token about to be
                                      grasped: its IR echo is not an obstacle (250) */
    uint8_t lost_steps;          /**< steps without the held token before SEARCH again (3) */
    uint16_t nest_radius_mm;     /**< nest radius, mm (750: d = 1.5 m) */
    uint16_t nest_margin_mm;     /**< beacon range must be this far inside the nest, mm (100) */
    uint8_t nest_confirm;        /**< beacon frames in a row inside the nest that mean
                                      arrival: the range estimate is noisy (3) */
    uint16_t light_detect;       /**< ambient below this = nest light seen, counts (3600) */
    uint8_t deposit_steps;       /**< steps of backing out of a deposited token (5) */
    uint8_t drtm_theta;          /**< ta_theta_mode_t: how theta0 and the bounds enter DRTM
                                      (TA_THETA_OFFSET: theta0 + eq 6 in [theta_min, theta_max]) */
    uint8_t decide_each_step;    /**< 1: once T1 has passed, draw every step (T1 a minimum
                                      waiting time, the paper's wording); 0: draw every T1 */
    uint8_t leave_nest;          /**< 1: leaving the nest, turn away from the lamp until
                                      the beacon is heard from outside the nest (1) */
    uint16_t leave_max_steps;    /**< give up turning away after this many steps (300) */
    uint8_t grasp_confirm;       /**< steps a wide red blob must stay centred, after an
                                      approach, to count as a token grasped (3) */
    random_walk_params_t walk;   /**< A(t) = 0 motion and obstacle avoidance; its
                                      speed_steps_s is replaced by speed_steps_s */
} forager_params_t;

typedef enum forager_state {
    FORAGER_WAIT = 0,      /**< S_W */
    FORAGER_SEARCH = 1,    /**< S_S */
    FORAGER_RETURN = 2,    /**< S_R, looking for the nest */
    FORAGER_DEPOSIT = 3    /**< S_R, backing out of the token in the nest */
} forager_state_t;

/** Bits of forager_t.beacon_known: which beacon quantities were heard. */
#define FORAGER_KNOWS_FOOD 1u
#define FORAGER_KNOWS_WAITING 2u
#define FORAGER_KNOWS_MEAN_OAE 4u
#define FORAGER_KNOWS_ALL 7u

typedef struct forager {
    forager_params_t params;
    random_walk_t walk;          /**< embedded; walk.oae_count is the robot's OAE total */
    rng_t rng;                   /**< n and the roulette (the walk has its own) */
    uint32_t seed;
    uint8_t state;               /**< forager_state_t */

    /* Task allocation, for telemetry: the values of the last decision. */
    uint16_t t1;                 /**< steps waited since the last decision */
    uint8_t n;                   /**< eq 7 exponent, drawn at reset */
    float theta;                 /**< threshold, tokens */
    float S;                     /**< stimulus, tokens */
    float S_prev;                /**< ARTM: stimulus at the previous decision */
    float P_s;                   /**< probability of leaving */
    float k;                     /**< traffic flow density, robots/m^2 */
    float M_A;                   /**< mean OAEs per robot over T2 */
    uint8_t decided;             /**< a decision has been made (S_prev valid) */

    uint32_t deposits;           /**< tokens deposited since reset */

    /* Last beacon frames heard. */
    uint8_t beacon_known;        /**< FORAGER_KNOWS_* bits */
    int16_t beacon_food_q4;      /**< F(t), 1/16 token */
    uint16_t beacon_n_waiting;   /**< N_W, robots */
    uint16_t beacon_mean_oae_q8; /**< M_A, 1/256 OAE per robot */
    uint16_t beacon_range_mm;    /**< range to the beacon, mm */
    uint8_t nest_frames;         /**< beacon frames in a row heard inside the nest */

    uint8_t carrying;            /**< a wide red blob was seen this step */
    uint8_t lost;                /**< RETURN: steps without the held token */
    uint16_t timer;              /**< DEPOSIT: steps backed (up to 2 * deposit_steps) */
    uint8_t report_oaes;         /**< next report: 0 deposits, 1 OAEs */

    uint8_t leaving;             /**< SEARCH: still turning away from the lamp */
    uint16_t leave_steps;        /**< steps spent leaving */
    uint8_t out_frames;          /**< beacon frames in a row heard from outside the nest */
    uint8_t approach;            /**< steps left in which a grasp may follow an approach */
    uint8_t grasp_steps;         /**< steps in a row with a wide, centred red blob */
    uint16_t out_timer;          /**< steps out of the nest, for the OAE reports' cadence */
} forager_t;

/* The controller contract (controller.h):
 *   default_params  seed 000's values (forager_params_t's comments), DRTM;
 *   init            copies params, keeps seed, resets;
 *   reset           WAIT with t1 = 0, nothing heard or deposited, theta at
 *                   its start (DRTM: its drtm_theta mode with k = M_A = 0,
 *                   3.3 by default; ARTM, FRTM: theta0), n drawn afresh,
 *                   the walk reset (OAE count 0);
 *   step            one control step;
 *   state_name      "wait", "search", "return", "deposit". */
CONTROLLER_API(forager);

/** Seed 000's name of a forager_state_t: 'W', 'S' or 'R' ('?' if unknown). */
char forager_paper_state(uint8_t state);

/** Its registered name, and what it shows (forager_def.c): the simulator's
 *  telemetry and the robot image's read the same table. */
#define FORAGER_NAME "forager"
extern const observable_t forager_observables[];

/** Its description for the simulator (forager_def.c). */
extern const controller_def_t forager_def;

/** controller_def_t.set_policy of a forager's params (forager_def.c): the
 *  policy of ta_policy_names' entry `index`. */
void forager_set_policy(void *params, uint8_t index);

#endif
