#include "units.h"

/* One step is pi * 41 mm / 1000 = 0.128805 mm.  The ratios below are
 * exact to 5 significant digits, more than the wheel's real tolerance. */
#define UM_PER_STEP_X1000 128805L   /* micrometres per step, times 1000 */

static int32_t div_round(int64_t num, int64_t den)
{
    return (int32_t)((num >= 0) ? (num + den / 2) / den : (num - den / 2) / den);
}

int32_t units_steps_to_mm(int32_t steps)
{
    return (int32_t)(((int64_t)steps * UM_PER_STEP_X1000) / 1000000L);
}

int32_t units_mm_to_steps(int32_t mm)
{
    return div_round((int64_t)mm * 1000000L, UM_PER_STEP_X1000);
}

int32_t units_turn_mrad_to_steps(int32_t mrad)
{
    /* arc per wheel = angle * axle / 2 */
    int64_t arc_um_x1000 = (int64_t)mrad * (EPUCK_AXLE_UM / 2);
    return div_round(arc_um_x1000 * 1000L, UM_PER_STEP_X1000 * 1000L);
}

int16_t units_mm_s_to_steps_s(int16_t mm_s)
{
    return (int16_t)units_mm_to_steps(mm_s);
}

int32_t units_steps_in_period(int16_t steps_s, uint16_t period_ms)
{
    return (int32_t)(((int32_t)steps_s * (int32_t)period_ms) / 1000L);
}

#define IR_MRAD_ITEM(deg) UNITS_DEG_TO_MRAD(deg),

int16_t units_ir_bearing_mrad(uint8_t index)
{
    /* Converted at compile time: the robot's poll path asks this for every
     * sensor of every IR message received. */
    static const int16_t mrad[8] = { EPUCK_IR_BEARINGS(IR_MRAD_ITEM) };
    return index < 8u ? mrad[index] : 0;
}
