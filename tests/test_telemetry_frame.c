/*
 * test_telemetry_frame.c - the robots' telemetry framing
 * (firmware/telemetry_frame, firmware/telemetry_tx): CRC-16 and COBS against
 * published vectors, frame layout, limits, the non-blocking sender over a
 * slow sink, and a robot_state_t encoded by the lcm-gen C code carried
 * through a frame and back.
 *
 * The HAL here is this file's own (a sink that takes a set number of bytes
 * per call): only hal_robot_id and hal_telemetry_write are needed.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "hal.h"
#include "swarmlcm_robot_state_t.h"
#include "telemetry/telemetry_frame.h"
#include "telemetry/telemetry_tx.h"

/* ------------------------------------------------------------ fake sink */

#define SINK_MAX 65536u

struct hal {
    uint16_t id;
    uint16_t accept;        /* bytes taken per call */
    uint32_t calls;
    uint32_t n;
    uint8_t out[SINK_MAX];
};

uint16_t hal_robot_id(hal_t *hal) { return hal->id; }

uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len)
{
    uint16_t take = len < hal->accept ? len : hal->accept;
    hal->calls++;
    if (hal->n + take > SINK_MAX) take = (uint16_t)(SINK_MAX - hal->n);
    memcpy(hal->out + hal->n, bytes, take);
    hal->n += take;
    return take;
}

static hal_t sink;

/* ------------------------------------------------------------ helpers */

/* A plain COBS decoder (the reference the host's Python one also follows).
 * Returns the decoded length, or -1 on a malformed input. */
static int cobs_decode(const uint8_t *in, int len, uint8_t *out, int out_max)
{
    int i = 0, n = 0;
    while (i < len) {
        int code = in[i++];
        if (code == 0 || i + code - 1 > len) return -1;
        for (int k = 1; k < code; k++) {
            if (n >= out_max || in[i] == 0) return -1;
            out[n++] = in[i++];
        }
        if (code < 0xFF && i < len) {
            if (n >= out_max) return -1;
            out[n++] = 0;
        }
    }
    return n;
}

/* Unframes one frame (0, COBS, 0): the body's length, or -1. */
static int unframe(const uint8_t *frame, int len, uint8_t *body, int body_max)
{
    if (len < 3 || frame[0] != 0 || frame[len - 1] != 0) return -1;
    for (int k = 1; k < len - 1; k++) {
        if (frame[k] == 0) return -1;
    }
    return cobs_decode(frame + 1, len - 2, body, body_max);
}

static void check_cobs(const uint8_t *in, uint16_t len, const uint8_t *want, uint16_t want_len)
{
    uint8_t out[600], back[600];
    uint16_t n = telemetry_cobs_encode(in, len, out, sizeof out);
    assert_int_equal(n, want_len);
    assert_memory_equal(out, want, want_len);
    assert_int_equal(cobs_decode(out, n, back, sizeof back), len);
    if (len) assert_memory_equal(back, in, len);
}

/* ------------------------------------------------------------ tests */

static void test_crc16_check_value(void **state)
{
    (void)state;
    /* CRC-16/CCITT-FALSE: check value of "123456789" is 0x29B1. */
    const uint8_t digits[] = "123456789";
    assert_int_equal(telemetry_crc16(0xFFFFu, digits, 9), 0x29B1);
    /* Continuing a CRC equals computing it at once. */
    uint16_t part = telemetry_crc16(0xFFFFu, digits, 4);
    assert_int_equal(telemetry_crc16(part, digits + 4, 5), 0x29B1);
    assert_int_equal(telemetry_crc16(0xFFFFu, digits, 0), 0xFFFF);
    /* Appending the CRC big-endian leaves residue 0 (no reflection, no xor). */
    uint8_t with_crc[11];
    memcpy(with_crc, digits, 9);
    with_crc[9] = 0x29;
    with_crc[10] = 0xB1;
    assert_int_equal(telemetry_crc16(0xFFFFu, with_crc, 11), 0);
}

static void test_cobs_vectors(void **state)
{
    (void)state;
    /* The examples of Cheshire and Baker's COBS (as on Wikipedia). */
    { const uint8_t i[] = { 0x00 }, o[] = { 0x01, 0x01 }; check_cobs(i, 1, o, 2); }
    { const uint8_t i[] = { 0x00, 0x00 }, o[] = { 0x01, 0x01, 0x01 }; check_cobs(i, 2, o, 3); }
    { const uint8_t i[] = { 0x00, 0x11, 0x00 }, o[] = { 0x01, 0x02, 0x11, 0x01 }; check_cobs(i, 3, o, 4); }
    { const uint8_t i[] = { 0x11, 0x22, 0x00, 0x33 }, o[] = { 0x03, 0x11, 0x22, 0x02, 0x33 }; check_cobs(i, 4, o, 5); }
    { const uint8_t i[] = { 0x11, 0x22, 0x33, 0x44 }, o[] = { 0x05, 0x11, 0x22, 0x33, 0x44 }; check_cobs(i, 4, o, 5); }
    { const uint8_t i[] = { 0x11, 0x00, 0x00, 0x00 }, o[] = { 0x02, 0x11, 0x01, 0x01, 0x01 }; check_cobs(i, 4, o, 5); }
    { const uint8_t o[] = { 0x01 }; check_cobs(NULL, 0, o, 1); }
    /* 01..FE (254 bytes): one full block, no trailing code byte. */
    uint8_t in[256], want[260];
    for (int k = 0; k < 254; k++) in[k] = (uint8_t)(k + 1);
    want[0] = 0xFF;
    memcpy(want + 1, in, 254);
    check_cobs(in, 254, want, 255);
    /* 00..FE (255 bytes): 01, then a full block. */
    for (int k = 0; k < 255; k++) in[k] = (uint8_t)k;
    want[0] = 0x01;
    want[1] = 0xFF;
    memcpy(want + 2, in + 1, 254);
    check_cobs(in, 255, want, 256);
    /* 01..FF (255 bytes): a full block, then 02 FF. */
    for (int k = 0; k < 255; k++) in[k] = (uint8_t)(k + 1);
    want[0] = 0xFF;
    memcpy(want + 1, in, 254);
    want[255] = 0x02;
    want[256] = 0xFF;
    check_cobs(in, 255, want, 257);
    /* Too small an output: 0. */
    uint8_t small[4];
    assert_int_equal(telemetry_cobs_encode(in, 4, small, 4), 0);
    assert_int_equal(telemetry_cobs_encode(in, 4, small, 0), 0);
}

static void test_frame_layout(void **state)
{
    (void)state;
    const uint8_t payload[] = { 0x00, 0x01, 0x00, 0x00, 0xFF, 0x7E, 0x00 };
    uint8_t frame[TELEMETRY_FRAME_MAX], body[300];
    uint16_t n = telemetry_frame_encode(frame, sizeof frame, TELEMETRY_CH_EVENT, 0x1234u, 0xBEEFu,
                                        payload, sizeof payload);
    assert_int_equal(n, TELEMETRY_FRAME_BYTES(sizeof payload));
    int len = unframe(frame, n, body, sizeof body);
    assert_int_equal(len, (int)(TELEMETRY_HEADER_BYTES + sizeof payload + TELEMETRY_CRC_BYTES));
    const uint8_t header[] = { TELEMETRY_VERSION, TELEMETRY_CH_EVENT, 0x12, 0x34, 0xBE, 0xEF };
    assert_memory_equal(body, header, sizeof header);
    assert_memory_equal(body + TELEMETRY_HEADER_BYTES, payload, sizeof payload);
    assert_int_equal(telemetry_crc16(0xFFFFu, body, (uint16_t)len), 0);
    /* An empty payload is a frame too. */
    n = telemetry_frame_encode(frame, sizeof frame, TELEMETRY_CH_ROBOT_STATE, 0, 0, NULL, 0);
    assert_int_equal(n, TELEMETRY_FRAME_BYTES(0));
    assert_int_equal(unframe(frame, n, body, sizeof body), 8);
}

static void test_frame_limits(void **state)
{
    (void)state;
    uint8_t payload[TELEMETRY_MAX_PAYLOAD + 1], frame[TELEMETRY_FRAME_MAX + 8], body[300];
    /* The largest payload, all zeros (every byte stuffed) and all 0xFF. */
    for (int fill = 0; fill < 2; fill++) {
        memset(payload, fill ? 0xFF : 0x00, sizeof payload);
        uint16_t n = telemetry_frame_encode(frame, TELEMETRY_FRAME_MAX, TELEMETRY_CH_ROBOT_STATE, 65535u, 7,
                                            payload, TELEMETRY_MAX_PAYLOAD);
        assert_int_equal(n, TELEMETRY_FRAME_MAX);
        assert_int_equal(TELEMETRY_FRAME_MAX, 251);
        int len = unframe(frame, n, body, sizeof body);
        assert_int_equal(len, TELEMETRY_MAX_BODY);
        assert_memory_equal(body + TELEMETRY_HEADER_BYTES, payload, TELEMETRY_MAX_PAYLOAD);
        assert_int_equal(telemetry_crc16(0xFFFFu, body, (uint16_t)len), 0);
    }
    /* One byte too many, or one byte too little room: nothing. */
    assert_int_equal(telemetry_frame_encode(frame, sizeof frame, 1, 0, 0, payload, TELEMETRY_MAX_PAYLOAD + 1), 0);
    assert_int_equal(telemetry_frame_encode(frame, TELEMETRY_FRAME_BYTES(10) - 1, 1, 0, 0, payload, 10), 0);
    assert_int_equal(telemetry_frame_encode(frame, TELEMETRY_FRAME_BYTES(10), 1, 0, 0, payload, 10),
                     TELEMETRY_FRAME_BYTES(10));
}

/* Frames sent through a sink taking `accept` bytes per call arrive whole,
 * in order, with consecutive sequence numbers. */
static void test_tx_slow_sink(void **state)
{
    (void)state;
    static telemetry_tx_t tx;
    uint8_t payload[100], want[4096];
    uint32_t want_n = 0;
    memset(&sink, 0, sizeof sink);
    sink.id = 42;
    sink.accept = 7;
    telemetry_tx_init(&tx);
    for (uint16_t f = 0; f < 10; f++) {
        for (int k = 0; k < 100; k++) payload[k] = (uint8_t)(f * 31 + k);
        uint16_t len = (uint16_t)(20 + f * 8);
        assert_int_equal(telemetry_tx_send(&tx, &sink, TELEMETRY_CH_ROBOT_STATE, payload, len), 1);
        want_n += telemetry_frame_encode(want + want_n, (uint16_t)(sizeof want - want_n), TELEMETRY_CH_ROBOT_STATE,
                                         42, f, payload, len);
        for (int step = 0; step < 40; step++) telemetry_tx_pump(&tx, &sink);   /* control steps */
    }
    assert_int_equal(telemetry_tx_pending(&tx), 0);
    assert_int_equal(sink.n, want_n);
    assert_memory_equal(sink.out, want, want_n);
    assert_int_equal(tx.frames_queued, 10);
    assert_int_equal(tx.frames_dropped, 0);
    assert_int_equal(tx.bytes_sent, want_n);
}

/* A sink that takes nothing: the buffer holds two largest frames, the
 * third is dropped whole (and uses its sequence number), and nothing is
 * lost of the queued ones once the sink drains. */
static void test_tx_full_buffer_drops_whole_frames(void **state)
{
    (void)state;
    static telemetry_tx_t tx;
    uint8_t payload[TELEMETRY_MAX_PAYLOAD], body[300];
    memset(payload, 0x5A, sizeof payload);
    memset(&sink, 0, sizeof sink);
    sink.id = 3;
    sink.accept = 0;
    telemetry_tx_init(&tx);
    assert_int_equal(telemetry_tx_send(&tx, &sink, 1, payload, sizeof payload), 1);
    assert_int_equal(telemetry_tx_send(&tx, &sink, 1, payload, sizeof payload), 1);
    assert_int_equal(telemetry_tx_send(&tx, &sink, 1, payload, sizeof payload), 0);
    assert_int_equal(telemetry_tx_send(&tx, &sink, 1, payload, TELEMETRY_MAX_PAYLOAD + 1u), 0);
    assert_int_equal(tx.frames_dropped, 2);
    assert_int_equal(telemetry_tx_pending(&tx), 2 * TELEMETRY_FRAME_MAX);
    assert_int_equal(tx.seq, 4);
    /* Half drains; a small frame now fits after compaction. */
    sink.accept = TELEMETRY_FRAME_MAX;
    assert_int_equal(telemetry_tx_pump(&tx, &sink), TELEMETRY_FRAME_MAX);
    sink.accept = 0;
    assert_int_equal(telemetry_tx_send(&tx, &sink, 2, payload, 10), 1);
    sink.accept = 1000;
    assert_int_equal(telemetry_tx_pump(&tx, &sink), 0);
    assert_int_equal(sink.n, 2 * TELEMETRY_FRAME_MAX + TELEMETRY_FRAME_BYTES(10));
    /* The stream: frames with sequence 0, 1, then 4. */
    const uint8_t *p = sink.out;
    const uint16_t seqs[] = { 0, 1, 4 };
    for (int f = 0; f < 3; f++) {
        int flen = f < 2 ? TELEMETRY_FRAME_MAX : TELEMETRY_FRAME_BYTES(10);
        int len = unframe(p, flen, body, sizeof body);
        assert_true(len > 0);
        assert_int_equal((body[4] << 8) | body[5], seqs[f]);
        assert_int_equal((body[2] << 8) | body[3], 3);
        assert_int_equal(telemetry_crc16(0xFFFFu, body, (uint16_t)len), 0);
        p += flen;
    }
}

/* The firmware path end to end: a robot_state_t encoded by the lcm-gen C
 * code fits one frame and comes back identical. */
static void test_lcm_message_through_a_frame(void **state)
{
    (void)state;
    swarmlcm_robot_state_t m, back;
    memset(&m, 0, sizeof m);
    m.utime = 123400000;
    m.robot_id = 7;
    m.controller = (char *)"forager";
    m.state = (char *)"return";
    m.version = SWARMLCM_ROBOT_STATE_T_VERSION;
    m.group = (char *)"";
    /* The forager's ten values (forager_def.c). */
    float values[10] = { 12.0f, 3.0f, 2.5f, 0.75f, 14.0f, 0.5f, 0.25f, 4.0f, 6.0f, 1.0f };
    m.n_values = 10;
    m.values = values;
    m.ir_max = 301;
    m.ir_max_index = 7;
    m.ambient_min = 3100;
    m.blobs = 1;
    m.wheel_left = 388;
    m.wheel_right = 350;
    m.leds = 0x101;
    m.pose_known = 0;
    m.x = m.y = m.theta = NAN;
    uint8_t payload[TELEMETRY_MAX_PAYLOAD], frame[TELEMETRY_FRAME_MAX], body[300];
    int size = swarmlcm_robot_state_t_encoded_size(&m);
    assert_true(size <= (int)TELEMETRY_MAX_PAYLOAD);
    assert_int_equal(swarmlcm_robot_state_t_encode(payload, 0, sizeof payload, &m), size);
    uint16_t n = telemetry_frame_encode(frame, sizeof frame, TELEMETRY_CH_ROBOT_STATE, 7, 1, payload, (uint16_t)size);
    assert_int_equal(n, TELEMETRY_FRAME_BYTES(size));
    int len = unframe(frame, n, body, sizeof body);
    assert_int_equal(len, size + 8);
    assert_int_equal(swarmlcm_robot_state_t_decode(body + TELEMETRY_HEADER_BYTES, 0, size, &back), size);
    assert_string_equal(back.controller, "forager");
    assert_string_equal(back.state, "return");
    assert_int_equal(back.robot_id, 7);
    assert_int_equal(back.n_values, 10);
    assert_true(back.values[0] == 12.0f && back.values[2] == 2.5f);
    assert_true(back.leds == 0x101 && isnan(back.x));
    swarmlcm_robot_state_t_decode_cleanup(&back);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc16_check_value),
        cmocka_unit_test(test_cobs_vectors),
        cmocka_unit_test(test_frame_layout),
        cmocka_unit_test(test_frame_limits),
        cmocka_unit_test(test_tx_slow_sink),
        cmocka_unit_test(test_tx_full_buffer_drops_whole_frames),
        cmocka_unit_test(test_lcm_message_through_a_frame),
    };
    return cmocka_run_group_tests_name("telemetry_frame", tests, NULL, NULL);
}
