/*
 * test_hal_epuck_host.c - host tests of platforms/epuck1/hal's host link
 * (host_link.c): poses and messages a host sends over UART1, scripted as
 * received bytes in the library stub (platforms/epuck1/tests/stubs/).  Built by
 * tools/make/firmware.mk over the turret backend (the link does not
 * depend on it).  Prints "N passed, M failed".
 */
#include <stdio.h>
#include <string.h>

#include "epuck_stubs.h"
#include "hal_epuck.h"
#include "telemetry/telemetry_frame.h"
#include "telemetry/telemetry_host.h"

static int passed, failed;

#define CHECK(cond) do { \
        if (cond) { passed++; } \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

#define ID 7u
#define STREAM_MAX 8192

static struct hal robot;
static hal_epuck_host_t host;
/* What the host "sent": the stub hands it out byte by byte. */
static unsigned char stream[STREAM_MAX];
static int stream_len;

static void start(uint8_t attach)
{
    hal_epuck_config_t cfg;
    epuck_stub_reset();
    hal_epuck_default_config(&cfg);
    cfg.robot_id = ID;
    cfg.camera = 0u;
    CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == 0);
    if (attach) {
        hal_epuck_host_attach(&robot, &host);
    }
    hal_epuck_start(&robot, NULL);
    stream_len = 0;
    epuck_stub.rx = stream;
    epuck_stub.rx_len = 0;
    epuck_stub.rx_pos = 0;
}

/* Appends bytes to what the link has received. */
static void arrive(const uint8_t *bytes, uint16_t n)
{
    CHECK(stream_len + n <= STREAM_MAX);
    memcpy(stream + stream_len, bytes, n);
    stream_len += n;
    epuck_stub.rx_len = stream_len;
}

static void send_pose(uint16_t id, int32_t x, int32_t y, int16_t h)
{
    hal_pose_t p = { x, y, h, 0u };
    uint8_t payload[TELEMETRY_POSE_PAYLOAD];
    uint8_t f[TELEMETRY_FRAME_BYTES(TELEMETRY_POSE_PAYLOAD)];
    uint16_t n;
    telemetry_pose_pack(&p, payload);
    n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_POSE, id, 1u, payload, sizeof payload);
    CHECK(n == sizeof f);
    arrive(f, n);
}

static void send_msg(uint16_t id, const uint8_t *bytes, uint16_t len)
{
    uint8_t f[TELEMETRY_FRAME_MAX];
    uint16_t n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_HOST_MSG, id, 2u, bytes, len);
    CHECK(n == TELEMETRY_FRAME_BYTES(len));
    arrive(f, n);
}

static void begin(void)
{
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    hal_epuck_begin_step(&robot);
}

static void step(void)
{
    begin();
    hal_epuck_end_step(&robot);
}

static void test_without_storage(void)
{
    hal_pose_t p;
    uint8_t buf[8], len = 9u;
    start(0u);
    send_pose(ID, 1, 2, 3);
    step();
    hal_epuck_poll(&robot);
    CHECK(epuck_stub.rx_pos == 0);            /* UART1 never read */
    CHECK(hal_pose(&robot, &p) == HAL_ERR_UNAVAILABLE);
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_ERR_UNAVAILABLE);
    CHECK(len == 0u);
}

static void test_pose_ages_and_expires(void)
{
    hal_pose_t p;
    uint16_t k;
    start(1u);
    begin();
    CHECK(hal_pose(&robot, &p) == HAL_ERR_UNAVAILABLE);   /* none yet */
    send_pose(ID, 1234, -5678, -1571);
    CHECK(hal_pose(&robot, &p) == HAL_ERR_UNAVAILABLE);   /* not within a step */
    hal_epuck_end_step(&robot);
    begin();                                              /* time 100 */
    CHECK(hal_pose(&robot, &p) == HAL_OK);
    CHECK(p.x_mm == 1234 && p.y_mm == -5678 && p.heading_mrad == -1571);
    CHECK(p.age_ms == 0u);
    CHECK(host.poses == 1u);
    hal_epuck_end_step(&robot);
    for (k = 1u; k <= 10u; k++) {
        begin();
        CHECK(hal_pose(&robot, &p) == HAL_OK);
        CHECK(p.age_ms == k * 100u);
        CHECK(p.x_mm == 1234);
        hal_epuck_end_step(&robot);
    }
    begin();                                              /* 1100 ms old */
    CHECK(hal_pose(&robot, &p) == HAL_ERR_UNAVAILABLE);
    CHECK(p.x_mm == 0 && p.age_ms == 0u);
    hal_epuck_end_step(&robot);
    /* A new fix, read in the idle loop between steps: age 0 at the next step. */
    send_pose(ID, 5, 6, 7);
    hal_epuck_poll(&robot);
    begin();
    CHECK(hal_pose(&robot, &p) == HAL_OK);
    CHECK(p.x_mm == 5 && p.y_mm == 6 && p.heading_mrad == 7 && p.age_ms == 0u);
    hal_epuck_end_step(&robot);
}

static void test_addressing(void)
{
    hal_pose_t p;
    start(1u);
    send_pose(ID + 1u, 1, 1, 1);                          /* another robot's */
    step();
    begin();
    CHECK(hal_pose(&robot, &p) == HAL_ERR_UNAVAILABLE);
    CHECK(host.not_ours == 1u);
    hal_epuck_end_step(&robot);
    send_pose(TELEMETRY_BROADCAST_ID, 2, 3, 4);            /* everyone's */
    step();
    begin();
    CHECK(hal_pose(&robot, &p) == HAL_OK);
    CHECK(p.x_mm == 2 && p.age_ms == 100u);
    hal_epuck_end_step(&robot);
    {
        /* A good frame for us on a robot's channel, a POSE of a wrong
         * length, an empty HOST_MSG: ignored, the pose kept. */
        uint8_t nine[9] = { 0 };
        uint8_t f[40];
        uint16_t n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_ROBOT_STATE, ID, 0u, nine, 9u);
        arrive(f, n);
        n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_POSE, ID, 0u, nine, 9u);
        arrive(f, n);
        send_msg(ID, nine, 0u);
    }
    begin();
    CHECK(host.ignored == 3u);
    CHECK(hal_pose(&robot, &p) == HAL_OK && p.x_mm == 2);
    hal_epuck_end_step(&robot);
}

static void test_messages_and_full_mailbox(void)
{
    uint8_t a[HAL_HOST_MSG_MAX], b[3] = { 0, 1, 0 }, c[1] = { 0xAB };
    uint8_t buf[HAL_HOST_MSG_MAX], len = 0u;
    uint16_t k;
    start(1u);
    begin();
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_ERR_EMPTY && len == 0u);
    hal_epuck_end_step(&robot);
    for (k = 0; k < sizeof a; k++) {
        a[k] = (uint8_t)(k * 7u);   /* zeros included */
    }
    send_msg(ID, a, sizeof a);
    send_msg(TELEMETRY_BROADCAST_ID, b, sizeof b);
    send_msg(ID, c, sizeof c);                         /* the mailbox is full */
    hal_epuck_poll(&robot);
    hal_epuck_poll(&robot);
    hal_epuck_poll(&robot);
    begin();
    CHECK(host.msgs == 2u && host.msg_dropped == 1u);
    /* Too long for the caller's buffer: it stays. */
    len = 5u;
    CHECK(hal_host_receive(&robot, buf, 10u, &len) == HAL_ERR_RANGE);
    CHECK(len == 0u);
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_OK);
    CHECK(len == sizeof a && memcmp(buf, a, sizeof a) == 0);
    CHECK(hal_host_receive(&robot, buf, 3u, &len) == HAL_OK);
    CHECK(len == 3u && memcmp(buf, b, 3u) == 0);
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_ERR_EMPTY);
    hal_epuck_end_step(&robot);
    /* Room again: the ring wraps. */
    send_msg(ID, c, sizeof c);
    send_msg(ID, b, sizeof b);
    begin();
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_OK && len == 1u && buf[0] == 0xABu);
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_OK && len == 3u && buf[1] == 1u);
    hal_epuck_end_step(&robot);
}

static void test_garbage_and_bad_crc(void)
{
    static const uint8_t junk[] = { 'A', 'T', '\r', 0xFF, 0x00, 0x05, 0x01, 0x80, 0x00, 0x00, 0x31 };
    uint8_t f[TELEMETRY_FRAME_BYTES(TELEMETRY_POSE_PAYLOAD)];
    uint8_t m[2] = { 9, 9 }, buf[4], len;
    hal_pose_t p = { 11, 22, 33, 0u };
    uint8_t payload[TELEMETRY_POSE_PAYLOAD];
    uint16_t n;
    start(1u);
    send_pose(ID, 100, 200, 300);
    step();
    arrive(junk, sizeof junk);
    /* A pose frame with its CRC broken, and a message cut short. */
    telemetry_pose_pack(&p, payload);
    n = telemetry_frame_encode(f, sizeof f, TELEMETRY_CH_POSE, ID, 5u, payload, sizeof payload);
    f[n - 2u] ^= 0x40u;
    arrive(f, n);
    {
        uint8_t g[TELEMETRY_FRAME_BYTES(2u)];
        n = telemetry_frame_encode(g, sizeof g, TELEMETRY_CH_HOST_MSG, ID, 6u, m, 2u);
        arrive(g, (uint16_t)(n - 3u));
    }
    arrive(junk, sizeof junk);
    begin();
    CHECK(host.rx.bad >= 3u);
    CHECK(host.poses == 1u && host.msgs == 0u);
    CHECK(hal_pose(&robot, &p) == HAL_OK);
    CHECK(p.x_mm == 100 && p.y_mm == 200 && p.heading_mrad == 300 && p.age_ms == 100u);
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_ERR_EMPTY);
    hal_epuck_end_step(&robot);
    /* ... and the link still works. */
    send_msg(ID, m, 2u);
    send_pose(ID, -1, -2, -3);
    begin();
    CHECK(hal_host_receive(&robot, buf, sizeof buf, &len) == HAL_OK && len == 2u && buf[1] == 9u);
    CHECK(hal_pose(&robot, &p) == HAL_OK && p.x_mm == -1 && p.age_ms == 0u);
    hal_epuck_end_step(&robot);
}

static void test_flood_is_bounded(void)
{
    hal_pose_t p;
    int k;
    uint16_t per_step = hal_epuck_host_step_bytes(100u);
    CHECK(per_step == 1152u);                 /* 100 ms of 115200 baud, 8N1 */
    CHECK(hal_epuck_host_step_bytes(0xFFFFu) == 0xFFFFu);
    start(1u);
    for (k = 0; k < 5000; k++) {
        stream[k] = (unsigned char)(k % 251 + 1);   /* no zero: one endless run */
    }
    stream_len = 5000;
    epuck_stub.rx_len = stream_len;
    hal_epuck_poll(&robot);
    CHECK(epuck_stub.rx_pos == (int)HAL_EPUCK_RX_POLL_BYTES);
    begin();
    CHECK(epuck_stub.rx_pos == (int)HAL_EPUCK_RX_POLL_BYTES + per_step);
    hal_epuck_end_step(&robot);
    CHECK(host.rx.oversize == 1u);
    /* The flood ends with a zero and a pose: taken once the backlog is read. */
    stream_len = 4000;
    send_pose(ID, 42, 43, 44);
    for (k = 0; k < 4; k++) {
        step();
    }
    begin();
    CHECK(epuck_stub.rx_pos == stream_len);
    CHECK(hal_pose(&robot, &p) == HAL_OK && p.x_mm == 42);
    CHECK(host.rx.oversize == 1u && host.rx.bad == 1u);
    hal_epuck_end_step(&robot);
}

int main(void)
{
    test_without_storage();
    test_pose_ages_and_expires();
    test_addressing();
    test_messages_and_full_mailbox();
    test_garbage_and_bad_crc();
    test_flood_is_bounded();
    printf("test_hal_epuck_host: %d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
