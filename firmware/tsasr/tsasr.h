/*
 * tsasr.h - TSASR, Luo, Guo, Ye et al.'s target search "based on robot
 * chains with elimination mechanism" (Int. J. Advanced Robotic Systems
 * 17(3), 2020, doi 10.1177/1729881420919954), a baseline of seed 003's
 * Figures 11-14, as a portable controller over the range-and-bearing turret.
 *
 * THIS IS A RECONSTRUCTION.  The paper's text was not found (only its
 * abstract: a robot-chain model and an elimination mechanism that keep the
 * swarm connected while it searches); docs/notes/i15_tsasr.md says what was
 * found and what every rule and constant below is reconstructed from.  In
 * short: PFIAS's chains (firmware/pfias/, which TSASR builds on) plus a
 * timed elimination of chains that found nothing:
 *
 *   LOST      random walk with obstacle avoidance until the nest or a chain
 *             member is perceived (within range_mm) (as PFIAS);
 *   EXPLORER  moves along chains about one member at a time at link_mm
 *             (adjust distance + move perpendicular + avoid obstacles),
 *             out to the tail by the colour pattern and back to the nest
 *             (as PFIAS).  At a tail that is not being eliminated (only
 *             that tail in view), or at a nest without a chain in view, it
 *             joins with probability p_join per step; perceiving the target
 *             and at most one member it joins at once (the prey rule).  An
 *             explorer going out that reaches a tail being eliminated turns
 *             back: the chain is not extended while it retracts;
 *   MEMBER    stands still and signals its colour, tail, prey and retreat
 *             flags.  Elimination: a tail that does not perceive the target
 *             counts the steps it has been the tail (with
 *             elim_explorer_resets, only the steps with no explorer in
 *             view); after elim_steps (the chain's frontier found nothing
 *             in that time) it raises
 *             `retreat`, and retreat_steps later it leaves the chain and
 *             goes back along it as an explorer.  With elim_cascade, a
 *             member whose successor left in retreat retreats at once in
 *             turn: the whole failed chain is eliminated from the tail to
 *             the nest, always connected, and its robots are free to grow
 *             a chain elsewhere.  A chain that reaches the target is never
 *             eliminated (its end perceives the target).  PFIAS's random
 *             leave of a tail (p_leave, only with no explorer in view) is
 *             kept as a parameter, and a member cut off from its
 *             predecessor for lost_steps leaves (as PFIAS).
 *
 * Units: distances mm, angles mrad, wheel speeds steps/s, probabilities in
 * 1/65536 per control step (rng_chance), times in control steps (100 ms).
 */
#ifndef FW_TSASR_H
#define FW_TSASR_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "common/random_walk.h"
#include "common/rng.h"

/** Neighbours remembered at once (the nest, the food, members, explorers). */
#define TSASR_MAX_NEIGHBOURS 12u

typedef struct tsasr_params {
    uint16_t p_join;        /**< explorer -> member per step at a tail or chainless nest, /65536 */
    uint16_t p_leave;       /**< PFIAS's P_c->e: a tail leaves at random per step, /65536 */
    uint16_t elim_steps;    /**< steps a tail may go without the target before it is eliminated */
    uint16_t retreat_steps; /**< steps an eliminated member shows `retreat` before it leaves */
    uint16_t range_mm;      /**< perception radius R: frames from farther are ignored */
    uint16_t link_mm;       /**< AD distance an explorer keeps from its reference (a chain link) */
    int16_t speed_steps_s;  /**< forward wheel speed, steps/s (388 = 5 cm/s) */
    int16_t turn_gain;      /**< wheel speed difference per rad of heading error, steps/s */
    uint8_t forget_steps;   /**< a neighbour not heard for this many steps is forgotten */
    uint8_t lost_steps;     /**< steps without the reference before giving it up */
    uint8_t leave_needs_no_explorer; /**< 1: p_leave only when no explorer is perceived */
    uint8_t elim_cascade;   /**< 1: a member whose successor left in retreat retreats too */
    uint8_t elim_explorer_resets; /**< 1: a tail's timer restarts while it perceives an explorer */
    uint8_t role;           /**< tsasr_role_t: swarm robot, or fixed nest/food source */
    random_walk_params_t walk;  /**< LOST's walk (its speed is speed_steps_s) */
} tsasr_params_t;

/** What a robot is: a swarm robot, or a fixed source that only broadcasts. */
typedef enum tsasr_role {
    TSASR_ROLE_ROBOT = 0,
    TSASR_ROLE_NEST = 1,
    TSASR_ROLE_FOOD = 2
} tsasr_role_t;

typedef enum tsasr_state {
    TSASR_LOST = 0,
    TSASR_EXPLORER = 1,
    TSASR_MEMBER = 2,
    TSASR_SOURCE = 3      /**< a nest or food robot */
} tsasr_state_t;

/** Where an explorer's reference is: the nest, or a chain member's colour. */
#define TSASR_REF_NEST 3u

/** One neighbour heard lately (tsasr_msg kinds). */
typedef struct tsasr_neighbour {
    uint8_t id;             /**< sender id & 255 */
    uint8_t kind;           /**< tsasr_kind_t; 0 = free slot */
    uint8_t colour, tail, prey, retreat;
    uint8_t age;            /**< steps since last heard */
    uint16_t range_mm;
    int16_t bearing_mrad;
} tsasr_neighbour_t;

typedef struct tsasr {
    tsasr_params_t params;
    rng_t rng;
    uint32_t seed;
    random_walk_t walk;
    uint8_t state;          /**< tsasr_state_t */
    uint8_t outward;        /**< explorer: 1 going to the tail, 0 back to the nest */
    uint8_t ref;            /**< explorer: TSASR_REF_NEST or the colour circled */
    int8_t circle_sign;     /**< explorer: +1 circles counter-clockwise */
    uint8_t colour;         /**< member: its colour */
    uint8_t tail;           /**< member: no successor perceived */
    uint8_t prey;           /**< member: perceives (has perceived) the target: never leaves */
    uint8_t retreat;        /**< member: being eliminated */
    uint8_t follow;         /**< member: its last successor heard was retreating */
    uint8_t missing;        /**< steps the reference (explorer) or the predecessor
                                 (member) has not been perceived */
    uint16_t idle;          /**< member: steps as the tail without the target;
                                 in retreat, steps since it was raised */
    uint32_t joins;         /**< times it became a chain member */
    uint32_t leaves;        /**< times it left a chain (any reason) */
    uint32_t eliminations;  /**< times it left a chain by elimination */
    tsasr_neighbour_t nb[TSASR_MAX_NEIGHBOURS];
} tsasr_t;

/* The controller contract (controller.h); state names "lost", "explorer",
 * "member", "source". */
CONTROLLER_API(tsasr);

/** The nearest remembered neighbour of `kind` (and, for chain frames,
 *  colour `colour`; TSASR_COLOURS = any colour), or NULL. */
const tsasr_neighbour_t *tsasr_nearest(const tsasr_t *self, uint8_t kind, uint8_t colour);

/** How many remembered neighbours are of `kind`. */
uint8_t tsasr_count(const tsasr_t *self, uint8_t kind);

#define TSASR_NAME "tsasr"
extern const observable_t tsasr_observables[];
extern const controller_def_t tsasr_def;

#endif
