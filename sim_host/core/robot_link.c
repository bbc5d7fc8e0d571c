/* A robot's telemetry stream, deframed as the bridge does (robot_link.h). */
#include "robot_link.h"

#include <string.h>

void robot_link_init(robot_link_t *l)
{
    memset(l, 0, sizeof *l);
}

void robot_link_begin_step(robot_link_t *l, uint32_t budget)
{
    l->n_frames = 0;
    l->raw_len = 0;
    l->budget = budget;
}

/* COBS-decodes `len` bytes into `out` (room for `cap`); the length, or -1. */
static int cobs_decode(const uint8_t *in, uint16_t len, uint8_t *out, uint16_t cap)
{
    uint16_t i = 0, n = 0;
    while (i < len) {
        uint8_t code = in[i++];
        if (code == 0) {
            return -1;
        }
        for (uint8_t k = 1; k < code; k++) {
            if (i >= len || n >= cap) {
                return -1;
            }
            out[n++] = in[i++];
        }
        if (code < 0xFF && i < len) {
            if (n >= cap) {
                return -1;
            }
            out[n++] = 0;
        }
    }
    return n;
}

/* One run of bytes between two zeros: a frame if it checks out.  The body
 * is decoded into exactly TELEMETRY_MAX_BODY bytes: a longer one breaks
 * the format, whatever its CRC, and its payload would not fit a frame's. */
static void end_frame(robot_link_t *l)
{
    uint8_t body[TELEMETRY_MAX_BODY];
    int n = l->overflow ? -1 : cobs_decode(l->acc, l->acc_len, body, sizeof body);
    uint16_t crc;
    if (l->acc_len == 0 && !l->overflow) {
        return;   /* the leading zero of a frame */
    }
    l->acc_len = 0;
    l->overflow = 0;
    if (n < (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES)) {
        l->bad++;
        return;
    }
    crc = telemetry_crc16(0xFFFFu, body, (uint16_t)(n - 2));
    if (body[n - 2] != (crc >> 8) || body[n - 1] != (crc & 0xFFu) || body[0] != TELEMETRY_VERSION
        || body[1] == 0 || body[1] >= TELEMETRY_CH_COUNT) {
        l->bad++;
        return;
    }
    if (l->n_frames == ROBOT_LINK_FRAMES) {
        l->dropped++;
        return;
    }
    robot_link_frame_t *f = &l->frames[l->n_frames++];
    f->channel = body[1];
    f->robot_id = (uint16_t)((body[2] << 8) | body[3]);
    f->seq = (uint16_t)((body[4] << 8) | body[5]);
    f->len = (uint16_t)(n - (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES));
    memcpy(f->payload, body + TELEMETRY_HEADER_BYTES, f->len);
    l->good++;
}

uint16_t robot_link_write(robot_link_t *l, const uint8_t *bytes, uint16_t len)
{
    uint16_t n = len <= l->budget ? len : (uint16_t)l->budget;
    l->budget -= n;
    l->bytes += n;
    for (uint16_t k = 0; k < n; k++) {
        if (l->raw_len < ROBOT_LINK_RAW) {
            l->raw[l->raw_len++] = bytes[k];
        }
        if (bytes[k] == 0) {
            end_frame(l);
        } else if (l->acc_len < sizeof l->acc) {
            l->acc[l->acc_len++] = bytes[k];
        } else {
            l->overflow = 1;
        }
    }
    return n;
}
