/*
 * nest_beacon.h - the nest beacon: a static e-puck at the nest centre that
 * keeps seed 000's nest ledger and broadcasts it to the foragers.
 *
 * Seed 000 computes F(t), N_W and M_T2 globally (simulation loop functions;
 * a beacon robot on the real e-pucks).  Here one robot does it with the
 * 16-bit messages of nest_link.h, so the foragers' firmware is the same in
 * the simulator and on the robots.  It never moves (wheels 0).
 *
 * Ledger, in integer energy units (a token is `token_energy` = 1500 units),
 * starting at F0 tokens; every control step:
 *   - minus the nest's consumption, C_rate = c_rate_milli_tokens_per_min
 *     / 1000 tokens per minute, exact over time (remainders are carried, so
 *     2 tokens/min at 100 ms is 5 units every step, and at 75 ms 3000
 *     units every 800 steps);
 *   - minus the movement of the foraging robots, (N_r - N_W) * move_cost
 *     (seed 000: 1 unit per robot per step in S_S or S_R);
 *   - plus token_energy per reported deposit;
 *   - minus E_a per reported obstacle-avoidance event (OAE).
 * F(t) = ledger / token_energy is broadcast in 1/16 token.
 *
 * Reports (nest_link.h types 1 and 2) carry running totals per robot id
 * (6 bits: 64 slots).  The beacon adds the mod-256 difference from the last
 * total heard from that id.  Every slot's baseline is 0 at reset, because
 * robots start with totals 0 at the same time as the beacon: the first
 * report from an id then counts everything that robot did so far.  (A
 * robot restarted mid-run would report from 0 again and be credited a
 * bogus difference; restart the beacon with the swarm.)
 *
 * N_W = ids whose deposit report was heard within the last
 * `wait_timeout_steps` steps: foragers send those only while waiting in the
 * nest, one every 2 report_steps steps (forager.h), so the timeout must
 * exceed that (5 for report_steps = 1; 4 report_steps + 1 in general).  (A robot the
 * beacon cannot hear counts as foraging; so does every robot in the first
 * step, before any report has arrived.)
 *
 * M_T2 = OAEs reported in the last T2: a sliding window of bins of
 * NB_BIN_STEPS steps, t2_steps / NB_BIN_STEPS of them (rounded down,
 * clamped to 1..NB_MAX_BINS, so T2 is 10..640 steps), the current bin
 * included: an OAE counts for between T2 - 9 and T2 steps after its report.
 * Seed 000: T2 = L / (2 v) = 4 m / (2 * 0.05 m/s) = 40 s = 400 steps.
 * M_A = M_T2 / N_r (eq 5).
 *
 * Broadcast: one nest_link beacon frame per step, cycling food (kind 0),
 * N_W (kind 1), M_A (kind 2).  Needs hal_ircom_payload_bits() == 16.
 */
#ifndef FW_NEST_BEACON_H
#define FW_NEST_BEACON_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "nest_link.h"

/** Steps per bin of the OAE window. */
#define NB_BIN_STEPS 10u
/** Most bins of the OAE window (T2 up to 640 steps). */
#define NB_MAX_BINS 64u
/** Slots of the per-robot report ledger (6-bit ids). */
#define NB_SLOTS NL_ID_COUNT
/** Age of a slot never heard (saturated). */
#define NB_AGE_NEVER 255u
/** The ledger saturates at +- this many tokens (a 12-bit broadcast carries
 *  +- 128): no stream of reports, however hostile, can wrap it. */
#define NB_LEDGER_LIMIT_TOKENS 4096
/** Most steps of report budget a robot can save up (a uint8_t). */
#define NB_BUDGET_MAX 255u

typedef struct nest_beacon_params {
    uint16_t n_robots;                     /**< N_r, robots in the swarm */
    int16_t f0_tokens;                     /**< F(0), food in the nest at start, tokens */
    uint16_t token_energy;                 /**< energy units per token (>= 1; 1500) */
    uint16_t c_rate_milli_tokens_per_min;  /**< nest consumption, 1/1000 token per minute (2000) */
    uint16_t move_cost;                    /**< units per foraging robot per step (1) */
    uint16_t e_a;                          /**< E_a, units per OAE (10) */
    uint16_t t2_steps;                     /**< T2, OAE window, steps (400; 10..640) */
    uint8_t wait_timeout_steps;            /**< a robot counts as waiting this many steps
                                                after its last deposit report (5; 1..254) */
    uint8_t min_deposit_steps;             /**< a robot is credited at most one deposit
                                                per this many steps (20: 2 s; >= 1) */
} nest_beacon_params_t;

typedef enum nest_beacon_state {
    NB_START = 0,    /**< first step: stop, light up */
    NB_RUN = 1       /**< keep the ledger, broadcast */
} nest_beacon_state_t;

typedef struct nest_beacon {
    nest_beacon_params_t params;
    uint32_t seed;                 /**< kept by convention; the beacon draws nothing */
    uint8_t state;                 /**< nest_beacon_state_t */

    /* Telemetry. */
    int32_t ledger_units;          /**< nest energy, units (F(t) * token_energy) */
    int32_t food_q4;               /**< F(t) = ledger / token_energy, 1/16 token */
    uint16_t n_waiting;            /**< N_W, ids heard within the timeout */
    uint32_t m_t2;                 /**< M_T2, OAEs reported in the last T2 */
    uint32_t deposits_total;       /**< deposits reported since reset */
    uint32_t oae_total;            /**< OAEs reported since reset */

    /* Per-id report ledger. */
    uint8_t last_deposits[NB_SLOTS];  /**< last deposit total heard, mod 256 */
    uint8_t last_oaes[NB_SLOTS];      /**< last OAE total heard, mod 256 */
    uint8_t age_steps[NB_SLOTS];      /**< steps since last heard, NB_AGE_NEVER if never */
    /* What a robot may still be credited: one step of budget a step, one
     * deposit costs min_deposit_steps, one OAE one step (a token bucket). */
    uint8_t deposit_budget[NB_SLOTS];
    uint8_t oae_budget[NB_SLOTS];

    /* OAE window. */
    uint16_t bins[NB_MAX_BINS];    /**< OAEs reported per bin */
    uint8_t n_bins;                /**< bins in the window */
    uint8_t bin;                   /**< current bin */
    uint8_t bin_step;              /**< steps done in the current bin */

    /* Exact consumption: remainders of the per-step division. */
    uint32_t cons_rem_milli_ms;    /**< (milli-units * ms) / 60000 carried */
    uint16_t cons_rem_milli;       /**< milli-units carried */

    uint8_t next_kind;             /**< nest_link_kind_t broadcast next */
} nest_beacon_t;

/* The controller contract (controller.h): default_params N_r 20, F0 5
 * tokens, 1500 units per token, 2 tokens/min, move cost 1, E_a 10, T2 400
 * steps (40 s), wait timeout 5 steps, a deposit credited at most every 20
 * steps; init
 * copies params, keeps seed, resets; reset: ledger at F0, every id unheard
 * with totals 0, empty OAE window; step reads the reports, updates the
 * ledger, broadcasts; state_name "start", "run". */
CONTROLLER_API(nest_beacon);

/** F(t) in 1/16 token, rounded to nearest (what kind-0 frames carry before
 *  saturation). */
int32_t nest_beacon_food_q4(const nest_beacon_t *self);

/** M_A = M_T2 / N_r in 1/256 OAE per robot, rounded down (kind-2 frames
 *  before saturation). */
uint32_t nest_beacon_mean_oae_q8(const nest_beacon_t *self);

/** Its registered name, and what it shows (nest_beacon_def.c): the simulator's
 *  telemetry and the robot image's read the same table. */
#define NEST_BEACON_NAME "nest_beacon"
extern const observable_t nest_beacon_observables[];

/** Its description for the simulator (nest_beacon_def.c). */
extern const controller_def_t nest_beacon_def;

#endif
