/*
 * sim.h - one simulation run: a Box2D world of e-pucks, each running its
 * firmware controller through the simulator's hal_t.
 *
 * Ownership: sim_create copies nothing it does not need; the scenario must
 * outlive the sim.  Not thread-safe: one sim is stepped by one thread, but
 * different sims run concurrently without sharing anything.
 */
#ifndef SIM_SIM_H
#define SIM_SIM_H

#include <stdint.h>

#include "hal.h"
#include "scenario.h"

typedef struct sim sim_t;

/** e-puck body radius, m (70 mm diameter). */
#define SIM_ROBOT_RADIUS 0.035f
/** Wheel travel per motor step, m (pi * 41 mm / 1000). */
#define SIM_STEP_M (3.14159265358979 * 0.041 / 1000.0)
/** Axle length (wheel separation), m. */
#define SIM_AXLE_M 0.053

/** Ground-truth observations of a run (never the robots' beliefs). */
typedef struct sim_metrics {
    uint64_t robot_contacts;      /**< robot-robot contacts begun */
    uint64_t static_contacts;     /**< robot-wall/obstacle contacts begun */
    double distance_m;            /**< summed path length of all robots, m */
    double min_wall_clearance_m;  /**< smallest body-to-wall gap seen, m (<0: overlap) */
    uint32_t escaped;             /**< robots ever outside the arena */
} sim_metrics_t;

/** Builds the world for run seed `seed`.  Returns NULL with a message in
 *  `err` (e.g. robots that cannot be placed). */
sim_t *sim_create(const scenario_t *sc, uint64_t seed, char err[256]);
void sim_destroy(sim_t *sim);

/** One control period: every controller steps (in robot-id order), IR
 *  messages are delivered, then physics advances. */
void sim_step(sim_t *sim);

uint64_t sim_step_count(const sim_t *sim);
/** All robots, the nest beacon included (it is the last one). */
uint32_t sim_robot_count(const sim_t *sim);
/** Robots running the scenario's controller: indices 0 .. count-1. */
uint32_t sim_swarm_count(const sim_t *sim);
/** Index of the nest-beacon robot, or -1. */
int32_t sim_beacon_index(const sim_t *sim);
const scenario_t *sim_scenario(const sim_t *sim);

/** The hal_t of robot `i`, to drive a robot from a test. */
hal_t *sim_robot_hal(sim_t *sim, uint32_t i);
/** The controller state of robot `i` (NULL for the idle controller). */
void *sim_robot_controller(sim_t *sim, uint32_t i);

/** Pose of robot `i`: m, m, rad (CCW from +x). */
void sim_robot_pose(const sim_t *sim, uint32_t i, double *x, double *y, double *theta);
/** Teleports robot `i` (tests and placement). */
void sim_set_robot_pose(sim_t *sim, uint32_t i, double x, double y, double theta);
/** LED state of robot `i`: bit k = ring LED k; bit 8 body; bit 9 front. */
uint16_t sim_robot_leds(const sim_t *sim, uint32_t i);

/** Seed 000's task state of robot `i`: 'W', 'S', 'R', or 0 (none);
 *  'B' for the nest beacon. */
char sim_robot_task_state(const sim_t *sim, uint32_t i);

/** Sum of the swarm robots' own obstacle-avoidance counts. */
uint64_t sim_oae_total(const sim_t *sim);

const sim_metrics_t *sim_metrics(const sim_t *sim);

struct foraging;
/** The foraging task's ground truth (foraging.h), or NULL when disabled. */
const struct foraging *sim_foraging(const sim_t *sim);

/** FNV-1a hash of every robot's pose bits and counters: equal hashes mean
 *  bit-identical runs. */
uint64_t sim_state_hash(const sim_t *sim);

#endif
