/*
 * telemetry_frame.h - the serial framing of LCM telemetry from a robot.
 *
 * A robot sends LCM-encoded messages (lcm_types/, the 8-byte fingerprint
 * included) over its telemetry sink (hal_telemetry_write: the Bluetooth
 * UART on the e-puck).  Each message travels in one frame:
 *
 *   frame body (before stuffing), multi-byte fields big-endian:
 *     [0]      protocol version, TELEMETRY_VERSION
 *     [1]      channel id, telemetry_channel_t (which LCM channel and type)
 *     [2..3]   robot id (hal_robot_id)
 *     [4..5]   sequence number, +1 per frame sent, wrapping (the receiver
 *              counts the frames it missed)
 *     [6..]    payload: the LCM-encoded message, 0..TELEMETRY_MAX_PAYLOAD bytes
 *     [-2..-1] CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection,
 *              no final xor) of every byte before it
 *   on the wire:  0x00, COBS(body), 0x00
 *
 * COBS (consistent overhead byte stuffing) removes every zero byte from the
 * body at a cost of one byte per 254, so a zero always means "frame
 * boundary": a receiver that starts mid-stream, or meets garbage, resyncs at
 * the next zero.  The leading zero closes whatever garbage came before (a
 * boot message, line noise) so it costs at most that one frame.  A body is
 * at most 248 bytes, so a frame is at most TELEMETRY_FRAME_MAX = 251 bytes.
 *
 * The same frames go the other way, from a host to robots (the tracker's
 * poses, a planner's messages: docs/host_link.md), on the channels of
 * telemetry_host_channel_t; there the robot id addresses the robot, or
 * every robot (TELEMETRY_BROADCAST_ID).
 *
 * Pure functions, no HAL: telemetry_tx.h sends frames through the HAL,
 * telemetry_rx.h decodes them on a robot, telemetry_host.h lays out the
 * host's payloads.  The host side is tools/swarmtools/telemetry/frames.py
 * (decoder), bridge.py and host_link.py (the host's frames), and the
 * simulator's sim_host/core/robot_link.c.
 */
#ifndef FW_TELEMETRY_FRAME_H
#define FW_TELEMETRY_FRAME_H

#include <stdint.h>

/** Protocol version carried in byte 0. */
#define TELEMETRY_VERSION 1u
/** Header bytes before the payload: version, channel, robot id, sequence. */
#define TELEMETRY_HEADER_BYTES 6u
/** CRC bytes after the payload. */
#define TELEMETRY_CRC_BYTES 2u
/** Largest payload (an LCM-encoded message) one frame carries. */
#define TELEMETRY_MAX_PAYLOAD 240u
/** Largest body: header + payload + CRC (248: one COBS block). */
#define TELEMETRY_MAX_BODY (TELEMETRY_HEADER_BYTES + TELEMETRY_MAX_PAYLOAD + TELEMETRY_CRC_BYTES)
/** Bytes of a frame on the wire for a payload of `len` bytes: the body, one
 *  COBS code byte (bodies stay under 254 bytes) and the two zeros. */
#define TELEMETRY_FRAME_BYTES(len) ((uint16_t)((len) + TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES + 3u))
/** Largest frame on the wire (251 bytes). */
#define TELEMETRY_FRAME_MAX TELEMETRY_FRAME_BYTES(TELEMETRY_MAX_PAYLOAD)

/** Channel ids: the LCM channel (and message type, lcm_types/) a frame's
 *  payload is republished on by the bridge.  Keep in step with
 *  tools/swarmtools/telemetry/frames.py (a test compares them). */
typedef enum telemetry_channel {
    TELEMETRY_CH_ROBOT_STATE = 1,   /**< ROBOT_STATE, swarmlcm.robot_state_t */
    TELEMETRY_CH_EVENT = 2,         /**< SWARM_EVENT, swarmlcm.event_t */
    TELEMETRY_CH_SWARM_STATE = 3,   /**< SWARM_STATE, swarmlcm.swarm_state_t (a nest beacon) */
    TELEMETRY_CH_RUN_INFO = 4,      /**< RUN_INFO, swarmlcm.run_info_t */
    TELEMETRY_CH_RUN_SUMMARY = 5,   /**< RUN_SUMMARY, swarmlcm.run_summary_t */
    TELEMETRY_CH_SCHEMA = 6,        /**< TELEMETRY_SCHEMA, swarmlcm.schema_t */
    TELEMETRY_CH_COUNT = 7
} telemetry_channel_t;

/** Channel ids of the frames a host sends robots.  Bit 7 set: apart from
 *  the robots' ids above, so TELEMETRY_CH_COUNT and the name table stay
 *  the robots' own, and a host that heard one from a robot would not
 *  republish it (the bridge counts it as an unknown channel, the
 *  simulator's robot_link as a bad frame).  Keep in step with frames.py's
 *  HOST_CHANNEL_IDS (a test compares them). */
typedef enum telemetry_host_channel {
    TELEMETRY_CH_POSE = 128,        /**< the tracker's pose of the robot (telemetry_host.h) */
    TELEMETRY_CH_HOST_MSG = 129     /**< 1..HAL_HOST_MSG_MAX bytes for the controller */
} telemetry_host_channel_t;

/** Robot id of a host's frame that every robot takes. */
#define TELEMETRY_BROADCAST_ID 0xFFFFu

/** The LCM channel of each id (index = id; "" for none), for the hosts that
 *  republish frames (the simulator; tools/swarmtools/telemetry/frames.py
 *  keeps the same table, a test compares them). */
#define TELEMETRY_CHANNEL_NAMES \
    { "", "ROBOT_STATE", "SWARM_EVENT", "SWARM_STATE", "RUN_INFO", "RUN_SUMMARY", "TELEMETRY_SCHEMA" }

/** CRC-16/CCITT-FALSE of `len` bytes continuing from `crc` (start with
 *  0xFFFF).  Bitwise: no table in flash.  "123456789" gives 0x29B1. */
uint16_t telemetry_crc16(uint16_t crc, const uint8_t *data, uint16_t len);

/** COBS-encodes `len` bytes into `out`, which has room for `out_size`
 *  bytes, with no delimiter (the common form: no code byte after a last
 *  full block of 254).  Returns the encoded length, len + 1 for len < 254
 *  and at most len + 1 + len / 254, or 0 if `out` is too small. */
uint16_t telemetry_cobs_encode(const uint8_t *in, uint16_t len, uint8_t *out, uint16_t out_size);

/** Writes the whole frame (delimiters included) of `len` payload bytes on
 *  `channel` from robot `robot_id` with sequence number `seq` into `out`
 *  (room for `out_size` bytes; TELEMETRY_FRAME_BYTES(len) needed).  Needs no
 *  other buffer.  Returns the frame's length, or 0 if `len` exceeds
 *  TELEMETRY_MAX_PAYLOAD or `out` is too small (nothing usable written). */
uint16_t telemetry_frame_encode(uint8_t *out, uint16_t out_size, uint8_t channel, uint16_t robot_id,
                                uint16_t seq, const uint8_t *payload, uint16_t len);

#endif
