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
 *
 * The code is PFIAS's (firmware/pfias/pfias.c) with its params `elim` on:
 * tsasr_t is pfias_t, and tsasr.c sets the elimination's parameters and
 * registers the controller with its keys and observables.
 */
#ifndef FW_TSASR_H
#define FW_TSASR_H

#include <stdint.h>

#include "hal.h"
#include "common/controller.h"
#include "pfias/pfias.h"
#include "tsasr/tsasr_msg.h"

/** Neighbours remembered at once (the nest, the food, members, explorers). */
#define TSASR_MAX_NEIGHBOURS PFIAS_MAX_NEIGHBOURS

/** PFIAS's parameters (pfias.h), with `elim` = 1 and the elimination's:
 *  elim_steps, retreat_steps, elim_cascade, elim_explorer_resets. */
typedef pfias_params_t tsasr_params_t;

/** What a robot is: a swarm robot, or a fixed source that only broadcasts. */
typedef pfias_role_t tsasr_role_t;
#define TSASR_ROLE_ROBOT PFIAS_ROLE_ROBOT
#define TSASR_ROLE_NEST PFIAS_ROLE_NEST
#define TSASR_ROLE_FOOD PFIAS_ROLE_FOOD

typedef pfias_state_t tsasr_state_t;
#define TSASR_LOST PFIAS_LOST
#define TSASR_EXPLORER PFIAS_EXPLORER
#define TSASR_MEMBER PFIAS_MEMBER
#define TSASR_SOURCE PFIAS_SOURCE

/** Where an explorer's reference is: the nest, or a chain member's colour. */
#define TSASR_REF_NEST PFIAS_REF_NEST

/** One neighbour heard lately (tsasr_msg kinds; ids & 255). */
typedef pfias_neighbour_t tsasr_neighbour_t;

/** PFIAS's state, with the elimination's fields (retreat, follow, idle,
 *  eliminations) in use. */
typedef pfias_t tsasr_t;

/* The controller contract (controller.h); state names "lost", "explorer",
 * "member", "source". */
CONTROLLER_API(tsasr);

/** The nearest remembered neighbour of `kind` (and, for chain frames,
 *  colour `colour`; TSASR_COLOURS = any colour), or NULL; how many
 *  remembered neighbours are of `kind`: PFIAS's. */
#define tsasr_nearest pfias_nearest
#define tsasr_count pfias_count

#define TSASR_NAME "tsasr"
extern const observable_t tsasr_observables[];
extern const controller_def_t tsasr_def;

#endif
