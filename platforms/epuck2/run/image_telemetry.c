/* image_telemetry.c - image_telemetry.h. */
#include "image_telemetry.h"

/* What the step commanded and, for a controller that reads them, the
 * strongest IR reading and the brightest ambient one. */
static void step_summary(struct hal *hal, uint8_t reads_sensors, robot_telemetry_platform_t *out)
{
    uint16_t best = 0u, darkest = 0xFFFFu, v;
    uint8_t k, at = 0u;
    out->wheel_left = hal->speed_left;
    out->wheel_right = hal->speed_right;
    out->leds = (int16_t)hal->leds;
    out->blobs = -1;
    out->ir_max = -1;
    out->ir_max_index = -1;
    out->ambient_min = -1;
    if (reads_sensors != 0u) {
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            v = hal_ir_proximity(hal, k);
            at = v > best ? k : at;
            best = v > best ? v : best;
            v = hal_ir_ambient(hal, k);
            darkest = v < darkest ? v : darkest;
        }
        out->ir_max = (int16_t)best;
        out->ir_max_index = (int8_t)at;
        out->ambient_min = (int16_t)darkest;
    }
}

void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src,
                          uint8_t reads_sensors)
{
    robot_telemetry_platform_t summary;
    if (robot_telemetry_state_due(t) == 0u) {
        robot_telemetry_step(t, hal, src, (const robot_telemetry_platform_t *)0);
        return;
    }
    step_summary(hal, reads_sensors, &summary);
    robot_telemetry_step(t, hal, src, &summary);
}
