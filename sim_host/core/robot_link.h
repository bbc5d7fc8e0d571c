/*
 * robot_link.h - the host end of a robot's serial telemetry in the
 * simulator: the bytes a controller's image code writes through
 * hal_telemetry_write (firmware/telemetry/robot_telemetry.c, as on the
 * robot), cut into frames and checked exactly as the serial bridge does
 * (tools/swarmtools/telemetry/bridge.py: COBS, CRC-16, version, channel),
 * and held until the step's telemetry republishes them.  A UART's rate
 * can be imposed: at most `baud / 10` bytes per second are accepted.
 */
#ifndef SIM_ROBOT_LINK_H
#define SIM_ROBOT_LINK_H

#include <stdint.h>

#include "telemetry/telemetry_frame.h"

/** Frames a link holds between two republications (one step). */
#define ROBOT_LINK_FRAMES 4u
/** Bytes of raw stream it keeps per step for a dump (a UART at 115200
 *  baud moves 1,152 bytes in 100 ms). */
#define ROBOT_LINK_RAW 4096u

typedef struct robot_link_frame {
    uint8_t channel;                            /**< telemetry_channel_t */
    uint16_t robot_id, seq;
    uint16_t len;
    uint8_t payload[TELEMETRY_MAX_PAYLOAD];
} robot_link_frame_t;

typedef struct robot_link {
    uint8_t acc[TELEMETRY_FRAME_MAX + 4];       /**< COBS bytes of the frame being received */
    uint16_t acc_len;
    uint8_t overflow;                           /**< the current run of bytes is too long */
    robot_link_frame_t frames[ROBOT_LINK_FRAMES];
    uint8_t n_frames;
    uint8_t raw[ROBOT_LINK_RAW];                /**< this step's bytes, for a dump */
    uint16_t raw_len;
    uint32_t budget;                            /**< bytes it may still accept this step */
    uint64_t bytes, good, bad, dropped;         /**< counters: bytes, frames kept, bad, not held */
} robot_link_t;

/** Empty link. */
void robot_link_init(robot_link_t *l);

/** Starts a step: forgets the frames and bytes of the last one and gives
 *  the UART's budget (bytes; UINT32_MAX: unlimited). */
void robot_link_begin_step(robot_link_t *l, uint32_t budget);

/** Takes what the budget allows of `len` bytes; returns how many. */
uint16_t robot_link_write(robot_link_t *l, const uint8_t *bytes, uint16_t len);

#endif
