/*
 * robot_telemetry.h - a robot's own telemetry: its controller's state as a
 * swarmlcm.robot_state_t once a second, and the controller's schema (the
 * names, units and kinds of its observables, observable.h) a few entries
 * per frame in turn, framed (telemetry_frame.h) and trickled out through
 * hal_telemetry_write without blocking (telemetry_tx.h).
 *
 * The same code runs in the e-puck images (firmware/apps/) and, when a
 * scenario asks for it (robot_telemetry: {enabled: true}), in the simulator
 * for every robot, whose bytes the simulator deframes and publishes as the
 * serial bridge does: what a robot says of itself is tested in software
 * in the loop.  Every value comes from the controller's observables table,
 * so the robot and the simulator cannot disagree on what a value means.
 *
 * What only the platform knows of this step (the wheel and LED commands,
 * sensor summaries) it passes in robot_telemetry_platform_t: reading a
 * sensor here would change a simulated run's noise.
 *
 * Ownership: the robot_telemetry_t lives with the robot (an image's static
 * state, a simulated robot's storage); this module keeps none.
 */
#ifndef FW_ROBOT_TELEMETRY_H
#define FW_ROBOT_TELEMETRY_H

#include <stdint.h>

#include "common/observable.h"
#include "hal.h"
#include "telemetry/telemetry_tx.h"

/** Control steps between two robot_state_t messages (1 s at 100 ms); a
 *  schema frame goes out halfway between two of them. */
#define ROBOT_TELEMETRY_STEPS 10u
/** Schema entries per frame (about 40 bytes each). */
#define ROBOT_TELEMETRY_SCHEMA_CHUNK 3u
/** Largest encoded message sent (the frame's payload limit). */
#define ROBOT_TELEMETRY_PAYLOAD TELEMETRY_MAX_PAYLOAD
/** Most observables sent per robot_state_t. */
#define ROBOT_TELEMETRY_MAX_VALUES 16u

/** What the platform knows of this step. */
typedef struct robot_telemetry_platform {
    int16_t wheel_left, wheel_right;  /**< commanded, steps/s */
    int16_t leds;                     /**< bits 0-7 ring, 8 body, 9 front */
    int16_t ir_max;                   /**< largest IR proximity, -1 if not read */
    int8_t ir_max_index;              /**< its sensor, -1 */
    int16_t ambient_min;              /**< smallest ambient reading, -1 if not read */
    int8_t blobs;                     /**< camera blobs, -1 if not read */
} robot_telemetry_platform_t;

/** The controller being reported. */
typedef struct robot_telemetry_source {
    const char *controller;           /**< its registered name */
    const observable_t *observables;  /**< its table (OBS_END-terminated), or NULL */
    const void *state;                /**< its state struct */
    const char *state_name;           /**< its state now */
} robot_telemetry_source_t;

typedef struct robot_telemetry {
    telemetry_tx_t tx;                              /**< frames waiting for the sink */
    uint8_t payload[ROBOT_TELEMETRY_PAYLOAD];       /**< the message being encoded */
    uint8_t countdown;                              /**< steps to the next state */
    uint8_t schema_next;                            /**< schema entry sent next */
} robot_telemetry_t;

/** Empty sender; the first state goes out at the first step. */
void robot_telemetry_init(robot_telemetry_t *t);

/** Non-zero when this step's robot_telemetry_step sends a robot_state_t:
 *  the only step that reads the platform values and the state name, so a
 *  caller gathers them then only. */
uint8_t robot_telemetry_state_due(const robot_telemetry_t *t);

/** Once per control step, after the controller's: sends what is due
 *  (robot_state_t, a schema chunk) and pumps the sender.  `platform` is
 *  read only when robot_telemetry_state_due() said so (NULL otherwise).
 *  Frames that do not fit are dropped and counted by the sender. */
void robot_telemetry_step(robot_telemetry_t *t, hal_t *hal, const robot_telemetry_source_t *src,
                          const robot_telemetry_platform_t *platform);

#endif
