/*
 * repatt.h - seed 002's RepAtt forager (Obute et al. 2020, Algorithm 1)
 * and, with all four gains 1, its random-walk baseline: one firmware, two
 * policies.
 *
 * Each control period, in Algorithm 1's order:
 *   3-4   an obstacle (IR proximity above avoid_enter) starts obstacle
 *         avoidance, AVOID: a front one (IR0, IR7) a random turn greater
 *         than 90 deg (uniform in (90, 180] deg, either way), one on a side
 *         (IR1, IR2 right; IR5, IR6 left) a 45 deg turn away from it; then
 *         AVOID_RUN, straight for a random length uniform in
 *         [0, oa_run_max_mm] (an obstacle met on the way starts another
 *         avoidance); then the other states again.  Turns and runs are
 *         measured on the wheel step counters.  A robot waiting to pick a
 *         target up (PICK) is stationary and does not avoid.
 *   5-6   cap == 0: HOME, to the start point by odometry (odometry.h),
 *         silent and deaf (the queues are emptied when homing starts);
 *         within home_radius_mm of it the targets are unloaded: cap back
 *         to `capacity`.
 *   8-21  otherwise G_r = G_a = 1, then from the signs of eq 6's changes
 *         (chemotaxis.h) P_t = P_b x G_r x G_a; the speaker: band 1
 *         (repulsion) when found == 0, band 2 (attraction) when
 *         found > cap, silence otherwise.
 *   22-23 found > 0 (red blobs in view): ACQUIRE, steer to the widest red
 *         blob (the nearest target); once it is at least reach_width_mrad
 *         wide, PICK: wheels (0, 0) for pick_time_ms (seed 002's 5 s).  With
 *         approach_mm > 0 (the e-puck's front camera, whose lens sits on the
 *         rim: a target within reach is wider than its 56 deg view, and below
 *         its lower edge) the robot first makes sure the blob is within
 *         APPROACH_CENTRED_MRAD of straight ahead, then APPROACH: straight on
 *         for approach_mm by its step counters, then PICK.  The task removes
 *         a target after that wait; if the blob is gone in the few periods
 *         after the wait, the target is carried (cap - 1); if it went during
 *         the wait, another robot took it; if it stays, the robot gives up on
 *         it and ignores targets for give_up_ms.  A PICK that began with no
 *         red blob near straight ahead (the target out of sight, too close)
 *         waits the whole pick_time_ms and counts the target carried.
 *   24-27 found == 0: SEARCH, straight; with probability P_t per period a
 *         TUMBLE, a turn in place by an angle drawn from
 *         N(tumble_mean_mrad, tumble_sd_mrad^2) (sum of 12 uniforms),
 *         made the short way round (the same heading).
 *
 * Listening (`listening`): DUPLEX emits and listens every period (the
 * paper's model; in the simulator it needs sound.self_masking false, else
 * every reading of an emitting robot is drowned).  SLOTTED is what an
 * e-puck can do: each period a robot with a band to emit emits it or stays
 * silent, at random with p = 1/2.  In both a reading is taken only when
 * hal_mic_level answers HAL_OK (after a silent period when self-masking):
 * the mean of the microphones that answer, per band; the queues count
 * readings.  Readings are taken in every state but HOME.
 *
 * Observables (repatt_def.c): state, found, cap, I_r, I_a, the change
 * signs, P_t, the band, the odometry and counts of avoidances, pick-ups
 * and unloads.
 *
 * Everything is in the HAL's units (mm, mrad, ms, steps); step counts are
 * derived from hal_control_period_ms.  Defaults: seed 002 at the e-puck
 * scale of the plan (v = 0.10 m/s = 776 steps/s, every length x 0.16529,
 * times kept, 25 ms periods).
 */
#ifndef FW_REPATT_H
#define FW_REPATT_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/rng.h"
#include "avoid.h"
#include "chemotaxis.h"
#include "odometry.h"

/** Queue size y the simulator's robots can hold: the paper's largest
 *  (Q120, Figure 2c).  An e-puck image holds fewer (repatt_main.c: 40). */
#define REPATT_QUEUE_MAX 120u
/** Bands followed: repulsion (band 1) and attraction (band 2). */
#define REPATT_BANDS 2u
#define REPATT_BAND_REPULSION 1u
#define REPATT_BAND_ATTRACTION 2u
/** uint32_t words of queue storage for queue size up to `max`: 2y
 *  readings per band. */
#define REPATT_QUEUE_WORDS(max) (REPATT_BANDS * 2u * (max))

/** Policies (repatt_def.c's names, in this order). */
typedef enum repatt_policy {
    REPATT_POLICY_REPATT = 0,       /**< A4m100d-R1m10d, the paper's best */
    REPATT_POLICY_RANDOM_WALK = 1,  /**< all gains 1 */
    REPATT_POLICY_CUSTOM = 2        /**< the gains as the params set them */
} repatt_policy_t;

typedef enum repatt_listening {
    REPATT_DUPLEX = 0,   /**< emit and listen every period */
    REPATT_SLOTTED = 1   /**< emit in a random half of the periods */
} repatt_listening_t;

typedef struct repatt_params {
    float p_b;                    /**< P_b, tumble probability per control period (0.0025) */
    chemo_gains_t gains;          /**< a_m, a_d, r_m, r_d (4, 100, 1, 10) */
    uint16_t queue_size;          /**< y, readings per average (eq 5; 40) */
    uint8_t listening;            /**< repatt_listening_t (SLOTTED) */
    uint8_t capacity;             /**< targets carried before homing (5) */
    int16_t speed_steps_s;        /**< forward speed, steps/s (776 = 0.10 m/s) */
    int16_t turn_speed_steps_s;   /**< wheel speed turning in place, steps/s (776) */
    int16_t steer_gain;           /**< wheel speed difference per rad of bearing, steps/s (1000) */
    uint16_t tumble_mean_mrad;    /**< mu of the tumble angle, mrad (3142 = 180 deg) */
    uint16_t tumble_sd_mrad;      /**< sigma of the tumble angle, mrad (1571 = 90 deg) */
    uint16_t avoid_enter;         /**< IR proximity that means an obstacle, counts (300) */
    uint16_t side_turn_mrad;      /**< turn away from a side obstacle, mrad (785 = 45 deg) */
    uint16_t oa_run_max_mm;       /**< longest straight run after a turn, mm (165 = 1 m x k) */
    uint16_t pick_time_ms;        /**< stationary time per target, ms (5000) */
    uint16_t reach_width_mrad;    /**< a red blob this wide is within reach, mrad (330) */
    uint16_t approach_mm;         /**< then straight on this far before stopping, mm (46; 0: stop at once) */
    uint16_t give_up_ms;          /**< targets ignored after a failed pick-up, ms (10000) */
    uint16_t home_radius_mm;      /**< unload this close to the start point, mm (100) */
} repatt_params_t;

typedef enum repatt_state {
    REPATT_SEARCH = 0,      /**< found == 0: straight (lines 24-27) */
    REPATT_TUMBLE = 1,      /**< found == 0: turning by the drawn angle */
    REPATT_ACQUIRE = 2,     /**< found > 0: to the widest red blob */
    REPATT_PICK = 3,        /**< stationary at a target */
    REPATT_HOME = 4,        /**< cap == 0: to the start point */
    REPATT_AVOID = 5,       /**< obstacle: turning away */
    REPATT_AVOID_RUN = 6,   /**< obstacle: the straight run after the turn */
    REPATT_APPROACH = 7     /**< the last approach_mm to a target, counted on the steps */
} repatt_state_t;

typedef struct repatt {
    repatt_params_t params;
    rng_t rng;
    uint32_t seed;
    uint32_t *queue;        /**< REPATT_QUEUE_WORDS(queue_max) words (repatt_attach_queue) */
    uint16_t queue_max;     /**< largest y the queue storage holds */
    uint8_t state;          /**< repatt_state_t */

    /* Algorithm 1's variables. */
    uint8_t cap;            /**< targets the robot can still take */
    uint8_t found;          /**< red blobs in view */
    chemo_filter_t filter[REPATT_BANDS];   /**< [0] repulsion, [1] attraction */
    uint32_t level_r;       /**< I_r(t), counts (eq 5) */
    uint32_t level_a;       /**< I_a(t), counts */
    int8_t d_r;             /**< sign of dI_r (eq 6) */
    int8_t d_a;             /**< sign of dI_a */
    uint32_t p_b_q32;       /**< P_b, Q32 */
    uint32_t p_t_q32;       /**< P_t of the last evaluation (lines 8-21), Q32 */
    uint8_t band;           /**< what the robot broadcasts: 0, 1 or 2 */
    uint8_t speaker;        /**< what it set this period (slotted: band or 0); 255 before the first */

    /* Motion. */
    odometry_t odo;
    avoid_t turn;           /**< the tumble, avoidance turn or run in progress */
    uint16_t timer;         /**< PICK: periods stopped */
    uint16_t ignore;        /**< periods left in which targets are ignored */
    int16_t pick_bearing_mrad;   /**< PICK: where the target is */
    uint16_t pick_width_mrad;    /**< PICK: how wide it was */

    /* Counts since reset. */
    uint32_t oae_count;     /**< obstacle avoidances */
    uint32_t pickups;       /**< targets counted as carried */
    uint32_t unloads;       /**< trips home */
    uint32_t readings;      /**< repulsion-band readings taken */
} repatt_t;

/** The simulator's per-robot state: the controller and its queues for
 *  y <= REPATT_QUEUE_MAX (repatt_def.c attaches them). */
typedef struct repatt_host {
    repatt_t ctrl;          /**< first: observables' offsets are repatt_t's */
    uint32_t queue[REPATT_QUEUE_WORDS(REPATT_QUEUE_MAX)];
} repatt_host_t;

/* The controller contract (controller.h):
 *   default_params  the plan's e-puck scale (repatt_params_t's comments),
 *                   the repatt gains, slotted listening;
 *   init            copies params, keeps seed, resets (the queue storage
 *                   attached before is kept);
 *   reset           SEARCH with cap = capacity, empty queues (y limited
 *                   to the storage), at the start point of the odometry,
 *                   P_t = P_b, counts 0, the seeded stream anew;
 *   step            one control period (above);
 *   state_name      "search", "tumble", "acquire", "pick", "home",
 *                   "avoid", "avoid_run", "approach". */
CONTROLLER_API(repatt);

/** Gives the controller its queue storage, REPATT_QUEUE_WORDS(queue_max)
 *  words, before init (the storage is the image's: its size is a RAM
 *  choice).  Without it no reading is kept: the changes stay 0 and the
 *  robot walks at P_b. */
void repatt_attach_queue(repatt_t *self, uint32_t *storage, uint16_t queue_max);

/** Sets the gains of a policy (repatt_policy_t); CUSTOM leaves them. */
void repatt_apply_policy(repatt_params_t *params, uint8_t policy);

#define REPATT_NAME "repatt"
extern const observable_t repatt_observables[];   /* repatt_observables.c */
extern const controller_def_t repatt_def;

/** controller_def_t.set_policy of RepAtt's params (repatt_def.c): the gains
 *  of policy `index` (repatt_apply_policy); an image's selector calls it. */
void repatt_set_policy(void *params, uint8_t index);

#endif
