/*
 * pfias.h - PFIAS, Nouyan, Campo and Dorigo's chain-based path formation
 * (Swarm Intelligence 2(1), 2008), the baseline of seed 003's Figures 11-14,
 * as a portable controller over the range-and-bearing turret.
 *
 * What is sourced and what is reconstructed is in
 * docs/notes/i15_baselines.md; in short:
 *
 *   LOST      random walk with obstacle avoidance until the nest or a chain
 *             member is perceived (within range_mm);
 *   EXPLORER  moves along chains with the behaviours of the swarm-bots
 *             controller: adjust distance (AD) to one object, the
 *             "reference", at link_mm, move perpendicular (MP) around it,
 *             avoid obstacles (AO), the three vectors summed.  Going out,
 *             the reference steps from a member to the next colour of the
 *             cyclic pattern (blue, green, red, blue...) until the tail;
 *             going back, to the previous colour and then the nest.
 *             Around the tail (the reference is a tail member and no other
 *             member is perceived), or around the nest when no chain member
 *             is perceived, it becomes a chain member with probability
 *             p_join per step (P_e->c).  An explorer that perceives the
 *             food, no more than one chain member, and the object it is
 *             circling, joins at once (the prey rule) and never leaves;
 *   MEMBER    stands still and signals its colour (the predecessor's next
 *             colour; blue beside the nest), whether it is the tail (no
 *             member of the next colour perceived) and whether it perceives
 *             the food.  Only the tail leaves, with probability p_leave per
 *             step (P_c->e), and only when it perceives no explorer
 *             (reconstruction, a parameter) and not the food: unused chains
 *             thus vanish from the tail.  It becomes an explorer going back
 *             to the nest.  A member that loses its predecessor (and the
 *             nest) for lost_steps steps leaves too.
 *
 * This is also the chain model of TSASR (firmware/tsasr/tsasr.h), which is
 * PFIAS plus an elimination mechanism: params `elim` turns it on (with
 * TSASR's frames, PFIAS_FMT_RETREAT); PFIAS leaves it off, and then the
 * elimination's fields below are unused.
 *
 * Units: distances mm, angles mrad, wheel speeds steps/s, probabilities in
 * 1/65536 per control step (rng_chance).
 */
#ifndef FW_PFIAS_H
#define FW_PFIAS_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/random_walk.h"
#include "common/rng.h"

/** Neighbours remembered at once (the nest, the food, members, explorers). */
#define PFIAS_MAX_NEIGHBOURS 12u

typedef struct pfias_params {
    uint16_t p_join;        /**< P_e->c per step, /65536 */
    uint16_t p_leave;       /**< P_c->e per step, /65536 (tail members only) */
    uint16_t elim_steps;    /**< elim: steps a tail may go without the target before it is eliminated */
    uint16_t retreat_steps; /**< elim: steps an eliminated member shows `retreat` before it leaves */
    uint16_t range_mm;      /**< perception radius R: frames from farther are ignored */
    uint16_t link_mm;       /**< AD distance an explorer keeps from its reference
                                 (and so the length of a chain link) */
    int16_t speed_steps_s;  /**< forward wheel speed, steps/s (388 = 5 cm/s) */
    int16_t turn_gain;      /**< wheel speed difference per rad of heading error, steps/s */
    uint8_t forget_steps;   /**< a neighbour not heard for this many steps is forgotten */
    uint8_t lost_steps;     /**< steps without the reference before giving it up */
    uint8_t leave_needs_no_explorer; /**< 1: a tail leaves only when no explorer is perceived */
    uint8_t elim_cascade;   /**< elim: 1: a member whose successor left in retreat retreats too */
    uint8_t elim_explorer_resets; /**< elim: 1: a tail's timer restarts while it perceives an explorer */
    uint8_t elim;           /**< 0: PFIAS; 1: TSASR's elimination, and its frames (8-bit ids) */
    uint8_t role;           /**< pfias_role_t: swarm robot, or fixed nest/food source */
    random_walk_params_t walk;  /**< LOST's walk (its speed is speed_steps_s) */
} pfias_params_t;

/** What a robot is: a swarm robot, or a fixed source that only broadcasts. */
typedef enum pfias_role {
    PFIAS_ROLE_ROBOT = 0,
    PFIAS_ROLE_NEST = 1,
    PFIAS_ROLE_FOOD = 2
} pfias_role_t;

typedef enum pfias_state {
    PFIAS_LOST = 0,
    PFIAS_EXPLORER = 1,
    PFIAS_MEMBER = 2,
    PFIAS_SOURCE = 3      /**< a nest or food robot */
} pfias_state_t;

/** Where an explorer's reference is: the nest, or a chain member's colour. */
#define PFIAS_REF_NEST 3u

/** One neighbour heard lately (pfias_msg kinds). */
typedef struct pfias_neighbour {
    uint16_t id;            /**< sender id & 511 (elim: & 255) */
    uint8_t kind;           /**< pfias_kind_t; 0 = free slot */
    uint8_t colour, tail, prey, retreat;
    uint8_t age;            /**< steps since last heard */
    uint16_t range_mm;
    int16_t bearing_mrad;
} pfias_neighbour_t;

typedef struct pfias {
    pfias_params_t params;
    rng_t rng;
    uint32_t seed;
    random_walk_t walk;
    uint8_t state;          /**< pfias_state_t */
    uint8_t outward;        /**< explorer: 1 going to the tail, 0 back to the nest */
    uint8_t ref;            /**< explorer: PFIAS_REF_NEST or the colour circled */
    int8_t circle_sign;     /**< explorer: +1 circles counter-clockwise */
    uint8_t colour;         /**< member: its colour */
    uint8_t tail;           /**< member: no successor perceived */
    uint8_t prey;           /**< member: perceives the food (then never leaves) */
    uint8_t retreat;        /**< member (elim): being eliminated */
    uint8_t follow;         /**< member (elim): its last successor heard was retreating */
    uint8_t missing;        /**< steps the reference (explorer) or the predecessor
                                 (member) has not been perceived */
    uint16_t idle;          /**< member (elim): steps as the tail without the target;
                                 in retreat, steps since it was raised */
    uint32_t joins;         /**< times it became a chain member */
    uint32_t leaves;        /**< times it left a chain (any reason) */
    uint32_t eliminations;  /**< times it left a chain by elimination */
    pfias_neighbour_t nb[PFIAS_MAX_NEIGHBOURS];
} pfias_t;

/* The controller contract (controller.h); state names "lost", "explorer",
 * "member", "source". */
CONTROLLER_API(pfias);

/** The nearest remembered neighbour of `kind` (and, for chain frames,
 *  colour `colour`; PFIAS_COLOURS = any colour), or NULL. */
const pfias_neighbour_t *pfias_nearest(const pfias_t *self, uint8_t kind, uint8_t colour);

/** How many remembered neighbours are of `kind`. */
uint8_t pfias_count(const pfias_t *self, uint8_t kind);

/** The keys of the chain model's perception and motion (range_mm, link_mm,
 *  speed_steps_s, turn_gain, forget_steps, lost_steps) in a param_desc_t
 *  table over params type T (pfias_def.c, tsasr_def.c). */
#define PFIAS_CHAIN_PARAMS(T)                                                                     \
    { .key = "range_mm", PARAM_FIELD(T, range_mm, uint16_t), .min = 1, .max = 10000,              \
      .doc = "perception radius R: frames heard from farther are ignored, mm" },                  \
    { .key = "link_mm", PARAM_FIELD(T, link_mm, uint16_t), .min = 1, .max = 10000,                \
      .doc = "distance an explorer keeps from the object it circles (chain link), mm" },          \
    { .key = "speed_steps_s", PARAM_FIELD(T, speed_steps_s, int16_t), .min = 1, .max = 1000,      \
      .doc = "forward wheel speed, steps/s (388 = 5 cm/s)" },                                     \
    { .key = "turn_gain", PARAM_FIELD(T, turn_gain, int16_t), .min = 0, .max = 10000,             \
      .doc = "wheel speed difference per rad of heading error, steps/s" },                        \
    { .key = "forget_steps", PARAM_FIELD(T, forget_steps, uint8_t), .min = 1, .max = 255,         \
      .doc = "a neighbour not heard for this many steps is forgotten" },                          \
    { .key = "lost_steps", PARAM_FIELD(T, lost_steps, uint8_t), .min = 1, .max = 255,             \
      .doc = "steps without the reference (explorer) or predecessor (member) before giving up" }

#define PFIAS_NAME "pfias"
extern const observable_t pfias_observables[];
extern const controller_def_t pfias_def;

#endif
