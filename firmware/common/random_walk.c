#include "random_walk.h"

#include "units.h"

void random_walk_default_params(random_walk_params_t *params)
{
    params->speed_steps_s = 500;
    params->turn_speed_steps_s = 300;
    params->turn_chance = 1311;   /* 0.02 * 65536 */
    params->avoid_enter = 300;
    params->avoid_exit = 150;
}

void random_walk_init(random_walk_t *self, const random_walk_params_t *params, uint32_t seed)
{
    self->params = *params;
    self->seed = seed;
    random_walk_reset(self);
}

void random_walk_reset(random_walk_t *self)
{
    rng_seed(&self->rng, self->seed);
    self->state = RW_FORWARD;
    self->turn_sign = 1;
    self->turn_steps_left = 0;
    self->oae_count = 0;
}

uint16_t random_walk_front_proximity(hal_t *hal)
{
    static const uint8_t front[4] = { 0u, 1u, 6u, 7u };
    uint16_t best = 0;
    uint8_t i;
    for (i = 0; i < 4u; i++) {
        uint16_t v = hal_ir_proximity(hal, front[i]);
        if (v > best) {
            best = v;
        }
    }
    return best;
}

/* Turns away from the side whose front sensors read more.  IR6/IR7 are on
 * the left: an obstacle there makes the robot turn clockwise (sign -1). */
static void start_avoidance(random_walk_t *self, hal_t *hal)
{
    uint16_t right = (uint16_t)(hal_ir_proximity(hal, 0u) / 2u + hal_ir_proximity(hal, 1u) / 2u);
    uint16_t left = (uint16_t)(hal_ir_proximity(hal, 7u) / 2u + hal_ir_proximity(hal, 6u) / 2u);
    self->turn_sign = (left > right) ? (int8_t)-1 : (int8_t)1;
    self->state = RW_AVOID;
    self->oae_count++;
    hal_set_led(hal, 0u, 1u);
}

static void turn_in_place(const random_walk_t *self, hal_t *hal)
{
    int16_t w = self->params.turn_speed_steps_s;
    if (self->turn_sign > 0) {
        hal_set_wheel_speeds(hal, (int16_t)-w, w);
    } else {
        hal_set_wheel_speeds(hal, w, (int16_t)-w);
    }
}

static void start_tumble(random_walk_t *self)
{
    int32_t angle = rng_range(&self->rng, -UNITS_PI_MRAD + 1, UNITS_PI_MRAD);
    self->turn_sign = (angle >= 0) ? (int8_t)1 : (int8_t)-1;
    self->turn_steps_left = units_turn_mrad_to_steps(angle >= 0 ? angle : -angle);
    self->state = RW_TUMBLE;
}

void random_walk_step(random_walk_t *self, hal_t *hal)
{
    uint16_t front = random_walk_front_proximity(hal);

    switch (self->state) {
    case RW_FORWARD:
        if (front > self->params.avoid_enter) {
            start_avoidance(self, hal);
        } else if (rng_chance(&self->rng, self->params.turn_chance) != 0u) {
            start_tumble(self);
        }
        break;
    case RW_TUMBLE:
        if (front > self->params.avoid_enter) {
            start_avoidance(self, hal);
        } else if (self->turn_steps_left <= 0) {
            self->state = RW_FORWARD;
        }
        break;
    case RW_AVOID:
        if (front < self->params.avoid_exit) {
            self->state = RW_FORWARD;
            hal_set_led(hal, 0u, 0u);
        }
        break;
    default:
        self->state = RW_FORWARD;
        break;
    }

    /* Act on the state we are now in. */
    switch (self->state) {
    case RW_TUMBLE:
        turn_in_place(self, hal);
        self->turn_steps_left -= units_steps_in_period(self->params.turn_speed_steps_s,
                                                       hal_control_period_ms(hal));
        break;
    case RW_AVOID:
        turn_in_place(self, hal);
        break;
    default:
        hal_set_wheel_speeds(hal, self->params.speed_steps_s, self->params.speed_steps_s);
        break;
    }
}

const char *random_walk_state_name(const random_walk_t *self)
{
    switch (self->state) {
    case RW_FORWARD: return "forward";
    case RW_TUMBLE: return "tumble";
    case RW_AVOID: return "avoid";
    default: return "?";
    }
}
