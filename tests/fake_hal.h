/*
 * fake_hal.h - a scripted hal.h for unit tests of controllers.
 *
 * Defines `struct hal` (sensor values the test sets, wheel speeds and LEDs
 * the controller sets, an IR inbox queue and an outbox log, a tracker pose
 * and a queue of host messages) and a
 * non-static definition of every hal_* function of hal/hal.h except
 * hal_ir_bearing_mrad and hal_camera_widest (hal/hal_common.c).  Include it from exactly one .c
 * per test binary; then the simulator's HAL is not linked in, so such a
 * test must not call any sim_* function.
 *
 * Between two controller steps call fake_hal_end_step(): it advances the
 * clock and lets the controller send again.
 */
#ifndef TESTS_FAKE_HAL_H
#define TESTS_FAKE_HAL_H

#include <stdint.h>
#include <string.h>

#include "hal.h"

#define FAKE_INBOX_MAX 64u
#define FAKE_OUTBOX_MAX 4096u
#define FAKE_HOST_QUEUE_MAX 8u

struct hal {
    /* Identity and time. */
    uint16_t id;
    uint32_t time_ms;
    uint16_t period_ms;
    uint8_t payload_bits;

    /* Scripted sensors. */
    uint16_t proximity[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint8_t n_blobs;
    hal_colour_stats_t frame_stats;  /* what hal_camera_colour_stats gives, */
    uint8_t has_frames;              /* when set (else unavailable) */
    uint32_t mic[HAL_MIC_COUNT][HAL_SOUND_BANDS];  /**< level counts */
    uint8_t has_ground;           /**< the robot carries the ground-sensor module */
    uint16_t ground[HAL_GROUND_COUNT];             /**< its readings, counts */

    /* Recorded actuators. */
    int16_t left, right;          /**< last wheel speeds set */
    uint32_t wheel_calls;
    int16_t steps_left, steps_right;
    uint8_t leds;                 /**< bit i = ring LED i */
    uint8_t body_led, front_led;
    uint8_t speaker_band;         /**< what the controller set */
    uint8_t speaker_played;       /**< what played during the last period (fake_hal_end_step) */
    uint32_t telemetry_bytes;

    /* IR communication. */
    hal_ircom_msg_t inbox[FAKE_INBOX_MAX];
    uint32_t in_head, in_count;
    uint16_t outbox[FAKE_OUTBOX_MAX];
    uint32_t out_count;           /**< frames sent in all (the log keeps the first FAKE_OUTBOX_MAX) */
    uint16_t last_sent;
    uint8_t sent_this_step;
    uint8_t tx_per_step;          /**< sends accepted per step (1, as the HAL's default) */

    /* Tracker: hal_pose gives `pose` while pose_valid (0 after init: no
     * tracker), and HAL_ERR_UNAVAILABLE when its age_ms is above
     * HAL_POSE_MAX_AGE_MS, as hal.h says. */
    uint8_t pose_valid;
    hal_pose_t pose;

    /* Host messages (hal_host_receive): a queue the test fills with
     * fake_hal_host_push; host_unavailable makes the link absent. */
    uint8_t host_msg[FAKE_HOST_QUEUE_MAX][HAL_HOST_MSG_MAX];
    uint8_t host_len[FAKE_HOST_QUEUE_MAX];
    uint32_t host_head, host_count;
    uint32_t host_polls;          /**< hal_host_receive calls */
    uint8_t host_unavailable;
};

/* ------------------------------------------------------------ test side */

/** Robot `id`, 100 ms steps, 16-bit messages, dark, nothing in view. */
static inline void fake_hal_init(hal_t *hal, uint16_t id)
{
    uint8_t i;
    memset(hal, 0, sizeof *hal);
    hal->id = id;
    hal->period_ms = 100u;
    hal->payload_bits = 16u;
    hal->tx_per_step = 1u;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->ambient[i] = 4000u;
    }
}

static inline void fake_hal_end_step(hal_t *hal)
{
    hal->time_ms += hal->period_ms;
    hal->sent_this_step = 0u;
    hal->speaker_played = hal->speaker_band;
}

/** Queues a received message; returns 0 when the inbox is full. */
static inline int fake_hal_push(hal_t *hal, uint16_t value, uint16_t range_mm, int16_t bearing_mrad)
{
    hal_ircom_msg_t *m;
    if (hal->in_count >= FAKE_INBOX_MAX) {
        return 0;
    }
    m = &hal->inbox[(hal->in_head + hal->in_count) % FAKE_INBOX_MAX];
    m->value = value;
    m->sensor = 0u;
    m->bearing_mrad = bearing_mrad;
    m->range_mm = range_mm;
    hal->in_count++;
    return 1;
}

/** Shows one blob (replacing what was in view). */
static inline void fake_hal_show_blob(hal_t *hal, uint8_t colour, int16_t bearing_mrad, uint16_t width_mrad)
{
    hal->n_blobs = 1u;
    hal->blobs[0].colour = colour;
    hal->blobs[0].bearing_mrad = bearing_mrad;
    hal->blobs[0].width_mrad = width_mrad;
    hal->blobs[0].pixels = (uint16_t)(width_mrad / 10u);
}

static inline void fake_hal_clear_blobs(hal_t *hal) { hal->n_blobs = 0u; }

/** The tracker sees the robot at (x, y) heading `heading_mrad`, a fix
 *  `age_ms` old. */
static inline void fake_hal_set_pose(hal_t *hal, int32_t x_mm, int32_t y_mm, int16_t heading_mrad, uint16_t age_ms)
{
    hal->pose_valid = 1u;
    hal->pose.x_mm = x_mm;
    hal->pose.y_mm = y_mm;
    hal->pose.heading_mrad = heading_mrad;
    hal->pose.age_ms = age_ms;
}

/** The tracker has lost the robot. */
static inline void fake_hal_lose_pose(hal_t *hal) { hal->pose_valid = 0u; }

/** Queues a message from the host (at most HAL_HOST_MSG_MAX bytes are
 *  kept, the length as given so that an over-long one can be tried);
 *  returns 0 when the queue is full. */
static inline int fake_hal_host_push(hal_t *hal, const uint8_t *bytes, uint8_t len)
{
    uint32_t k;
    if (hal->host_count >= FAKE_HOST_QUEUE_MAX) {
        return 0;
    }
    k = (hal->host_head + hal->host_count) % FAKE_HOST_QUEUE_MAX;
    memcpy(hal->host_msg[k], bytes, len < HAL_HOST_MSG_MAX ? len : HAL_HOST_MSG_MAX);
    hal->host_len[k] = len;
    hal->host_count++;
    return 1;
}

/* ------------------------------------------------------------ hal.h */

uint16_t hal_robot_id(hal_t *hal) { return hal->id; }
uint32_t hal_time_ms(hal_t *hal) { return hal->time_ms; }
uint16_t hal_control_period_ms(hal_t *hal) { return hal->period_ms; }

uint16_t hal_ir_proximity(hal_t *hal, uint8_t index)
{
    return index < HAL_IR_COUNT ? hal->proximity[index] : 0u;
}

uint16_t hal_ir_ambient(hal_t *hal, uint8_t index)
{
    return index < HAL_IR_COUNT ? hal->ambient[index] : (uint16_t)HAL_RAW_MAX;
}

uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max)
{
    uint8_t i;
    uint8_t n = hal->n_blobs < max ? hal->n_blobs : max;
    for (i = 0; i < n; i++) {
        out[i] = hal->blobs[i];
    }
    return n;
}

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px)
{
    (void)hal;
    *width_px = 40u;
    *height_px = 20u;
    return HAL_OK;
}

hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    memset(out, 0, sizeof *out);
    if (colour >= (uint8_t)HAL_COLOUR_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (!hal->has_frames) {
        return HAL_ERR_UNAVAILABLE;
    }
    *out = hal->frame_stats;
    return HAL_OK;
}

hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level)
{
    if (mic >= HAL_MIC_COUNT || band == 0u || band >= HAL_SOUND_BANDS) {
        *level = 0;
        return HAL_ERR_RANGE;
    }
    if (hal->speaker_played != 0u) {
        *level = 0;
        return HAL_ERR_BUSY;     /* its own tone drowned the microphones */
    }
    *level = hal->mic[mic][band];
    return HAL_OK;
}

hal_status_t hal_speaker_set(hal_t *hal, uint8_t band)
{
    if (band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    hal->speaker_band = band;
    return HAL_OK;
}

hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected)
{
    *reflected = 0;
    if (index >= HAL_GROUND_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (!hal->has_ground) {
        return HAL_ERR_UNAVAILABLE;
    }
    *reflected = hal->ground[index];
    return HAL_OK;
}

hal_status_t hal_pose(hal_t *hal, hal_pose_t *out)
{
    if (hal->pose_valid == 0u || hal->pose.age_ms > HAL_POSE_MAX_AGE_MS) {
        return HAL_ERR_UNAVAILABLE;
    }
    *out = hal->pose;
    return HAL_OK;
}

hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    uint32_t k = hal->host_head;
    hal->host_polls++;
    if (hal->host_unavailable != 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (hal->host_count == 0u) {
        return HAL_ERR_EMPTY;
    }
    if (hal->host_len[k] > cap || hal->host_len[k] > HAL_HOST_MSG_MAX) {
        return HAL_ERR_RANGE;   /* it stays (an over-long one always) */
    }
    memcpy(buf, hal->host_msg[k], hal->host_len[k]);
    *len = hal->host_len[k];
    hal->host_head = (hal->host_head + 1u) % FAKE_HOST_QUEUE_MAX;
    hal->host_count--;
    return HAL_OK;
}

uint8_t hal_ircom_payload_bits(hal_t *hal) { return hal->payload_bits; }

hal_status_t hal_ircom_send(hal_t *hal, uint16_t value)
{
    if (hal->sent_this_step >= hal->tx_per_step) {
        return HAL_ERR_BUSY;
    }
    if (hal->payload_bits < 16u) {
        value = (uint16_t)(value & ((1u << hal->payload_bits) - 1u));
    }
    hal->sent_this_step++;
    if (hal->out_count < FAKE_OUTBOX_MAX) {
        hal->outbox[hal->out_count] = value;
    }
    hal->out_count++;
    hal->last_sent = value;
    return HAL_OK;
}

hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out)
{
    if (hal->in_count == 0u) {
        return HAL_ERR_EMPTY;
    }
    *out = hal->inbox[hal->in_head];
    hal->in_head = (hal->in_head + 1u) % FAKE_INBOX_MAX;
    hal->in_count--;
    return HAL_OK;
}

void hal_set_wheel_speeds(hal_t *hal, int16_t left_steps_s, int16_t right_steps_s)
{
    if (left_steps_s > HAL_WHEEL_SPEED_MAX) left_steps_s = HAL_WHEEL_SPEED_MAX;
    if (left_steps_s < -HAL_WHEEL_SPEED_MAX) left_steps_s = -HAL_WHEEL_SPEED_MAX;
    if (right_steps_s > HAL_WHEEL_SPEED_MAX) right_steps_s = HAL_WHEEL_SPEED_MAX;
    if (right_steps_s < -HAL_WHEEL_SPEED_MAX) right_steps_s = -HAL_WHEEL_SPEED_MAX;
    hal->left = left_steps_s;
    hal->right = right_steps_s;
    hal->wheel_calls++;
}

void hal_wheel_steps(hal_t *hal, int16_t *left, int16_t *right)
{
    *left = hal->steps_left;
    *right = hal->steps_right;
}

void hal_set_led(hal_t *hal, uint8_t index, uint8_t on)
{
    if (index >= HAL_LED_COUNT) {
        return;
    }
    if (on != 0u) {
        hal->leds = (uint8_t)(hal->leds | (1u << index));
    } else {
        hal->leds = (uint8_t)(hal->leds & ~(1u << index));
    }
}

void hal_set_body_led(hal_t *hal, uint8_t on) { hal->body_led = on; }
void hal_set_front_led(hal_t *hal, uint8_t on) { hal->front_led = on; }

uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len)
{
    (void)bytes;
    hal->telemetry_bytes += len;
    return len;
}

#endif
