/*
 * telemetry_host.h - the payloads of the frames a host sends a robot
 * (telemetry_frame.h: TELEMETRY_CH_POSE, TELEMETRY_CH_HOST_MSG), and the
 * largest such frame, which sizes a robot's receive buffer.
 *
 *   POSE      x_mm int32, y_mm int32, heading_mrad int16, big-endian like
 *             the frame's header: TELEMETRY_POSE_PAYLOAD = 10 bytes.  The
 *             tracker's fix in the arena's frame (hal.h: hal_pose_t).
 *   HOST_MSG  1..HAL_HOST_MSG_MAX opaque bytes, the controller's to read
 *             (hal_host_receive).
 *
 * The host's encoder is tools/swarmtools/telemetry/host_link.py.  Pure
 * functions, no state.
 */
#ifndef FW_TELEMETRY_HOST_H
#define FW_TELEMETRY_HOST_H

#include <stdint.h>

#include "hal.h"
#include "telemetry/telemetry_frame.h"

/** Bytes of a POSE payload. */
#define TELEMETRY_POSE_PAYLOAD 10u
/** Largest body a robot takes from a host: a HOST_MSG of HAL_HOST_MSG_MAX
 *  bytes with its header and CRC (72).  A robot's decoder needs this much,
 *  not TELEMETRY_MAX_BODY: the robots' 248-byte frames never come its way. */
#define TELEMETRY_HOST_MAX_BODY (TELEMETRY_HEADER_BYTES + HAL_HOST_MSG_MAX + TELEMETRY_CRC_BYTES)

/** Writes the POSE payload of `pose` (age_ms is not sent) into `out`. */
void telemetry_pose_pack(const hal_pose_t *pose, uint8_t out[TELEMETRY_POSE_PAYLOAD]);

/** Reads a POSE payload of `len` bytes into `pose` (age_ms 0), its heading
 *  wrapped to (-3142, 3142] in case a host sent another turn of it.
 *  Returns 1, or 0 when `len` is not TELEMETRY_POSE_PAYLOAD (`pose`
 *  untouched). */
uint8_t telemetry_pose_unpack(const uint8_t *payload, uint16_t len, hal_pose_t *pose);

#endif
