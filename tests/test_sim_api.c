/*
 * test_sim_api.c - the public API's parts for bindings and stand-in robots
 * (sim_bind.c, the host model's live link): a scenario on the heap and its
 * errors, many steps a call (stopping where a run stops), a group's
 * observables as strided views equal to the per-robot accessor, every
 * robot's state in one call, robot ids, a robot's UART bytes, the live
 * host link's mailbox and pose ages, the summary as text.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"
#include "models/host/host.h"
#include "swarmsim/command.h"

#define FORAGING "../sim_host/scenarios/foraging_base.yaml"
#define GATHER "../sim_host/scenarios/phototaxis_gather.yaml"   /* done at 44 s (tests/golden) */

static void test_scenario_on_the_heap(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    scenario_override_t set[] = { { "robots.0.count=4" }, { "seed=77" } };
    scenario_t *sc = scenario_create(FORAGING, set, 2, err);
    assert_non_null(sc);
    assert_int_equal(scenario_robot_count(sc), 5);
    assert_int_equal(scenario_seed(sc), 77);
    assert_int_equal(scenario_steps(sc), 12000);   /* 1200 s at 100 ms */
    scenario_destroy(sc);
    scenario_override_t bad[] = { { "robots.0.count=x" } };
    assert_null(scenario_create(FORAGING, bad, 1, err));
    assert_non_null(strstr(err, "--set robots.0.count=x: robots[0].count"));
    assert_null(scenario_create("../no/such.yaml", NULL, 0, err));
    assert_non_null(strstr(err, "cannot open"));
    scenario_destroy(NULL);
}

static void test_step_n_is_steps_and_stops_with_the_run(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    scenario_t *sc = scenario_create(FORAGING, NULL, 0, err);
    assert_non_null(sc);
    sim_t *a = fixture_sim(sc, 5), *b = fixture_sim(sc, 5);
    assert_int_equal(sim_step_n(a, 250), 250);
    for (int k = 0; k < 250; k++) sim_step(b);
    assert_int_equal(sim_step_count(a), 250);
    assert_true(sim_state_hash(a) == sim_state_hash(b));
    assert_int_equal(sim_step_n(a, 0), 0);
    sim_destroy(a);
    sim_destroy(b);
    scenario_destroy(sc);

    /* A run with a stop condition: sim_step_n ends at the step it holds. */
    sc = scenario_create(GATHER, NULL, 0, err);
    assert_non_null(sc);
    sim_t *sim = fixture_sim(sc, scenario_seed(sc));
    assert_int_equal(sim_step_n(sim, 100000), 440);
    assert_true(sim_done(sim));
    assert_int_equal(sim_step_n(sim, 5), 0);
    assert_int_equal(sim_step_count(sim), 440);
    sim_destroy(sim);
    scenario_destroy(sc);
}

static double field_value(const sim_field_t *f, uint32_t j)
{
    const char *p = (const char *)f->base + (size_t)j * f->stride;
    switch (f->type) {
    case SIM_FIELD_U8: return *(const uint8_t *)p;
    case SIM_FIELD_I8: return *(const int8_t *)p;
    case SIM_FIELD_U16: return *(const uint16_t *)p;
    case SIM_FIELD_I16: return *(const int16_t *)p;
    case SIM_FIELD_U32: return *(const uint32_t *)p;
    case SIM_FIELD_I32: return *(const int32_t *)p;
    case SIM_FIELD_F32: return *(const float *)p;
    default: fail_msg("type %d", f->type); return 0;
    }
}

static void test_group_views_states_and_ids(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    scenario_override_t set[] = { { "robots.0.count=9" } };
    scenario_t *sc = scenario_create(FORAGING, set, 1, err);
    assert_non_null(sc);
    sim_t *sim = fixture_sim(sc, 3);
    sim_step_n(sim, 300);
    assert_int_equal(sim_group_count(sim), 2);
    assert_string_equal(sim_group_name(sim, 0), "foragers");
    uint32_t seen = 0;
    for (uint32_t g = 0; g < sim_group_count(sim); g++) {
        uint32_t first, count;
        sim_group_robots(sim, g, &first, &count);
        assert_int_equal(first, seen);
        seen += count;
        sim_field_t f;
        float scale;
        uint32_t k = 0;
        for (; sim_group_observable_at(sim, g, k, &f, &scale) == 0; k++) {
            for (uint32_t j = 0; j < count; j++) {
                float want;
                assert_int_equal(sim_robot_observable(sim, first + j, f.name, &want), 0);
                assert_true((float)(field_value(&f, j) * scale) == want);
            }
        }
        assert_int_equal(k, observable_count(sim_robot_def(sim, first)->observables));
    }
    assert_int_equal(seen, sim_robot_count(sim));
    const char *names[10];
    sim_robot_state_names(sim, 0, 10, names);
    for (uint32_t i = 0; i < 10; i++) {
        assert_string_equal(names[i], sim_robot_state_name(sim, i));
    }
    hal_t *h = sim_robot_hal(sim, 4);
    assert_int_equal(hal_robot_id(h), 4);
    assert_int_equal(sim_robot_id(sim, 4), 4);
    sim_set_robot_id(sim, 4, 4321);
    assert_int_equal(hal_robot_id(h), 4321);
    char *json = sim_summary_json(sim, "v1", "a command", set, 1, err);
    assert_non_null(json);
    char hash[40];
    snprintf(hash, sizeof hash, "\"state_hash\": \"%016llx\"", (unsigned long long)sim_state_hash(sim));
    assert_non_null(strstr(json, hash));
    assert_non_null(strstr(json, "\"overrides\": [\"robots.0.count=9\"]"));
    assert_non_null(strstr(json, "\"steps\": 300"));
    assert_non_null(strstr(json, "\"command\": \"a command\""));
    free(json);
    sim_destroy(sim);
    scenario_destroy(sc);
}

static void test_uart_bytes_are_the_images_frames(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "";
    scenario_override_t set[] = { { "robots.0.count=3" }, { "robot_telemetry.enabled=true" } };
    scenario_t *sc = scenario_create(FORAGING, set, 2, err);
    assert_non_null(sc);
    sim_t *sim = fixture_sim(sc, 1);
    sim_set_robot_id(sim, 1, 700);
    uint64_t total = 0;
    int saw_id = 0;
    for (int s = 0; s < 30; s++) {
        sim_step(sim);
        const uint8_t *bytes;
        uint32_t n = sim_robot_uart(sim, 1, &bytes);
        total += n;
        /* Frames: 0x00, COBS(version, channel, id 0x02BC = 700, ...), 0x00. */
        for (uint32_t k = 0; k + 5 < n; k++) {
            if (bytes[k] == 0 && bytes[k + 2] == 1 && bytes[k + 4] == 0x02 && bytes[k + 5] == 0xBC) saw_id = 1;
        }
    }
    assert_true(total > 100);
    assert_true(saw_id);
    sim_destroy(sim);
    scenario_destroy(sc);
    sc = scenario_create(FORAGING, NULL, 0, err);
    sim = fixture_sim(sc, 1);
    sim_step(sim);
    const uint8_t *bytes = (const uint8_t *)"x";
    assert_int_equal(sim_robot_uart(sim, 0, &bytes), 0);
    assert_null(bytes);
    sim_destroy(sim);
    scenario_destroy(sc);
}

static void test_live_host_link(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(2, 2.0f);
    host_config_t *hc = (host_config_t *)scenario_model_config_mut(sc, SIM_MODEL_host);
    sim_t *off = fixture_sim(sc, 1);
    uint8_t one = 1;
    hal_pose_t p = { 10, 20, 30, 0 };
    assert_int_equal(sim_host_send(off, 0, &one, 1), -2);
    assert_int_equal(sim_host_pose(off, 0, &p), -2);
    sim_destroy(off);

    hc->live = 1;
    sim_t *sim = fixture_sim(sc, 1);
    hal_t *h = sim_robot_hal(sim, 1);
    uint8_t buf[64], len = 0;
    hal_pose_t got;
    assert_int_equal(hal_host_receive(h, buf, sizeof buf, &len), HAL_ERR_EMPTY);   /* a link, nothing yet */
    assert_int_equal(hal_pose(h, &got), HAL_ERR_UNAVAILABLE);                      /* no fix yet */
    uint8_t a[3] = { 1, 2, 3 }, b[1] = { 9 }, c[1] = { 7 };
    assert_int_equal(sim_host_send(sim, 1, a, 3), 0);
    assert_int_equal(sim_host_send(sim, 1, b, 1), 0);
    assert_int_equal(sim_host_send(sim, 1, c, 1), -1);                            /* the mailbox holds two */
    assert_int_equal(sim_host_dropped(sim, 1), 1);
    assert_int_equal(sim_host_send(sim, 1, a, 0), -2);
    assert_int_equal(hal_host_receive(h, buf, 2, &len), HAL_ERR_RANGE);            /* too small: it stays */
    assert_int_equal(hal_host_receive(h, buf, sizeof buf, &len), HAL_OK);
    assert_int_equal(len, 3);
    assert_memory_equal(buf, a, 3);
    assert_int_equal(hal_host_receive(h, buf, sizeof buf, &len), HAL_OK);
    assert_int_equal(buf[0], 9);
    assert_int_equal(hal_host_receive(h, buf, sizeof buf, &len), HAL_ERR_EMPTY);
    assert_int_equal(hal_host_receive(sim_robot_hal(sim, 0), buf, sizeof buf, &len), HAL_ERR_EMPTY);

    /* A fix ages one period a step and is gone past 1000 ms (11 steps at 100 ms). */
    assert_int_equal(sim_host_pose(sim, 1, &p), 0);
    for (int s = 0; s <= 12; s++) {
        hal_status_t st = hal_pose(h, &got);
        if (s <= 10) {
            assert_int_equal(st, HAL_OK);
            assert_int_equal(got.x_mm, 10);
            assert_int_equal(got.heading_mrad, 30);
            assert_int_equal(got.age_ms, 100 * s);
        } else {
            assert_int_equal(st, HAL_ERR_UNAVAILABLE);
        }
        sim_step(sim);
    }
    assert_int_equal(hal_pose(sim_robot_hal(sim, 0), &got), HAL_ERR_UNAVAILABLE);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scenario_on_the_heap),
        cmocka_unit_test(test_step_n_is_steps_and_stops_with_the_run),
        cmocka_unit_test(test_group_views_states_and_ids),
        cmocka_unit_test(test_uart_bytes_are_the_images_frames),
        cmocka_unit_test(test_live_host_link),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
