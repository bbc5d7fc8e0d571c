/*
 * controller.h - the contract every controller keeps, and its description
 * for a platform that runs controllers by name (the simulator).
 *
 * A controller NAME (firmware/<folder>/NAME.h and .c) is
 *
 *   NAME_params_t   its parameters: plain data, set before init
 *   NAME_t          its state: everything it remembers (no static storage)
 *   void NAME_default_params(NAME_params_t *params);
 *   void NAME_init(NAME_t *self, const NAME_params_t *params, uint32_t seed);
 *                   copies params, keeps seed, and ends with NAME_reset
 *   void NAME_reset(NAME_t *self);
 *                   back to the start state; the random stream restarts
 *                   from the seed
 *   void NAME_step(NAME_t *self, hal_t *hal);
 *                   one control period: reads sensors, sets actuators,
 *                   never blocks, never reads a wall clock; its body is a
 *                   switch over the state enum
 *   const char *NAME_state_name(const NAME_t *self);
 *                   the current state, lower case ("search")
 *
 * CONTROLLER_API(NAME) in the controller's header declares these five, so
 * the compiler checks the definitions against the contract.  A controller
 * with policies also exports
 *
 *   void NAME_set_policy(void *params, uint8_t index);
 *                   applies policy `index` (its def's set_policy), which a
 *                   robot image's selector switch calls
 *
 * and one that shows values exports NAME_observables.  The robot images
 * (platforms/<p>/images.list) run a controller through these functions,
 * called by name, not through its controller_def_t: a function pointer
 * would hide the call chain from the stack gate, and the def carries the
 * simulator's parameter tables.
 *
 * The description (controller_def_t) lives in NAME_def.c beside the
 * controller: its parameter keys (param.h), what it shows (observable.h),
 * its policies and what it needs of the platform.  CONTROLLER_ADAPTERS and
 * CONTROLLER_FUNCS fill the function slots from the five functions:
 *
 *     CONTROLLER_ADAPTERS(forager)
 *     const controller_def_t forager_def = {
 *         .name = "forager", .doc = "...", CONTROLLER_FUNCS(forager),
 *         .params = forager_param_descs, .observables = forager_observables,
 *         .ircom_bits = 16,
 *     };
 *
 * and the simulator registers it by itself: the build finds every
 * `const controller_def_t NAME = {` (on one line) in
 * firmware/<folder>/<name>_def.c (tools/make/registry.sh).
 */
#ifndef FW_CONTROLLER_H
#define FW_CONTROLLER_H

#include <stddef.h>
#include <stdint.h>

#include "hal.h"
#include "common/observable.h"
#include "common/param.h"

#define CONTROLLER_API(NAME)                                                       \
    void NAME##_default_params(NAME##_params_t *params);                           \
    void NAME##_init(NAME##_t *self, const NAME##_params_t *params, uint32_t seed); \
    void NAME##_reset(NAME##_t *self);                                             \
    void NAME##_step(NAME##_t *self, hal_t *hal);                                  \
    const char *NAME##_state_name(const NAME##_t *self)

typedef struct controller_def {
    const char *name;                 /**< the scenario's `controller:` value */
    const char *doc;                  /**< one line for --help */
    size_t state_size;                /**< sizeof(NAME_t) */
    size_t params_size;               /**< sizeof(NAME_params_t) */
    const param_desc_t *params;       /**< keys of a group's `params:`, PARAM_END-terminated */
    const char *const *policies;      /**< variants (NULL-terminated, the first is the
                                           default), or NULL */
    const observable_t *observables;  /**< what it shows, OBS_END-terminated, or NULL */
    uint8_t ircom_bits;               /**< IR message bits it needs (hal_ircom_payload_bits);
                                           0 if it uses no IR messages */
    /** Where its state keeps the copy of its params that its steps read
     *  (CONTROLLER_LIVE_PARAMS): a key marked `live` (param.h) is set there
     *  while the run goes.  0 in params_in_state: nothing is settable. */
    uint8_t params_in_state;
    size_t params_offset;
    void (*default_params)(void *params);
    /** Applies policy `index` (into `policies`) to params; NULL without policies. */
    void (*set_policy)(void *params, uint8_t index);
    /* self is the robot's state.  A stateless controller (state_size 0, the
     * simulator's idle) is not initialised or stepped, and its state_name
     * gets NULL. */
    void (*init)(void *self, const void *params, uint32_t seed);
    void (*reset)(void *self);
    void (*step)(void *self, hal_t *hal);
    const char *(*state_name)(const void *self);
} controller_def_t;

/** Declares that NAME_t's member `field` is the NAME_params_t copy its
 *  steps read (a build error if it is not of that type), so that its keys
 *  marked `.live = 1` can be set while the run goes. */
#define CONTROLLER_LIVE_PARAMS(NAME, field) \
    .params_in_state = 1, .params_offset = FIELD_OFFSET_AS(NAME##_t, field, NAME##_params_t)

/** Static functions NAME_def_* that adapt the contract to controller_def_t. */
#define CONTROLLER_ADAPTERS(NAME)                                                            \
    static void NAME##_def_default_params(void *params)                                     \
    { NAME##_default_params((NAME##_params_t *)params); }                                    \
    static void NAME##_def_init(void *self, const void *params, uint32_t seed)              \
    { NAME##_init((NAME##_t *)self, (const NAME##_params_t *)params, seed); }                \
    static void NAME##_def_reset(void *self) { NAME##_reset((NAME##_t *)self); }             \
    static void NAME##_def_step(void *self, hal_t *hal) { NAME##_step((NAME##_t *)self, hal); } \
    static const char *NAME##_def_state_name(const void *self)                              \
    { return NAME##_state_name((const NAME##_t *)self); }

/** The sizes and function slots of a controller_def_t initialiser. */
#define CONTROLLER_FUNCS(NAME)                                                       \
    .state_size = sizeof(NAME##_t), .params_size = sizeof(NAME##_params_t),         \
    .default_params = NAME##_def_default_params, .init = NAME##_def_init,           \
    .reset = NAME##_def_reset, .step = NAME##_def_step,                             \
    .state_name = NAME##_def_state_name

#endif
