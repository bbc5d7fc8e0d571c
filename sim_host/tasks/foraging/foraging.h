/*
 * foraging.h - seed 000's foraging task on the simulator side: food tokens,
 * the passive gripper, deliveries to the nest, and the ground-truth energy
 * ledger behind the metrics (sections 2.3-2.4 and 3.1 of seed 000).
 *
 * Tokens are red cylinders the camera sees (they are not rigid bodies and
 * the IR sensors do not see them: as food items on the floor of the
 * seed's ARGoS arena).  A robot whose gripper is empty picks up a token its
 * front touches; it carries it right in front of its lens; it lets go when
 * both wheels are commanded backward.  A token let go inside the nest is
 * delivered (one more token in the nest, a new one placed at random outside
 * the nest), elsewhere it is dropped on the floor.
 *
 * The nest food F(t), in tokens, is
 *   F(0) + delivered - C_rate t - (move_cost * foraging robot-steps
 *   + E_a * OAEs) / token_energy
 * where a robot forages in S_S and S_R (its controller's task state).
 */
#ifndef SIM_FORAGING_H
#define SIM_FORAGING_H

#include <stdint.h>

#include "core/rand.h"

struct sim;

typedef struct food_token {
    float x, y;          /**< m (for a carried token: in front of its robot) */
    int32_t carrier;     /**< robot index, or -1 when on the floor */
} food_token_t;

typedef struct foraging {
    uint32_t n_tokens;
    food_token_t *tokens;
    int32_t *carried;        /**< per robot: token index or -1 */
    sim_rand_t rand;         /**< token placement */

    uint64_t delivered;      /**< tokens deposited in the nest */
    uint64_t dropped;        /**< tokens let go outside the nest */
    uint64_t forage_steps;   /**< robot-steps spent in S_S or S_R */
    uint64_t oae_seen;       /**< OAEs already charged */
    double nest_units;       /**< energy the nest consumed, units */
    double food;             /**< F(t), tokens */
    double deviation_sum;    /**< sum over steps of |F_d - F(t)| */
    uint32_t waiting, searching, returning;   /**< robots by task state now */
    uint32_t *oae_window;    /**< swarm OAEs per step over the last T2 (global info) */
    uint32_t window_len, window_pos;
    uint64_t window_sum;
} foraging_t;

/** Sets up tokens and the ledger (when the scenario enables foraging). */
int foraging_init(struct sim *sim, char err[256]);
void foraging_free(struct sim *sim);

/** Before physics: robots backing up let go of their tokens. */
void foraging_release(struct sim *sim);
/** After physics: carried tokens follow, grippers pick up, energy is charged. */
void foraging_update(struct sim *sim);
/** Ideal global information: the true nest state, sent as a nest beacon would. */
void foraging_broadcast_truth(struct sim *sim);

/** Makes robot `i` lose the token it carries where it is (a test of the
 *  firmware's lost-token path).  Returns 1 if it carried one. */
int foraging_drop(struct sim *sim, uint32_t i);

/** Exact energy balance: F(0) + delivered - consumed, in tokens. */
double foraging_balance(const struct sim *sim);

#endif
