/*
 * test_app_telemetry.c - runs the forager image (firmware/apps/forager_main.c,
 * included here with its main renamed) against the stubs of the e-puck
 * library for 25 control steps, collects every byte the UART stub was given,
 * and checks that the stream is telemetry frames (telemetry_frame.h: COBS,
 * CRC, header) on TELEMETRY_CH_ROBOT_STATE whose payloads decode, with
 * lcm-gen's decoder, to robot_state_t messages carrying the controller's
 * values at the step each was sent.  Built by tools/make/firmware.mk
 * (firmware-hal-tests).  Prints "N passed, M failed".
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "epuck_stubs.h"

int forager_image_main(void);
#define main forager_image_main
#include "../../firmware/apps/forager_main.c"
#undef main

static int passed, failed;

#define CHECK(cond) do { \
        if (cond) { passed++; } \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

#define STEPS 25
#define ROBOT 7u

typedef struct expected {
    const char *state;
    char task;
    int32_t oae;
    int32_t deposits;
    uint32_t time_lo, time_hi;   /* hal_time_ms before and after the step */
} expected_t;

static unsigned char uart_log[8192];

/* COBS-decodes `len` bytes (no zeros) into `out`; returns the length or -1. */
static int cobs_decode(const unsigned char *in, int len, unsigned char *out, int out_size)
{
    int i = 0, n = 0;
    while (i < len) {
        int code = in[i++], k;
        if (code == 0) {
            return -1;
        }
        for (k = 1; k < code; k++) {
            if (i >= len || n >= out_size) {
                return -1;
            }
            out[n++] = in[i++];
        }
        if (code < 0xFF && i < len) {
            if (n >= out_size) {
                return -1;
            }
            out[n++] = 0;
        }
    }
    return n;
}

int main(void)
{
    expected_t want[STEPS];
    int sent = 0, frames = 0, i, start;
    uint32_t queued = 0u;

    epuck_stub_reset();
    epuck_stub.flash_id = ROBOT;
    epuck_stub.uart_log = uart_log;
    epuck_stub.uart_log_size = (int)sizeof uart_log;
    app_setup();
    CHECK(hal_robot_id(&app_hal) == ROBOT);

    for (i = 0; i < STEPS; i++) {
        uint32_t before;
        if (i == 5) {   /* values the frames must show */
            app_forager.walk.oae_count = 1234u;
            app_forager.deposits = 3u;
        }
        before = hal_time_ms(&app_hal);
        epuck_stub.agenda();
        app_loop_once();
        if (app_telemetry.tx.frames_queued != queued) {
            queued = app_telemetry.tx.frames_queued;
            want[sent].state = forager_state_name(app_forager.state);
            want[sent].task = forager_paper_state(app_forager.state);
            want[sent].oae = (int32_t)app_forager.walk.oae_count;
            want[sent].deposits = (int32_t)app_forager.deposits;
            want[sent].time_lo = before;
            want[sent].time_hi = hal_time_ms(&app_hal);
            sent++;
        }
    }
    CHECK(sent == 3);   /* steps 0, 10 and 20 */
    CHECK(app_telemetry.tx.frames_dropped == 0u);
    CHECK(telemetry_tx_pending(&app_telemetry.tx) == 0u);
    CHECK(epuck_stub.uart_log_len > 0 && epuck_stub.uart_log_len < (int)sizeof uart_log);

    /* Frames: zero-delimited COBS bodies. */
    start = 0;
    for (i = 0; i <= epuck_stub.uart_log_len; i++) {
        unsigned char body[TELEMETRY_MAX_BODY];
        swarmlcm_robot_state_t m;
        int n, len = i - start;
        uint16_t crc;
        if (i < epuck_stub.uart_log_len && uart_log[i] != 0u) {
            continue;
        }
        if (len == 0) {
            start = i + 1;
            continue;
        }
        CHECK(i < epuck_stub.uart_log_len);   /* every frame closed */
        n = cobs_decode(uart_log + start, len, body, (int)sizeof body);
        start = i + 1;
        CHECK(n > (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES));
        if (n <= (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES) || frames >= sent) {
            failed++;
            printf("FAIL: frame %d unexpected (%d bytes)\n", frames, n);
            continue;
        }
        crc = telemetry_crc16(0xFFFFu, body, (uint16_t)(n - 2));
        CHECK(body[n - 2] == (crc >> 8) && body[n - 1] == (crc & 0xFFu));
        CHECK(body[0] == TELEMETRY_VERSION);
        CHECK(body[1] == TELEMETRY_CH_ROBOT_STATE);
        CHECK(((body[2] << 8) | body[3]) == (int)ROBOT);
        CHECK(((body[4] << 8) | body[5]) == frames);
        memset(&m, 0, sizeof m);
        CHECK(swarmlcm_robot_state_t_decode(body + TELEMETRY_HEADER_BYTES, 0,
                                            n - (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES),
                                            &m) == n - (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES));
        CHECK(m.robot_id == (int16_t)ROBOT);
        CHECK(m.utime >= (int64_t)want[frames].time_lo * 1000 && m.utime <= (int64_t)want[frames].time_hi * 1000);
        CHECK(m.run == 0);
        CHECK(strcmp(m.controller, "forager") == 0);
        CHECK(strcmp(m.state, want[frames].state) == 0);
        CHECK(m.task_state == want[frames].task);
        CHECK(strcmp(m.policy, "drtm") == 0);
        CHECK(m.oae_count == want[frames].oae);
        CHECK(m.deposits == want[frames].deposits);
        CHECK(m.response_n == (int8_t)app_forager.n);
        CHECK(isnan(m.energy));          /* no beacon heard */
        CHECK(m.carried_item == -2);
        CHECK(m.ir_max >= 0 && m.ir_max_index >= 0 && m.ir_max_index < 8);
        CHECK(m.pose_known == 0 && isnan(m.x) && isnan(m.y) && isnan(m.theta));
        swarmlcm_robot_state_t_decode_cleanup(&m);
        frames++;
    }
    CHECK(frames == sent);
    CHECK(want[0].oae == 0 && want[1].oae == 1234);

    printf("app telemetry (forager image, %d frames): %d passed, %d failed\n", frames, passed, failed);
    return failed != 0;
}
