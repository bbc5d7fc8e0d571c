/* pil_robot.c - pil_robot.h. */
#include "pil_robot.h"

#include "blob_detect.h"

#define PAYLOAD(r) ((r)->mailbox + PIL_HEADER_BYTES)
#define ROOM(r) ((uint16_t)((r)->mailbox_cap - PIL_HEADER_BYTES - PIL_CRC_BYTES))

void pil_robot_init(pil_robot_t *r, uint8_t *mailbox, uint16_t cap, uint8_t image_flags, uint8_t ircom_bits,
                    uint8_t tx_per_period)
{
    uint16_t k;
    uint8_t *p = (uint8_t *)r;
    for (k = 0u; k < (uint16_t)sizeof *r; k++) {
        p[k] = 0u;
    }
    r->mailbox = mailbox;
    r->mailbox_cap = cap;
    r->image_flags = image_flags;
    r->ircom_bits = ircom_bits;
    r->tx_per_period = tx_per_period;
    r->pose_status = HAL_ERR_UNAVAILABLE;
}

/* The simulator's frame in the mailbox, checked: its payload length, or -1
 * after a FAULT naming what was wrong. */
static int16_t fault(pil_robot_t *r, uint8_t code, uint8_t type)
{
    uint8_t *p = PAYLOAD(r);
    p[0] = code;
    p[1] = type;
    r->faults++;
    pil_port_exchange(r->mailbox, r->mailbox_cap,
                      pil_frame_seal(r->mailbox, r->mailbox_cap, PIL_FAULT, r->seq, 2u));
    return -1;
}

/* Sends the `len`-byte payload already in the mailbox as `type` and reads
 * the answer, which must be of type `want` and this step's: its payload's
 * length, or -1 after a FAULT. */
static int16_t exchange(pil_robot_t *r, uint8_t type, uint16_t len, uint8_t want, uint8_t seq)
{
    pil_frame_t f;
    uint16_t n = pil_frame_seal(r->mailbox, r->mailbox_cap, type, r->seq, len);
    pil_port_exchange(r->mailbox, r->mailbox_cap, n);
    if (pil_frame_check(r->mailbox, r->mailbox_cap, &f) != PIL_FRAME_OK) {
        return fault(r, PIL_FAULT_FRAME, 0u);
    }
    if (f.type != want) {
        return fault(r, PIL_FAULT_TYPE, f.type);
    }
    if (f.seq != seq) {
        return fault(r, PIL_FAULT_SEQ, f.type);
    }
    return (int16_t)f.len;
}

int8_t pil_robot_hello(pil_robot_t *r, pil_hello_t *hello)
{
    int16_t n;
    hello->ircom_bits = r->ircom_bits;
    hello->tx_per_period = r->tx_per_period;
    hello->flags = r->image_flags;
    hello->mailbox = r->mailbox_cap;
    n = exchange(r, PIL_HELLO, pil_hello_encode(PAYLOAD(r), ROOM(r), hello), PIL_CONFIG, 0u);
    if (n < 0) {
        return -1;
    }
    if (pil_config_decode(PAYLOAD(r), (uint16_t)n, &r->cfg) != 0) {
        (void)fault(r, PIL_FAULT_PAYLOAD, PIL_CONFIG);
        return -1;
    }
    return 0;
}

/* The STEP now in the mailbox (n payload bytes, or -1): this step's. */
static int8_t take_step(pil_robot_t *r, int16_t n)
{
    r->have = 0u;
    r->tx_count = 0u;
    r->telemetry_len = 0u;
    r->running = 1u;
    if (n < 0) {
        r->telemetry_room = 0u;
        return -1;
    }
    if (pil_step_decode(PAYLOAD(r), (uint16_t)n, &r->step) != 0) {
        r->telemetry_room = 0u;
        (void)fault(r, PIL_FAULT_PAYLOAD, PIL_STEP);
        return -1;
    }
    r->seq = (uint8_t)(r->step.step & 0xFFu);
    r->telemetry_room = r->step.telemetry_room;
    return 0;
}

int8_t pil_robot_ready(pil_robot_t *r)
{
    return take_step(r, exchange(r, PIL_READY, 0u, PIL_STEP, 0u));
}

int8_t pil_robot_end_step(pil_robot_t *r)
{
    pil_act_t act;
    uint16_t len;
    act.wheel_left = r->wheel_left;
    act.wheel_right = r->wheel_right;
    act.leds = r->leds;
    act.speaker = r->speaker;
    act.tx_count = r->tx_count;
    for (len = 0u; len < PIL_TX_MAX; len++) {
        act.tx[len] = r->tx[len];
    }
    act.telemetry_len = r->telemetry_len;
    act.telemetry = r->telemetry;
    len = pil_act_encode(PAYLOAD(r), ROOM(r), &act);
    r->running = 0u;
    return take_step(r, exchange(r, PIL_ACT, len, PIL_STEP, (uint8_t)(r->seq + 1u)));
}

/* A REQUEST for `what` (arg), its REPLY's payload length or -1. */
static int16_t request(pil_robot_t *r, uint8_t what, uint8_t arg, const uint8_t *bytes, uint16_t len)
{
    pil_request_t q;
    q.what = what;
    q.arg = arg;
    q.bytes = bytes;
    q.len = len;
    if (!r->running) {
        return -1;   /* between steps (a failed STEP): nothing to ask */
    }
    return exchange(r, PIL_REQUEST, pil_request_encode(PAYLOAD(r), ROOM(r), &q), PIL_REPLY, r->seq);
}

/* A reply that does not decode: FAULT, and the channel reads as empty. */
static void bad_reply(pil_robot_t *r)
{
    (void)fault(r, PIL_FAULT_PAYLOAD, PIL_REPLY);
}

static void readings(pil_robot_t *r, uint8_t what, uint8_t bit, uint16_t *out, uint16_t none)
{
    uint8_t k;
    int16_t n;
    if (r->have & bit) {
        return;
    }
    r->have |= bit;
    n = request(r, what, 0u, (const uint8_t *)0, 0u);
    if (n < 0 || pil_read_readings(PAYLOAD(r), (uint16_t)n, what, out) != 0) {
        if (n >= 0) {
            bad_reply(r);
        }
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            out[k] = none;
        }
    }
}

uint16_t pil_robot_ir(pil_robot_t *r, uint8_t index)
{
    if (index >= HAL_IR_COUNT) {
        return 0u;
    }
    readings(r, PIL_WHAT_IR, PIL_HAVE_IR, r->ir, 0u);
    return r->ir[index];
}

uint16_t pil_robot_ambient(pil_robot_t *r, uint8_t index)
{
    if (index >= HAL_IR_COUNT) {
        return HAL_RAW_MAX;
    }
    readings(r, PIL_WHAT_AMBIENT, PIL_HAVE_AMBIENT, r->ambient, HAL_RAW_MAX);
    return r->ambient[index];
}

/* The frame in the mailbox's reply, through the robot's own detector with
 * the parameters the simulator's rendered camera uses (blob_detect.h's
 * defaults, the frame's field of view, the driver's byte order). */
static uint8_t detect(pil_robot_t *r, const uint8_t *frame)
{
    blob_detect_params_t bp = blob_detect_default_params();
    blob_detect_work_t work;
    bp.fov_mrad = r->cfg.fov_mrad;
    bp.byte_order = BLOB_BYTE_ORDER_BIG;
    return blob_detect(&bp, frame, r->cfg.cam_width, r->cfg.cam_height, &work, r->blobs, (uint8_t)HAL_MAX_BLOBS);
}

uint8_t pil_robot_blobs(pil_robot_t *r, hal_blob_t *out, uint8_t max)
{
    uint8_t k, n;
    if (!(r->image_flags & PIL_HAS_CAMERA)) {
        return 0u;
    }
    if (!(r->have & PIL_HAVE_CAMERA)) {
        int16_t len;
        r->have |= PIL_HAVE_CAMERA;
        r->blob_count = 0u;
        len = request(r, PIL_WHAT_CAMERA, 0u, (const uint8_t *)0, 0u);
        if (len >= 0 && (r->cfg.flags & PIL_SIM_FRAMES)) {
            const uint8_t *frame = pil_read_frame(PAYLOAD(r), (uint16_t)len,
                                                  (uint16_t)(2u * r->cfg.cam_width * r->cfg.cam_height));
            if (frame) {
                r->blob_count = detect(r, frame);
            } else {
                bad_reply(r);
            }
        } else if (len >= 0 && pil_read_blobs(PAYLOAD(r), (uint16_t)len, r->blobs, (uint8_t)HAL_MAX_BLOBS,
                                              &r->blob_count) != 0) {
            r->blob_count = 0u;
            bad_reply(r);
        }
    }
    n = r->blob_count < max ? r->blob_count : max;
    for (k = 0u; k < n; k++) {
        out[k] = r->blobs[k];
    }
    return n;
}

hal_status_t pil_robot_frame_size(pil_robot_t *r, uint16_t *width_px, uint16_t *height_px)
{
    if (!(r->image_flags & PIL_HAS_CAMERA)) {
        return HAL_ERR_UNAVAILABLE;
    }
    *width_px = r->cfg.cam_width;
    *height_px = r->cfg.cam_height;
    return HAL_OK;
}

hal_status_t pil_robot_ground(pil_robot_t *r, uint8_t index, uint16_t *reflected)
{
    *reflected = 0u;
    if (index >= HAL_GROUND_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (!(r->image_flags & PIL_HAS_GROUND)) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (!(r->have & PIL_HAVE_GROUND)) {
        int16_t n;
        uint8_t k;
        r->have |= PIL_HAVE_GROUND;
        r->ground_status = HAL_ERR_UNAVAILABLE;
        n = request(r, PIL_WHAT_GROUND, 0u, (const uint8_t *)0, 0u);
        if (n < 0 || pil_read_ground(PAYLOAD(r), (uint16_t)n, &r->ground_status, r->ground) != 0) {
            if (n >= 0) {
                bad_reply(r);
            }
            r->ground_status = HAL_ERR_UNAVAILABLE;
            for (k = 0u; k < HAL_GROUND_COUNT; k++) {
                r->ground[k] = 0u;
            }
        }
    }
    if (r->ground_status == HAL_OK) {
        *reflected = r->ground[index];
    }
    return r->ground_status;
}

hal_status_t pil_robot_mic_level(pil_robot_t *r, uint8_t mic, uint8_t band, uint32_t *level)
{
    const pil_mic_cell_t *c;
    *level = 0u;
    if (mic >= HAL_MIC_COUNT || band == 0u || band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (!(r->image_flags & PIL_HAS_SOUND) || r->step.mic_count != PIL_MIC_CELLS) {
        return HAL_ERR_UNAVAILABLE;
    }
    c = &r->step.mic[(uint8_t)(mic * (HAL_SOUND_BANDS - 1u) + band - 1u)];
    *level = c->status == HAL_OK ? c->level : 0u;
    return c->status;
}

hal_status_t pil_robot_speaker_set(pil_robot_t *r, uint8_t band)
{
    if (band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (!(r->image_flags & PIL_HAS_SOUND) || !(r->cfg.flags & PIL_SIM_SOUND)) {
        return HAL_ERR_UNAVAILABLE;
    }
    r->speaker = band;
    return HAL_OK;
}

uint8_t pil_robot_ircom_bits(pil_robot_t *r)
{
    return r->ircom_bits;
}

hal_status_t pil_robot_ircom_send(pil_robot_t *r, uint16_t value)
{
    if (r->tx_count >= r->tx_per_period || r->tx_count >= PIL_TX_MAX) {
        return HAL_ERR_BUSY;
    }
    r->tx[r->tx_count++] = r->ircom_bits >= 16u ? value : (uint16_t)(value & (uint16_t)((1u << r->ircom_bits) - 1u));
    return HAL_OK;
}

hal_status_t pil_robot_ircom_receive(pil_robot_t *r, hal_ircom_msg_t *out)
{
    hal_status_t st;
    hal_ircom_msg_t m;
    int16_t n = request(r, PIL_WHAT_RX, 0u, (const uint8_t *)0, 0u);
    if (n < 0) {
        return HAL_ERR_EMPTY;
    }
    if (pil_read_rx(PAYLOAD(r), (uint16_t)n, &st, &m) != 0 || (st != HAL_OK && st != HAL_ERR_EMPTY)) {
        bad_reply(r);
        return HAL_ERR_EMPTY;
    }
    if (st == HAL_OK) {
        *out = m;
    }
    return st;
}

void pil_robot_wheels(pil_robot_t *r, int16_t left, int16_t right)
{
    r->wheel_left = left > HAL_WHEEL_SPEED_MAX ? HAL_WHEEL_SPEED_MAX
                    : (left < -HAL_WHEEL_SPEED_MAX ? -HAL_WHEEL_SPEED_MAX : left);
    r->wheel_right = right > HAL_WHEEL_SPEED_MAX ? HAL_WHEEL_SPEED_MAX
                     : (right < -HAL_WHEEL_SPEED_MAX ? -HAL_WHEEL_SPEED_MAX : right);
}

void pil_robot_led_bit(pil_robot_t *r, uint8_t bit, uint8_t on)
{
    r->leds = on ? (uint16_t)(r->leds | (1u << bit)) : (uint16_t)(r->leds & ~(1u << bit));
}

hal_status_t pil_robot_pose(pil_robot_t *r, hal_pose_t *out)
{
    if (!(r->image_flags & PIL_HAS_HOST_LINK)) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (!(r->have & PIL_HAVE_POSE)) {
        hal_status_t st;
        int16_t n;
        r->have |= PIL_HAVE_POSE;
        r->pose_status = HAL_ERR_UNAVAILABLE;
        n = request(r, PIL_WHAT_POSE, 0u, (const uint8_t *)0, 0u);
        if (n >= 0 && pil_read_pose(PAYLOAD(r), (uint16_t)n, &st, &r->pose) == 0) {
            r->pose_status = st;
        } else if (n >= 0) {
            bad_reply(r);
        }
    }
    *out = r->pose;
    return r->pose_status;
}

hal_status_t pil_robot_host_receive(pil_robot_t *r, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    hal_status_t st;
    int16_t n;
    *len = 0u;
    if (!(r->image_flags & PIL_HAS_HOST_LINK)) {
        return HAL_ERR_UNAVAILABLE;
    }
    n = request(r, PIL_WHAT_HOST, cap, (const uint8_t *)0, 0u);
    if (n < 0) {
        return HAL_ERR_EMPTY;
    }
    if (pil_read_host(PAYLOAD(r), (uint16_t)n, &st, buf, cap, len) != 0) {
        bad_reply(r);
        *len = 0u;
        return HAL_ERR_EMPTY;
    }
    return st;
}

/* Hands the step's telemetry bytes over before ACT, to make room. */
static void flush_telemetry(pil_robot_t *r)
{
    uint16_t accepted;
    int16_t n = request(r, PIL_WHAT_TELEMETRY, 0u, r->telemetry, r->telemetry_len);
    if (n >= 0 && (pil_read_accepted(PAYLOAD(r), (uint16_t)n, &accepted) != 0 || accepted != r->telemetry_len)) {
        bad_reply(r);
    }
    r->telemetry_len = 0u;
}

uint16_t pil_robot_telemetry_write(pil_robot_t *r, const uint8_t *bytes, uint16_t len)
{
    uint16_t k, n;
    if (!r->running) {
        return 0u;
    }
    n = len;
    if (r->telemetry_room != PIL_ROOM_UNLIMITED) {
        n = n < r->telemetry_room ? n : r->telemetry_room;
        r->telemetry_room = (uint16_t)(r->telemetry_room - n);
    }
    for (k = 0u; k < n; k++) {
        if (r->telemetry_len == PIL_TELEMETRY_MAX) {
            flush_telemetry(r);
        }
        r->telemetry[r->telemetry_len++] = bytes[k];
    }
    return n;
}
