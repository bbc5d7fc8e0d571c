/*
 * ground.h - the ground-sensor module of the e-puck (GCtronic's extension
 * for the e-puck1 and e-puck2): three IR emitter/receivers under the front
 * of the robot, looking down, that measure how much IR the floor reflects
 * (hal_ground).  A robot carries the module when its group says so
 * (`robots[].ground_sensors: true`); on the others hal_ground answers
 * HAL_ERR_UNAVAILABLE.
 *
 * The floor (section `ground`): a grey level everywhere (`floor`, the IR
 * reflectance: 1 white paper, 0 black) and regions of their own grey level
 * (`regions`, discs and boxes, the last listed on top); a task may declare
 * its own regions when it is created (ground_add_region: a nest or a food
 * area drawn on the floor).  docs/models/ground-sensors.md gives the
 * sources of every number.
 *
 * Sensor k reads black + (white - black) R, R the reflectance of the floor
 * under it, with Gaussian noise of sd noise_rel times the value plus
 * noise_abs counts, rounded and clamped to 0..4095, once per control step
 * and only when the controller asks; the draws come from the robot's own
 * stream, so a run whose controllers never ask is unchanged.
 */
#ifndef SIM_MODELS_GROUND_H
#define SIM_MODELS_GROUND_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"

/** Where the sensors are, robot frame (x ahead, y to the left), m: 30 mm
 *  ahead of the axle, 10 mm apart, GS0 on the left (ARGoS's Pi-puck
 *  ground sensor, the same module; Webots' E-puckGroundSensors: 10 mm
 *  apart). */
#define GROUND_SENSOR_AHEAD_M 0.030f
#define GROUND_SENSOR_SPACING_M 0.010f

/** Most regions a scenario lists (tasks may add more). */
#define GROUND_MAX_REGIONS 256u

typedef enum ground_shape { GROUND_DISC = 0, GROUND_BOX = 1 } ground_shape_t;

/** An area of the floor with its own grey level. */
typedef struct ground_region {
    int shape;                 /**< ground_shape_t: "disc" or "box" */
    float x, y;                /**< centre, m */
    float radius;              /**< disc, m */
    float width, depth;        /**< box sides along its x and y, m */
    float angle;               /**< box rotation, deg CCW */
    float reflectance;         /**< IR reflectance, 0 (black) to 1 (white) */
} ground_region_t;

/** Section `ground`. */
typedef struct ground_config {
    float floor;               /**< reflectance of the bare floor */
    float white;               /**< counts over reflectance 1 */
    float black;               /**< counts over reflectance 0 */
    float noise_rel;           /**< relative Gaussian sd of the value */
    float noise_abs;           /**< additive Gaussian sd, counts */
    uint32_t region_count;
    ground_region_t *regions;  /**< on the heap (scenario_free frees them) */
} ground_config_t;

/** A group's key. */
typedef struct ground_group_config {
    uint8_t fitted;            /**< its robots carry the module (`ground_sensors`) */
} ground_group_config_t;

MODEL_CONFIG_ACCESSORS(ground, ground_config_t)

/** Adds a region on top of the scenario's for this run (a task's create:
 *  its nest or food area).  Returns 0, or -1 out of memory. */
int ground_add_region(sim_t *sim, const ground_region_t *region);

/** The reflectance of the floor at (x, y), m: the topmost region holding
 *  the point, else the floor's. */
float ground_reflectance(const sim_t *sim, float x, float y);

#endif
