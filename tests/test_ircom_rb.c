/*
 * test_ircom_rb.c - the simulator's IR messaging as seed 003 needs it
 * (sim_host/models/ircom/ircom.c): several messages a period (ircom.tx_per_period),
 * per-message loss, the paper's random-vector bearing noise
 * (ircom.bearing_noise_vec), collisions (ircom.slots) and the inbox size
 * (ircom.queue).  Time: about a second.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "hal.h"
#include "registry.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
/* The IR model's keys, set in code (an internal header). */
#include "models/ircom/ircom.h"

static scenario_t *idle_scenario(uint32_t robots)
{
    scenario_t *sc = fixture_idle_scenario(robots, 3.0f);
    ircom_config_mut(sc)->payload_bits = 16;
    ircom_config_mut(sc)->range = 0.8f;
    ircom_config_mut(sc)->loss = 0.0f;
    ircom_config_mut(sc)->quantise_bearing = 0;
    ircom_config_mut(sc)->bearing_noise = 0.0f;
    ircom_config_mut(sc)->range_noise_rel = 0.0f;
    return sc;
}

static uint32_t drain(sim_t *sim, uint32_t robot)
{
    hal_ircom_msg_t m;
    uint32_t n = 0;
    while (hal_ircom_receive(sim_robot_hal(sim, robot), &m) == HAL_OK) n++;
    return n;
}

static void test_several_per_period(void **state)
{
    (void)state;
    scenario_t *sc = idle_scenario(2);
    ircom_config_mut(sc)->tx_per_period = 3;
    sim_t *sim = fixture_sim(sc, 1);
    hal_ircom_msg_t m;
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.5, 0.0, 0.0);
    for (uint16_t v = 1; v <= 3; v++) assert_int_equal(hal_ircom_send(sim_robot_hal(sim, 1), v), HAL_OK);
    assert_int_equal(hal_ircom_send(sim_robot_hal(sim, 1), 4), HAL_ERR_BUSY);
    sim_step(sim);
    for (uint16_t v = 1; v <= 3; v++) {
        assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_OK);
        assert_int_equal(m.value, v);                  /* in sending order */
        assert_int_equal(m.range_mm, 500);
        assert_int_equal(m.bearing_mrad, 0);
    }
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_ERR_EMPTY);
    /* The quota is per period. */
    assert_int_equal(hal_ircom_send(sim_robot_hal(sim, 1), 5), HAL_OK);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_loss_is_per_message(void **state)
{
    (void)state;
    scenario_t *sc = idle_scenario(2);
    ircom_config_mut(sc)->loss = 0.3f;
    ircom_config_mut(sc)->tx_per_period = 4;
    sim_t *sim = fixture_sim(sc, 2);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.3, 0.0, 0.0);
    uint32_t got = 0, sent = 0;
    for (int k = 0; k < 1000; k++) {
        for (uint16_t v = 0; v < 4; v++, sent++) hal_ircom_send(sim_robot_hal(sim, 1), v);
        sim_step(sim);
        got += drain(sim, 0);
    }
    double lost = 1.0 - (double)got / sent;
    assert_true(lost > 0.28 && lost < 0.32);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_bearing_noise_vector(void **state)
{
    (void)state;
    scenario_t *sc = idle_scenario(2);
    ircom_config_mut(sc)->bearing_noise_vec = 0.05f;
    sim_t *sim = fixture_sim(sc, 3);
    /* Sender 0.5 m ahead: the measured vector minus the true one is the
     * noise vector, whose mean squared length is sd^2 (uniform azimuth,
     * Gaussian length) and whose mean is zero. */
    double sum2 = 0, sx = 0, sy = 0, n = 0;
    for (int k = 0; k < 4000; k++) {
        hal_ircom_msg_t m;
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        sim_set_robot_pose(sim, 1, 0.5, 0.0, 0.0);
        hal_ircom_send(sim_robot_hal(sim, 1), 7);
        sim_step(sim);
        while (hal_ircom_receive(sim_robot_hal(sim, 0), &m) == HAL_OK) {
            double a = m.bearing_mrad / 1000.0, r = m.range_mm / 1000.0;
            double ex = r * cos(a) - 0.5, ey = r * sin(a);
            sum2 += ex * ex + ey * ey;
            sx += ex;
            sy += ey;
            n++;
        }
    }
    assert_true(n > 3900);
    double ms = sum2 / n;
    assert_true(ms > 0.9 * 0.0025 && ms < 1.1 * 0.0025);
    assert_true(fabs(sx / n) < 0.004 && fabs(sy / n) < 0.004);
    sim_destroy(sim);

    /* sd 0: exact. */
    ircom_config_mut(sc)->bearing_noise_vec = 0.0f;
    sim = fixture_sim(sc, 3);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.0, 0.4, 0.0);
    hal_ircom_send(sim_robot_hal(sim, 1), 7);
    sim_step(sim);
    hal_ircom_msg_t m;
    assert_int_equal(hal_ircom_receive(sim_robot_hal(sim, 0), &m), HAL_OK);
    assert_int_equal(m.bearing_mrad, 1571);
    assert_int_equal(m.range_mm, 400);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_collisions(void **state)
{
    (void)state;
    /* Robot 0 hears robots 1 and 2: with one slot a period their frames
     * collide at robot 0, and each is deaf while it sends. */
    scenario_t *sc = idle_scenario(3);
    ircom_config_mut(sc)->slots = 1;
    sim_t *sim = fixture_sim(sc, 4);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.3, 0.0, 0.0);
    sim_set_robot_pose(sim, 2, -0.3, 0.0, 0.0);
    for (int k = 0; k < 20; k++) {
        hal_ircom_send(sim_robot_hal(sim, 1), 1);
        hal_ircom_send(sim_robot_hal(sim, 2), 2);
        sim_step(sim);
        assert_int_equal(drain(sim, 0), 0);
        assert_int_equal(drain(sim, 1), 0);   /* half duplex: each is sending */
        assert_int_equal(drain(sim, 2), 0);
    }
    /* A lone sender never collides. */
    for (int k = 0; k < 20; k++) {
        hal_ircom_send(sim_robot_hal(sim, 1), 1);
        sim_step(sim);
        assert_int_equal(drain(sim, 0), 1);
        assert_int_equal(drain(sim, 2), 1);
    }
    sim_destroy(sim);
    /* With 10 slots the two frames share one a tenth of the time. */
    ircom_config_mut(sc)->slots = 10;
    sim = fixture_sim(sc, 5);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.3, 0.0, 0.0);
    sim_set_robot_pose(sim, 2, -0.3, 0.0, 0.0);
    uint32_t got = 0;
    for (int k = 0; k < 2000; k++) {
        hal_ircom_send(sim_robot_hal(sim, 1), 1);
        hal_ircom_send(sim_robot_hal(sim, 2), 2);
        sim_step(sim);
        got += drain(sim, 0);
        drain(sim, 1);
        drain(sim, 2);
    }
    double collided = 1.0 - got / 4000.0;
    assert_true(collided > 0.08 && collided < 0.12);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void test_queue_size(void **state)
{
    (void)state;
    scenario_t *sc = idle_scenario(4);
    ircom_config_mut(sc)->queue = 2;
    sim_t *sim = fixture_sim(sc, 6);
    sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.3, 0.0, 0.0);
    sim_set_robot_pose(sim, 2, -0.3, 0.0, 0.0);
    sim_set_robot_pose(sim, 3, 0.0, 0.3, 0.0);
    for (uint32_t i = 1; i < 4; i++) hal_ircom_send(sim_robot_hal(sim, i), (uint16_t)i);
    sim_step(sim);
    assert_int_equal(drain(sim, 0), 2);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_several_per_period),
        cmocka_unit_test(test_loss_is_per_message),
        cmocka_unit_test(test_bearing_noise_vector),
        cmocka_unit_test(test_collisions),
        cmocka_unit_test(test_queue_size),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
