/*
 * odometry.h - dead reckoning from the wheel step counters
 * (hal_wheel_steps), in integers, and the integer trigonometry it needs.
 *
 * RepAtt's homing cue (seed 002 assumes a nest that broadcasts a homing
 * signal): a real e-puck has its two step counters everywhere in a world of
 * any size, needs no beacon, and the simulator gives the same counters.
 * The pose is kept in the robot's start frame: the start point is the
 * origin, x straight ahead at the start, y to the start's left, heading
 * counter-clockwise from x.  The counters count commanded motor steps, so
 * a wheel that slips or is blocked (pushing another robot) still counts:
 * the error grows with every collision (hence the unloading radius,
 * home_radius_mm).
 *
 * One wheel step is pi x 41 mm / 1000 = 0.12881 mm; the wheels are 53 mm
 * apart (hal/units.h).  Position in micrometres, heading in microradians
 * (int32), so that the per-step rounding does not accumulate.
 */
#ifndef FW_ODOMETRY_H
#define FW_ODOMETRY_H

#include <stdint.h>

/** A counter change larger than this in one control period is not a
 *  motion (1000 steps/s at most): it is taken as this. */
#define ODO_MAX_STEP_DELTA 4000

/** Positions are kept within +- this, micrometres (1 km). */
#define ODO_LIMIT_UM 1000000000L

typedef struct odometry {
    int32_t x_um;           /**< from the start point, start frame, um */
    int32_t y_um;
    int32_t heading_urad;   /**< CCW from the start heading, (-pi, pi], urad */
    int16_t last_left;      /**< counters at the last update */
    int16_t last_right;
    uint8_t primed;         /**< the counters have been read once */
} odometry_t;

/** At the start point, heading 0; the next update only reads the counters. */
void odometry_reset(odometry_t *o);

/** Integrates the counters' change since the last update (16-bit wrap
 *  handled) and gives it in *d_left, *d_right (steps). */
void odometry_update(odometry_t *o, int16_t left, int16_t right, int16_t *d_left, int16_t *d_right);

/** Bearing of the start point from the robot, robot frame, mrad in
 *  (-3142, 3142], CCW positive; 0 at the start point itself. */
int16_t odometry_home_bearing_mrad(const odometry_t *o);

/** 1 when the start point is within `radius_mm` of the robot. */
uint8_t odometry_within_mm(const odometry_t *o, uint16_t radius_mm);

/** sin of an angle in mrad (any value), Q14 (16384 = 1), table with
 *  linear interpolation: within 1e-4. */
int16_t odo_sin_q14(int32_t mrad);
int16_t odo_cos_q14(int32_t mrad);

/** atan2(y, x) in mrad, (-3142, 3142], within 5 mrad; 0 for (0, 0). */
int16_t odo_atan2_mrad(int32_t y, int32_t x);

/** An angle in mrad wrapped to (-3142, 3142]. */
int32_t odo_wrap_mrad(int32_t mrad);

/** now - last on 16-bit step counters that wrap, in [-32768, 32767], then
 *  limited to what a wheel can do in a period (+-ODO_MAX_STEP_DELTA). */
int16_t odo_counter_delta(int16_t now, int16_t last);

#endif
