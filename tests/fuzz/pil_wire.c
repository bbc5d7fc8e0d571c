/*
 * pil_wire.c - fuzz target: the processor-in-the-loop protocol
 * (wire/pil/): what the simulator reads from an emulated MCU, which runs
 * an image that may misbehave.  The first byte picks one of:
 *
 *   0  a frame: arbitrary bytes through pil_frame_check; a frame it
 *      accepts has a payload within the frame and PIL_MAX_PAYLOAD, and
 *      sealing its payload again gives the same bytes; then its payload
 *      through every message decoder and every reply reader: what one
 *      accepts, encoded again, decodes to the same message, and encodes
 *      to the same bytes;
 *   1  the simulator's end over a hostile robot: pil_host_hello,
 *      pil_host_config and up to 8 pil_host_step calls over frames cut
 *      from the input (each well formed around an arbitrary type, step
 *      and payload, or arbitrary bytes) with arbitrary emulator reports;
 *      each call succeeds or fails with a one-line error, and what a
 *      successful step hands back is within the protocol's bounds.
 */
#include "fuzz.h"

#include "pil/pil_frame.h"
#include "pil/pil_host.h"
#include "pil/pil_msg.h"

/* ------------------------------------------------------------- frames */

/* Decode, encode again, decode again: the same message; encode again:
 * the same bytes.  T_ is the message type, its pointer fields cleared
 * before the two are compared (their bytes compared by the caller). */
#define ROUND_TRIP(T_, dec_, enc_, p_, n_, fix_)                                     \
    do {                                                                             \
        T_ a, b;                                                                     \
        static uint8_t e1[PIL_MAX_PAYLOAD], e2[PIL_MAX_PAYLOAD];                     \
        memset(&a, 0, sizeof a);                                                     \
        memset(&b, 0, sizeof b);                                                     \
        if (dec_(p_, n_, &a) == 0) {                                                 \
            uint16_t k1 = enc_(e1, (uint16_t)sizeof e1, &a);                         \
            FUZZ_CHECK(k1 > 0 && k1 <= PIL_MAX_PAYLOAD);                             \
            FUZZ_CHECK(dec_(e1, k1, &b) == 0);                                       \
            uint16_t k2 = enc_(e2, (uint16_t)sizeof e2, &b);                         \
            FUZZ_CHECK(k2 == k1 && memcmp(e1, e2, k1) == 0);                         \
            fix_;                                                                    \
            FUZZ_CHECK(memcmp(&a, &b, sizeof a) == 0);                               \
        }                                                                            \
    } while (0)

static void messages(const uint8_t *p, uint16_t n)
{
    ROUND_TRIP(pil_hello_t, pil_hello_decode, pil_hello_encode, p, n, (void)0);
    ROUND_TRIP(pil_config_t, pil_config_decode, pil_config_encode, p, n, (void)0);
    ROUND_TRIP(pil_step_t, pil_step_decode, pil_step_encode, p, n, (void)0);
    ROUND_TRIP(pil_emu_t, pil_emu_decode, pil_emu_encode, p, n, (void)0);
    ROUND_TRIP(pil_peek_t, pil_peek_decode, pil_peek_encode, p, n, (void)0);
    ROUND_TRIP(pil_request_t, pil_request_decode, pil_request_encode, p, n, {
        FUZZ_CHECK(a.len == b.len && a.len <= PIL_TELEMETRY_MAX);
        FUZZ_CHECK(a.len == 0 || memcmp(a.bytes, b.bytes, a.len) == 0);
        a.bytes = b.bytes = NULL;
    });
    ROUND_TRIP(pil_act_t, pil_act_decode, pil_act_encode, p, n, {
        FUZZ_CHECK(a.telemetry_len == b.telemetry_len && a.telemetry_len <= PIL_TELEMETRY_MAX);
        FUZZ_CHECK(a.tx_count <= PIL_TX_MAX);
        FUZZ_CHECK(a.telemetry_len == 0 || memcmp(a.telemetry, b.telemetry, a.telemetry_len) == 0);
        a.telemetry = b.telemetry = NULL;
    });

    /* The robot's readers of the simulator's replies: within their bounds. */
    uint16_t v[HAL_IR_COUNT], g[HAL_GROUND_COUNT], acc;
    hal_blob_t blobs[HAL_MAX_BLOBS];
    hal_status_t st;
    hal_pose_t pose;
    hal_ircom_msg_t m;
    uint8_t buf[HAL_HOST_MSG_MAX], len = 0, count = 0;
    (void)pil_read_readings(p, n, PIL_WHAT_IR, v);
    (void)pil_read_readings(p, n, PIL_WHAT_AMBIENT, v);
    if (pil_read_blobs(p, n, blobs, HAL_MAX_BLOBS, &count) == 0) {
        FUZZ_CHECK(count <= HAL_MAX_BLOBS);
        for (uint8_t k = 0; k < count; k++) {
            FUZZ_CHECK(blobs[k].colour < HAL_COLOUR_COUNT);
        }
    }
    (void)pil_read_pose(p, n, &st, &pose);
    (void)pil_read_rx(p, n, &st, &m);
    if (pil_read_host(p, n, &st, buf, (uint8_t)sizeof buf, &len) == 0) {
        FUZZ_CHECK(len <= sizeof buf);
    }
    (void)pil_read_accepted(p, n, &acc);
    (void)pil_read_ground(p, n, &st, g);
    const uint8_t *frame = pil_read_frame(p, n, 3200);
    FUZZ_CHECK(frame == NULL || (frame >= p && frame + 3200 <= p + n));
}

static void one_frame(fuzz_in_t *in)
{
    static uint8_t buf[PIL_FRAME_MAX + 16], again[PIL_FRAME_MAX + 16];
    uint16_t n = (uint16_t)fuzz_bytes(in, buf, sizeof buf);
    pil_frame_t f;
    if (pil_frame_check(buf, n, &f) == PIL_FRAME_OK) {
        FUZZ_CHECK(f.len <= PIL_MAX_PAYLOAD);
        FUZZ_CHECK(f.payload == buf + PIL_HEADER_BYTES);
        FUZZ_CHECK(PIL_FRAME_BYTES(f.len) <= n);
        memcpy(again + PIL_HEADER_BYTES, f.payload, f.len);
        uint16_t k = pil_frame_seal(again, (uint16_t)sizeof again, f.type, f.seq, f.len);
        FUZZ_CHECK(k == PIL_FRAME_BYTES(f.len) && memcmp(again, buf, k) == 0);
        messages(f.payload, f.len);
    }
    /* The bytes as a bare payload too: the decoders see any length. */
    messages(buf, n < PIL_MAX_PAYLOAD ? n : (uint16_t)PIL_MAX_PAYLOAD);
}

/* ------------------------------------------------- the simulator's end */

typedef struct robot {
    fuzz_in_t *in;
    uint32_t sent;
} robot_t;

static int io_send(void *ctx, const uint8_t *frame, uint16_t len, char *err)
{
    robot_t *r = ctx;
    pil_frame_t f;
    /* What the simulator sends is always a good frame. */
    FUZZ_CHECK(pil_frame_check(frame, len, &f) == PIL_FRAME_OK);
    (void)err;
    r->sent++;
    return 0;
}

static int io_recv(void *ctx, uint8_t *buf, uint16_t cap, uint16_t *len, pil_emu_t *emu, char *err)
{
    robot_t *r = ctx;
    if (r->in->left == 0) {
        snprintf(err, PIL_HOST_ERR, "its emulator exited");
        return -1;
    }
    uint8_t kind = fuzz_u8(r->in);
    emu->event = (kind & 0x80u) ? fuzz_u8(r->in) : PIL_EMU_FRAME;
    emu->cycles = fuzz_u32(r->in);
    emu->first_mark = (kind & 0x40u) ? fuzz_u32(r->in) : PIL_NO_MARK;
    emu->last_mark = (kind & 0x40u) ? fuzz_u32(r->in) : PIL_NO_MARK;
    uint16_t want = fuzz_u16(r->in);
    if (kind & 1u) {
        /* Raw bytes. */
        *len = (uint16_t)fuzz_bytes(r->in, buf, want < cap ? want : cap);
    } else {
        /* A well-formed frame around an arbitrary type, step and payload. */
        uint8_t type = fuzz_u8(r->in), seq = fuzz_u8(r->in);
        uint16_t room = (uint16_t)(cap - PIL_HEADER_BYTES - PIL_CRC_BYTES);
        if (room > PIL_MAX_PAYLOAD) {
            room = PIL_MAX_PAYLOAD;
        }
        uint16_t n = (uint16_t)fuzz_bytes(r->in, buf + PIL_HEADER_BYTES, want < room ? want : room);
        *len = pil_frame_seal(buf, cap, type, seq, n);
    }
    return 0;
}

static void op_readings(void *ctx, uint16_t out[HAL_IR_COUNT])
{
    (void)ctx;
    for (uint8_t k = 0; k < HAL_IR_COUNT; k++) {
        out[k] = (uint16_t)(k * 100u);
    }
}
static uint8_t op_blobs(void *ctx, hal_blob_t out[HAL_MAX_BLOBS])
{
    (void)ctx;
    memset(&out[0], 0, sizeof out[0]);
    out[0].pixels = 12;
    return 1;
}
static int op_frame(void *ctx, uint8_t *out, uint16_t bytes, char *err)
{
    (void)ctx;
    (void)err;
    memset(out, 0x5A, bytes);
    return 0;
}
static hal_status_t op_pose(void *ctx, hal_pose_t *out)
{
    (void)ctx;
    memset(out, 0, sizeof *out);
    return HAL_OK;
}
static hal_status_t op_rx(void *ctx, hal_ircom_msg_t *out)
{
    (void)ctx;
    memset(out, 0, sizeof *out);
    return HAL_ERR_EMPTY;
}
static hal_status_t op_host(void *ctx, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    (void)ctx;
    (void)buf;
    (void)cap;
    *len = 0;
    return HAL_ERR_EMPTY;
}
static hal_status_t op_ground(void *ctx, uint16_t out[HAL_GROUND_COUNT])
{
    (void)ctx;
    memset(out, 0, sizeof(uint16_t) * HAL_GROUND_COUNT);
    return HAL_OK;
}
static uint16_t op_telemetry(void *ctx, const uint8_t *bytes, uint16_t len)
{
    (void)ctx;
    (void)bytes;
    return len;
}

static void checked(int rc, const char *err)
{
    FUZZ_CHECK(rc == 0 || rc == -1);
    if (rc != 0) {
        size_t n = strnlen(err, PIL_HOST_ERR);
        FUZZ_CHECK(n > 0 && n < PIL_HOST_ERR && strchr(err, '\n') == NULL);
    }
}

static void host_end(fuzz_in_t *in)
{
    static pil_host_t h;   /* 5 KB: kept off the stack */
    robot_t r = { in, 0 };
    pil_host_io_t io = { &r, io_send, io_recv };
    pil_host_ops_t ops = { NULL,     op_readings, op_readings, op_blobs,  op_frame,    op_pose,
                           op_rx,    op_host,     op_ground,   op_telemetry };
    char err[PIL_HOST_ERR];
    pil_host_init(&h, &io);
    uint8_t sim_flags = fuzz_u8(in);
    err[0] = '\0';
    int rc = pil_host_hello(&h, err);
    checked(rc, err);
    if (rc != 0) {
        return;
    }
    h.config.period_ms = h.hello.period_ms;
    h.config.ircom_bits = h.hello.ircom_bits;
    h.config.tx_per_period = h.hello.tx_per_period;
    h.config.flags = sim_flags & (PIL_SIM_SOUND | PIL_SIM_FRAMES);
    h.config.cam_width = 40;
    h.config.cam_height = 20;
    rc = pil_host_config(&h, err);
    checked(rc, err);
    for (uint32_t s = 0; rc == 0 && s < 8; s++) {
        pil_step_t st;
        pil_act_t act;
        memset(&st, 0, sizeof st);
        st.step = s;
        st.telemetry_room = fuzz_u16(in);
        rc = pil_host_step(&h, &st, &ops, &act, err);
        checked(rc, err);
        if (rc == 0) {
            FUZZ_CHECK(act.tx_count <= h.config.tx_per_period && act.tx_count <= PIL_TX_MAX);
            FUZZ_CHECK(act.telemetry_len <= PIL_TELEMETRY_MAX);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_in_t in = fuzz_in(data, size);
    switch (fuzz_u8(&in) % 2u) {
    case 0:
        one_frame(&in);
        break;
    default:
        host_end(&in);
        break;
    }
    return 0;
}
