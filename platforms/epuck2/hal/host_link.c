/*
 * host_link.c - poses and messages from the host over UART3 (host_link.h):
 * hal_pose and hal_host_receive on the e-puck2.  No mutable static
 * storage: the state is the image's hal_epuck2_host_t, reached through
 * struct hal.
 */
#include "host_link.h"

#include <stddef.h>

#include "epuck2_os.h"
#include "hal_epuck2.h"

/* Bytes taken from the serial queue at once (on the stack). */
#define RX_CHUNK 32u

void hal_epuck2_host_attach(hal_t *hal, hal_epuck2_host_t *host)
{
    uint8_t *b = (uint8_t *)host;
    size_t i;
    for (i = 0; i < sizeof *host; i++) {
        b[i] = 0u;
    }
    telemetry_rx_init(&host->rx, host->body, (uint16_t)sizeof host->body);
    hal->host = host;
}

uint16_t hal_epuck2_host_step_bytes(uint16_t period_ms)
{
    uint32_t n = (uint32_t)period_ms * HAL_EPUCK2_UART_BYTES_PER_S / 1000u;
    return n > 0xFFFFu ? (uint16_t)0xFFFFu : (uint16_t)n;
}

/* A HOST_MSG frame into the mailbox, or counted as dropped when it is full
 * (the waiting ones are older, and a route's order matters). */
static void mailbox_put(hal_epuck2_host_t *h, const telemetry_rx_frame_t *f)
{
    uint8_t slot;
    uint8_t i;
    if (h->msg_count >= HAL_EPUCK2_HOST_SLOTS) {
        h->msg_dropped = (uint16_t)(h->msg_dropped + 1u);
        return;
    }
    slot = (uint8_t)((h->msg_head + h->msg_count) % HAL_EPUCK2_HOST_SLOTS);
    for (i = 0; i < (uint8_t)f->len; i++) {
        h->msg[slot][i] = f->payload[i];
    }
    h->msg_len[slot] = (uint8_t)f->len;
    h->msg_count++;
    h->msgs = (uint16_t)(h->msgs + 1u);
}

/* A good frame: ours (or everyone's), then by channel. */
static void frame_in(hal_t *hal, hal_epuck2_host_t *h, const telemetry_rx_frame_t *f)
{
    if (f->robot_id != hal->cfg.robot_id && f->robot_id != TELEMETRY_BROADCAST_ID) {
        h->not_ours = (uint16_t)(h->not_ours + 1u);
    } else if (f->channel == TELEMETRY_CH_POSE && telemetry_pose_unpack(f->payload, f->len, &h->pose) != 0u) {
        h->pose_at_ms = hal->time_ms;
        h->has_pose = 1u;
        h->poses = (uint16_t)(h->poses + 1u);
    } else if (f->channel == TELEMETRY_CH_HOST_MSG && f->len >= 1u && f->len <= HAL_HOST_MSG_MAX) {
        mailbox_put(h, f);
    } else {
        h->ignored = (uint16_t)(h->ignored + 1u);
    }
}

void hal_epuck2_host_drain(hal_t *hal, uint16_t max_bytes)
{
    hal_epuck2_host_t *h = hal->host;
    telemetry_rx_frame_t f;
    uint8_t chunk[RX_CHUNK];
    uint16_t done = 0u;
    if (h == NULL) {
        return;
    }
    while (done < max_bytes) {
        uint16_t want = (uint16_t)(max_bytes - done) < RX_CHUNK ? (uint16_t)(max_bytes - done) : (uint16_t)RX_CHUNK;
        uint16_t got = epuck2_os_serial_read(chunk, want);
        uint16_t i;
        for (i = 0u; i < got; i++) {
            if (telemetry_rx_feed(&h->rx, chunk[i], &f) != 0u) {
                frame_in(hal, h, &f);
            }
        }
        done = (uint16_t)(done + got);
        if (got < want) {
            return;   /* the queue is empty */
        }
    }
}

/* ------------------------------------------------------------ hal.h */

hal_status_t hal_pose(hal_t *hal, hal_pose_t *out)
{
    const hal_epuck2_host_t *h = hal->host;
    if (h != NULL && h->has_pose != 0u && hal->time_ms - h->pose_at_ms <= HAL_POSE_MAX_AGE_MS) {
        *out = h->pose;
        out->age_ms = (uint16_t)(hal->time_ms - h->pose_at_ms);
        return HAL_OK;
    }
    out->x_mm = 0;
    out->y_mm = 0;
    out->heading_mrad = 0;
    out->age_ms = 0u;
    return HAL_ERR_UNAVAILABLE;
}

hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    hal_epuck2_host_t *h = hal->host;
    uint8_t n;
    uint8_t i;
    *len = 0u;
    if (h == NULL) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (h->msg_count == 0u) {
        return HAL_ERR_EMPTY;
    }
    n = h->msg_len[h->msg_head];
    if (n > cap) {
        return HAL_ERR_RANGE;
    }
    for (i = 0; i < n; i++) {
        buf[i] = h->msg[h->msg_head][i];
    }
    *len = n;
    h->msg_head = (uint8_t)((h->msg_head + 1u) % HAL_EPUCK2_HOST_SLOTS);
    h->msg_count--;
    return HAL_OK;
}
