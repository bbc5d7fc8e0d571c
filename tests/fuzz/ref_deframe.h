/*
 * ref_deframe.h - a second decoder of the robots' serial framing, written
 * from the format in wire/telemetry/telemetry_frame.h alone, for the
 * harnesses to check the product's (sim_host/core/robot_link.c) against.
 * It shares no code with it: a whole run between two zeros is unstuffed at
 * once, the CRC is table-free and bytewise, and every rule of the format is
 * one test below.  Slow and plain on purpose.
 */
#ifndef TESTS_FUZZ_REF_DEFRAME_H
#define TESTS_FUZZ_REF_DEFRAME_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define REF_HEADER 6
#define REF_CRC 2
#define REF_MAX_PAYLOAD 240
#define REF_MAX_BODY (REF_HEADER + REF_MAX_PAYLOAD + REF_CRC)
#define REF_CHANNELS 7   /* ids 1..6 name a channel; 0 is none */

typedef struct ref_frame {
    uint8_t channel;
    uint16_t robot_id, seq;
    uint16_t len;
    uint8_t payload[REF_MAX_PAYLOAD];
} ref_frame_t;

/** CRC-16/CCITT-FALSE: polynomial 0x1021, init 0xFFFF, MSB first. */
static inline uint16_t ref_crc16(const uint8_t *p, size_t n)
{
    uint32_t crc = 0xFFFF;
    for (size_t i = 0; i < n; i++) {
        for (int b = 7; b >= 0; b--) {
            uint32_t in = (p[i] >> b) & 1u;
            uint32_t top = (crc >> 15) & 1u;
            crc = (crc << 1) & 0xFFFF;
            if (in ^ top) {
                crc ^= 0x1021;
            }
        }
    }
    return (uint16_t)crc;
}

/** Unstuffs one run (no zero in it).  Returns the body's length, or -1 if
 *  a code byte points past the run or the body would exceed `cap`. */
static inline long ref_cobs_decode(const uint8_t *run, size_t n, uint8_t *body, size_t cap)
{
    size_t at = 0, out = 0;
    while (at < n) {
        size_t code = run[at];
        if (code == 0 || at + code > n) {
            return -1;
        }
        if (out + code - 1 > cap) {
            return -1;
        }
        memcpy(body + out, run + at + 1, code - 1);
        out += code - 1;
        at += code;
        /* A block shorter than 254 bytes stands for a zero after it,
         * unless it is the last block. */
        if (code != 0xFF && at < n) {
            if (out + 1 > cap) {
                return -1;
            }
            body[out++] = 0;
        }
    }
    return (long)out;
}

/** The frame in one run between zeros, if it is one: 1 and `*f`, else 0. */
static inline int ref_unframe(const uint8_t *run, size_t n, ref_frame_t *f)
{
    uint8_t body[REF_MAX_BODY];
    long len = ref_cobs_decode(run, n, body, sizeof body);
    if (len < REF_HEADER + REF_CRC) {
        return 0;   /* bad stuffing, too long for the format, or too short */
    }
    uint16_t crc = ref_crc16(body, (size_t)len - REF_CRC);
    if (body[len - 2] != (crc >> 8) || body[len - 1] != (crc & 0xFF)) {
        return 0;
    }
    if (body[0] != 1 || body[1] == 0 || body[1] >= REF_CHANNELS) {
        return 0;   /* another protocol version, or no such channel */
    }
    f->channel = body[1];
    f->robot_id = (uint16_t)(body[2] * 256 + body[3]);
    f->seq = (uint16_t)(body[4] * 256 + body[5]);
    f->len = (uint16_t)(len - REF_HEADER - REF_CRC);
    memcpy(f->payload, body + REF_HEADER, f->len);
    return 1;
}

/** What a stream holds: its frames (the first `cap` kept), how many there
 *  were, and how many non-empty runs between zeros were not frames.  The
 *  bytes after the last zero are an unfinished run: neither. */
typedef struct ref_result {
    size_t frames, bad;
} ref_result_t;

static inline ref_result_t ref_deframe(const uint8_t *s, size_t n, ref_frame_t *out, size_t cap)
{
    ref_result_t r = { 0, 0 };
    size_t start = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] != 0) {
            continue;
        }
        if (i > start) {
            ref_frame_t f;
            if (ref_unframe(s + start, i - start, &f)) {
                if (r.frames < cap) {
                    out[r.frames] = f;
                }
                r.frames++;
            } else {
                r.bad++;
            }
        }
        start = i + 1;
    }
    return r;
}

#endif
