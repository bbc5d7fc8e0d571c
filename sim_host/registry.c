/* The registry: the controllers and tasks the simulator runs.  The lists
 * come from the sources (tools/make/registry.sh writes registry_list.h from
 * every controller_def_t in firmware/<folder>/<name>_def.c and every
 * task_def_t in sim_host/tasks/<task>/), so no hand-kept list names one. */
#include "registry.h"

#include <string.h>

#include "models/model.h"
#include "registry_list.h"

static const controller_def_t *const controllers[] = {
    REGISTRY_CONTROLLERS
    &idle_def,
};

static const task_def_t *const tasks[] = {
    REGISTRY_TASKS
};

/* The models, from their one list (models/model_list.h). */
#define SIM_MODEL(name) &name##_model,
const model_def_t *const sim_models[SIM_MODEL_COUNT] = {
#include "models/model_list.h"
};
#undef SIM_MODEL

#define COUNT(a) (sizeof (a) / sizeof (a)[0])

/* ------------------------------------------------------------------ idle */

typedef struct idle_params { uint8_t unused; } idle_params_t;
static const param_desc_t idle_params[] = { PARAM_END };
static void idle_default_params(void *params) { (void)params; }
static void idle_init(void *self, const void *params, uint32_t seed) { (void)self; (void)params; (void)seed; }
static void idle_reset(void *self) { (void)self; }
static void idle_step(void *self, hal_t *hal) { (void)self; (void)hal; }
static const char *idle_state_name(const void *self) { (void)self; return "idle"; }

const controller_def_t idle_def = {
    .name = "idle",
    .doc = "no firmware: robots keep the wheel speeds set through their hal_t",
    .state_size = 0,
    .params_size = sizeof(idle_params_t),
    .params = idle_params,
    .default_params = idle_default_params,
    .init = idle_init,
    .reset = idle_reset,
    .step = idle_step,
    .state_name = idle_state_name,
};

/* ------------------------------------------------------------------ lookups */

const controller_def_t *registry_controller(const char *name)
{
    for (size_t i = 0; i < COUNT(controllers); i++) {
        if (strcmp(controllers[i]->name, name) == 0) {
            return controllers[i];
        }
    }
    return NULL;
}

const controller_def_t *registry_controller_at(size_t i)
{
    return i < COUNT(controllers) ? controllers[i] : NULL;
}

const task_def_t *registry_task(const char *name)
{
    for (size_t i = 0; i < COUNT(tasks); i++) {
        if (strcmp(tasks[i]->name, name) == 0) {
            return tasks[i];
        }
    }
    return NULL;
}

const task_def_t *registry_task_at(size_t i)
{
    return i < COUNT(tasks) ? tasks[i] : NULL;
}

const task_def_t *registry_task_for_controller(const char *controller)
{
    for (size_t i = 0; i < COUNT(tasks); i++) {
        for (size_t k = 0; tasks[i]->controllers != NULL && tasks[i]->controllers[k] != NULL; k++) {
            if (strcmp(tasks[i]->controllers[k], controller) == 0) {
                return tasks[i];
            }
        }
    }
    return NULL;
}
