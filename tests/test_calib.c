/*
 * test_calib.c - the calibration image's controller (firmware/calib/) on a
 * fake HAL: it settles for a whole window after a command, then latches
 * each window's mean and variance; a drive runs exactly its periods and
 * counts the steps through the 16-bit counters' wrap, saying "driven" only
 * once the counts include the last period; malformed commands are counted
 * and change nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "calib/calib.h"
#include "fake_hal.h"

static void start(calib_t *self, hal_t *hal)
{
    calib_params_t p;
    fake_hal_init(hal, 7);
    calib_default_params(&p);
    calib_init(self, &p, 1u);
}

static void steps(calib_t *self, hal_t *hal, int n)
{
    for (int k = 0; k < n; k++) {
        calib_step(self, hal);
        fake_hal_end_step(hal);
    }
}

static void test_prox_settles_then_latches_windows(void **state)
{
    (void)state;
    calib_t self;
    hal_t hal;
    start(&self, &hal);
    steps(&self, &hal, 3);
    assert_string_equal(calib_state_name(&self), "idle");
    const uint8_t cmd = 'P';
    assert_int_equal(fake_hal_host_push(&hal, &cmd, 1), 1);
    /* The first window (10 periods) is dropped, the second latched. */
    for (int k = 0; k < 19; k++) {
        hal.proximity[2] = (uint16_t)(k % 2 ? 1010 : 990);
        calib_step(&self, &hal);
        fake_hal_end_step(&hal);
        assert_string_equal(calib_state_name(&self), "settle");
    }
    hal.proximity[2] = 1010;
    steps(&self, &hal, 1);
    assert_string_equal(calib_state_name(&self), "prox");
    assert_float_equal(self.mean[2], 1000.0f, 1e-3);
    assert_float_equal(self.var[2], 100.0f, 1e-2);    /* +-10 around 1000 */
    assert_float_equal(self.mean[0], 0.0f, 1e-6);
    assert_float_equal(self.var[0], 0.0f, 1e-6);
    assert_int_equal(hal.left, 0);
    assert_int_equal(hal.right, 0);
}

static void test_ambient_and_mic_channels(void **state)
{
    (void)state;
    calib_t self;
    hal_t hal;
    start(&self, &hal);
    const uint8_t amb = 'A';
    fake_hal_host_push(&hal, &amb, 1);
    for (uint8_t i = 0; i < HAL_IR_COUNT; i++) hal.ambient[i] = (uint16_t)(3000u + i);
    steps(&self, &hal, 20);
    assert_string_equal(calib_state_name(&self), "ambient");
    assert_float_equal(self.mean[7], 3007.0f, 1e-3);
    const uint8_t mic[2] = { 'M', 2 };
    fake_hal_host_push(&hal, mic, 2);
    hal.mic[1][2] = 123456u;     /* beyond float's exact sums if not taken relative to the first */
    steps(&self, &hal, 20);
    assert_string_equal(calib_state_name(&self), "mic");
    assert_float_equal(self.mean[1], 123456.0f, 1e-2);
    assert_float_equal(self.var[1], 0.0f, 1e-6);
    const uint8_t bad_band[2] = { 'M', 9 };
    fake_hal_host_push(&hal, bad_band, 2);
    steps(&self, &hal, 1);
    assert_string_equal(calib_state_name(&self), "no_sound");
}

/* 'F': the frame's pixel statistics, as hal_camera_colour_stats gives
 * them; a platform without frames says so. */
static void test_frame_statistics(void **state)
{
    (void)state;
    calib_t self;
    hal_t hal;
    start(&self, &hal);
    const uint8_t cmd[2] = { 'F', 1 };
    hal.has_frames = 1u;
    hal.frame_stats.pixels = 800u;
    hal.frame_stats.mean[0] = 172u;
    hal.frame_stats.mean[1] = 38u;
    hal.frame_stats.mean[2] = 43u;
    hal.frame_stats.sd[0] = 4u;
    hal.frame_stats.sd[2] = 6u;
    fake_hal_host_push(&hal, cmd, 2);
    steps(&self, &hal, 20);
    assert_string_equal(calib_state_name(&self), "frame");
    assert_float_equal(self.mean[0], 800.0f, 1e-3);
    assert_float_equal(self.mean[1], 172.0f, 1e-3);
    assert_float_equal(self.mean[3], 43.0f, 1e-3);
    assert_float_equal(self.mean[4], 4.0f, 1e-3);
    assert_float_equal(self.mean[6], 6.0f, 1e-3);
    assert_float_equal(self.var[1], 0.0f, 1e-6);
    hal.has_frames = 0u;
    fake_hal_host_push(&hal, cmd, 2);
    steps(&self, &hal, 1);
    assert_string_equal(calib_state_name(&self), "no_frame");
}

static void test_drive_counts_through_the_wrap(void **state)
{
    (void)state;
    calib_t self;
    hal_t hal;
    start(&self, &hal);
    hal.steps_left = 32700;      /* wraps within the run */
    hal.steps_right = -32700;
    const uint8_t cmd[7] = { 'D', 0x01, 0xF4, 0xFE, 0x0C, 0x00, 0x0C };   /* 500, -500, 12 periods */
    fake_hal_host_push(&hal, cmd, 7);
    for (int k = 0; k < 12; k++) {
        calib_step(&self, &hal);
        assert_string_equal(calib_state_name(&self), "drive");
        assert_int_equal(hal.left, 500);
        assert_int_equal(hal.right, -500);
        hal.steps_left = (int16_t)(uint16_t)((uint16_t)hal.steps_left + 50u);     /* the period's steps */
        hal.steps_right = (int16_t)(uint16_t)((uint16_t)hal.steps_right - 50u);
        fake_hal_end_step(&hal);
    }
    calib_step(&self, &hal);     /* stopped; the counts include the last period */
    assert_string_equal(calib_state_name(&self), "driven");
    assert_int_equal(hal.left, 0);
    assert_int_equal(hal.right, 0);
    assert_float_equal(self.mean[0], 600.0f, 1e-6);
    assert_float_equal(self.mean[1], -600.0f, 1e-6);
    assert_float_equal(self.mean[2], 12.0f, 1e-6);
}

static void test_malformed_commands_are_counted(void **state)
{
    (void)state;
    calib_t self;
    hal_t hal;
    start(&self, &hal);
    const uint8_t p = 'P';
    fake_hal_host_push(&hal, &p, 1);
    steps(&self, &hal, 20);
    const uint8_t short_drive[3] = { 'D', 1, 2 };
    const uint8_t unknown = 'Z';
    fake_hal_host_push(&hal, short_drive, 3);
    fake_hal_host_push(&hal, &unknown, 1);
    steps(&self, &hal, 2);
    assert_int_equal(self.bad_msgs, 2);
    assert_string_equal(calib_state_name(&self), "prox");
    calib_cmd_t c;
    assert_int_equal(calib_msg_decode((const uint8_t *)"P", 0, &c), -1);
    assert_int_equal(calib_msg_decode((const uint8_t *)"PP", 2, &c), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_prox_settles_then_latches_windows),
        cmocka_unit_test(test_ambient_and_mic_channels),
        cmocka_unit_test(test_frame_statistics),
        cmocka_unit_test(test_drive_counts_through_the_wrap),
        cmocka_unit_test(test_malformed_commands_are_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
