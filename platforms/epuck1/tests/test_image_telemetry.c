/*
 * test_image_telemetry.c - runs the forager image (its main generated from
 * platforms/epuck1/images.list over run/image_main.h, included here with its
 * main renamed) against the stubs of the e-puck library for 25 control
 * steps, collects every byte the UART stub was given, and checks that the
 * stream is telemetry frames (telemetry_frame.h: COBS, CRC, header):
 * robot_state_t on TELEMETRY_CH_ROBOT_STATE carrying the controller's
 * observables at the step each was sent, and schema_t chunks on
 * TELEMETRY_CH_SCHEMA naming them in the table's order (lcm-gen's
 * decoders).  Built by platforms/epuck1/platform.mk (epuck1-hal-tests).
 * Prints "N passed, M failed".
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "epuck_stubs.h"
#include "swarmlcm_robot_state_t.h"
#include "swarmlcm_schema_t.h"

int forager_image_main(void);
#define main forager_image_main
#include "forager_main.c"
#undef main

static int passed, failed;

#define CHECK(cond) do { \
        if (cond) { passed++; } \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

#define STEPS 25
#define ROBOT 7u

typedef struct expected {
    uint8_t channel;
    const char *state;
    float values[ROBOT_TELEMETRY_MAX_VALUES];
    uint32_t time_lo, time_hi;   /* hal_time_ms before and after the step */
} expected_t;

/* Index of the forager's observable `name`. */
static int value_index(const char *name)
{
    int k;
    for (k = 0; forager_observables[k].name != 0; k++) {
        if (strcmp(forager_observables[k].name, name) == 0) {
            return k;
        }
    }
    return -1;
}

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
            app_ctrl.walk.oae_count = 1234u;
            app_ctrl.deposits = 3u;
        }
        before = hal_time_ms(&app_hal);
        epuck_stub.agenda();
        app_loop_once();
        if (app_telemetry.tx.frames_queued != queued) {
            int k;
            queued = app_telemetry.tx.frames_queued;
            /* States at steps 0, 10, 20; schema chunks halfway (5, 15). */
            want[sent].channel = (i % 10 == 0) ? TELEMETRY_CH_ROBOT_STATE : TELEMETRY_CH_SCHEMA;
            want[sent].state = forager_state_name(&app_ctrl);
            for (k = 0; forager_observables[k].name != 0; k++) {
                want[sent].values[k] = observable_read(&forager_observables[k], &app_ctrl);
            }
            want[sent].time_lo = before;
            want[sent].time_hi = hal_time_ms(&app_hal);
            sent++;
        }
    }
    CHECK(sent == 5);
    CHECK(app_telemetry.tx.frames_dropped == 0u);
    CHECK(telemetry_tx_pending(&app_telemetry.tx) == 0u);
    CHECK(epuck_stub.uart_log_len > 0 && epuck_stub.uart_log_len < (int)sizeof uart_log);

    /* Frames: zero-delimited COBS bodies. */
    start = 0;
    for (i = 0; i <= epuck_stub.uart_log_len; i++) {
        unsigned char body[TELEMETRY_MAX_BODY];
        swarmlcm_robot_state_t m;
        swarmlcm_schema_t sch;
        int n, len = i - start, k, size;
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
        CHECK(body[1] == want[frames].channel);
        CHECK(((body[2] << 8) | body[3]) == (int)ROBOT);
        CHECK(((body[4] << 8) | body[5]) == frames);
        size = n - (int)(TELEMETRY_HEADER_BYTES + TELEMETRY_CRC_BYTES);
        if (body[1] == TELEMETRY_CH_SCHEMA) {
            memset(&sch, 0, sizeof sch);
            CHECK(swarmlcm_schema_t_decode(body + TELEMETRY_HEADER_BYTES, 0, size, &sch) == size);
            CHECK(strcmp(sch.kind, "controller") == 0 && strcmp(sch.name, "forager") == 0);
            CHECK(sch.total == (int16_t)observable_count(forager_observables));
            CHECK(sch.first == (frames == 1 ? 0 : (int16_t)ROBOT_TELEMETRY_SCHEMA_CHUNK));
            CHECK(sch.n == (int16_t)ROBOT_TELEMETRY_SCHEMA_CHUNK);
            for (k = 0; k < sch.n; k++) {
                const observable_t *o = &forager_observables[sch.first + k];
                CHECK(strcmp(sch.names[k], o->name) == 0);
                CHECK(strcmp(sch.units[k], o->unit) == 0);
                CHECK(sch.counters[k] == (o->kind == OBS_COUNTER));
            }
            swarmlcm_schema_t_decode_cleanup(&sch);
            frames++;
            continue;
        }
        memset(&m, 0, sizeof m);
        CHECK(swarmlcm_robot_state_t_decode(body + TELEMETRY_HEADER_BYTES, 0, size, &m) == size);
        CHECK(m.version == SWARMLCM_ROBOT_STATE_T_VERSION);
        CHECK(m.robot_id == (int16_t)ROBOT);
        CHECK(m.utime >= (int64_t)want[frames].time_lo * 1000 && m.utime <= (int64_t)want[frames].time_hi * 1000);
        CHECK(m.run == 0);
        CHECK(strcmp(m.controller, "forager") == 0);
        CHECK(strcmp(m.state, want[frames].state) == 0);
        CHECK(m.n_values == (int8_t)observable_count(forager_observables));
        for (k = 0; k < m.n_values; k++) {
            CHECK(m.values[k] == want[frames].values[k]);
        }
        CHECK(m.values[value_index("n")] == (float)app_ctrl.n);
        CHECK(m.ir_max >= 0 && m.ir_max_index >= 0 && m.ir_max_index < 8);
        CHECK(m.pose_known == 0 && isnan(m.x) && isnan(m.y) && isnan(m.theta));
        swarmlcm_robot_state_t_decode_cleanup(&m);
        frames++;
    }
    CHECK(frames == sent);
    CHECK(want[0].values[value_index("oae")] == 0.0f);
    CHECK(want[2].values[value_index("oae")] == 1234.0f);
    CHECK(want[2].values[value_index("deposits")] == 3.0f);

    printf("image telemetry (forager image, %d frames): %d passed, %d failed\n", frames, passed, failed);
    return failed != 0;
}
