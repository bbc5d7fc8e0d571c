/*
 * wheels.h - the e-puck's two stepper motors and their noise (section
 * `wheels`): hal_set_wheel_speeds sets the commanded speeds (clamped to
 * +-HAL_WHEEL_SPEED_MAX), hal_wheel_steps counts the commanded steps (16
 * bits, wrapping), and at each step's drive phase the commands become the
 * body's velocity for Box2D (differential drive), through ARGoS's
 * actuation-noise model as seed 003's eq 3 reads: a = f (w + b) per wheel,
 * w the command, f ~ N(1, speed_noise_rel) drawn every step, b ~ N(0,
 * bias_sd) drawn once per robot and wheel per run (or every step with
 * bias_per_step).  Faults act on it (faults.h: stop, stall, drift).
 */
#ifndef SIM_MODELS_WHEELS_H
#define SIM_MODELS_WHEELS_H

#include <stdint.h>

#include "models/model.h"

typedef struct wheels_config {
    float speed_noise_rel;     /**< per-wheel relative speed noise (sd): f's sd */
    float bias_sd;             /**< sd of each wheel's bias b, m/s; 0 = none */
    uint8_t bias_per_step;     /**< 1: b drawn anew every control step (a reading of
                                    eq 3 other than ARGoS's once-a-run bias) */
} wheels_config_t;

MODEL_CONFIG_ACCESSORS(wheels, wheels_config_t)

#endif
