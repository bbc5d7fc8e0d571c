/*
 * test_robot_link.c - the robots' own telemetry in the loop
 * (robot_telemetry.enabled): every robot runs the image's sender
 * (firmware/telemetry/robot_telemetry.c) and the simulator deframes what it
 * writes through hal_telemetry_write as the serial bridge does
 * (sim_host/core/robot_link.c).  The messages decode to the controller's
 * own values at that step; the run is the same with it or without it; a
 * slow UART delays frames (and drops what does not fit) without changing
 * the run; a corrupted stream costs only the frames it touches.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core/robot_link.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "foraging/forager.h"
#include "swarmlcm_robot_state_t.h"
#include "swarmlcm_schema_t.h"

#define BASE "../sim_host/scenarios/foraging_base.yaml"

static scenario_t *load(int sil, const char *baud)
{
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX];
    scenario_override_t o[2] = { { sil ? "robot_telemetry.enabled=true" : "robot_telemetry.enabled=false" },
                                 { baud } };
    assert_non_null(sc);
    if (scenario_load(BASE, o, baud ? 2 : 1, sc, err) != 0) fail_msg("%s", err);
    return sc;
}

static sim_t *make(const scenario_t *sc)
{
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 6, err);
    if (!sim) fail_msg("%s", err);
    return sim;
}

/* Every robot_state_t a forager's image sends carries its observables at
 * that step; the schema chunks name them in order. */
static void test_frames_carry_the_controllers_values(void **state)
{
    (void)state;
    scenario_t *sc = load(1, NULL);
    sim_t *sim = make(sc);
    uint32_t states = 0, schemas = 0;
    for (int k = 0; k < 400; k++) {
        sim_step(sim);
        for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
            const robot_link_t *l = sim_robot_link(sim, i);
            assert_non_null(l);
            for (uint8_t f = 0; f < l->n_frames; f++) {
                const robot_link_frame_t *fr = &l->frames[f];
                assert_int_equal(fr->robot_id, i);
                if (fr->channel == TELEMETRY_CH_SCHEMA) {
                    swarmlcm_schema_t m;
                    assert_int_equal(swarmlcm_schema_t_decode(fr->payload, 0, fr->len, &m), fr->len);
                    const observable_t *obs = sim_robot_def(sim, i)->observables;
                    for (int e = 0; e < m.n; e++) assert_string_equal(m.names[e], obs[m.first + e].name);
                    swarmlcm_schema_t_decode_cleanup(&m);
                    schemas++;
                    continue;
                }
                assert_int_equal(fr->channel, TELEMETRY_CH_ROBOT_STATE);
                swarmlcm_robot_state_t m;
                assert_int_equal(swarmlcm_robot_state_t_decode(fr->payload, 0, fr->len, &m), fr->len);
                const controller_def_t *def = sim_robot_def(sim, i);
                assert_string_equal(m.controller, def->name);
                assert_string_equal(m.state, sim_robot_state_name(sim, i));
                assert_int_equal(m.utime, (int64_t)(sim_step_count(sim) - 1) * 100000);
                for (int v = 0; v < m.n_values; v++) {
                    assert_true(m.values[v] == observable_read(&def->observables[v], sim_robot_controller(sim, i)));
                }
                int16_t wl, wr;
                sim_robot_wheels(sim, i, &wl, &wr);
                assert_true(m.wheel_left == wl && m.wheel_right == wr);
                assert_false(m.pose_known);
                swarmlcm_robot_state_t_decode_cleanup(&m);
                states++;
            }
            assert_int_equal(l->bad, 0);
        }
    }
    assert_int_equal(states, 21 * 40);    /* once a second, 40 s */
    assert_int_equal(schemas, 21 * 40);   /* halfway between */
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The robots' telemetry only reads: same run with it, without it, and
 * with a slow UART; a slow UART carries fewer frames. */
static void test_same_run_and_a_slow_uart(void **state)
{
    (void)state;
    uint64_t hash[3];
    uint64_t good[3] = { 0, 0, 0 };
    const char *baud[3] = { NULL, "robot_telemetry.baud=0", "robot_telemetry.baud=2400" };
    for (int pass = 0; pass < 3; pass++) {
        scenario_t *sc = load(pass > 0, baud[pass]);
        sim_t *sim = make(sc);
        for (int k = 0; k < 600; k++) sim_step(sim);
        hash[pass] = sim_state_hash(sim);
        if (pass) good[pass] = sim_robot_link(sim, 0)->good;
        else assert_null(sim_robot_link(sim, 0));
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    assert_true(hash[0] == hash[1] && hash[0] == hash[2]);
    assert_int_equal(good[1], 120);                  /* 60 states and 60 schema chunks */
    assert_true(good[2] > 0 && good[2] < good[1]);   /* 24 bytes a step: some wait, some are dropped */
}

/* A corrupted byte costs its frame only; the next one comes through. */
static void test_corruption_costs_one_frame(void **state)
{
    (void)state;
    uint8_t payload[40], frame[TELEMETRY_FRAME_MAX];
    robot_link_t l;
    for (int k = 0; k < 40; k++) payload[k] = (uint8_t)(k * 7);
    uint16_t n = telemetry_frame_encode(frame, sizeof frame, TELEMETRY_CH_ROBOT_STATE, 3, 9, payload, 40);
    robot_link_init(&l);
    robot_link_begin_step(&l, UINT32_MAX);
    frame[10] ^= 0x20;                              /* a flipped bit */
    assert_int_equal(robot_link_write(&l, frame, n), n);
    frame[10] ^= 0x20;
    assert_int_equal(robot_link_write(&l, frame, n), n);
    assert_int_equal(l.bad, 1);
    assert_int_equal(l.good, 1);
    assert_int_equal(l.n_frames, 1);
    assert_int_equal(l.frames[0].robot_id, 3);
    assert_int_equal(l.frames[0].seq, 9);
    assert_memory_equal(l.frames[0].payload, payload, 40);
    /* Garbage without zeros longer than any frame is dropped, then resync. */
    uint8_t junk[600];
    memset(junk, 0x55, sizeof junk);
    robot_link_write(&l, junk, sizeof junk);
    robot_link_write(&l, frame, n);
    assert_int_equal(l.bad, 2);
    assert_int_equal(l.good, 2);
    /* The budget: a 10-byte UART takes 10 bytes. */
    robot_link_begin_step(&l, 10);
    assert_int_equal(robot_link_write(&l, frame, n), 10);
    assert_int_equal(robot_link_write(&l, frame, n), 0);
}

/* A body longer than the format allows (found by tests/fuzz/telemetry_frame.c):
 * 242 payload bytes with a good CRC, stuffed and delimited as a sender that
 * ignores the limit would write them.  It is a bad frame, and the frames
 * held before it stay as they were (the old decoder copied 242 bytes into
 * a 240-byte payload, over the next frame or the frame count). */
static void test_a_body_longer_than_the_format_is_bad(void **state)
{
    (void)state;
    uint8_t body[TELEMETRY_MAX_BODY + 2], wire[TELEMETRY_MAX_BODY + 8], small[TELEMETRY_FRAME_MAX];
    uint8_t payload[3] = { 1, 2, 3 };
    size_t blen = sizeof body;
    robot_link_t l;
    memset(body, 0x41, sizeof body);
    body[0] = TELEMETRY_VERSION;
    body[1] = TELEMETRY_CH_ROBOT_STATE;
    uint16_t crc = telemetry_crc16(0xFFFFu, body, (uint16_t)(blen - 2));
    body[blen - 2] = (uint8_t)(crc >> 8);
    body[blen - 1] = (uint8_t)crc;
    wire[0] = 0;
    uint16_t n = telemetry_cobs_encode(body, (uint16_t)blen, wire + 1, sizeof wire - 2);
    assert_int_equal(n, blen + 1);
    wire[n + 1] = 0;

    robot_link_init(&l);
    robot_link_begin_step(&l, UINT32_MAX);
    uint16_t m = telemetry_frame_encode(small, sizeof small, TELEMETRY_CH_EVENT, 5, 6, payload, 3);
    for (int k = 0; k < (int)ROBOT_LINK_FRAMES - 1; k++) robot_link_write(&l, small, m);
    robot_link_write(&l, wire, (uint16_t)(n + 2));
    assert_int_equal(l.bad, 1);
    assert_int_equal(l.good, ROBOT_LINK_FRAMES - 1);
    assert_int_equal(l.n_frames, ROBOT_LINK_FRAMES - 1);
    for (int k = 0; k < (int)ROBOT_LINK_FRAMES - 1; k++) {
        assert_int_equal(l.frames[k].len, 3);
        assert_int_equal(l.frames[k].robot_id, 5);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frames_carry_the_controllers_values),
        cmocka_unit_test(test_same_run_and_a_slow_uart),
        cmocka_unit_test(test_corruption_costs_one_frame),
        cmocka_unit_test(test_a_body_longer_than_the_format_is_bad),
    };
    return cmocka_run_group_tests_name("robot_link", tests, NULL, NULL);
}
