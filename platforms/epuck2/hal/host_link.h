/*
 * host_link.h - what a host PC sends an e-puck2 over its Bluetooth serial
 * link (UART3 through the ESP32, 115200 8N1, the link its telemetry goes
 * out on): the overhead tracker's pose (hal_pose) and messages for the
 * controller (hal_host_receive).  Frames, payloads and rules are the
 * e-puck1's (platforms/epuck1/hal/host_link.h, docs/host_link.md): the same
 * bridge serves both robots.
 *
 * An image that wants them (`host_link yes`) gives the HAL the storage
 * after hal_epuck2_init (hal_epuck2_host_attach); without it hal_pose and
 * hal_host_receive say HAL_ERR_UNAVAILABLE.
 *
 * Receiving: ChibiOS's serial driver keeps received bytes in its input
 * queue (SERIAL_BUFFERS_SIZE = 128 B, 11 ms at 115200 baud); poll reads up
 * to HAL_EPUCK2_RX_POLL_BYTES a call (the idle loop polls every ms) and
 * begin_step up to the bytes one control period brings, so a flood can
 * neither stall the step nor starve the idle loop.  Bytes that overflow the
 * queue during a long step are lost: the frame caught in it fails its CRC
 * and is counted (rx.bad).
 */
#ifndef HAL_EPUCK2_HOST_LINK_H
#define HAL_EPUCK2_HOST_LINK_H

#include <stdint.h>

#include "hal.h"
#include "telemetry/telemetry_host.h"
#include "telemetry/telemetry_rx.h"

/** Messages the mailbox holds. */
#define HAL_EPUCK2_HOST_SLOTS 2u
/** Bytes UART3 brings per second: 115200 baud, 10 bits a byte (8N1). */
#define HAL_EPUCK2_UART_BYTES_PER_S 11520u
/** Bytes one poll reads at most: ChibiOS's input queue. */
#define HAL_EPUCK2_RX_POLL_BYTES 128u

/** The host link's state: given by the image, private to platforms/epuck2/hal. */
typedef struct hal_epuck2_host {
    telemetry_rx_t rx;                           /**< the frame decoder */
    uint8_t body[TELEMETRY_HOST_MAX_BODY];       /**< its buffer: one frame */
    hal_pose_t pose;                             /**< the last pose (age unused) */
    uint32_t pose_at_ms;                         /**< hal_time_ms it came at */
    uint8_t has_pose;
    uint8_t msg_head, msg_count;
    uint8_t msg_len[HAL_EPUCK2_HOST_SLOTS];
    uint8_t msg[HAL_EPUCK2_HOST_SLOTS][HAL_HOST_MSG_MAX];
    uint16_t poses;                              /**< POSE frames taken (wraps) */
    uint16_t msgs;                               /**< messages put in the mailbox (wraps) */
    uint16_t msg_dropped;                        /**< messages lost: mailbox full */
    uint16_t not_ours;                           /**< good frames for another robot */
    uint16_t ignored;                            /**< good frames for us on another
                                                      channel, or of a wrong length */
} hal_epuck2_host_t;

/** Gives the HAL `host` (cleared here).  Call after hal_epuck2_init. */
void hal_epuck2_host_attach(hal_t *hal, hal_epuck2_host_t *host);

/** Reads up to `max_bytes` received bytes and takes the frames they
 *  complete (nothing without host link storage). */
void hal_epuck2_host_drain(hal_t *hal, uint16_t max_bytes);

/** Bytes UART3 can bring in `period_ms`: the most begin_step reads. */
uint16_t hal_epuck2_host_step_bytes(uint16_t period_ms);

#endif
