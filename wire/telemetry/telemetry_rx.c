/*
 * telemetry_rx.c - the streaming frame decoder (telemetry_rx.h).
 *
 * COBS, one byte at a time: a code byte c opens a block of c - 1 data
 * bytes; a block with c < 0xFF stood for its data and a zero, but the
 * zero is written only when another block follows (the last block's is
 * not part of the body), so it is written when the next code byte comes.
 */
#include "telemetry/telemetry_rx.h"

/* rx->state */
#define RX_IDLE 0u      /* nothing since the last zero */
#define RX_FRAME 1u     /* decoding a frame */
#define RX_SKIP 2u      /* a frame too long for the buffer: drop to the next zero */

static void rx_restart(telemetry_rx_t *rx)
{
    rx->len = 0u;
    rx->code = 0u;
    rx->left = 0u;
    rx->state = RX_IDLE;
}

void telemetry_rx_init(telemetry_rx_t *rx, uint8_t *body, uint16_t cap)
{
    rx->body = body;
    rx->cap = cap;
    rx->frames = 0u;
    rx->bad = 0u;
    rx->oversize = 0u;
    rx_restart(rx);
}

static void rx_put(telemetry_rx_t *rx, uint8_t byte)
{
    if (rx->len >= rx->cap) {
        /* Counted now, once: the closing zero only restarts. */
        rx->oversize = (uint16_t)(rx->oversize + 1u);
        rx->bad = (uint16_t)(rx->bad + 1u);
        rx->state = RX_SKIP;
        return;
    }
    rx->body[rx->len] = byte;
    rx->len = (uint16_t)(rx->len + 1u);
}

/* The closing zero: is what came since the last zero a good frame? */
static uint8_t rx_end(telemetry_rx_t *rx, telemetry_rx_frame_t *frame)
{
    uint16_t n = rx->len;
    uint16_t crc;
    uint8_t state = rx->state;
    uint8_t complete = (uint8_t)(rx->left == 0u);
    rx_restart(rx);
    if (state != RX_FRAME) {
        return 0u;   /* no frame, or an oversize one already counted */
    }
    if (!complete || n < (uint16_t)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES)
        || rx->body[0] != TELEMETRY_VERSION) {
        rx->bad = (uint16_t)(rx->bad + 1u);
        return 0u;
    }
    crc = telemetry_crc16(0xFFFFu, rx->body, (uint16_t)(n - TELEMETRY_CRC_BYTES));
    if (rx->body[n - 2u] != (uint8_t)(crc >> 8) || rx->body[n - 1u] != (uint8_t)(crc & 0xFFu)) {
        rx->bad = (uint16_t)(rx->bad + 1u);
        return 0u;
    }
    frame->channel = rx->body[1];
    frame->robot_id = (uint16_t)(((uint16_t)rx->body[2] << 8) | rx->body[3]);
    frame->seq = (uint16_t)(((uint16_t)rx->body[4] << 8) | rx->body[5]);
    frame->payload = rx->body + TELEMETRY_HEADER_BYTES;
    frame->len = (uint16_t)(n - TELEMETRY_HEADER_BYTES - TELEMETRY_CRC_BYTES);
    rx->frames = (uint16_t)(rx->frames + 1u);
    return 1u;
}

uint8_t telemetry_rx_feed(telemetry_rx_t *rx, uint8_t byte, telemetry_rx_frame_t *frame)
{
    if (byte == 0u) {
        return rx_end(rx, frame);
    }
    if (rx->state == RX_SKIP) {
        return 0u;
    }
    rx->state = RX_FRAME;
    if (rx->left == 0u) {
        /* A code byte: the previous block's zero, if it had one, comes first. */
        if (rx->code != 0u && rx->code != 0xFFu) {
            rx_put(rx, 0u);
        }
        rx->code = byte;
        rx->left = (uint8_t)(byte - 1u);
    } else {
        rx_put(rx, byte);
        rx->left = (uint8_t)(rx->left - 1u);
    }
    return 0u;
}
