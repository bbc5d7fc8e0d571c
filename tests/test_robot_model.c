/*
 * test_robot_model.c - the robot model of a group (robots[].robot,
 * sim_host/models/robot/): a group without the key is an e-puck1 and
 * its models take the e-puck1's facts (so every golden hash stays as it
 * was); an e-puck2 group's robots take the e-puck2's facts
 * (hal/platform_facts.h) in the models that use them (the camera's frame
 * rate, the wheels' top speed, the microphones); a model's own key set in
 * the scenario overrides the facts for every robot; an unknown model is
 * refused with file, line and the known names.  Well under a second.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "hal.h"
#include "platform_facts.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "models/camera/camera.h"
#include "models/robot/robot.h"

static int load_text(const char *yaml, const char *set, scenario_t *sc, char err[SIM_ERR_MAX])
{
    char path[] = "/tmp/test_robot_model_XXXXXX";
    scenario_override_t ov[1] = { { set } };
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
    close(fd);
    int rc = scenario_load(path, ov, set ? 1 : 0, sc, err);
    unlink(path);
    return rc;
}

static sim_t *make(const char *yaml, const char *set, scenario_t **out)
{
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (load_text(yaml, set, sc, err) != 0) fail_msg("%s", err);
    *out = sc;
    return fixture_sim(sc, 1);
}

static void done(sim_t *sim, scenario_t *sc)
{
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Robot `i`'s value of field `name`, as a double. */
static double field(const sim_t *sim, const char *name, uint32_t i)
{
    sim_field_t f;
    if (sim_field(sim, name, &f) != 0) fail_msg("no field %s", name);
    const char *p = (const char *)f.base + (size_t)i * f.stride;
    switch (f.type) {
    case SIM_FIELD_U8: return *(const uint8_t *)p;
    case SIM_FIELD_U16: return *(const uint16_t *)(const void *)p;
    case SIM_FIELD_I16: return *(const int16_t *)(const void *)p;
    case SIM_FIELD_F32: return *(const float *)(const void *)p;
    default: fail_msg("field %s: unexpected type", name);
    }
    return 0.0;
}

/* Group 0 says nothing (an e-puck1), group 1 is an e-puck2. */
#define TWO_MODELS                                                                      \
    "arena: {width: 2, height: 2}\n"                                                    \
    "robots:\n"                                                                         \
    "  - {name: old, count: 2, controller: idle}\n"                                     \
    "  - {name: new, count: 2, controller: idle, robot: e-puck2}\n"

static void test_each_group_gets_its_models_facts(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_MODELS, NULL, &sc);
    for (uint32_t i = 0; i < 2; i++) {
        assert_int_equal(field(sim, "robot.model", i), ROBOT_MODEL_EPUCK1);
        assert_float_equal(field(sim, "camera.fps", i), 4.3, 1e-6);   /* CAMERA_EPUCK_FPS */
        assert_float_equal(field(sim, "camera.fps", i), CAMERA_EPUCK_FPS, 0.0);
        assert_int_equal(field(sim, "wheels.speed_max", i), 1000);
        assert_int_equal(field(sim, "robot.mic_count", i), 3);
        assert_int_equal(field(sim, "robot.mic_rate_hz", i), 16384);
    }
    for (uint32_t i = 2; i < 4; i++) {
        assert_int_equal(field(sim, "robot.model", i), ROBOT_MODEL_EPUCK2);
        assert_float_equal(field(sim, "camera.fps", i), 15.0, 1e-6);
        /* The motors' 1100 steps/s, under hal.h's 1000 (the e-puck2's HAL
         * clamps to it too). */
        assert_int_equal(field(sim, "wheels.speed_max", i), HAL_WHEEL_SPEED_MAX);
        assert_int_equal(field(sim, "robot.mic_count", i), 4);
        assert_int_equal(field(sim, "robot.mic_rate_hz", i), 16000);
    }
    /* The wheels clamp to the robot's limit. */
    hal_set_wheel_speeds(sim_robot_hal(sim, 3), 1100, -1100);
    assert_int_equal(field(sim, "wheels.cmd_left", 3), 1000);
    assert_int_equal(field(sim, "wheels.cmd_right", 3), -1000);
    done(sim, sc);
}

/* camera.fps set in the scenario is every robot's, whatever its model. */
static void test_a_models_own_key_overrides(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_MODELS, "camera.fps=2.5", &sc);
    for (uint32_t i = 0; i < 4; i++) {
        assert_float_equal(field(sim, "camera.fps", i), 2.5, 1e-6);
    }
    done(sim, sc);
    sim = make(TWO_MODELS "camera: {fps: 0}\n", NULL, &sc);
    assert_float_equal(field(sim, "camera.fps", 2), 0.0, 0.0);
    done(sim, sc);
}

/* `robot: e-puck1` said outright is the default; --set changes a group's model. */
static void test_named_and_overridden(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_MODELS, "robots.1.robot=e-puck1", &sc);
    assert_int_equal(field(sim, "robot.model", 3), ROBOT_MODEL_EPUCK1);
    assert_float_equal(field(sim, "camera.fps", 3), CAMERA_EPUCK_FPS, 0.0);
    done(sim, sc);
    sim = make(TWO_MODELS, "robots.0.robot=e-puck2", &sc);
    assert_int_equal(field(sim, "robot.model", 0), ROBOT_MODEL_EPUCK2);
    done(sim, sc);
}

/* An unknown model: the file, the line, the key and the known names. */
static void test_unknown_model_is_refused(void **state)
{
    (void)state;
    scenario_t *sc = calloc(1, sizeof *sc);
    char err[SIM_ERR_MAX] = "";
    assert_non_null(sc);
    assert_int_equal(load_text("robots:\n  - {count: 1, controller: idle}\n"
                               "  - {count: 1, controller: idle, robot: e-puck3}\n", NULL, sc, err), -1);
    assert_non_null(strstr(err, ":3:"));
    assert_non_null(strstr(err, "robot"));
    assert_non_null(strstr(err, "e-puck1"));
    assert_non_null(strstr(err, "e-puck2"));
    assert_non_null(strstr(err, "e-puck3"));
    assert_int_equal(load_text("robots:\n  - {count: 1, controller: idle, robot: 2}\n", NULL, sc, err), -1);
    assert_non_null(strstr(err, ":2:"));
    free(sc);
}

/* The table is the header's constants, in PLATFORM_MODELS order. */
static void test_table_is_the_headers(void **state)
{
    (void)state;
    const platform_facts_t *a = robot_model_facts(ROBOT_MODEL_EPUCK1), *b = robot_model_facts(ROBOT_MODEL_EPUCK2);
    assert_string_equal(a->name, "e-puck1");
    assert_string_equal(b->name, "e-puck2");
    assert_string_equal(robot_model_names[ROBOT_MODEL_EPUCK2], "e-puck2");
    assert_null(robot_model_names[ROBOT_MODEL_COUNT]);
    assert_int_equal(a->mic_rate_hz, SOUND_MIC_RATE_HZ);
    assert_int_equal(b->mic_rate_hz, EPUCK2_MIC_RATE_HZ);
    assert_int_equal(a->motor_speed_limit, 1000);
    assert_int_equal(b->motor_speed_limit, 1100);
    assert_int_equal(a->rgb_leds, 0);
    assert_int_equal(b->rgb_leds, 4);
    assert_int_equal(a->tof, 0);
    assert_int_equal(b->tof, 1);
    assert_int_equal(b->gyroscope, 1);
    assert_int_equal(a->camera_frame_width_px, EPUCK_CAMERA_WIDTH_PX);
    assert_int_equal(b->camera_frame_height_px, EPUCK_CAMERA_HEIGHT_PX);
    assert_int_equal(b->ircom_backends, PLATFORM_IRCOM_LIBIRCOM | PLATFORM_IRCOM_RANDB);
    assert_int_equal(b->mic_bearing_deg[2], 180);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_group_gets_its_models_facts),
        cmocka_unit_test(test_a_models_own_key_overrides),
        cmocka_unit_test(test_named_and_overridden),
        cmocka_unit_test(test_unknown_model_is_refused),
        cmocka_unit_test(test_table_is_the_headers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
