/*
 * phototaxis.h - the example controller of the tutorial "Your first
 * controller": drive to the brightest light, stop under it.
 *
 * States:
 *   SEEK     steer towards the ambient sensor that reads the most light
 *            (the smallest raw value), turning in place when it is behind;
 *            in the dark, drive straight on.
 *   AVOID    a front IR sensor reads above avoid_enter: turn in place away
 *            from it until every front sensor is below avoid_exit.
 *   ARRIVED  the light is brighter than arrive_level: stop, body LED on,
 *            until it falls below leave_level (hysteresis), then SEEK.
 * It shows (observables): the brightest ambient reading, the bearing of its
 * sensor, and a counter of arrivals.
 */
#ifndef FW_PHOTOTAXIS_H
#define FW_PHOTOTAXIS_H

#include <stdint.h>

#include "common/controller.h"
#include "hal.h"

typedef struct phototaxis_params {
    int16_t speed_steps_s;     /**< forward wheel speed, steps/s (400) */
    int16_t steer_gain;        /**< wheel speed difference per rad of bearing, steps/s (300) */
    uint16_t arrive_level;     /**< ambient below this: arrived, counts (800) */
    uint16_t leave_level;      /**< ambient above this: seek again, counts (1200) */
    uint16_t avoid_enter;      /**< front proximity that starts avoiding, counts (300) */
    uint16_t avoid_exit;       /**< front proximity that ends it, counts (150) */
} phototaxis_params_t;

typedef enum phototaxis_state {
    PHOTOTAXIS_SEEK = 0,
    PHOTOTAXIS_AVOID = 1,
    PHOTOTAXIS_ARRIVED = 2
} phototaxis_state_t;

typedef struct phototaxis {
    phototaxis_params_t params;
    uint32_t seed;               /**< kept by the contract; it draws nothing */
    uint8_t state;               /**< phototaxis_state_t */
    int8_t turn_sign;            /**< AVOID: +1 counter-clockwise, -1 clockwise */
    uint16_t brightest;          /**< smallest ambient reading this step, counts */
    int16_t light_bearing_mrad;  /**< bearing of that sensor */
    uint32_t arrivals;           /**< times it reached the light */
} phototaxis_t;

/* The controller contract (controller.h): default_params as in the
 * comments above; init copies params, keeps seed, resets; reset: SEEK,
 * no arrivals; step: one control period; state_name "seek", "avoid",
 * "arrived". */
CONTROLLER_API(phototaxis);

#define PHOTOTAXIS_NAME "phototaxis"
extern const observable_t phototaxis_observables[];
extern const controller_def_t phototaxis_def;

#endif
