/* pil_msg.c - pil_msg.h: each layout, written and read a byte at a time. */
#include "pil_msg.h"

#define HELLO_FIXED 20u
#define CONFIG_BYTES 18u
#define STEP_FIXED 15u
#define MIC_CELL_BYTES 5u
#define ACT_FIXED 8u
#define EMU_BYTES 27u
#define BLOB_BYTES 7u

static uint16_t put_name(uint8_t *p, const char *s)
{
    uint8_t n = 0u;
    while (n < PIL_NAME_MAX && s[n] != '\0') {
        p[1u + n] = (uint8_t)s[n];
        n++;
    }
    p[0] = n;
    return (uint16_t)(1u + n);
}

/* The name at p (n bytes left) into out; its length with the count byte,
 * or 0 when it does not fit or holds a byte that is not printable. */
static uint16_t get_name(const uint8_t *p, uint16_t n, char *out)
{
    uint8_t k, len;
    if (n < 1u || p[0] > PIL_NAME_MAX || n < (uint16_t)(1u + p[0])) {
        return 0u;
    }
    len = p[0];
    for (k = 0u; k < len; k++) {
        if (p[1u + k] < 0x20u || p[1u + k] > 0x7Eu) {
            return 0u;
        }
        out[k] = (char)p[1u + k];
    }
    out[len] = '\0';
    return (uint16_t)(1u + len);
}

uint16_t pil_hello_encode(uint8_t *p, uint16_t cap, const pil_hello_t *m)
{
    uint16_t n;
    if (cap < HELLO_FIXED + 2u * (1u + PIL_NAME_MAX)) {
        return 0u;
    }
    pil_put_u16(p, m->period_ms);
    p[2] = m->ircom_bits;
    p[3] = m->tx_per_period;
    p[4] = m->flags;
    pil_put_u16(p + 5, m->mailbox);
    pil_put_u32(p + 7, m->state_addr);
    pil_put_u16(p + 11, m->state_size);
    pil_put_u32(p + 13, m->storage_addr);
    pil_put_u16(p + 17, m->storage_size);
    n = 19u;
    n = (uint16_t)(n + put_name(p + n, m->name));
    n = (uint16_t)(n + put_name(p + n, m->controller));
    return n;
}

int8_t pil_hello_decode(const uint8_t *p, uint16_t n, pil_hello_t *m)
{
    uint16_t at = 19u, k;
    if (n < HELLO_FIXED + 1u) {
        return -1;
    }
    m->period_ms = pil_get_u16(p);
    m->ircom_bits = p[2];
    m->tx_per_period = p[3];
    m->flags = p[4];
    m->mailbox = pil_get_u16(p + 5);
    m->state_addr = pil_get_u32(p + 7);
    m->state_size = pil_get_u16(p + 11);
    m->storage_addr = pil_get_u32(p + 13);
    m->storage_size = pil_get_u16(p + 17);
    k = get_name(p + at, (uint16_t)(n - at), m->name);
    if (k == 0u) {
        return -1;
    }
    at = (uint16_t)(at + k);
    k = get_name(p + at, (uint16_t)(n - at), m->controller);
    if (k == 0u || (uint16_t)(at + k) != n) {
        return -1;
    }
    return 0;
}

uint16_t pil_config_encode(uint8_t *p, uint16_t cap, const pil_config_t *m)
{
    if (cap < CONFIG_BYTES) {
        return 0u;
    }
    pil_put_u16(p, m->robot_id);
    pil_put_u32(p + 2, m->seed);
    pil_put_u16(p + 6, m->period_ms);
    p[8] = m->ircom_bits;
    p[9] = m->tx_per_period;
    p[10] = m->flags;
    pil_put_u16(p + 11, m->cam_width);
    pil_put_u16(p + 13, m->cam_height);
    pil_put_u16(p + 15, m->fov_mrad);
    p[17] = m->selector;
    return CONFIG_BYTES;
}

int8_t pil_config_decode(const uint8_t *p, uint16_t n, pil_config_t *m)
{
    if (n != CONFIG_BYTES) {
        return -1;
    }
    m->robot_id = pil_get_u16(p);
    m->seed = pil_get_u32(p + 2);
    m->period_ms = pil_get_u16(p + 6);
    m->ircom_bits = p[8];
    m->tx_per_period = p[9];
    m->flags = p[10];
    m->cam_width = pil_get_u16(p + 11);
    m->cam_height = pil_get_u16(p + 13);
    m->fov_mrad = pil_get_u16(p + 15);
    m->selector = p[17];
    return (m->ircom_bits == 0u || m->ircom_bits > 16u || m->tx_per_period > PIL_TX_MAX) ? -1 : 0;
}

uint16_t pil_step_encode(uint8_t *p, uint16_t cap, const pil_step_t *m)
{
    uint8_t k;
    uint16_t n = (uint16_t)(STEP_FIXED + (uint16_t)m->mic_count * MIC_CELL_BYTES);
    if (m->mic_count > PIL_MIC_CELLS || cap < n) {
        return 0u;
    }
    pil_put_u32(p, m->step);
    pil_put_u32(p + 4, m->time_ms);
    pil_put_u16(p + 8, (uint16_t)m->steps_left);
    pil_put_u16(p + 10, (uint16_t)m->steps_right);
    pil_put_u16(p + 12, m->telemetry_room);
    p[14] = m->mic_count;
    for (k = 0u; k < m->mic_count; k++) {
        uint8_t *c = p + STEP_FIXED + (uint16_t)k * MIC_CELL_BYTES;
        c[0] = (uint8_t)m->mic[k].status;
        pil_put_u32(c + 1, m->mic[k].level);
    }
    return n;
}

int8_t pil_step_decode(const uint8_t *p, uint16_t n, pil_step_t *m)
{
    uint8_t k;
    if (n < STEP_FIXED || (p[14] != 0u && p[14] != PIL_MIC_CELLS)
        || n != (uint16_t)(STEP_FIXED + (uint16_t)p[14] * MIC_CELL_BYTES)) {
        return -1;
    }
    m->step = pil_get_u32(p);
    m->time_ms = pil_get_u32(p + 4);
    m->steps_left = (int16_t)pil_get_u16(p + 8);
    m->steps_right = (int16_t)pil_get_u16(p + 10);
    m->telemetry_room = pil_get_u16(p + 12);
    m->mic_count = p[14];
    for (k = 0u; k < m->mic_count; k++) {
        const uint8_t *c = p + STEP_FIXED + (uint16_t)k * MIC_CELL_BYTES;
        m->mic[k].status = (int8_t)c[0];
        m->mic[k].level = pil_get_u32(c + 1);
    }
    return 0;
}

uint16_t pil_request_encode(uint8_t *p, uint16_t cap, const pil_request_t *m)
{
    uint16_t k, n = (uint16_t)(2u + (m->what == PIL_WHAT_TELEMETRY ? m->len : 0u));
    if (cap < n || (m->what == PIL_WHAT_TELEMETRY && m->len > PIL_TELEMETRY_MAX)) {
        return 0u;
    }
    p[0] = m->what;
    p[1] = m->arg;
    for (k = 2u; k < n; k++) {
        p[k] = m->bytes[k - 2u];
    }
    return n;
}

int8_t pil_request_decode(const uint8_t *p, uint16_t n, pil_request_t *m)
{
    if (n < 2u || p[0] < PIL_WHAT_IR || p[0] > PIL_WHAT_GROUND) {
        return -1;
    }
    m->what = p[0];
    m->arg = p[1];
    m->bytes = p + 2;
    m->len = (uint16_t)(n - 2u);
    if (m->what == PIL_WHAT_TELEMETRY) {
        return m->len > PIL_TELEMETRY_MAX ? -1 : 0;
    }
    return n == 2u ? 0 : -1;
}

uint16_t pil_act_encode(uint8_t *p, uint16_t cap, const pil_act_t *m)
{
    uint16_t k, at;
    if (m->tx_count > PIL_TX_MAX || m->telemetry_len > PIL_TELEMETRY_MAX
        || cap < (uint16_t)(ACT_FIXED + 2u * m->tx_count + 2u + m->telemetry_len)) {
        return 0u;
    }
    pil_put_u16(p, (uint16_t)m->wheel_left);
    pil_put_u16(p + 2, (uint16_t)m->wheel_right);
    pil_put_u16(p + 4, m->leds);
    p[6] = m->speaker;
    p[7] = m->tx_count;
    at = ACT_FIXED;
    for (k = 0u; k < m->tx_count; k++) {
        pil_put_u16(p + at, m->tx[k]);
        at = (uint16_t)(at + 2u);
    }
    pil_put_u16(p + at, m->telemetry_len);
    at = (uint16_t)(at + 2u);
    for (k = 0u; k < m->telemetry_len; k++) {
        p[at + k] = m->telemetry[k];
    }
    return (uint16_t)(at + m->telemetry_len);
}

int8_t pil_act_decode(const uint8_t *p, uint16_t n, pil_act_t *m)
{
    uint16_t k, at;
    if (n < ACT_FIXED + 2u || p[7] > PIL_TX_MAX || n < (uint16_t)(ACT_FIXED + 2u * p[7] + 2u)) {
        return -1;
    }
    m->wheel_left = (int16_t)pil_get_u16(p);
    m->wheel_right = (int16_t)pil_get_u16(p + 2);
    m->leds = pil_get_u16(p + 4);
    m->speaker = p[6];
    m->tx_count = p[7];
    at = ACT_FIXED;
    for (k = 0u; k < m->tx_count; k++) {
        m->tx[k] = pil_get_u16(p + at);
        at = (uint16_t)(at + 2u);
    }
    m->telemetry_len = pil_get_u16(p + at);
    at = (uint16_t)(at + 2u);
    m->telemetry = p + at;
    return (m->telemetry_len > PIL_TELEMETRY_MAX || (uint16_t)(at + m->telemetry_len) != n) ? -1 : 0;
}

uint16_t pil_emu_encode(uint8_t *p, uint16_t cap, const pil_emu_t *m)
{
    if (cap < EMU_BYTES) {
        return 0u;
    }
    p[0] = m->event;
    pil_put_u32(p + 1, m->cycles);
    pil_put_u32(p + 5, (uint32_t)(m->total & 0xFFFFFFFFu));
    pil_put_u32(p + 9, (uint32_t)(m->total >> 16 >> 16));
    pil_put_u16(p + 13, m->stack_max);
    pil_put_u32(p + 15, m->pc);
    pil_put_u32(p + 19, m->first_mark);
    pil_put_u32(p + 23, m->last_mark);
    return EMU_BYTES;
}

int8_t pil_emu_decode(const uint8_t *p, uint16_t n, pil_emu_t *m)
{
    if (n != EMU_BYTES || p[0] > PIL_EMU_BAD_MAILBOX) {
        return -1;
    }
    m->event = p[0];
    m->cycles = pil_get_u32(p + 1);
    m->total = (uint64_t)pil_get_u32(p + 5) | ((uint64_t)pil_get_u32(p + 9) << 16 << 16);
    m->stack_max = pil_get_u16(p + 13);
    m->pc = pil_get_u32(p + 15);
    m->first_mark = pil_get_u32(p + 19);
    m->last_mark = pil_get_u32(p + 23);
    return 0;
}

/* ---------------------------------------------------------------- replies */

uint16_t pil_reply_readings(uint8_t *p, uint16_t cap, uint8_t what, const uint16_t v[HAL_IR_COUNT])
{
    uint8_t k;
    if (cap < 1u + 2u * HAL_IR_COUNT) {
        return 0u;
    }
    p[0] = what;
    for (k = 0u; k < HAL_IR_COUNT; k++) {
        pil_put_u16(p + 1u + 2u * k, v[k]);
    }
    return 1u + 2u * HAL_IR_COUNT;
}

int8_t pil_read_readings(const uint8_t *p, uint16_t n, uint8_t what, uint16_t out[HAL_IR_COUNT])
{
    uint8_t k;
    if (n != 1u + 2u * HAL_IR_COUNT || p[0] != what) {
        return -1;
    }
    for (k = 0u; k < HAL_IR_COUNT; k++) {
        out[k] = pil_get_u16(p + 1u + 2u * k);
    }
    return 0;
}

uint16_t pil_reply_blobs(uint8_t *p, uint16_t cap, const hal_blob_t *blobs, uint8_t n)
{
    uint8_t k;
    if (n > HAL_MAX_BLOBS || cap < (uint16_t)(2u + (uint16_t)n * BLOB_BYTES)) {
        return 0u;
    }
    p[0] = PIL_WHAT_CAMERA;
    p[1] = n;
    for (k = 0u; k < n; k++) {
        uint8_t *b = p + 2u + (uint16_t)k * BLOB_BYTES;
        b[0] = blobs[k].colour;
        pil_put_u16(b + 1, (uint16_t)blobs[k].bearing_mrad);
        pil_put_u16(b + 3, blobs[k].width_mrad);
        pil_put_u16(b + 5, blobs[k].pixels);
    }
    return (uint16_t)(2u + (uint16_t)n * BLOB_BYTES);
}

int8_t pil_read_blobs(const uint8_t *p, uint16_t n, hal_blob_t *out, uint8_t max, uint8_t *count)
{
    uint8_t k;
    if (n < 2u || p[0] != PIL_WHAT_CAMERA || p[1] > max || n != (uint16_t)(2u + (uint16_t)p[1] * BLOB_BYTES)) {
        return -1;
    }
    *count = p[1];
    for (k = 0u; k < *count; k++) {
        const uint8_t *b = p + 2u + (uint16_t)k * BLOB_BYTES;
        if (b[0] >= HAL_COLOUR_COUNT) {
            return -1;
        }
        out[k].colour = b[0];
        out[k].bearing_mrad = (int16_t)pil_get_u16(b + 1);
        out[k].width_mrad = pil_get_u16(b + 3);
        out[k].pixels = pil_get_u16(b + 5);
    }
    return 0;
}

uint16_t pil_reply_frame(uint8_t *p, uint16_t cap, uint16_t bytes)
{
    if (cap < (uint16_t)(1u + bytes)) {
        return 0u;
    }
    p[0] = PIL_WHAT_CAMERA;
    return (uint16_t)(1u + bytes);
}

const uint8_t *pil_read_frame(const uint8_t *p, uint16_t n, uint16_t bytes)
{
    return (n == (uint16_t)(1u + bytes) && p[0] == PIL_WHAT_CAMERA) ? p + 1 : (const uint8_t *)0;
}

static int8_t status_ok(int8_t st)
{
    return (st == HAL_OK || st == HAL_ERR_UNAVAILABLE || st == HAL_ERR_BUSY || st == HAL_ERR_EMPTY
            || st == HAL_ERR_RANGE) ? 0 : -1;
}

uint16_t pil_reply_pose(uint8_t *p, uint16_t cap, hal_status_t st, const hal_pose_t *pose)
{
    if (cap < 14u) {
        return 0u;
    }
    p[0] = PIL_WHAT_POSE;
    p[1] = (uint8_t)st;
    pil_put_u32(p + 2, (uint32_t)pose->x_mm);
    pil_put_u32(p + 6, (uint32_t)pose->y_mm);
    pil_put_u16(p + 10, (uint16_t)pose->heading_mrad);
    pil_put_u16(p + 12, pose->age_ms);
    return 14u;
}

int8_t pil_read_pose(const uint8_t *p, uint16_t n, hal_status_t *st, hal_pose_t *out)
{
    if (n != 14u || p[0] != PIL_WHAT_POSE || status_ok((int8_t)p[1]) != 0) {
        return -1;
    }
    *st = (hal_status_t)p[1];
    out->x_mm = (int32_t)pil_get_u32(p + 2);
    out->y_mm = (int32_t)pil_get_u32(p + 6);
    out->heading_mrad = (int16_t)pil_get_u16(p + 10);
    out->age_ms = pil_get_u16(p + 12);
    return 0;
}

uint16_t pil_reply_rx(uint8_t *p, uint16_t cap, hal_status_t st, const hal_ircom_msg_t *msg)
{
    if (cap < 9u) {
        return 0u;
    }
    p[0] = PIL_WHAT_RX;
    p[1] = (uint8_t)st;
    pil_put_u16(p + 2, msg->value);
    p[4] = msg->sensor;
    pil_put_u16(p + 5, (uint16_t)msg->bearing_mrad);
    pil_put_u16(p + 7, msg->range_mm);
    return 9u;
}

int8_t pil_read_rx(const uint8_t *p, uint16_t n, hal_status_t *st, hal_ircom_msg_t *out)
{
    if (n != 9u || p[0] != PIL_WHAT_RX || status_ok((int8_t)p[1]) != 0) {
        return -1;
    }
    *st = (hal_status_t)p[1];
    out->value = pil_get_u16(p + 2);
    out->sensor = p[4];
    out->bearing_mrad = (int16_t)pil_get_u16(p + 5);
    out->range_mm = pil_get_u16(p + 7);
    return 0;
}

uint16_t pil_reply_host(uint8_t *p, uint16_t cap, hal_status_t st, const uint8_t *bytes, uint8_t len)
{
    uint8_t k;
    if (len > HAL_HOST_MSG_MAX || cap < (uint16_t)(3u + len)) {
        return 0u;
    }
    p[0] = PIL_WHAT_HOST;
    p[1] = (uint8_t)st;
    p[2] = len;
    for (k = 0u; k < len; k++) {
        p[3u + k] = bytes[k];
    }
    return (uint16_t)(3u + len);
}

int8_t pil_read_host(const uint8_t *p, uint16_t n, hal_status_t *st, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    uint8_t k;
    if (n < 3u || p[0] != PIL_WHAT_HOST || status_ok((int8_t)p[1]) != 0 || p[2] > cap
        || n != (uint16_t)(3u + p[2]) || ((int8_t)p[1] != HAL_OK && p[2] != 0u)) {
        return -1;
    }
    *st = (hal_status_t)p[1];
    *len = p[2];
    for (k = 0u; k < *len; k++) {
        buf[k] = p[3u + k];
    }
    return 0;
}

uint16_t pil_reply_accepted(uint8_t *p, uint16_t cap, uint16_t accepted)
{
    if (cap < 3u) {
        return 0u;
    }
    p[0] = PIL_WHAT_TELEMETRY;
    pil_put_u16(p + 1, accepted);
    return 3u;
}

int8_t pil_read_accepted(const uint8_t *p, uint16_t n, uint16_t *accepted)
{
    if (n != 3u || p[0] != PIL_WHAT_TELEMETRY) {
        return -1;
    }
    *accepted = pil_get_u16(p + 1);
    return 0;
}

uint16_t pil_reply_ground(uint8_t *p, uint16_t cap, hal_status_t st, const uint16_t v[HAL_GROUND_COUNT])
{
    uint8_t k;
    if (cap < 2u + 2u * HAL_GROUND_COUNT) {
        return 0u;
    }
    p[0] = PIL_WHAT_GROUND;
    p[1] = (uint8_t)st;
    for (k = 0u; k < HAL_GROUND_COUNT; k++) {
        pil_put_u16(p + 2u + 2u * k, v[k]);
    }
    return 2u + 2u * HAL_GROUND_COUNT;
}

int8_t pil_read_ground(const uint8_t *p, uint16_t n, hal_status_t *st, uint16_t out[HAL_GROUND_COUNT])
{
    uint8_t k;
    if (n != 2u + 2u * HAL_GROUND_COUNT || p[0] != PIL_WHAT_GROUND
        || ((int8_t)p[1] != HAL_OK && (int8_t)p[1] != HAL_ERR_UNAVAILABLE)) {
        return -1;
    }
    *st = (hal_status_t)p[1];
    for (k = 0u; k < HAL_GROUND_COUNT; k++) {
        out[k] = pil_get_u16(p + 2u + 2u * k);
    }
    return 0;
}

uint16_t pil_peek_encode(uint8_t *p, uint16_t cap, const pil_peek_t *m)
{
    if (cap < 6u) {
        return 0u;
    }
    pil_put_u32(p, m->addr);
    pil_put_u16(p + 4, m->len);
    return 6u;
}

int8_t pil_peek_decode(const uint8_t *p, uint16_t n, pil_peek_t *m)
{
    if (n != 6u) {
        return -1;
    }
    m->addr = pil_get_u32(p);
    m->len = pil_get_u16(p + 4);
    return m->len > PIL_MAX_PAYLOAD ? -1 : 0;
}
