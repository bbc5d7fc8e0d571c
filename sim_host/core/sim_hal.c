/*
 * sim_hal.c - the simulator's implementation of hal.h.  Each robot's
 * controller gets its own hal_t; sensors are computed lazily, once per
 * control step, from the pose at the start of the step.
 */
#include <math.h>
#include <string.h>

#include "models/faults/faults.h"
#include "sim_internal.h"
#include "units.h"

static sim_robot_t *robot(hal_t *hal) { return &hal->sim->robots[hal->index]; }
static uint64_t stamp(const hal_t *hal) { return hal->sim->step + 1; }

uint16_t hal_robot_id(hal_t *hal) { return (uint16_t)hal->index; }

uint32_t hal_time_ms(hal_t *hal)
{
    return (uint32_t)(hal->sim->step * hal->sim->sc->control_period_ms);
}

uint16_t hal_control_period_ms(hal_t *hal) { return hal->sim->sc->control_period_ms; }

uint8_t hal_camera_blobs
(hal_t *hal, hal_blob_t *out, uint8_t max)
{
    sim_robot_t *r = robot(hal);
    if (r->camera_stamp != stamp(hal)) {
        camera_update(hal->sim, hal->index);   /* a frame only when one is due */
        r->camera_stamp = stamp(hal);
    }
    uint8_t n = r->blob_count < max ? r->blob_count : max;
    for (uint8_t k = 0; k < n; k++) {
        out[k] = r->blobs[k];
    }
    return n;
}

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px)
{
    *width_px = hal->sim->sc->camera.width_px;
    *height_px = hal->sim->sc->camera.height_px;
    return HAL_OK;
}

static void set_bit(uint16_t *bits, unsigned bit, uint8_t on)
{
    *bits = on ? (uint16_t)(*bits | (1u << bit)) : (uint16_t)(*bits & ~(1u << bit));
}

void hal_set_led(hal_t *hal, uint8_t index, uint8_t on)
{
    if (index < HAL_LED_COUNT) {
        set_bit(&robot(hal)->leds, index, on);
    }
}

void hal_set_body_led(hal_t *hal, uint8_t on) { set_bit(&robot(hal)->leds, HAL_LED_WORD_BODY_BIT, on); }
void hal_set_front_led(hal_t *hal, uint8_t on) { set_bit(&robot(hal)->leds, HAL_LED_WORD_FRONT_BIT, on); }
