/*
 * wheels.h - the e-puck's two stepper motors and their noise (section
 * `wheels`): hal_set_wheel_speeds sets the commanded speeds (clamped to
 * +-HAL_WHEEL_SPEED_MAX), hal_wheel_steps counts the commanded steps (16
 * bits, wrapping), and at each step's drive phase the commands become the
 * body's velocity for Box2D (differential drive), through ARGoS's
 * actuation-noise model as seed 003's eq 3 reads: a = f (w + b) per wheel,
 * w the command, f ~ N(1, speed_noise_rel) drawn every step, b ~ N(0,
 * bias_sd) drawn once per robot and wheel per run (or every step with
 * bias_per_step).  A wheel's gain (its true diameter over the nominal)
 * scales the speed it achieves, not the steps counted: per robot id in
 * `robots` (the calibration kit's fit).  Faults act on it (faults.h: stop,
 * stall, drift).
 */
#ifndef SIM_MODELS_WHEELS_H
#define SIM_MODELS_WHEELS_H

#include <stdint.h>

#include "models/model.h"

/** One robot's wheels as fitted (`wheels.robots`, models/per_robot.h):
 *  NaN takes the section's. */
typedef struct wheels_robot_cal {
    uint16_t id;               /**< hal_robot_id */
    float gain_left, gain_right;
    float speed_noise_rel;
} wheels_robot_cal_t;

typedef struct wheels_config {
    float speed_noise_rel;     /**< per-wheel relative speed noise (sd): f's sd */
    float bias_sd;             /**< sd of each wheel's bias b, m/s; 0 = none */
    uint8_t bias_per_step;     /**< 1: b drawn anew every control step (a reading of
                                    eq 3 other than ARGoS's once-a-run bias) */
    float gain_left;           /**< actual / commanded wheel speed (a wheel's true diameter
                                    over the nominal 41 mm; the steps counted are as commanded) */
    float gain_right;
    uint32_t robot_count;      /**< `robots` */
    wheels_robot_cal_t *robots;   /**< on the heap (free_config) */
} wheels_config_t;

MODEL_CONFIG_ACCESSORS(wheels, wheels_config_t)

#endif
