/*
 * telemetry_frame.c - CRC-16, COBS and frames (see telemetry_frame.h).
 * 16-bit int safe: every length and index is a uint16_t, bytes are masked.
 */
#include "telemetry_frame.h"

uint16_t telemetry_crc16(uint16_t crc, const uint8_t *data, uint16_t len)
{
    uint16_t i;
    uint8_t bit;
    for (i = 0u; i < len; i++) {
        crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)data[i] << 8));
        for (bit = 0u; bit < 8u; bit++) {
            if (crc & 0x8000u) {
                crc = (uint16_t)((uint16_t)(crc << 1) ^ 0x1021u);
            } else {
                crc = (uint16_t)(crc << 1);
            }
        }
    }
    return crc;
}

/* A COBS encoder fed one byte at a time, so a frame is stuffed straight
 * from its header, payload and CRC without assembling the body first.
 * A block's code byte is reserved when its first byte comes; a block that
 * fills up (254 data bytes) is closed at once, and the next one opens only
 * if more bytes follow, so no code byte trails the data needlessly (the
 * common form of COBS). */
typedef struct cobs_writer {
    uint8_t *out;
    uint16_t size;       /* room in out */
    uint16_t pos;        /* next byte to write */
    uint16_t code_pos;   /* where the open block's code byte goes */
    uint8_t code;        /* 1 + data bytes in the open block */
    uint8_t open;        /* a block is open */
    uint8_t overflow;    /* out was too small */
} cobs_writer_t;

static void cobs_set(cobs_writer_t *w, uint16_t at, uint8_t byte)
{
    if (at < w->size) {
        w->out[at] = byte;
    } else {
        w->overflow = 1u;
    }
}

static void cobs_open(cobs_writer_t *w)
{
    w->code_pos = w->pos;
    w->pos = (uint16_t)(w->pos + 1u);
    w->code = 1u;
    w->open = 1u;
}

static void cobs_begin(cobs_writer_t *w, uint8_t *out, uint16_t size, uint16_t start)
{
    w->out = out;
    w->size = size;
    w->pos = start;
    w->overflow = 0u;
    cobs_open(w);
}

static void cobs_put(cobs_writer_t *w, uint8_t byte)
{
    if (!w->open) {
        cobs_open(w);
    }
    if (byte == 0u) {
        cobs_set(w, w->code_pos, w->code);
        cobs_open(w);
        return;
    }
    cobs_set(w, w->pos, byte);
    w->pos = (uint16_t)(w->pos + 1u);
    w->code = (uint8_t)(w->code + 1u);
    if (w->code == 0xFFu) {
        cobs_set(w, w->code_pos, w->code);
        w->open = 0u;
    }
}

/* Closes the last block; returns the end position, 0 on overflow. */
static uint16_t cobs_end(cobs_writer_t *w)
{
    if (w->open) {
        cobs_set(w, w->code_pos, w->code);
    }
    return w->overflow ? 0u : w->pos;
}

uint16_t telemetry_cobs_encode(const uint8_t *in, uint16_t len, uint8_t *out, uint16_t out_size)
{
    cobs_writer_t w;
    uint16_t i;
    if (len > 0xFFF0u) {
        return 0u;
    }
    cobs_begin(&w, out, out_size, 0u);
    for (i = 0u; i < len; i++) {
        cobs_put(&w, in[i]);
    }
    return cobs_end(&w);
}

uint16_t telemetry_frame_encode(uint8_t *out, uint16_t out_size, uint8_t channel, uint16_t robot_id,
                                uint16_t seq, const uint8_t *payload, uint16_t len)
{
    uint8_t header[TELEMETRY_HEADER_BYTES];
    uint8_t crc_bytes[TELEMETRY_CRC_BYTES];
    uint16_t crc, i, end;
    cobs_writer_t w;

    if (len > TELEMETRY_MAX_PAYLOAD || out_size < TELEMETRY_FRAME_BYTES(len)) {
        return 0u;
    }
    header[0] = (uint8_t)TELEMETRY_VERSION;
    header[1] = channel;
    header[2] = (uint8_t)(robot_id >> 8);
    header[3] = (uint8_t)(robot_id & 0xFFu);
    header[4] = (uint8_t)(seq >> 8);
    header[5] = (uint8_t)(seq & 0xFFu);
    crc = telemetry_crc16(0xFFFFu, header, TELEMETRY_HEADER_BYTES);
    crc = telemetry_crc16(crc, payload, len);
    crc_bytes[0] = (uint8_t)(crc >> 8);
    crc_bytes[1] = (uint8_t)(crc & 0xFFu);

    out[0] = 0u;
    cobs_begin(&w, out, (uint16_t)(out_size - 1u), 1u);
    for (i = 0u; i < TELEMETRY_HEADER_BYTES; i++) {
        cobs_put(&w, header[i]);
    }
    for (i = 0u; i < len; i++) {
        cobs_put(&w, payload[i]);
    }
    for (i = 0u; i < TELEMETRY_CRC_BYTES; i++) {
        cobs_put(&w, crc_bytes[i]);
    }
    end = cobs_end(&w);
    if (end == 0u) {
        return 0u;
    }
    out[end] = 0u;
    return (uint16_t)(end + 1u);
}
