/*
 * telemetry_tx.h - sends telemetry frames (telemetry_frame.h) through the
 * HAL's telemetry sink without ever blocking.
 *
 * hal_telemetry_write may take fewer bytes than offered (the UART's buffer
 * is full, the Bluetooth link is slow), so frames wait in a bounded buffer
 * inside the caller's telemetry_tx_t (no malloc, no static storage) and go
 * out as the sink accepts them: call telemetry_tx_pump once per control
 * step.  A frame is queued whole or not at all: when it does not fit it is
 * dropped and counted, so the byte stream stays a sequence of whole frames
 * and the receiver, seeing the sequence number jump, counts the loss too.
 *
 * Typical use in a controller step, with an LCM message encoded by the
 * lcm-gen C code of lcm_types/ into `buf`:
 *     n = swarmlcm_robot_state_t_encode(buf, 0, sizeof buf, &msg);
 *     if (n > 0) telemetry_tx_send(&self->tx, hal, TELEMETRY_CH_ROBOT_STATE, buf, (uint16_t)n);
 *     telemetry_tx_pump(&self->tx, hal);
 */
#ifndef FW_TELEMETRY_TX_H
#define FW_TELEMETRY_TX_H

#include <stdint.h>

#include "hal.h"
#include "telemetry_frame.h"

/** Bytes of frames a sender holds: two frames of the largest size. */
#define TELEMETRY_TX_BUFFER (2u * TELEMETRY_FRAME_MAX)

typedef struct telemetry_tx {
    uint8_t buf[TELEMETRY_TX_BUFFER];
    uint16_t start;           /**< first byte not yet accepted by the sink */
    uint16_t end;             /**< end of the queued bytes */
    uint16_t seq;             /**< sequence number of the next frame */
    uint32_t frames_queued;   /**< frames accepted into the buffer */
    uint32_t frames_dropped;  /**< frames dropped: no room, or payload too long */
    uint32_t bytes_sent;      /**< bytes the sink accepted */
} telemetry_tx_t;

/** Empty buffer, sequence 0, counters 0. */
void telemetry_tx_init(telemetry_tx_t *tx);

/** Frames `len` payload bytes on `channel` (telemetry_channel_t) with the
 *  robot's id, queues the frame if it fits whole, then pumps.  Every call
 *  uses one sequence number.  Returns 1 if queued, 0 if dropped. */
uint8_t telemetry_tx_send(telemetry_tx_t *tx, hal_t *hal, uint8_t channel,
                          const uint8_t *payload, uint16_t len);

/** Offers the queued bytes to hal_telemetry_write once; returns how many
 *  still wait. */
uint16_t telemetry_tx_pump(telemetry_tx_t *tx, hal_t *hal);

/** Bytes waiting to be sent. */
uint16_t telemetry_tx_pending(const telemetry_tx_t *tx);

#endif
