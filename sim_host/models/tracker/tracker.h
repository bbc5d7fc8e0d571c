/*
 * tracker.h - an overhead tracker (a camera above the arena, a motion-capture
 * system) that tells every robot its pose: hal_pose.  Ground truth with
 * Gaussian noise on x, y and heading, and a chance per step of losing the
 * robot (HAL_ERR_UNAVAILABLE).  Off by default: a bare e-puck knows no pose.
 *
 * Scenario section `tracker`; each robot's draws come from its own stream
 * (RAND_TRACKER), taken only when its controller asks, so a run whose
 * controllers never ask is the same with the tracker on or off.
 */
#ifndef SIM_MODELS_TRACKER_H
#define SIM_MODELS_TRACKER_H

#include <stdint.h>

#include "models/model.h"

typedef struct tracker_config {
    uint8_t enabled;   /**< an overhead tracker gives hal_pose */
    float noise_mm;    /**< Gaussian sd of x and y, mm */
    float noise_deg;   /**< Gaussian sd of the heading, deg */
    float dropout;     /**< probability a step has no pose */
} tracker_config_t;

MODEL_CONFIG_ACCESSORS(tracker, tracker_config_t)

#endif
