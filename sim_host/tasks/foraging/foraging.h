/*
 * foraging.h - seed 000's foraging task on the simulator side: the nest,
 * food tokens, the foragers' passive gripper, deliveries, and the
 * ground-truth energy ledger behind the metrics (sections 2.3-2.4 and 3.1
 * of seed 000).  Scenario section `foraging:`.
 *
 * Tokens are red cylinders the camera sees (items: not rigid bodies, and
 * the IR sensors do not see them, as food items on the floor of the seed's
 * ARGoS arena).  A forager whose gripper is empty picks up a token its front
 * touches; it carries it right in front of its lens; it lets go when both
 * wheels are commanded backward.  A token let go inside the nest is
 * delivered (one more token in the nest, a new one placed at random outside
 * the nest), elsewhere it is dropped on the floor.
 *
 * The nest food F(t), in tokens, is
 *   F(0) + delivered - C_rate t - (move_cost * foraging robot-steps
 *   + E_a * OAEs) / token_energy
 * where a forager forages in S_S and S_R (forager_paper_state).
 *
 * Where foragers learn the nest's state (seed 000, 3.2): `information:
 * beacon` needs a group running nest_beacon (a static e-puck at the nest
 * centre keeps the ledger from the foragers' reports and broadcasts it);
 * `global` replaces it by the simulator, which sends the true values in the
 * same frames (no beacon group then).
 */
#ifndef TASK_FORAGING_H
#define TASK_FORAGING_H

#include <stdint.h>

#include "swarmsim/task.h"

typedef enum foraging_info {
    FORAGING_INFO_BEACON = 0,
    FORAGING_INFO_GLOBAL = 1
} foraging_info_t;

/** The `foraging:` section.  Food in tokens, energy in units (one token is
 *  token_energy units). */
typedef struct foraging_config {
    struct {
        float x, y;                /**< centre, m */
        float diameter;            /**< d, m (a grey floor circle under a lamp) */
    } nest;
    uint32_t food_count;           /**< N_f tokens kept in the arena */
    float token_radius;            /**< m (seed: 3.5 cm diameter) */
    float token_height;            /**< m (seed: 4.2 cm) */
    float token_energy;            /**< units per token (1500) */
    float initial_food;            /**< F(0), tokens in the nest at start */
    float desired_food;            /**< F_d, tokens */
    float consumption;             /**< nest consumption C_rate, tokens/min */
    float move_cost;               /**< units per step per foraging robot */
    float oae_energy;              /**< E_a, units per obstacle-avoidance event */
    float robot_speed;             /**< v, m/s: foragers drive at it; T2 = L/(2v) */
    int information;               /**< foraging_info_t */
} foraging_config_t;

extern const task_def_t foraging_task;

/** The ground truth a test or a tool may read. */
typedef struct foraging_truth {
    uint64_t delivered;            /**< tokens deposited in the nest */
    uint64_t dropped;              /**< tokens let go outside the nest */
    double food;                   /**< F(t), tokens */
    uint32_t waiting, searching, returning;   /**< foragers by task state now */
} foraging_truth_t;

/** The foraging task's ground truth in `sim`, or 0 when it does not run. */
int foraging_truth(const sim_t *sim, foraging_truth_t *out);

/** The token robot `i` carries, or -1. */
int32_t foraging_carried(const sim_t *sim, uint32_t i);

/** Makes robot `i` lose the token it carries where it is (a test of the
 *  firmware's lost-token path).  Returns 1 if it carried one. */
int foraging_drop(sim_t *sim, uint32_t i);

/** Exact energy balance: F(0) + delivered - consumed, in tokens. */
double foraging_balance(const sim_t *sim);

#endif
