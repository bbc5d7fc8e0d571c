/*
 * sim_hal.c - the simulator's part of hal.h that is every robot's, whatever
 * the models: its id, the clock and the LEDs.  The sensors and actuators
 * are the models' (sim_host/models/): each defines the HAL calls it serves,
 * computed lazily, once per control step, from the pose at the start of
 * the step; hal/hal_common.c holds the platform-neutral ones.
 */
#include <math.h>
#include <string.h>

#include "sim_internal.h"
#include "units.h"

static sim_robot_t *robot(hal_t *hal) { return &hal->sim->robots[hal->index]; }

uint16_t hal_robot_id(hal_t *hal) { return (uint16_t)hal->index; }

uint32_t hal_time_ms(hal_t *hal)
{
    return (uint32_t)(hal->sim->step * hal->sim->sc->control_period_ms);
}

uint16_t hal_control_period_ms(hal_t *hal) { return hal->sim->sc->control_period_ms; }

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
