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
 */
#ifndef SIM_MODELS_IR_H
#define SIM_MODELS_IR_H

#include <stdint.h>

#include "models/model.h"

typedef struct ir_config {
    float aperture;            /**< half-angle of the sensing cone, deg */
    float range;               /**< beyond this the sensor reads ~0, m */
    float noise_rel;           /**< relative Gaussian sd of the value */
    float noise_abs;           /**< additive Gaussian sd, raw counts */
    struct {
        float dark;            /**< raw reading in the dark, counts */
        float half;            /**< irradiance at which the reading halves */
        float noise_rel;       /**< relative Gaussian sd */
    } ambient;                 /**< section `ambient` */
} ir_config_t;

MODEL_CONFIG_ACCESSORS(ir, ir_config_t)

/** Noise-free calibrated proximity at distance d (m) from a surface. */
float ir_curve(float d, float range);

#endif
