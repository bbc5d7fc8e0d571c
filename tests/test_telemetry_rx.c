/*
 * test_telemetry_rx.c - the robot's streaming decoder of the frames a host
 * sends (wire/telemetry/telemetry_rx, telemetry_host): frames made by
 * telemetry_frame_encode decoded back byte by byte; corrupted CRC,
 * truncated frames, garbage between frames, a frame too long for the
 * robot's buffer, resync at the next zero; the POSE payload; and the fixed
 * vectors that tools/tests/telemetry/test_host_link.py asserts of the
 * Python encoder, so both encoders are held to the same bytes.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "hal.h"
#include "telemetry/telemetry_frame.h"
#include "telemetry/telemetry_host.h"
#include "telemetry/telemetry_rx.h"

/* A POSE frame to robot 7, seq 0x0102, (1234, -5678) mm, -1571 mrad; and a
 * HOST_MSG broadcast, seq 3, of 01 00 02 7F FF 80.  The same bytes are in
 * tools/tests/telemetry/test_host_link.py. */
static const uint8_t POSE_VECTOR[] = {
    0x00, 0x03, 0x01, 0x80, 0x04, 0x07, 0x01, 0x02, 0x01, 0x0B, 0x04, 0xD2, 0xFF, 0xFF, 0xE9,
    0xD2, 0xF9, 0xDD, 0x10, 0xE2, 0x00 };
static const uint8_t MSG_VECTOR[] = {
    0x00, 0x05, 0x01, 0x81, 0xFF, 0xFF, 0x03, 0x03, 0x01, 0x07, 0x02, 0x7F, 0xFF, 0x80, 0x21,
    0x52, 0x00 };
static const uint8_t MSG_BYTES[] = { 0x01, 0x00, 0x02, 0x7F, 0xFF, 0x80 };

typedef struct rig {
    telemetry_rx_t rx;
    uint8_t body[TELEMETRY_HOST_MAX_BODY];
    telemetry_rx_frame_t got[8];
    uint8_t payload[8][HAL_HOST_MSG_MAX];   /* copies: the decoder's buffer moves on */
    int n;
} rig_t;

static void rig_init(rig_t *r)
{
    memset(r, 0, sizeof *r);
    telemetry_rx_init(&r->rx, r->body, sizeof r->body);
}

static void feed(rig_t *r, const uint8_t *bytes, uint16_t len)
{
    telemetry_rx_frame_t f;
    for (uint16_t i = 0; i < len; i++) {
        if (telemetry_rx_feed(&r->rx, bytes[i], &f) && r->n < 8) {
            assert_true(f.len <= HAL_HOST_MSG_MAX);
            memcpy(r->payload[r->n], f.payload, f.len);
            r->got[r->n] = f;
            r->got[r->n].payload = r->payload[r->n];
            r->n++;
        }
    }
}

static uint16_t pose_frame(uint8_t *out, uint16_t size, uint16_t id, uint16_t seq, int32_t x, int32_t y, int16_t h)
{
    hal_pose_t p = { x, y, h, 0u };
    uint8_t payload[TELEMETRY_POSE_PAYLOAD];
    telemetry_pose_pack(&p, payload);
    return telemetry_frame_encode(out, size, TELEMETRY_CH_POSE, id, seq, payload, TELEMETRY_POSE_PAYLOAD);
}

/* ------------------------------------------------------------ tests */

static void test_fixed_vectors(void **state)
{
    (void)state;
    uint8_t out[100];
    uint16_t n = pose_frame(out, sizeof out, 7u, 0x0102u, 1234, -5678, -1571);
    assert_int_equal(n, sizeof POSE_VECTOR);
    assert_int_equal(n, TELEMETRY_FRAME_BYTES(TELEMETRY_POSE_PAYLOAD));   /* 21 bytes on the wire */
    assert_memory_equal(out, POSE_VECTOR, n);
    n = telemetry_frame_encode(out, sizeof out, TELEMETRY_CH_HOST_MSG, TELEMETRY_BROADCAST_ID, 3u,
                               MSG_BYTES, sizeof MSG_BYTES);
    assert_int_equal(n, sizeof MSG_VECTOR);
    assert_memory_equal(out, MSG_VECTOR, n);

    rig_t r;
    rig_init(&r);
    feed(&r, POSE_VECTOR, sizeof POSE_VECTOR);
    feed(&r, MSG_VECTOR, sizeof MSG_VECTOR);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.got[0].channel, TELEMETRY_CH_POSE);
    assert_int_equal(r.got[0].robot_id, 7);
    assert_int_equal(r.got[0].seq, 0x0102);
    hal_pose_t p;
    assert_int_equal(telemetry_pose_unpack(r.got[0].payload, r.got[0].len, &p), 1);
    assert_int_equal(p.x_mm, 1234);
    assert_int_equal(p.y_mm, -5678);
    assert_int_equal(p.heading_mrad, -1571);
    assert_int_equal(r.got[1].channel, TELEMETRY_CH_HOST_MSG);
    assert_int_equal(r.got[1].robot_id, 0xFFFF);
    assert_int_equal(r.got[1].len, sizeof MSG_BYTES);
    assert_memory_equal(r.got[1].payload, MSG_BYTES, sizeof MSG_BYTES);
    assert_int_equal(r.rx.frames, 2);
    assert_int_equal(r.rx.bad, 0);
}

static void test_pose_payload(void **state)
{
    (void)state;
    hal_pose_t p = { INT32_MIN, INT32_MAX, 3142, 500u }, q = { 1, 2, 3, 4u };
    uint8_t b[TELEMETRY_POSE_PAYLOAD];
    telemetry_pose_pack(&p, b);
    const uint8_t want[] = { 0x80, 0, 0, 0, 0x7F, 0xFF, 0xFF, 0xFF, 0x0C, 0x46 };
    assert_memory_equal(b, want, sizeof want);
    assert_int_equal(telemetry_pose_unpack(b, sizeof b, &q), 1);
    assert_int_equal(q.x_mm, INT32_MIN);
    assert_int_equal(q.y_mm, INT32_MAX);
    assert_int_equal(q.heading_mrad, 3142);
    assert_int_equal(q.age_ms, 0);
    /* Another turn of the heading is wrapped into (-3142, 3142]. */
    p.heading_mrad = -3142;
    telemetry_pose_pack(&p, b);
    assert_int_equal(telemetry_pose_unpack(b, sizeof b, &q), 1);
    assert_int_equal(q.heading_mrad, 3141);
    p.heading_mrad = 32767;
    telemetry_pose_pack(&p, b);
    assert_int_equal(telemetry_pose_unpack(b, sizeof b, &q), 1);
    assert_int_equal(q.heading_mrad, 32767 - 5 * 6283);
    /* Only a 10-byte payload is a pose. */
    q.x_mm = 99;
    assert_int_equal(telemetry_pose_unpack(b, 9, &q), 0);
    assert_int_equal(telemetry_pose_unpack(b, 11, &q), 0);
    assert_int_equal(q.x_mm, 99);
}

static void test_every_length_round_trips(void **state)
{
    (void)state;
    uint8_t payload[HAL_HOST_MSG_MAX], out[TELEMETRY_FRAME_BYTES(HAL_HOST_MSG_MAX)];
    rig_t r;
    rig_init(&r);
    for (uint16_t len = 0; len <= HAL_HOST_MSG_MAX; len++) {
        for (uint16_t k = 0; k < len; k++) payload[k] = (uint8_t)(k % 3u == 0u ? 0u : k * 37u);
        uint16_t n = telemetry_frame_encode(out, sizeof out, TELEMETRY_CH_HOST_MSG, 5u, len, payload, len);
        assert_int_equal(n, TELEMETRY_FRAME_BYTES(len));
        r.n = 0;
        feed(&r, out, n);
        assert_int_equal(r.n, 1);
        assert_int_equal(r.got[0].len, len);
        assert_int_equal(r.got[0].seq, len);
        if (len) assert_memory_equal(r.got[0].payload, payload, len);
    }
    assert_int_equal(r.rx.frames, HAL_HOST_MSG_MAX + 1u);
    assert_int_equal(r.rx.bad, 0);
}

static void test_corrupted_crc_and_version(void **state)
{
    (void)state;
    uint8_t f[64];
    uint16_t n = pose_frame(f, sizeof f, 1u, 9u, 10, 20, 30);
    rig_t r;
    rig_init(&r);
    /* Each byte of the stuffed body flipped in one bit (never into a zero). */
    for (uint16_t k = 1; k + 1u < n; k++) {
        uint8_t g[64];
        memcpy(g, f, n);
        g[k] ^= (uint8_t)(g[k] == 0x01u ? 0x02u : 0x01u);
        feed(&r, g, n);
    }
    assert_int_equal(r.n, 0);
    assert_int_equal(r.rx.bad, n - 2u);
    uint16_t flipped = (uint16_t)(n - 2u);
    /* A good frame of another protocol version is refused too. */
    uint8_t body[TELEMETRY_HOST_MAX_BODY];
    const uint8_t v2[] = { 2, TELEMETRY_CH_POSE, 0, 1, 0, 0 };
    memcpy(body, v2, sizeof v2);
    uint16_t crc = telemetry_crc16(0xFFFFu, body, sizeof v2);
    body[6] = (uint8_t)(crc >> 8);
    body[7] = (uint8_t)crc;
    f[0] = 0;
    n = telemetry_cobs_encode(body, 8, f + 1, sizeof f - 2);
    f[n + 1] = 0;
    feed(&r, f, (uint16_t)(n + 2u));
    assert_int_equal(r.n, 0);
    assert_int_equal(r.rx.bad, flipped + 1u);
    /* The decoder is not stuck: the next good frame comes through. */
    n = pose_frame(f, sizeof f, 1u, 10u, 10, 20, 30);
    feed(&r, f, n);
    assert_int_equal(r.n, 1);
}

static void test_truncated_and_garbage(void **state)
{
    (void)state;
    uint8_t f[64];
    uint16_t n = pose_frame(f, sizeof f, 2u, 1u, -1, -2, -3);
    rig_t r;
    rig_init(&r);
    /* Joined mid-frame: the tail of a frame, then whole ones. */
    feed(&r, f + 8, (uint16_t)(n - 8u));
    assert_int_equal(r.rx.bad, 1);
    feed(&r, f, n);
    assert_int_equal(r.n, 1);
    /* Every truncation of a frame, each closed by the next frame's zero. */
    for (uint16_t cut = 2; cut + 1u < n; cut++) {
        feed(&r, f, cut);
        feed(&r, f, n);
    }
    assert_int_equal(r.n, 8);   /* the rig keeps 8; the decoder counts all */
    assert_int_equal(r.rx.frames, 1 + (n - 3));
    assert_int_equal(r.rx.bad, 1 + (n - 3));
    /* Garbage between frames (no zero in it) costs only itself. */
    const uint8_t junk[] = { 0x41, 0x54, 0x0D, 0xFF, 0x02, 0x99, 0x07 };
    rig_init(&r);
    feed(&r, junk, sizeof junk);
    feed(&r, f, n);
    feed(&r, junk, sizeof junk);
    feed(&r, f, n);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.rx.bad, 2);
    /* Zeros alone (closing and opening delimiters) are no frames. */
    const uint8_t zeros[5] = { 0 };
    feed(&r, zeros, sizeof zeros);
    assert_int_equal(r.rx.bad, 2);
    /* A frame whose closing zero is lost is lost with the next one's
     * leading zero gone too: merged, they fail; the third survives. */
    feed(&r, f, (uint16_t)(n - 1u));
    feed(&r, f + 1, (uint16_t)(n - 1u));
    feed(&r, f, n);
    assert_int_equal(r.n, 3);
    assert_int_equal(r.rx.bad, 3);
}

static void test_oversize_dropped_then_resync(void **state)
{
    (void)state;
    uint8_t big[TELEMETRY_MAX_PAYLOAD], f[TELEMETRY_FRAME_MAX], g[64];
    memset(big, 0x5A, sizeof big);
    rig_t r;
    rig_init(&r);
    /* One byte more than a HOST_MSG may carry: longer than the buffer. */
    uint16_t n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_HOST_MSG, 1u, 0u, big, HAL_HOST_MSG_MAX + 1u);
    feed(&r, f, n);
    assert_int_equal(r.n, 0);
    assert_int_equal(r.rx.oversize, 1);
    assert_int_equal(r.rx.bad, 1);
    /* A robot's largest telemetry frame, the same. */
    n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_ROBOT_STATE, 1u, 0u, big, sizeof big);
    feed(&r, f, n);
    assert_int_equal(r.rx.oversize, 2);
    assert_int_equal(r.rx.bad, 2);
    /* A long run of non-zero garbage, then a good frame right after it. */
    feed(&r, big, sizeof big);
    uint16_t m = pose_frame(g, sizeof g, 3u, 4u, 5, 6, 7);
    feed(&r, g, m);
    assert_int_equal(r.rx.oversize, 3);
    assert_int_equal(r.n, 1);
    assert_int_equal(r.got[0].robot_id, 3);
    /* The largest HOST_MSG fits exactly. */
    n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_HOST_MSG, 1u, 0u, big, HAL_HOST_MSG_MAX);
    feed(&r, f, n);
    assert_int_equal(r.n, 2);
    assert_int_equal(r.got[1].len, HAL_HOST_MSG_MAX);
    assert_int_equal(r.rx.bad, 3);
}

static void test_bad_stuffing(void **state)
{
    (void)state;
    rig_t r;
    rig_init(&r);
    /* A code byte that promises more bytes than come before the zero. */
    const uint8_t short_block[] = { 0x00, 0x09, 0x01, 0x80, 0x00 };
    feed(&r, short_block, sizeof short_block);
    /* Too short for a header and a CRC, though complete. */
    const uint8_t tiny[] = { 0x00, 0x03, 0x01, 0x80, 0x00 };
    feed(&r, tiny, sizeof tiny);
    assert_int_equal(r.n, 0);
    assert_int_equal(r.rx.bad, 2);
    assert_int_equal(r.rx.oversize, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_vectors),
        cmocka_unit_test(test_pose_payload),
        cmocka_unit_test(test_every_length_round_trips),
        cmocka_unit_test(test_corrupted_crc_and_version),
        cmocka_unit_test(test_truncated_and_garbage),
        cmocka_unit_test(test_oversize_dropped_then_resync),
        cmocka_unit_test(test_bad_stuffing),
    };
    return cmocka_run_group_tests_name("telemetry_rx", tests, NULL, NULL);
}
