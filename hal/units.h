/*
 * units.h - e-puck geometry and integer unit conversions shared by the
 * firmware and the simulator (no floating point: the dsPIC has no FPU).
 */
#ifndef HAL_UNITS_H
#define HAL_UNITS_H

#include <stdint.h>

/** Wheel diameter, micrometres (41 mm). */
#define EPUCK_WHEEL_DIAMETER_UM 41000L
/** Distance between the wheels, micrometres (53 mm). */
#define EPUCK_AXLE_UM 53000L
/** Motor steps per wheel revolution. */
#define EPUCK_STEPS_PER_REV 1000L
/** Body diameter, micrometres (70 mm). */
#define EPUCK_BODY_DIAMETER_UM 70000L
/** IR sensors: on a circle of this radius around the centre, this high
 *  above the floor, micrometres (about 33 mm and 33 mm, as in the
 *  public Webots and Enki e-puck models). */
#define EPUCK_IR_MOUNT_RADIUS_UM 33000L
#define EPUCK_IR_HEIGHT_UM 33000L
/** The camera lens above the floor, micrometres (our estimate: the lens
 *  sits below the ring of IR sensors; used for the apparent height of
 *  objects in blob pixel counts). */
#define EPUCK_CAMERA_HEIGHT_UM 30000L

/** IR sensor bearings IR0..IR7, degrees counter-clockwise from straight
 *  ahead (GCtronic's e-puck documentation, the Webots model): the one
 *  list, X(deg) for each sensor in turn; everything else derives from it. */
#define EPUCK_IR_BEARINGS(X) X(-17) X(-50) X(-90) X(-150) X(150) X(90) X(50) X(17)
#define EPUCK_IR_DEG_ITEM(deg) deg,
/** The bearings as an initialiser, degrees. */
#define EPUCK_IR_BEARINGS_DEG { EPUCK_IR_BEARINGS(EPUCK_IR_DEG_ITEM) }

/** `deg` (an integer constant, |deg| <= 180) in milliradians, rounded to
 *  nearest, as a constant expression: pi/180 = 314159 / 18000000 to 6
 *  digits, exact enough for every e-puck bearing. */
#define UNITS_DEG_TO_MRAD(deg) \
    ((int16_t)(((int32_t)(deg) * 314159L + ((deg) < 0 ? -9000L : 9000L)) / 18000L))

/** Bearing of IR sensor `index` in milliradians, rounded to nearest
 *  (integer arithmetic only); 0 for an index out of range. */
int16_t units_ir_bearing_mrad(uint8_t index);

/** pi, a quarter turn and a full turn in milliradians, rounded. */
#define UNITS_PI_MRAD 3142
#define UNITS_HALF_PI_MRAD 1571
#define UNITS_TWO_PI_MRAD 6283

/* The same facts in floating point, for the simulator and host tools (the
 * firmware uses the integer forms above), derived from them. */
#define UNITS_PI 3.14159265358979323846
/** Body radius, m (float: the simulator's geometry is float). */
#define EPUCK_BODY_RADIUS_M ((float)(EPUCK_BODY_DIAMETER_UM / 2) / 1e6f)
/** Wheel travel per motor step, m (pi * 41 mm / 1000). */
#define EPUCK_STEP_M (UNITS_PI * (double)EPUCK_WHEEL_DIAMETER_UM / 1e6 / (double)EPUCK_STEPS_PER_REV)
/** Axle length (wheel separation), m. */
#define EPUCK_AXLE_M ((double)EPUCK_AXLE_UM / 1e6)
#define EPUCK_IR_MOUNT_RADIUS_M ((float)EPUCK_IR_MOUNT_RADIUS_UM / 1e6f)
#define EPUCK_IR_HEIGHT_M ((float)EPUCK_IR_HEIGHT_UM / 1e6f)
#define EPUCK_CAMERA_HEIGHT_M ((float)EPUCK_CAMERA_HEIGHT_UM / 1e6f)
/** The camera frame of the e-puck image: 40 x 20 pixels (platforms/epuck1/hal). */
#define EPUCK_CAMERA_WIDTH_PX 40u
#define EPUCK_CAMERA_HEIGHT_PX 20u

/** Millimetres travelled by a wheel for `steps` motor steps
 *  (0.12881 mm per step), rounded toward zero.  |steps| <= 1,000,000. */
int32_t units_steps_to_mm(int32_t steps);

/** Motor steps for a wheel to travel `mm`, rounded to nearest.
 *  |mm| <= 200,000. */
int32_t units_mm_to_steps(int32_t mm);

/** Steps each wheel makes (in opposite directions) to turn the robot in
 *  place by `mrad` milliradians, rounded to nearest.  |mrad| <= 1,000,000. */
int32_t units_turn_mrad_to_steps(int32_t mrad);

/** Wheel speed in steps/s for a ground speed in mm/s, rounded to nearest. */
int16_t units_mm_s_to_steps_s(int16_t mm_s);

/** Steps a wheel at `steps_s` makes in `period_ms`, rounded toward zero. */
int32_t units_steps_in_period(int16_t steps_s, uint16_t period_ms);

#endif
