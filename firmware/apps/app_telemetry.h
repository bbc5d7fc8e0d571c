/*
 * app_telemetry.h - what the e-puck images that publish telemetry share:
 * a swarmlcm.robot_state_t every APP_TELEMETRY_STEPS control steps, framed
 * on TELEMETRY_CH_ROBOT_STATE (telemetry_frame.h) and trickled out through
 * the Bluetooth UART by telemetry_tx.  Each image fills its controller's
 * fields; the fields every robot reports alike are filled here.
 *
 * Ownership: the app_telemetry_t lives in the image's static state (the
 * images' one exception to the no-statics rule); this module keeps none.
 */
#ifndef APP_TELEMETRY_H
#define APP_TELEMETRY_H

#include <stdint.h>

#include "hal_epuck.h"
#include "swarmlcm_robot_state_t.h"
#include "common/telemetry_tx.h"

/** Control steps between two robot_state_t messages (1 s at 100 ms). */
#define APP_TELEMETRY_STEPS 10u
/** Largest encoded robot_state_t an image sends (about 125 bytes). */
#define APP_STATE_PAYLOAD 160u

typedef struct app_telemetry {
    telemetry_tx_t tx;                    /**< frames waiting for the UART */
    uint8_t payload[APP_STATE_PAYLOAD];   /**< the encoded message */
    uint8_t countdown;                    /**< steps to the next message */
} app_telemetry_t;

/** Empty sender; the first message goes out at the first step. */
void app_telemetry_init(app_telemetry_t *t);

/** Called once per control step: 1 on the steps a message is due (the
 *  first, then every APP_TELEMETRY_STEPS), else 0. */
uint8_t app_telemetry_due(app_telemetry_t *t);

/** Fills the fields every image reports alike (time, id, this step's wheel
 *  and LED commands, no pose on a robot), encodes `m` and queues its frame;
 *  a frame that does not fit is dropped and counted by the sender. */
void app_telemetry_send(app_telemetry_t *t, struct hal *hal, swarmlcm_robot_state_t *m);

/** Hands queued bytes to the UART; call every step. */
void app_telemetry_pump(app_telemetry_t *t, struct hal *hal);

#endif
