/*
 * test_phototaxis.c - the tutorial's example controller on a fake HAL: it
 * steers towards the brightest ambient sensor, stops under the light with
 * its body LED on (counting the arrival), seeks again when the light fades
 * past the hysteresis, and turns away from an obstacle.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "examples/phototaxis.h"
#include "fake_hal.h"

/* The controller alone: turns towards the brighter side, stops when bright. */

static void test_controller_steers_and_arrives(void **state)
{
    (void)state;
    phototaxis_params_t p;
    phototaxis_t self;
    hal_t hal;
    fake_hal_init(&hal, 1);
    phototaxis_default_params(&p);
    phototaxis_init(&self, &p, 1u);
    for (uint8_t i = 0; i < HAL_IR_COUNT; i++) hal.ambient[i] = 3000;
    hal.ambient[6] = 2000;                     /* +50 deg: the light is ahead on the left */
    phototaxis_step(&self, &hal);
    assert_string_equal(phototaxis_state_name(&self), "seek");
    assert_true(hal.right > hal.left);         /* steers left */
    assert_int_equal(self.brightest, 2000);
    assert_int_equal(self.light_bearing_mrad, 873);
    hal.ambient[6] = 500;                      /* under the lamp */
    phototaxis_step(&self, &hal);
    assert_string_equal(phototaxis_state_name(&self), "arrived");
    assert_true(hal.left == 0 && hal.right == 0 && hal.body_led);
    assert_int_equal(self.arrivals, 1);
    hal.ambient[6] = 1100;                     /* between the levels: stays */
    phototaxis_step(&self, &hal);
    assert_string_equal(phototaxis_state_name(&self), "arrived");
    hal.ambient[6] = 1300;                     /* darker than leave_level: seeks */
    phototaxis_step(&self, &hal);
    assert_string_equal(phototaxis_state_name(&self), "seek");
    hal.proximity[7] = 1000;                        /* an obstacle ahead on the left */
    phototaxis_step(&self, &hal);
    assert_string_equal(phototaxis_state_name(&self), "avoid");
    phototaxis_step(&self, &hal);
    assert_true(hal.left > 0 && hal.right < 0);   /* turns clockwise, away from it */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_controller_steers_and_arrives),
    };
    return cmocka_run_group_tests_name("phototaxis", tests, NULL, NULL);
}
