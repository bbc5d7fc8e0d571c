#include "app_telemetry.h"

void app_telemetry_platform(struct hal *hal, robot_telemetry_platform_t *out)
{
    uint16_t ir_best = 0u, amb_low = 0xFFFFu, v;
    uint8_t k, ir_at = 0u;
    for (k = 0u; k < HAL_IR_COUNT; k++) {
        v = hal_ir_proximity(hal, k);
        if (v > ir_best) {
            ir_best = v;
            ir_at = k;
        }
        v = hal_ir_ambient(hal, k);
        amb_low = v < amb_low ? v : amb_low;
    }
    /* The commands of this step: the image owns its struct hal. */
    out->wheel_left = hal->speed_left;
    out->wheel_right = hal->speed_right;
    out->leds = (int16_t)hal->leds;
    out->ir_max = (int16_t)ir_best;
    out->ir_max_index = (int8_t)ir_at;
    out->ambient_min = (int16_t)amb_low;
    out->blobs = -1;   /* not recomputed for telemetry */
}
