/* The tutorial's example controller (phototaxis.h; docs/tutorials/first-controller.md). */
#include "phototaxis.h"

#include "units.h"

void phototaxis_default_params(phototaxis_params_t *params)
{
    params->speed_steps_s = 400;
    params->steer_gain = 300;
    params->arrive_level = 800u;
    params->leave_level = 1200u;
    params->avoid_enter = 300u;
    params->avoid_exit = 150u;
}

void phototaxis_init(phototaxis_t *self, const phototaxis_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    phototaxis_reset(self);
}

void phototaxis_reset(phototaxis_t *self)
{
    self->state = PHOTOTAXIS_SEEK;
    self->turn_sign = 1;
    self->brightest = HAL_RAW_MAX;
    self->light_bearing_mrad = 0;
    self->arrivals = 0u;
}

/* Largest reading of the four front sensors (IR0, IR1, IR6, IR7), and on
 * which side. */
static uint16_t front_proximity(hal_t *hal, int8_t *away)
{
    uint16_t right = hal_ir_proximity(hal, 0u) > hal_ir_proximity(hal, 1u)
                     ? hal_ir_proximity(hal, 0u) : hal_ir_proximity(hal, 1u);
    uint16_t left = hal_ir_proximity(hal, 7u) > hal_ir_proximity(hal, 6u)
                    ? hal_ir_proximity(hal, 7u) : hal_ir_proximity(hal, 6u);
    *away = left > right ? (int8_t)-1 : (int8_t)1;   /* obstacle on the left: turn clockwise */
    return left > right ? left : right;
}

/* The brightest ambient sensor: the smallest raw value (it falls as light
 * rises). */
static void look(phototaxis_t *self, hal_t *hal)
{
    uint8_t i, best = 0u;
    self->brightest = HAL_RAW_MAX;
    for (i = 0u; i < HAL_IR_COUNT; i++) {
        uint16_t v = hal_ir_ambient(hal, i);
        if (v < self->brightest) {
            self->brightest = v;
            best = i;
        }
    }
    self->light_bearing_mrad = hal_ir_bearing_mrad(hal, best);
}

static void seek(phototaxis_t *self, hal_t *hal)
{
    int16_t v = self->params.speed_steps_s;
    int32_t d = (int32_t)self->params.steer_gain * self->light_bearing_mrad / 1000;
    if (self->light_bearing_mrad > UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, (int16_t)-v, v);   /* behind on the left: turn CCW */
    } else if (self->light_bearing_mrad < -UNITS_HALF_PI_MRAD) {
        hal_set_wheel_speeds(hal, v, (int16_t)-v);
    } else {
        hal_set_wheel_speeds(hal, (int16_t)(v - d), (int16_t)(v + d));
    }
}

void phototaxis_step(phototaxis_t *self, hal_t *hal)
{
    int8_t away;
    uint16_t front = front_proximity(hal, &away);
    look(self, hal);
    switch (self->state) {
    case PHOTOTAXIS_SEEK:
        if (self->brightest < self->params.arrive_level) {
            self->state = PHOTOTAXIS_ARRIVED;
            self->arrivals++;
            hal_set_wheel_speeds(hal, 0, 0);
            hal_set_body_led(hal, 1u);
        } else if (front > self->params.avoid_enter) {
            self->state = PHOTOTAXIS_AVOID;
            self->turn_sign = away;
        } else {
            seek(self, hal);
        }
        break;
    case PHOTOTAXIS_AVOID:
        if (front < self->params.avoid_exit) {
            self->state = PHOTOTAXIS_SEEK;
            seek(self, hal);
        } else {
            int16_t w = self->params.speed_steps_s;
            hal_set_wheel_speeds(hal, (int16_t)(-self->turn_sign * w), (int16_t)(self->turn_sign * w));
        }
        break;
    case PHOTOTAXIS_ARRIVED:
        if (self->brightest > self->params.leave_level) {
            self->state = PHOTOTAXIS_SEEK;
            hal_set_body_led(hal, 0u);
        } else {
            hal_set_wheel_speeds(hal, 0, 0);
        }
        break;
    default:
        phototaxis_reset(self);
        break;
    }
}

const char *phototaxis_state_name(const phototaxis_t *self)
{
    switch (self->state) {
    case PHOTOTAXIS_SEEK: return "seek";
    case PHOTOTAXIS_AVOID: return "avoid";
    case PHOTOTAXIS_ARRIVED: return "arrived";
    default: return "?";
    }
}
