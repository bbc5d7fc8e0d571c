/*
 * ir.h - the e-puck's eight TCRT1000 IR sensors (sections `ir` and
 * `ambient`): each measures proximity (the reflection of its own emitter
 * off the nearest surface within its cone: other robots' bodies,
 * obstacles, walls) and ambient light (the scenario's lamps).  Calibrated
 * to the facts of hal/units.h and EPUCK.md: Webots' measured proximity
 * curve, relative and additive noise; the ambient reading falls as light
 * rises.  Each is computed at most once per control step per robot, and
 * only when the controller asks.  The two readings draw from one stream
 * per robot (RAND_SENSORS), in the order the controller asks for them.
 * A lab's robots differ (IR sensors by a factor of two): each sensor's
 * curve has a gain and an offset (`sensors`), and a robot id its own
 * (`robots`, models/per_robot.h), which the calibration kit fits.
 */
#ifndef SIM_MODELS_IR_H
#define SIM_MODELS_IR_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"

/** One sensor's response as fitted: gain * (the table's curve) + offset. */
typedef struct ir_sensor_cal {
    float gain;                /**< times the table's value */
    float offset;              /**< added, counts (what it reads with nothing in range) */
} ir_sensor_cal_t;

/** One robot's proximity parameters (`ir.robots`, per_robot.h): NaN or no
 *  `sensors` take the section's. */
typedef struct ir_robot_cal {
    uint16_t id;               /**< hal_robot_id */
    float noise_rel, noise_abs;
    uint32_t sensor_count;     /**< 0, or HAL_IR_COUNT */
    ir_sensor_cal_t sensor[HAL_IR_COUNT];
} ir_robot_cal_t;

/** One robot's ambient-light parameters (`ambient.robots`). */
typedef struct ambient_robot_cal {
    uint16_t id;
    float dark, half, noise_rel;
} ambient_robot_cal_t;

typedef struct ir_config {
    float aperture;            /**< half-angle of the sensing cone, deg */
    float range;               /**< beyond this the sensor reads ~0, m */
    float noise_rel;           /**< relative Gaussian sd of the value */
    float noise_abs;           /**< additive Gaussian sd, raw counts */
    int noise_draws;           /**< noise_draws_t: the two parts drawn apart, or one draw of their sum */
    uint32_t sensor_count;     /**< `sensors`: 0 (gain 1, offset 0) or HAL_IR_COUNT */
    ir_sensor_cal_t sensor[HAL_IR_COUNT];
    uint32_t robot_count;      /**< `robots` */
    ir_robot_cal_t *robots;    /**< on the heap (free_config) */
    struct {
        float dark;            /**< raw reading in the dark, counts */
        float half;            /**< irradiance at which the reading halves */
        float noise_rel;       /**< relative Gaussian sd */
        uint32_t robot_count;  /**< `robots` */
        ambient_robot_cal_t *robots;   /**< on the heap */
    } ambient;                 /**< section `ambient` */
} ir_config_t;

MODEL_CONFIG_ACCESSORS(ir, ir_config_t)

/** Noise-free calibrated proximity at distance d (m) from a surface. */
float ir_curve(float d, float range);

#endif
