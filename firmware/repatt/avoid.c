#include "avoid.h"

#include "common/motion.h"
#include "units.h"
#include "odometry.h"

/* IR sensors: the front pair, and each side's two (hal.h's bearings). */
#define IR_FRONT_RIGHT 0u
#define IR_RIGHT_50 1u
#define IR_RIGHT_90 2u
#define IR_LEFT_90 5u
#define IR_LEFT_50 6u
#define IR_FRONT_LEFT 7u

void avoid_reset(avoid_t *a)
{
    a->target2 = 0;
    a->done2 = 0;
    a->turn_sign = 1;
}

void avoid_count(avoid_t *a, uint8_t phase, int32_t d_left, int32_t d_right)
{
    if (phase == AVOID_TURNING) {
        a->done2 += (int32_t)a->turn_sign * (d_right - d_left);
    } else if (phase == AVOID_RUNNING) {
        a->done2 += d_left + d_right;
    }
}

uint8_t avoid_obstacle(hal_t *hal, uint16_t avoid_enter)
{
    uint16_t e = avoid_enter;
    uint16_t fr = hal_ir_proximity(hal, IR_FRONT_RIGHT);
    uint16_t fl = hal_ir_proximity(hal, IR_FRONT_LEFT);
    uint16_t r1 = hal_ir_proximity(hal, IR_RIGHT_50), r2 = hal_ir_proximity(hal, IR_RIGHT_90);
    uint16_t l1 = hal_ir_proximity(hal, IR_LEFT_50), l2 = hal_ir_proximity(hal, IR_LEFT_90);
    uint16_t right = (r1 > r2) ? r1 : r2;
    uint16_t left = (l1 > l2) ? l1 : l2;
    if (fr > e || fl > e) {
        return (uint8_t)AVOID_FRONT;
    }
    if (right > e || left > e) {
        return (uint8_t)((right >= left) ? AVOID_RIGHT : AVOID_LEFT);
    }
    return (uint8_t)AVOID_NONE;
}

void avoid_turn_by(avoid_t *a, int32_t mrad)
{
    mrad = odo_wrap_mrad(mrad);
    a->turn_sign = (mrad >= 0) ? (int8_t)1 : (int8_t)-1;
    a->target2 = 2 * units_turn_mrad_to_steps(mrad >= 0 ? mrad : -mrad);
    a->done2 = 0;
}

void avoid_start_turn(avoid_t *a, rng_t *rng, uint8_t where, uint16_t side_turn_mrad)
{
    int32_t mrad;
    if (where == AVOID_FRONT) {
        /* Greater than 90 deg, up to 180, either way. */
        mrad = rng_range(rng, UNITS_HALF_PI_MRAD + 1, UNITS_PI_MRAD);
        if ((rng_next(rng) & 1u) != 0u) {
            mrad = -mrad;
        }
    } else {
        /* Away from the side: to the left (CCW) for an obstacle on the right. */
        mrad = (where == AVOID_RIGHT) ? (int32_t)side_turn_mrad : -(int32_t)side_turn_mrad;
    }
    avoid_turn_by(a, mrad);
}

void avoid_start_run(avoid_t *a, rng_t *rng, uint16_t oa_run_max_mm)
{
    avoid_start_run_mm(a, rng_range(rng, 0, (int32_t)oa_run_max_mm));
}

void avoid_start_run_mm(avoid_t *a, int32_t mm)
{
    a->target2 = 2 * units_mm_to_steps(mm);
    a->done2 = 0;
}

uint8_t avoid_turn_step(avoid_t *a, hal_t *hal, int16_t turn_speed_steps_s)
{
    int16_t w = motion_capped_speed(hal, turn_speed_steps_s, (a->target2 - a->done2 + 1) / 2);
    if (a->done2 >= a->target2 || w <= 0) {
        return 0u;
    }
    if (a->turn_sign > 0) {
        hal_set_wheel_speeds(hal, (int16_t)-w, w);
    } else {
        hal_set_wheel_speeds(hal, w, (int16_t)-w);
    }
    return 1u;
}

uint8_t avoid_run_step(avoid_t *a, hal_t *hal, int16_t speed_steps_s)
{
    int16_t v = motion_capped_speed(hal, speed_steps_s, (a->target2 - a->done2 + 1) / 2);
    if (v <= 0) {
        return 0u;
    }
    hal_set_wheel_speeds(hal, v, v);
    return 1u;
}
