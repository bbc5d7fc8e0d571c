/*
 * host.h - the host link: messages the host (the PC running a study: a
 * planner, an operator) sends the robots, which hal_host_receive gives each
 * robot in file order once their time has come.  On the e-puck the same
 * bytes arrive over Bluetooth (docs/host_link.md); here they come from the
 * scenario's `host.messages`.  A scenario without messages has no host
 * link: hal_host_receive answers HAL_ERR_UNAVAILABLE.
 */
#ifndef SIM_MODELS_HOST_H
#define SIM_MODELS_HOST_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"

/** Most messages the host sends in one run (`host.messages`). */
#define HOST_MAX_MESSAGES 128u

/** A message the host sends one robot: hal_host_receive gives it from the
 *  first control step at or after `at`. */
typedef struct host_message_def {
    uint32_t robot;                       /**< robot id, 0-based over every group */
    float at;                             /**< s from the start */
    char hex[2 * HAL_HOST_MSG_MAX + 1];   /**< the bytes as written: two hex digits each */
    uint8_t len;                          /**< bytes, decoded from hex when loading */
    uint8_t bytes[HAL_HOST_MSG_MAX];
} host_message_def_t;

/** Section `host`: the messages in file order (a robot's with `at` not
 *  decreasing), on the heap (scenario_free frees them). */
typedef struct host_config {
    uint32_t message_count;
    host_message_def_t *messages;
} host_config_t;

MODEL_CONFIG_ACCESSORS(host, host_config_t)

/** Appends a message (code that builds a scenario without a file).
 *  Returns 0, or -1 past HOST_MAX_MESSAGES or out of memory. */
int host_add_message(scenario_t *sc, const host_message_def_t *m);

#endif
