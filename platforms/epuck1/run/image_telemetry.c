/* image_telemetry.c - image_telemetry.h. */
#include "image_telemetry.h"

static void platform_of(struct hal *hal, uint8_t reads_sensors, robot_telemetry_platform_t *out)
{
    uint16_t ir_best = 0u, amb_low = 0xFFFFu, v;
    uint8_t k, ir_at = 0u;
    /* The commands of this step: the image owns its struct hal. */
    out->wheel_left = hal->speed_left;
    out->wheel_right = hal->speed_right;
    out->leds = (int16_t)hal->leds;
    out->blobs = -1;   /* not recomputed for telemetry */
    out->ir_max = -1;
    out->ir_max_index = -1;
    out->ambient_min = -1;
    if (reads_sensors == 0u) {
        return;
    }
    for (k = 0u; k < HAL_IR_COUNT; k++) {
        v = hal_ir_proximity(hal, k);
        if (v > ir_best) {
            ir_best = v;
            ir_at = k;
        }
        v = hal_ir_ambient(hal, k);
        amb_low = v < amb_low ? v : amb_low;
    }
    out->ir_max = (int16_t)ir_best;
    out->ir_max_index = (int8_t)ir_at;
    out->ambient_min = (int16_t)amb_low;
}

void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src,
                          uint8_t reads_sensors)
{
    robot_telemetry_platform_t platform;
    const robot_telemetry_platform_t *p = 0;
    if (robot_telemetry_state_due(t) != 0u) {
        platform_of(hal, reads_sensors, &platform);
        p = &platform;
    }
    robot_telemetry_step(t, hal, src, p);
}
