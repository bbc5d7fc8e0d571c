/*
 * motion.c - motion.h.  32-bit intermediates where a product could pass
 * 16 bits (the dsPIC's int).
 */
#include "common/motion.h"

int16_t motion_clamp_speed(int32_t v)
{
    if (v > HAL_WHEEL_SPEED_MAX) {
        return HAL_WHEEL_SPEED_MAX;
    }
    if (v < -HAL_WHEEL_SPEED_MAX) {
        return (int16_t)-HAL_WHEEL_SPEED_MAX;
    }
    return (int16_t)v;
}

uint16_t motion_periods(hal_t *hal, uint16_t ms)
{
    uint16_t period = hal_control_period_ms(hal);
    uint32_t n;
    if (period == 0u) {
        period = 1u;
    }
    n = ((uint32_t)ms + period - 1u) / period;
    return (uint16_t)(n == 0u ? 1u : n);
}

int16_t motion_capped_speed(hal_t *hal, int16_t speed, int32_t remaining)
{
    uint16_t period = hal_control_period_ms(hal);
    int32_t cap;
    if (period == 0u || remaining <= 0) {
        return 0;
    }
    if (remaining > 100000L) {
        return speed;   /* more than any period makes: no cap (and no overflow below) */
    }
    cap = (remaining * 1000L + period - 1) / period;
    return (int16_t)((cap < speed) ? cap : speed);
}
