/* The registry: one entry per firmware controller the simulator can run. */
#include "controllers.h"

#include <string.h>

#include "common/random_walk.h"

/* ---------------------------------------------------------- random_walk */

#define RW_FIELD(f) offsetof(random_walk_params_t, f), sizeof(((random_walk_params_t *)0)->f)
static const param_desc_t random_walk_param_descs[] = {
    { "speed_steps_s", PARAM_I16, RW_FIELD(speed_steps_s), 0, 1000, NULL,
      "forward wheel speed, steps/s (500 = 64.4 mm/s)" },
    RANDOM_WALK_TUNING_DESCS(RW_FIELD),
    PARAM_END
};

static void rw_defaults(void *params) { random_walk_default_params(params); }
static void rw_init(void *state, const void *params, uint32_t seed) { random_walk_init(state, params, seed); }
static void rw_step(void *state, hal_t *hal) { random_walk_step(state, hal); }
static uint32_t rw_oae(const void *state) { return ((const random_walk_t *)state)->oae_count; }
static const char *rw_state(const void *state)
{
    return random_walk_state_name(((const random_walk_t *)state)->state);
}

/* ---------------------------------------------------------- idle */

/* Robots that run no firmware: they keep the wheel speeds last set through
 * their hal_t (tests drive robots this way) and are obstacles otherwise. */
static const param_desc_t idle_param_descs[] = { PARAM_END };
static void idle_defaults(void *params) { (void)params; }
static void idle_init(void *state, const void *params, uint32_t seed) { (void)state; (void)params; (void)seed; }
static void idle_step(void *state, hal_t *hal) { (void)state; (void)hal; }
static uint32_t idle_oae(const void *state) { (void)state; return 0; }
static const char *idle_state(const void *state) { (void)state; return "idle"; }

static const sim_controller_t controller_random_walk = {
    "random_walk", "random walk with IR obstacle avoidance (seed 000's ASM, A(t) = 0)",
    sizeof(random_walk_t), sizeof(random_walk_params_t), random_walk_param_descs, NULL,
    rw_defaults, rw_init, rw_step, rw_oae, rw_state, NULL, NULL
};

static const sim_controller_t controller_idle = {
    "idle", "no firmware: robots keep the wheel speeds set through their hal_t",
    0, 0, idle_param_descs, NULL, idle_defaults, idle_init, idle_step, idle_oae, idle_state, NULL, NULL
};

/* ---------------------------------------------------------- registry */

static const sim_controller_t *const registry[] = {
    &controller_random_walk, &controller_idle, &controller_forager, &controller_nest_beacon
};

#define REGISTRY_SIZE (sizeof registry / sizeof registry[0])

const sim_controller_t *controllers_find(const char *name)
{
    for (size_t i = 0; i < REGISTRY_SIZE; i++) {
        if (strcmp(registry[i]->name, name) == 0) {
            return registry[i];
        }
    }
    return NULL;
}

const sim_controller_t *controllers_at(size_t i)
{
    return i < REGISTRY_SIZE ? registry[i] : NULL;
}
