/*
 * test_pil_wire.c - the PIL protocol (wire/pil/): frames and their every
 * error, each message's layout both ways and what its decoder refuses, the
 * robot's end over a scripted simulator (reads cached per step, inbox pops
 * one request each, the telemetry room honoured and flushed, a bad answer
 * answered with FAULT) and the simulator's end over a scripted robot (its
 * FAULT, a frame of another step, too many IR messages: each an error).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "pil/pil_frame.h"
#include "pil/pil_host.h"
#include "pil/pil_msg.h"
#include "pil/pil_robot.h"

/* ---------------------------------------------------------------- frames */

static void test_frame_round_trip_and_errors(void **state)
{
    (void)state;
    uint8_t buf[64];
    pil_frame_t f;
    memcpy(buf + PIL_HEADER_BYTES, "abc", 3);
    uint16_t n = pil_frame_seal(buf, sizeof buf, PIL_STEP, 7, 3);
    assert_int_equal(n, PIL_FRAME_BYTES(3));
    assert_int_equal(pil_frame_size(buf), n);
    assert_int_equal(pil_frame_check(buf, n, &f), PIL_FRAME_OK);
    assert_int_equal(f.type, PIL_STEP);
    assert_int_equal(f.seq, 7);
    assert_int_equal(f.len, 3);
    assert_memory_equal(f.payload, "abc", 3);
    assert_int_equal(pil_frame_check(buf, (uint16_t)(n - 1), &f), PIL_FRAME_SHORT);
    assert_int_equal(pil_frame_check(buf, 4, &f), PIL_FRAME_SHORT);
    buf[n - 1] ^= 1;
    assert_int_equal(pil_frame_check(buf, n, &f), PIL_FRAME_CRC);
    buf[n - 1] ^= 1;
    buf[1] = PIL_VERSION + 1;
    assert_int_equal(pil_frame_check(buf, n, &f), PIL_FRAME_VERSION);
    assert_int_equal(pil_frame_size(buf), 0);
    buf[1] = PIL_VERSION;
    buf[0] = 0;
    assert_int_equal(pil_frame_check(buf, n, &f), PIL_FRAME_MAGIC);
    buf[0] = PIL_MAGIC;
    pil_put_u16(buf + 4, PIL_MAX_PAYLOAD + 1);
    assert_int_equal(pil_frame_check(buf, sizeof buf, &f), PIL_FRAME_LENGTH);
    /* A frame that does not fit is not sealed. */
    assert_int_equal(pil_frame_seal(buf, 10, PIL_STEP, 0, 3), 0);
    assert_non_null(strstr(pil_frame_error_name(PIL_FRAME_CRC), "CRC"));
}

static void test_little_endian_fields(void **state)
{
    (void)state;
    uint8_t b[4];
    pil_put_u32(b, 0x11223344u);
    assert_int_equal(b[0], 0x44);
    assert_int_equal(b[3], 0x11);
    assert_int_equal(pil_get_u32(b), 0x11223344u);
    pil_put_u16(b, 0xBEEF);
    assert_int_equal(pil_get_u16(b), 0xBEEF);
}

/* ---------------------------------------------------------------- messages */

static void test_hello_config_step(void **state)
{
    (void)state;
    uint8_t p[256];
    pil_hello_t h = { 25, 8, 3, PIL_HAS_SOUND | PIL_HAS_CAMERA, 1800, 0x210, 163, 0x300, 960, "repatt", "repatt" }, h2;
    uint16_t n = pil_hello_encode(p, sizeof p, &h);
    assert_int_equal(pil_hello_decode(p, n, &h2), 0);
    assert_int_equal(h2.period_ms, 25);
    assert_int_equal(h2.tx_per_period, 3);
    assert_int_equal(h2.state_addr, 0x210);
    assert_int_equal(h2.storage_size, 960);
    assert_string_equal(h2.name, "repatt");
    assert_string_equal(h2.controller, "repatt");
    assert_int_equal(pil_hello_decode(p, (uint16_t)(n - 1), &h2), -1);
    assert_int_equal(pil_hello_decode(p, (uint16_t)(n + 1), &h2), -1);
    p[20] = 0x07;   /* a control character in the name */
    assert_int_equal(pil_hello_decode(p, n, &h2), -1);

    pil_config_t c = { 7, 0xDEADBEEFu, 100, 16, 1, PIL_SIM_SOUND, 40, 20, 977, 2 }, c2;
    n = pil_config_encode(p, sizeof p, &c);
    assert_int_equal(pil_config_decode(p, n, &c2), 0);
    assert_int_equal(c2.seed, 0xDEADBEEFu);
    assert_int_equal(c2.selector, 2);
    assert_int_equal(pil_config_decode(p, (uint16_t)(n - 1), &c2), -1);
    c.tx_per_period = PIL_TX_MAX + 1;
    n = pil_config_encode(p, sizeof p, &c);
    assert_int_equal(pil_config_decode(p, n, &c2), -1);

    pil_step_t s, s2;
    memset(&s, 0, sizeof s);
    s.step = 70000;
    s.time_ms = 7000000;
    s.steps_left = -3;
    s.steps_right = 32000;
    s.telemetry_room = 1152;
    s.mic_count = PIL_MIC_CELLS;
    s.mic[8].status = HAL_ERR_BUSY;
    s.mic[3].level = 4000000000u;
    n = pil_step_encode(p, sizeof p, &s);
    assert_int_equal(pil_step_decode(p, n, &s2), 0);
    assert_int_equal(s2.steps_left, -3);
    assert_int_equal(s2.mic[8].status, HAL_ERR_BUSY);
    assert_int_equal(s2.mic[3].level, 4000000000u);
    assert_int_equal(pil_step_decode(p, (uint16_t)(n - 1), &s2), -1);
    p[14] = 4;   /* neither 0 nor every cell */
    assert_int_equal(pil_step_decode(p, n, &s2), -1);
}

static void test_request_act_emu_peek(void **state)
{
    (void)state;
    uint8_t p[512], bytes[PIL_TELEMETRY_MAX + 1];
    memset(bytes, 0x5A, sizeof bytes);
    pil_request_t q = { PIL_WHAT_TELEMETRY, 0, bytes, 10 }, q2;
    uint16_t n = pil_request_encode(p, sizeof p, &q);
    assert_int_equal(pil_request_decode(p, n, &q2), 0);
    assert_int_equal(q2.len, 10);
    q.len = PIL_TELEMETRY_MAX + 1;
    assert_int_equal(pil_request_encode(p, sizeof p, &q), 0);
    p[0] = PIL_WHAT_IR;
    assert_int_equal(pil_request_decode(p, 3, &q2), -1);   /* bytes after an IR request */
    p[0] = 42;
    assert_int_equal(pil_request_decode(p, 2, &q2), -1);

    pil_act_t a = { -1000, 1000, 0x3FF, 3, 2, { 0xABCD, 0x1234, 0 }, 4, (const uint8_t *)"tlm!" }, a2;
    n = pil_act_encode(p, sizeof p, &a);
    assert_int_equal(pil_act_decode(p, n, &a2), 0);
    assert_int_equal(a2.wheel_left, -1000);
    assert_int_equal(a2.tx[1], 0x1234);
    assert_memory_equal(a2.telemetry, "tlm!", 4);
    assert_int_equal(pil_act_decode(p, (uint16_t)(n + 1), &a2), -1);
    p[7] = PIL_TX_MAX + 1;
    assert_int_equal(pil_act_decode(p, n, &a2), -1);

    pil_emu_t e = { PIL_EMU_FRAME, 12345, UINT64_C(0x123456789A), 410, 0x2AE, 17, 9000 }, e2;
    n = pil_emu_encode(p, sizeof p, &e);
    assert_int_equal(pil_emu_decode(p, n, &e2), 0);
    assert_true(e2.total == UINT64_C(0x123456789A));
    assert_int_equal(e2.last_mark, 9000);
    p[0] = 99;
    assert_int_equal(pil_emu_decode(p, n, &e2), -1);

    pil_peek_t k = { 0x210, 163 }, k2;
    n = pil_peek_encode(p, sizeof p, &k);
    assert_int_equal(pil_peek_decode(p, n, &k2), 0);
    assert_int_equal(k2.len, 163);
}

static void test_replies(void **state)
{
    (void)state;
    uint8_t p[512], buf[HAL_HOST_MSG_MAX], len, count;
    uint16_t v[HAL_IR_COUNT] = { 1, 2, 3, 4, 5, 6, 7, 4095 }, w[HAL_IR_COUNT], g[HAL_GROUND_COUNT] = { 9, 8, 7 };
    hal_status_t st;
    uint16_t n = pil_reply_readings(p, sizeof p, PIL_WHAT_AMBIENT, v);
    assert_int_equal(pil_read_readings(p, n, PIL_WHAT_AMBIENT, w), 0);
    assert_memory_equal(v, w, sizeof v);
    assert_int_equal(pil_read_readings(p, n, PIL_WHAT_IR, w), -1);   /* answers another request */

    hal_blob_t b[2] = { { 1, -300, 200, 120 }, { 3, 10, 40, 6 } }, b2[HAL_MAX_BLOBS];
    n = pil_reply_blobs(p, sizeof p, b, 2);
    assert_int_equal(pil_read_blobs(p, n, b2, HAL_MAX_BLOBS, &count), 0);
    assert_int_equal(count, 2);
    assert_int_equal(b2[0].bearing_mrad, -300);
    assert_int_equal(pil_read_blobs(p, n, b2, 1, &count), -1);       /* more than it has room for */
    p[2] = HAL_COLOUR_COUNT;
    assert_int_equal(pil_read_blobs(p, n, b2, HAL_MAX_BLOBS, &count), -1);

    hal_pose_t pose = { -1500000, 2000, -3141, 40 }, pose2;
    n = pil_reply_pose(p, sizeof p, HAL_OK, &pose);
    assert_int_equal(pil_read_pose(p, n, &st, &pose2), 0);
    assert_int_equal(pose2.x_mm, -1500000);
    p[1] = (uint8_t)-9;
    assert_int_equal(pil_read_pose(p, n, &st, &pose2), -1);          /* not a status */

    hal_ircom_msg_t m = { 0xFFFF, 7, -2000, 900 }, m2;
    n = pil_reply_rx(p, sizeof p, HAL_OK, &m);
    assert_int_equal(pil_read_rx(p, n, &st, &m2), 0);
    assert_int_equal(m2.bearing_mrad, -2000);

    n = pil_reply_host(p, sizeof p, HAL_OK, (const uint8_t *)"route", 5);
    assert_int_equal(pil_read_host(p, n, &st, buf, sizeof buf, &len), 0);
    assert_int_equal(len, 5);
    assert_int_equal(pil_read_host(p, n, &st, buf, 4, &len), -1);    /* longer than its room */
    n = pil_reply_host(p, sizeof p, HAL_ERR_EMPTY, buf, 0);
    assert_int_equal(pil_read_host(p, n, &st, buf, sizeof buf, &len), 0);
    assert_int_equal(st, HAL_ERR_EMPTY);

    n = pil_reply_ground(p, sizeof p, HAL_OK, g);
    assert_int_equal(pil_read_ground(p, n, &st, w), 0);
    assert_int_equal(w[2], 7);
    n = pil_reply_accepted(p, sizeof p, 77);
    assert_int_equal(pil_read_accepted(p, n, &v[0]), 0);
    assert_int_equal(v[0], 77);
    n = pil_reply_frame(p, sizeof p, 100);
    assert_non_null(pil_read_frame(p, n, 100));
    assert_null(pil_read_frame(p, n, 99));
}

/* ------------------------------------------------- the robot's end, scripted */

/* The simulator this side: it answers each frame the robot hands over. */
static struct {
    uint8_t last_type, last_payload[PIL_FRAME_MAX];
    uint16_t last_len;
    uint32_t frames, requests[16];
    int corrupt_next;              /* damage the next answer's CRC */
    uint8_t step_seq;
} sim;

static void answer(uint8_t *mb, uint16_t cap, uint8_t type, uint8_t seq, uint16_t len)
{
    uint16_t n = pil_frame_seal(mb, cap, type, seq, len);
    if (sim.corrupt_next) {
        mb[n - 1] ^= 0xFF;
        sim.corrupt_next = 0;
    }
}

void pil_port_mark(void) {}

void pil_port_exchange(uint8_t *mb, uint16_t cap, uint16_t len)
{
    pil_frame_t f;
    assert_int_equal(pil_frame_check(mb, len, &f), PIL_FRAME_OK);
    sim.frames++;
    sim.last_type = f.type;
    sim.last_len = f.len;
    memcpy(sim.last_payload, f.payload, f.len);
    uint8_t *p = mb + PIL_HEADER_BYTES;
    if (f.type == PIL_HELLO) {
        pil_config_t c = { 5, 99, 100, 16, 1, 0, 40, 20, 977, 0 };
        answer(mb, cap, PIL_CONFIG, 0, pil_config_encode(p, 64, &c));
    } else if (f.type == PIL_READY || f.type == PIL_ACT) {
        pil_step_t s;
        memset(&s, 0, sizeof s);
        s.step = f.type == PIL_READY ? 0u : (uint32_t)(f.seq + 1u);
        s.telemetry_room = 300;
        answer(mb, cap, PIL_STEP, (uint8_t)s.step, pil_step_encode(p, 256, &s));
    } else if (f.type == PIL_REQUEST) {
        pil_request_t q;
        assert_int_equal(pil_request_decode(f.payload, f.len, &q), 0);
        sim.requests[q.what]++;
        if (q.what == PIL_WHAT_IR) {
            uint16_t v[HAL_IR_COUNT] = { 100, 0, 0, 0, 0, 0, 0, 4000 };
            answer(mb, cap, PIL_REPLY, f.seq, pil_reply_readings(p, 64, PIL_WHAT_IR, v));
        } else if (q.what == PIL_WHAT_RX) {
            hal_ircom_msg_t m = { 0x42, 1, 0, 100 };
            answer(mb, cap, PIL_REPLY, f.seq, pil_reply_rx(p, 64, sim.requests[q.what] == 1 ? HAL_OK : HAL_ERR_EMPTY, &m));
        } else if (q.what == PIL_WHAT_TELEMETRY) {
            answer(mb, cap, PIL_REPLY, f.seq, pil_reply_accepted(p, 64, q.len));
        } else {
            answer(mb, cap, PIL_REPLY, f.seq, pil_reply_readings(p, 64, PIL_WHAT_AMBIENT, (uint16_t[8]){ 0 }));
        }
    }
}

static void test_robot_end(void **state)
{
    (void)state;
    static uint8_t mailbox[PIL_MAILBOX_BYTES(0u)];
    static pil_robot_t r;
    pil_hello_t h;
    memset(&sim, 0, sizeof sim);
    memset(&h, 0, sizeof h);
    strcpy(h.name, "test");
    strcpy(h.controller, "none");
    pil_robot_init(&r, mailbox, sizeof mailbox, PIL_HAS_TELEMETRY, 16, 1);
    assert_int_equal(pil_robot_hello(&r, &h), 0);
    assert_int_equal(r.cfg.robot_id, 5);
    assert_int_equal(pil_robot_ready(&r), 0);
    /* IR asked for once per step, however often it is read. */
    assert_int_equal(pil_robot_ir(&r, 0), 100);
    assert_int_equal(pil_robot_ir(&r, 7), 4000);
    assert_int_equal(pil_robot_ir(&r, 8), 0);
    assert_int_equal(sim.requests[PIL_WHAT_IR], 1);
    /* The inbox: one request a pop. */
    hal_ircom_msg_t m;
    assert_int_equal(pil_robot_ircom_receive(&r, &m), HAL_OK);
    assert_int_equal(m.value, 0x42);
    assert_int_equal(pil_robot_ircom_receive(&r, &m), HAL_ERR_EMPTY);
    assert_int_equal(sim.requests[PIL_WHAT_RX], 2);
    /* No camera, sound or host link in this image: no request at all. */
    hal_blob_t b[2];
    hal_pose_t pose;
    uint32_t level;
    assert_int_equal(pil_robot_blobs(&r, b, 2), 0);
    assert_int_equal(pil_robot_pose(&r, &pose), HAL_ERR_UNAVAILABLE);
    assert_int_equal(pil_robot_mic_level(&r, 0, 1, &level), HAL_ERR_UNAVAILABLE);
    assert_int_equal(pil_robot_mic_level(&r, 3, 1, &level), HAL_ERR_RANGE);
    /* One IR message a period, masked to the image's bits. */
    assert_int_equal(pil_robot_ircom_send(&r, 0x1234), HAL_OK);
    assert_int_equal(pil_robot_ircom_send(&r, 0x1234), HAL_ERR_BUSY);
    /* Telemetry: 300 bytes of room; beyond the buffer a request flushes. */
    uint8_t t[200];
    memset(t, 1, sizeof t);
    assert_int_equal(pil_robot_telemetry_write(&r, t, 200), 200);
    assert_int_equal(pil_robot_telemetry_write(&r, t, 200), 100);
    assert_int_equal(pil_robot_telemetry_write(&r, t, 200), 0);
    assert_int_equal(sim.requests[PIL_WHAT_TELEMETRY], 1);
    pil_robot_wheels(&r, 2000, -5);
    assert_int_equal(pil_robot_end_step(&r), 0);
    pil_act_t act;
    assert_int_equal(sim.last_type, PIL_ACT);
    assert_int_equal(pil_act_decode(sim.last_payload, sim.last_len, &act), 0);
    assert_int_equal(act.wheel_left, HAL_WHEEL_SPEED_MAX);
    assert_int_equal(act.tx_count, 1);
    assert_int_equal(act.telemetry_len, 300 - PIL_TELEMETRY_MAX);
    /* The next step's reads are asked for again. */
    (void)pil_robot_ir(&r, 0);
    assert_int_equal(sim.requests[PIL_WHAT_IR], 2);
    /* A reply that does not check out: the robot says FAULT and reads 0. */
    sim.corrupt_next = 1;
    assert_int_equal(pil_robot_ambient(&r, 2), HAL_RAW_MAX);
    assert_int_equal(sim.last_type, PIL_FAULT);
    assert_int_equal(sim.last_payload[0], PIL_FAULT_FRAME);
    assert_int_equal(r.faults, 1);
}

/* --------------------------------------------- the simulator's end, scripted */

/* A robot this side: its frames, queued; the host's frames, kept. */
static struct {
    uint8_t out[8][128];
    uint16_t out_len[8];
    int n, at;
    uint8_t sent_type;
} robot;

static void queue(uint8_t type, uint8_t seq, const uint8_t *payload, uint16_t len)
{
    memcpy(robot.out[robot.n] + PIL_HEADER_BYTES, payload, len);
    robot.out_len[robot.n] = pil_frame_seal(robot.out[robot.n], 128, type, seq, len);
    robot.n++;
}

static int io_send(void *ctx, const uint8_t *frame, uint16_t len, char *err)
{
    (void)ctx;
    (void)len;
    (void)err;
    robot.sent_type = frame[2];
    return 0;
}

static int io_recv(void *ctx, uint8_t *buf, uint16_t cap, uint16_t *len, pil_emu_t *emu, char *err)
{
    (void)ctx;
    (void)cap;
    emu->cycles = 1000;
    if (robot.at == robot.n) {
        snprintf(err, PIL_HOST_ERR, "nothing more");
        return -1;
    }
    memcpy(buf, robot.out[robot.at], robot.out_len[robot.at]);
    *len = robot.out_len[robot.at++];
    return 0;
}

static void test_host_end_errors(void **state)
{
    (void)state;
    static pil_host_t h;
    pil_host_io_t io = { NULL, io_send, io_recv };
    pil_host_ops_t ops;
    memset(&ops, 0, sizeof ops);
    pil_step_t s;
    memset(&s, 0, sizeof s);
    pil_act_t act;
    char err[PIL_HOST_ERR];
    uint8_t p[64];

    /* A FAULT from the robot names what it could not read. */
    memset(&robot, 0, sizeof robot);
    pil_host_init(&h, &io);
    h.config.tx_per_period = 1;
    p[0] = PIL_FAULT_SEQ;
    p[1] = PIL_STEP;
    queue(PIL_FAULT, 0, p, 2);
    assert_int_equal(pil_host_step(&h, &s, &ops, &act, err), -1);
    assert_non_null(strstr(err, "of another step"));
    assert_int_equal(robot.sent_type, PIL_STEP);

    /* An ACT of another step. */
    memset(&robot, 0, sizeof robot);
    pil_act_t a = { 0, 0, 0, 0, 0, { 0, 0, 0 }, 0, NULL };
    queue(PIL_ACT, 9, p, pil_act_encode(p, sizeof p, &a));
    assert_int_equal(pil_host_step(&h, &s, &ops, &act, err), -1);
    assert_non_null(strstr(err, "of step 9"));

    /* More IR messages than the period takes. */
    memset(&robot, 0, sizeof robot);
    a.tx_count = 2;
    queue(PIL_ACT, 0, p, pil_act_encode(p, sizeof p, &a));
    assert_int_equal(pil_host_step(&h, &s, &ops, &act, err), -1);
    assert_non_null(strstr(err, "2 IR messages"));

    /* A good step: its cycles counted. */
    memset(&robot, 0, sizeof robot);
    a.tx_count = 1;
    queue(PIL_ACT, 0, p, pil_act_encode(p, sizeof p, &a));
    assert_int_equal(pil_host_step(&h, &s, &ops, &act, err), 0);
    assert_int_equal(h.step_cycles, 1000);
    assert_int_equal(act.tx_count, 1);

    /* A damaged frame. */
    memset(&robot, 0, sizeof robot);
    queue(PIL_ACT, 0, p, pil_act_encode(p, sizeof p, &a));
    robot.out[0][robot.out_len[0] - 1] ^= 1;
    assert_int_equal(pil_host_step(&h, &s, &ops, &act, err), -1);
    assert_non_null(strstr(err, "bad CRC"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_round_trip_and_errors),
        cmocka_unit_test(test_little_endian_fields),
        cmocka_unit_test(test_hello_config_step),
        cmocka_unit_test(test_request_act_emu_peek),
        cmocka_unit_test(test_replies),
        cmocka_unit_test(test_robot_end),
        cmocka_unit_test(test_host_end_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
