/*
 * telemetry_tx.c - a bounded, non-blocking frame sender (telemetry_tx.h).
 */
#include "telemetry_tx.h"

void telemetry_tx_init(telemetry_tx_t *tx)
{
    uint16_t i;
    for (i = 0u; i < TELEMETRY_TX_BUFFER; i++) {
        tx->buf[i] = 0u;
    }
    tx->start = 0u;
    tx->end = 0u;
    tx->seq = 0u;
    tx->frames_queued = 0u;
    tx->frames_dropped = 0u;
    tx->bytes_sent = 0u;
}

uint16_t telemetry_tx_pending(const telemetry_tx_t *tx)
{
    return (uint16_t)(tx->end - tx->start);
}

/* Moves the waiting bytes to the front of the buffer. */
static void compact(telemetry_tx_t *tx)
{
    uint16_t i, n = telemetry_tx_pending(tx);
    for (i = 0u; i < n; i++) {
        tx->buf[i] = tx->buf[(uint16_t)(tx->start + i)];
    }
    tx->start = 0u;
    tx->end = n;
}

uint8_t telemetry_tx_send(telemetry_tx_t *tx, hal_t *hal, uint8_t channel,
                          const uint8_t *payload, uint16_t len)
{
    uint16_t seq = tx->seq, need, n;
    tx->seq = (uint16_t)(tx->seq + 1u);
    if (len > TELEMETRY_MAX_PAYLOAD) {
        tx->frames_dropped++;
        return 0u;
    }
    need = TELEMETRY_FRAME_BYTES(len);
    if ((uint16_t)(TELEMETRY_TX_BUFFER - tx->end) < need && tx->start > 0u) {
        compact(tx);
    }
    if ((uint16_t)(TELEMETRY_TX_BUFFER - tx->end) < need) {
        tx->frames_dropped++;
        (void)telemetry_tx_pump(tx, hal);
        return 0u;
    }
    n = telemetry_frame_encode(&tx->buf[tx->end], (uint16_t)(TELEMETRY_TX_BUFFER - tx->end), channel,
                               hal_robot_id(hal), seq, payload, len);
    if (n == 0u) {
        tx->frames_dropped++;
        return 0u;
    }
    tx->end = (uint16_t)(tx->end + n);
    tx->frames_queued++;
    (void)telemetry_tx_pump(tx, hal);
    return 1u;
}

uint16_t telemetry_tx_pump(telemetry_tx_t *tx, hal_t *hal)
{
    uint16_t waiting = telemetry_tx_pending(tx), took;
    if (waiting == 0u) {
        tx->start = 0u;
        tx->end = 0u;
        return 0u;
    }
    took = hal_telemetry_write(hal, &tx->buf[tx->start], waiting);
    if (took > waiting) {
        took = waiting;   /* a sink that claims more than offered */
    }
    tx->start = (uint16_t)(tx->start + took);
    tx->bytes_sent += took;
    if (tx->start == tx->end) {
        tx->start = 0u;
        tx->end = 0u;
    }
    return telemetry_tx_pending(tx);
}
