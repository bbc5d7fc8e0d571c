/*
 * host_link.h - what a host PC sends an e-puck over its Bluetooth serial
 * link (UART1, 115200 8N1, the link its telemetry goes out on): the
 * overhead tracker's pose (hal_pose) and messages for the controller
 * (hal_host_receive).  Frames: wire/telemetry/telemetry_frame.h with
 * the payloads of telemetry_host.h; the host's side and the rates:
 * docs/host_link.md.
 *
 * An image that wants them (`host_link yes` in images.list) gives the HAL
 * the storage (about 250 bytes, static in the image like the camera
 * frames) after hal_epuck_init; the run loop (run/image_main.h) does:
 *
 *     static hal_epuck_host_t app_host;
 *     hal_epuck_init(&app_hal, &cfg, NULL, 0);
 *     hal_epuck_host_attach(&app_hal, &app_host);
 *
 * Images without it pay two bytes of RAM (a pointer) and never read UART1;
 * there hal_pose and hal_host_receive say HAL_ERR_UNAVAILABLE.
 *
 * Receiving.  The library's receive interrupt keeps the last 64 bytes in
 * a ring and overwrites what is not read in time, so the HAL reads it
 * often: hal_epuck_poll (the idle loop between steps) reads up to
 * HAL_EPUCK_RX_POLL_BYTES a call, and hal_epuck_begin_step up to the
 * bytes 115200 baud brings in one control period (1152 at 100 ms), so a
 * flood can neither stall the step nor starve the idle loop.  A step that
 * lasts longer than 64 bytes' time (5.6 ms) while the host sends loses
 * what overflowed: the frame caught in it fails its CRC and is counted
 * (rx.bad), the next one comes through.  Frames arrive only between
 * steps, so what hal_pose and hal_host_receive give cannot change within
 * a step (hal.h).
 *
 * Frames are taken when addressed to this robot (hal_robot_id) or to
 * every robot (TELEMETRY_BROADCAST_ID); others are counted (not_ours).
 * Sequence numbers are not checked (one stream may serve several robots).
 *
 * Pose.  A POSE frame replaces the pose and stamps it with hal_time_ms of
 * the step that first sees it; hal_pose gives it with age_ms = now - that
 * stamp (so in whole control periods; the tracker's and the link's own
 * latency come on top: docs/host_link.md), HAL_ERR_UNAVAILABLE before the
 * first pose and once the age exceeds HAL_POSE_MAX_AGE_MS.
 *
 * Messages.  A HOST_MSG frame (1..HAL_HOST_MSG_MAX bytes) goes into a
 * mailbox of HAL_EPUCK_HOST_SLOTS messages that hal_host_receive empties
 * oldest first.  When it is full a new message is dropped and counted
 * (msg_dropped): the ones waiting are older and a route's order matters,
 * and the host can send again.  hal_host_receive: HAL_OK with the message
 * in buf and its length in *len; HAL_ERR_EMPTY; HAL_ERR_RANGE when the
 * message is longer than cap (it stays); HAL_ERR_UNAVAILABLE without host
 * link storage; *len is 0 on every error, as in the simulator.
 */
#ifndef HAL_EPUCK_HOST_LINK_H
#define HAL_EPUCK_HOST_LINK_H

#include <stdint.h>

#include "hal.h"
#include "telemetry/telemetry_host.h"
#include "telemetry/telemetry_rx.h"

/** Messages the mailbox holds. */
#define HAL_EPUCK_HOST_SLOTS 2u
/** Bytes UART1 brings per second: 115200 baud, 10 bits a byte (8N1). */
#define HAL_EPUCK_UART_BYTES_PER_S 11520u
/** Bytes one hal_epuck_poll reads at most: the library's receive ring. */
#define HAL_EPUCK_RX_POLL_BYTES 64u

/** The host link's state: given by the image, private to platforms/epuck1/hal (tests
 *  read the counters). */
typedef struct hal_epuck_host {
    telemetry_rx_t rx;                           /**< the frame decoder */
    uint8_t body[TELEMETRY_HOST_MAX_BODY];       /**< its buffer: one frame */
    hal_pose_t pose;                             /**< the last pose (age unused) */
    uint32_t pose_at_ms;                         /**< hal_time_ms it came at */
    uint8_t has_pose;
    uint8_t msg_head, msg_count;
    uint8_t msg_len[HAL_EPUCK_HOST_SLOTS];
    uint8_t msg[HAL_EPUCK_HOST_SLOTS][HAL_HOST_MSG_MAX];
    uint16_t poses;                              /**< POSE frames taken (wraps) */
    uint16_t msgs;                               /**< messages put in the mailbox (wraps) */
    uint16_t msg_dropped;                        /**< messages lost: mailbox full */
    uint16_t not_ours;                           /**< good frames for another robot */
    uint16_t ignored;                            /**< good frames for us on another
                                                      channel, or of a wrong length */
} hal_epuck_host_t;

/** Gives the HAL `host` (cleared here) and starts reading UART1 into it.
 *  Call after hal_epuck_init, which forgets it. */
void hal_epuck_host_attach(hal_t *hal, hal_epuck_host_t *host);

/** Reads up to `max_bytes` received bytes and takes the frames they
 *  complete (nothing without host link storage).  Called by
 *  hal_epuck_poll and hal_epuck_begin_step. */
void hal_epuck_host_drain(hal_t *hal, uint16_t max_bytes);

/** Bytes UART1 can bring in `period_ms`: the most begin_step reads. */
uint16_t hal_epuck_host_step_bytes(uint16_t period_ms);

#endif
