/*
 * fake_drive.h - a differential-drive robot for controller tests on the
 * fake HAL: after each step the commanded wheel speeds (steps/s) move the
 * step counters (16-bit, wrapping, as on the e-puck) and the pose (mm,
 * rad, CCW from +x) over one control period.  Include after fake_hal.h.
 */
#ifndef TESTS_FAKE_DRIVE_H
#define TESTS_FAKE_DRIVE_H

#include <math.h>

#include "units.h"

typedef struct fake_drive {
    double x, y, th;         /* the robot's true pose, mm and rad */
    double acc_l, acc_r;     /* wheel steps so far, unwrapped */
} fake_drive_t;

static inline void fake_drive_start(fake_drive_t *d, double x, double y, double th)
{
    d->x = x;
    d->y = y;
    d->th = th;
    d->acc_l = d->acc_r = 0.0;
}

/* A step count on the e-puck's 16-bit counter. */
static inline int16_t fake_drive_wrap16(double steps)
{
    long v = (long)floor(steps);
    return (int16_t)(uint16_t)((unsigned long)v & 0xFFFFu);
}

/* One period of `period_ms` at the wheel speeds hal->left, hal->right. */
static inline void fake_drive_move(fake_drive_t *d, hal_t *hal, double period_ms)
{
    double dl = (double)hal->left * period_ms / 1000.0;
    double dr = (double)hal->right * period_ms / 1000.0;
    double ds = (dl + dr) / 2.0 * EPUCK_STEP_M * 1000.0;   /* mm */
    double dth = (dr - dl) * EPUCK_STEP_M / EPUCK_AXLE_M;
    d->acc_l += dl;
    d->acc_r += dr;
    hal->steps_left = fake_drive_wrap16(d->acc_l);
    hal->steps_right = fake_drive_wrap16(d->acc_r);
    d->x += ds * cos(d->th + dth / 2.0);
    d->y += ds * sin(d->th + dth / 2.0);
    d->th += dth;
}

/* An angle in (-pi, pi]. */
static inline double fake_drive_wrap_pi(double a)
{
    while (a > UNITS_PI) a -= 2.0 * UNITS_PI;
    while (a <= -UNITS_PI) a += 2.0 * UNITS_PI;
    return a;
}

#endif
