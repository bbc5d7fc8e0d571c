/*
 * telemetry_rx.h - a streaming decoder of the frames of telemetry_frame.h,
 * for a robot that reads its serial link one byte at a time (the frames a
 * host sends it: telemetry_host.h).
 *
 * Bytes between two zeros are COBS-decoded as they come into a buffer the
 * caller owns and sizes for the frames it expects (TELEMETRY_HOST_MAX_BODY
 * on a robot, 72 bytes: the robot has 2 KB of RAM for everything).  At the
 * closing zero the body is checked (COBS complete, at least a header and a
 * CRC, TELEMETRY_VERSION, CRC-16) and a good frame is returned.  Anything
 * else between two zeros counts as one bad frame: garbage, a truncated
 * frame, a corrupted one, one longer than the buffer (also counted as
 * oversize; the rest of it is skipped).  Every zero ends whatever came
 * before it, so the decoder resyncs at the next zero and a bad run costs
 * at most its own frame.  Two zeros in a row (a frame's closing zero and
 * the next one's opening zero) are no frame and count as nothing.
 *
 * The decoder starts as if after a zero: a stream joined mid-frame costs
 * one bad frame.  It does not check channels, robot ids or sequence
 * numbers: its caller does.  No allocation, no static state.
 */
#ifndef FW_TELEMETRY_RX_H
#define FW_TELEMETRY_RX_H

#include <stdint.h>

#include "telemetry/telemetry_frame.h"

/** The decoder.  Fields are private; the counters may be read. */
typedef struct telemetry_rx {
    uint8_t *body;        /**< the caller's buffer: the decoded body */
    uint16_t cap;         /**< its size, bytes */
    uint16_t len;         /**< body bytes decoded so far */
    uint8_t code;         /**< COBS code of the current block (0: none yet) */
    uint8_t left;         /**< its data bytes still to come */
    uint8_t state;        /**< telemetry_rx.c: idle, in a frame, skipping */
    uint16_t frames;      /**< good frames (wraps) */
    uint16_t bad;         /**< bad frames, oversize ones included (wraps) */
    uint16_t oversize;    /**< frames longer than the buffer (wraps) */
} telemetry_rx_t;

/** A good frame.  `payload` points into the decoder's buffer: valid until
 *  the next byte is fed. */
typedef struct telemetry_rx_frame {
    uint8_t channel;
    uint16_t robot_id;
    uint16_t seq;
    const uint8_t *payload;
    uint16_t len;         /**< payload bytes */
} telemetry_rx_frame_t;

/** Starts a decoder on `body` (`cap` bytes: TELEMETRY_HEADER_BYTES +
 *  the largest payload expected + TELEMETRY_CRC_BYTES); counters 0. */
void telemetry_rx_init(telemetry_rx_t *rx, uint8_t *body, uint16_t cap);

/** Feeds one byte off the link.  Returns 1 when it completes a good frame,
 *  which is then in *frame; otherwise 0 (*frame untouched). */
uint8_t telemetry_rx_feed(telemetry_rx_t *rx, uint8_t byte, telemetry_rx_frame_t *frame);

#endif
