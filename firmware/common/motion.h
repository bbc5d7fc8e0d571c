/*
 * motion.h - wheel-speed arithmetic the controllers share: a speed within
 * the wheels' range, a time in whole control periods, and a speed that
 * stops a counted turn or run on its last step.
 */
#ifndef FW_MOTION_H
#define FW_MOTION_H

#include <stdint.h>

#include "hal.h"

/** `v` within the wheels' range, +-HAL_WHEEL_SPEED_MAX steps/s. */
int16_t motion_clamp_speed(int32_t v);

/** Control periods of `ms` at this platform's period, rounded up; at
 *  least 1 (a zero period counts as 1 ms). */
uint16_t motion_periods(hal_t *hal, uint16_t ms);

/** `speed` (steps/s, > 0), lowered so that one period makes at most
 *  `remaining` steps; 0 when nothing remains. */
int16_t motion_capped_speed(hal_t *hal, int16_t speed, int32_t remaining);

#endif
