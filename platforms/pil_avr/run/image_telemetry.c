/* image_telemetry.c - image_telemetry.h. */
#include "image_telemetry.h"

static void platform_of(const pil_robot_t *r, robot_telemetry_platform_t *out)
{
    uint8_t k, at = 0u;
    uint16_t best = 0u, low = HAL_RAW_MAX;
    out->wheel_left = r->wheel_left;
    out->wheel_right = r->wheel_right;
    out->leds = (int16_t)r->leds;
    out->ir_max = -1;
    out->ir_max_index = -1;
    out->ambient_min = -1;
    out->blobs = (r->have & PIL_HAVE_CAMERA) ? (int8_t)r->blob_count : -1;
    if (r->have & PIL_HAVE_IR) {
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            if (r->ir[k] > best) {
                best = r->ir[k];
                at = k;
            }
        }
        out->ir_max = (int16_t)best;
        out->ir_max_index = (int8_t)at;
    }
    if (r->have & PIL_HAVE_AMBIENT) {
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            low = r->ambient[k] < low ? r->ambient[k] : low;
        }
        out->ambient_min = (int16_t)low;
    }
}

void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src)
{
    robot_telemetry_platform_t platform;
    const robot_telemetry_platform_t *p = 0;
    if (robot_telemetry_state_due(t) != 0u) {
        platform_of(&hal->link, &platform);
        p = &platform;
    }
    robot_telemetry_step(t, hal, src, p);
}
