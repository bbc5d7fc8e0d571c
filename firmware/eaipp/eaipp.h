/*
 * eaipp.h - EAIPP (seed 003, Luo et al., Complexity 2021): Physarum-inspired
 * path formation by robot chains over the range-and-bearing turret.
 *
 * One controller, three roles (param `role`): `robot`, the swarm robot with
 * the paper's three states Robot_Lost, Robot_Explorer and Robot_Node; `nest`
 * and `food`, the fixed robots Robot_Nest and Robot_Food, which only
 * broadcast themselves as gradient sources (gradient 0, their Source_Type,
 * Root_ID = own id) and never move.  A scenario makes the nest and food
 * robot groups with `controller: eaipp` and `params: {role: nest}` (or
 * food); each role has its own e-puck image (firmware/apps/eaipp_*_main.c).
 *
 * Every step: the neighbour table ages (neighbours.h), every message in the
 * inbox is filed, the state's rule runs (eaipp.c, one function per
 * mechanism, each written from the paper's Algorithms 1-4 and eq 1), and the
 * robot sends its message kinds in turn, as many as the platform takes this
 * period (one with the HAL's default; ircom.tx_per_period in the simulator).
 *
 * Units: ranges mm, bearings mrad, speeds steps/s, periods control steps.
 */
#ifndef FW_EAIPP_H
#define FW_EAIPP_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/rng.h"
#include "eaipp/eaipp_msg.h"
#include "eaipp/neighbours.h"

#define EAIPP_NAME "eaipp"

typedef enum eaipp_role {
    EAIPP_ROLE_ROBOT = 0,
    EAIPP_ROLE_NEST = 1,
    EAIPP_ROLE_FOOD = 2
} eaipp_role_t;

/** States; the values are those of eaipp_msg_state_t. */
typedef enum eaipp_state {
    EAIPP_LOST = EAIPP_ST_LOST,
    EAIPP_EXPLORER = EAIPP_ST_EXPLORER,
    EAIPP_NODE = EAIPP_ST_NODE,
    EAIPP_NEST = EAIPP_ST_NEST,
    EAIPP_FOOD = EAIPP_ST_FOOD,
    EAIPP_EXITING = EAIPP_ST_EXITING   /**< leaving the maze's waiting area (section 5.1, lj_exit) */
} eaipp_state_t;

/** Eq 1's node term: how a neighbour's distance D_i weighs it (the printed
 *  formula lost its symbols). */
typedef enum eaipp_a_distance {
    EAIPP_A_INVERSE = 0,           /**< (g_i - g_mean) u_i / D_i: the nearest high node attracts most */
    EAIPP_A_LINEAR = 1             /**< (g_i - g_mean) D_i u_i: one direction down the branch */
} eaipp_a_distance_t;

typedef struct eaipp_params {
    uint8_t role;                  /**< eaipp_role_t */
    uint16_t speed_steps_s;        /**< m_fWheelVelocity of Algorithm 3, steps/s (388 = 5 cm/s) */
    uint16_t b_ul_mm;              /**< B_UL (Algorithm 4, Table 2: 0.7 R < B_UL < 0.8 R): an explorer
                                        becomes a node when its one node is farther than this, mm */
    uint16_t b_ul_max_mm;          /**< 0 (default): no upper bound, as printed; else the one node
                                        must also be no farther than this (a window), mm */
    uint16_t period1_steps;        /**< PERIOD_TIME_1: a branch end with no explorer near leaves
                                        (reconstruction: the paper gives no value) */
    uint16_t period2_steps;        /**< PERIOD_TIME_2: explorers near a branch end but no child:
                                        the branch contracts (reconstruction) */
    uint8_t timeout_steps;         /**< a neighbour not heard for this long is forgotten */
    float w_nodes;                 /**< eq 1's weight of the node (gradient) term */
    float w_obstacles;             /**< eq 1's weight of the obstacle term */
    uint16_t prox_full;            /**< proximity counts taken as eq 1's reading 1 */
    uint16_t lost_turn_prox;       /**< Robot_Lost turns away above this proximity */
    uint8_t a_distance;            /**< eq 1's D_i in the node term: EAIPP_A_INVERSE (u_i / D_i) or
                                        EAIPP_A_LINEAR (D_i u_i, the vector to the neighbour) */
    uint8_t ext_strict;            /**< Algorithm 4 only on current, known entries: wait for every
                                        neighbour's STATE, use this period's range (0: off) */
    uint16_t turn_hold_mrad;       /**< Algorithm 3: a direction within this of straight behind keeps
                                        the side of the last turn (0: off) */
    uint8_t lj_exit;               /**< section 5.1: robots leave the waiting area in the "exiting"
                                        state (Lennard-Jones model) before they search */
    uint16_t lj_sigma_mm;          /**< LJ sigma: exiting robots settle 2^(1/6) sigma apart, mm */
    float lj_weight;               /**< LJ term's weight against the pull to the nest (1) */
    uint16_t exit_near_mm;         /**< an exiting robot this near the nest has left: explorer, mm */
    uint8_t food_source;           /**< 1: the food is a second gradient source and network root
                                        (sections 4.2.1, 4.3); 0 (default): Algorithm 4, eq 1 and
                                        section 5.2 as printed, the food is the target only (also
                                        section 5.1's maze rule) */
    uint8_t same_source;           /**< with food_source: an explorer counts only the holders of its
                                        own Source_Type (the nest's if it hears any) in Algorithm 4
                                        and eq 1, so it may join one network's end while it hears
                                        the other's nodes and link them (0, default: every holder) */
} eaipp_params_t;

typedef struct eaipp {
    eaipp_params_t p;
    uint32_t seed;
    rng_t rng;
    neighbours_t nb;
    uint8_t state;                 /**< eaipp_state_t */
    uint8_t id;                    /**< hal_robot_id & 127 */
    uint8_t gradient;              /**< own gradient, EAIPP_GRADIENT_MAX when none */
    uint8_t source;                /**< own Source_Type */
    uint8_t root;                  /**< own Root_ID */
    uint8_t parent;                /**< id of P_Node (meaningful with gradient < MAX) */
    uint8_t children;              /**< C_Nodes heard: nodes of my source at my gradient + 1 */
    uint8_t contraction;           /**< Flag_Contraction */
    uint8_t tx_cursor;             /**< next message kind of the role's cycle */
    uint8_t turning;               /**< Robot_Lost: steps left of a turn away */
    int8_t turn_dir;               /**< +1 left, -1 right */
    int8_t turn_side;              /**< Algorithm 3: side of the last turn, +1 left, -1 right, 0 none */
    uint8_t shun_root;             /**< a node that left a branch does not rejoin it (its Root_ID) ... */
    uint8_t shun_parent;           /**< ... nor its P_Node (by id, whatever Root_ID it has now) ... */
    uint16_t shun_steps;           /**< ... for this many more steps */
    uint16_t counter1;             /**< Algorithm 2: steps with no explorer near a branch end */
    uint16_t counter2;             /**< Algorithm 2: steps with explorers near it */
    uint8_t orphan_steps;          /**< a node's steps without any source heard */
    uint8_t retreating;            /**< left a contracting branch as an explorer (Algorithm 2): the
                                        branch it shuns still guides it back */
    uint8_t exited;                /**< went through the exiting state once (lj_exit) */
    uint16_t exit_mm;              /**< exiting: own distance to the nest as broadcast (0xFFFF: unknown) */
    float heading_x, heading_y;    /**< eq 1's last direction, robot frame (observables) */
    uint32_t joins;                /**< explorer -> node transitions */
    uint32_t leaves;               /**< node -> lost/explorer transitions */
} eaipp_t;

CONTROLLER_API(eaipp);

/* The mechanisms, exposed for tests (each reads only the table and self). */

/** Algorithm 1: own gradient, Source_Type, parent, children and Root_ID from
 *  the table; returns 1 if any source was heard. */
uint8_t eaipp_gradient_update(eaipp_t *self);

/** Algorithm 2, one step of a node; may change self->state. */
void eaipp_extinction_step(eaipp_t *self);

/** Algorithm 4: 1 if an explorer should become a node now. */
uint8_t eaipp_extension_due(const eaipp_t *self);

/** Eq 1 (reconstructed): the direction to move in, robot frame, into
 *  (*vx, *vy) (not normalised), from the table and the proximity readings. */
void eaipp_direction(const eaipp_t *self, const uint16_t prox[HAL_IR_COUNT], const int16_t bearing_mrad[HAL_IR_COUNT],
                     float *vx, float *vy);

/** Section 5.1, one step of an exiting robot: the direction to move in
 *  (robot frame, into *vx, *vy) toward the nest or the exiting neighbour
 *  nearest to it, with the Lennard-Jones term of the other exiting robots,
 *  and self->exit_mm.  Returns 0 when neither the nest nor an exiting robot
 *  with a known distance is heard. */
uint8_t eaipp_exit_direction(eaipp_t *self, float *vx, float *vy);

/** Algorithm 3: wheel speeds (steps/s) steering toward (vx, vy); a direction
 *  within hold_mrad of straight behind turns to the side *side of the last
 *  turn (when nonzero), and *side is updated. */
void eaipp_wheel_law(float vx, float vy, uint16_t speed, uint16_t hold_mrad, int8_t *side, int16_t *left,
                     int16_t *right);

extern const observable_t eaipp_observables[];

#endif
