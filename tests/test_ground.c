/*
 * test_ground.c - the ground-sensor model (sim_host/models/ground/): a
 * robot without the module answers HAL_ERR_UNAVAILABLE; the three sensors
 * sit ahead, left to right, and read the floor's grey level and its
 * regions (the last listed on top, a task's on top of the scenario's);
 * readings are consistent within a step and noisy across steps with the
 * configured sd from the robot's own stream; a run whose controllers never
 * ask is the same with the module or without; bad regions are refused with
 * file, line and key.  About a second.
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
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
/* The model's own header: its regions (ground_add_region stands in for a
 * task that draws its nest on the floor). */
#include "models/ground/ground.h"

/* Loads YAML text (through a temporary file) with overrides. */
static int load_text(const char *yaml, const char *set, scenario_t *sc, char err[SIM_ERR_MAX])
{
    char path[] = "/tmp/test_ground_XXXXXX";
    scenario_override_t ov[1] = { { set } };
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
    close(fd);
    int rc = scenario_load(path, ov, set ? 1 : 0, sc, err);
    unlink(path);
    return rc;
}

static sim_t *make(const char *yaml, const char *set, uint64_t seed, scenario_t **out)
{
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    if (load_text(yaml, set, sc, err) != 0) fail_msg("%s", err);
    *out = sc;
    return fixture_sim(sc, seed);
}

static void done(sim_t *sim, scenario_t *sc)
{
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static void read3(sim_t *sim, uint32_t robot, uint16_t v[HAL_GROUND_COUNT])
{
    for (uint8_t k = 0; k < HAL_GROUND_COUNT; k++) {
        assert_int_equal(hal_ground(sim_robot_hal(sim, robot), k, &v[k]), HAL_OK);
    }
}

/* Group 0 carries the module, group 1 does not; no noise. */
#define TWO_GROUPS                                                                      \
    "arena: {width: 2, height: 2}\n"                                                    \
    "ground: {noise_rel: 0, floor: 0.8, regions: [{shape: box, x: 0.5, y: 0.5, width: 0.2," \
    " depth: 0.2, reflectance: 0}]}\n"                                                  \
    "robots:\n"                                                                         \
    "  - {name: fitted, count: 1, controller: idle, ground_sensors: true}\n"            \
    "  - {name: bare, count: 1, controller: idle}\n"

static void test_fitted_or_unavailable(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_GROUPS, NULL, 1, &sc);
    uint16_t v = 77;
    sim_set_robot_pose(sim, 0, -0.5, -0.5, 0.0);
    sim_set_robot_pose(sim, 1, -0.5, 0.5, 0.0);
    assert_int_equal(hal_ground(sim_robot_hal(sim, 1), 0, &v), HAL_ERR_UNAVAILABLE);
    assert_int_equal(v, 0);
    v = 77;
    assert_int_equal(hal_ground(sim_robot_hal(sim, 0), HAL_GROUND_COUNT, &v), HAL_ERR_RANGE);
    assert_int_equal(v, 0);
    uint16_t g[HAL_GROUND_COUNT];
    read3(sim, 0, g);   /* the bare floor: black + (white - black) 0.8 */
    for (int k = 0; k < 3; k++) assert_int_equal(g[k], 800);
    sim_field_t f;
    assert_int_equal(sim_field(sim, "ground.fitted", &f), 0);
    assert_int_equal(*(const uint8_t *)f.base, 1);
    assert_int_equal(*((const uint8_t *)f.base + f.stride), 0);
    done(sim, sc);

    /* No group with the module: every robot answers unavailable, and the
     * run allocates nothing for it (no field). */
    sim = make(TWO_GROUPS, "robots.0.ground_sensors=false", 1, &sc);
    assert_int_equal(hal_ground(sim_robot_hal(sim, 0), 1, &v), HAL_ERR_UNAVAILABLE);
    assert_int_equal(sim_field(sim, "ground.reflected", &f), -1);
    done(sim, sc);
}

/* The black square's edge under the sensors: 30 mm ahead, GS0 10 mm to
 * the left, GS2 10 mm to the right, whatever the heading. */
static void test_geometry_left_to_right(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_GROUPS, NULL, 1, &sc);
    uint16_t g[HAL_GROUND_COUNT];
    /* Heading +x, 5 mm below the square's lower edge (y = 0.4): GS0 sits
     * 5 mm inside it, GS1 and GS2 outside. */
    sim_set_robot_pose(sim, 0, 0.5 - 0.03, 0.395, 0.0);
    read3(sim, 0, g);
    assert_int_equal(g[0], 0);
    assert_int_equal(g[1], 800);
    assert_int_equal(g[2], 800);
    /* Heading -y, 5 mm right of the square's left edge (x = 0.4) seen from
     * outside: the robot's left is +x, so GS0 is the one inside. */
    sim_set_robot_pose(sim, 0, 0.395, 0.5 + 0.03, -1.5707963267948966);
    read3(sim, 0, g);
    assert_int_equal(g[0], 0);
    assert_int_equal(g[1], 800);
    assert_int_equal(g[2], 800);
    /* Centred on the square: all three black. */
    sim_set_robot_pose(sim, 0, 0.47, 0.5, 0.0);
    read3(sim, 0, g);
    for (int k = 0; k < 3; k++) assert_int_equal(g[k], 0);
    done(sim, sc);
}

/* The last region listed is on top; a task's region goes on top of the
 * scenario's; a disc holds its centre and not what lies beyond its radius. */
static void test_regions_on_top(void **state)
{
    (void)state;
    scenario_t *sc;
    sim_t *sim = make(TWO_GROUPS, "ground.regions=[{shape: box, x: 0.5, y: 0.5, width: 0.2, depth: 0.2, "
                      "reflectance: 0}, {shape: disc, x: 0.5, y: 0.5, radius: 0.05, reflectance: 0.5}]", 1, &sc);
    assert_true(fabsf(ground_reflectance(sim, 0.5f, 0.5f) - 0.5f) < 1e-6f);     /* the disc, on top */
    assert_true(ground_reflectance(sim, 0.5f, 0.44f) == 0.0f);                   /* the box around it */
    assert_true(fabsf(ground_reflectance(sim, -0.5f, 0.0f) - 0.8f) < 1e-6f);    /* the floor */
    const ground_region_t nest = { GROUND_DISC, 0.5f, 0.5f, 0.02f, 0.0f, 0.0f, 0.0f, 1.0f };
    assert_int_equal(ground_add_region(sim, &nest), 0);
    assert_true(ground_reflectance(sim, 0.5f, 0.5f) == 1.0f);
    assert_true(fabsf(ground_reflectance(sim, 0.5f, 0.53f) - 0.5f) < 1e-6f);
    /* A rotated box: 45 deg, sides 0.2 x 0.02 along the diagonal. */
    const ground_region_t strip = { GROUND_BOX, -0.5f, 0.0f, 0.0f, 0.2f, 0.02f, 45.0f, 0.25f };
    assert_int_equal(ground_add_region(sim, &strip), 0);
    assert_true(fabsf(ground_reflectance(sim, -0.45f, 0.05f) - 0.25f) < 1e-6f);  /* on the diagonal */
    assert_true(fabsf(ground_reflectance(sim, -0.45f, -0.05f) - 0.8f) < 1e-6f);  /* across it */
    done(sim, sc);
}

/* One reading a step (two reads agree), the configured noise across steps
 * (sd within 10 % over 600 readings), the same for the same seed. */
static void test_noise_and_consistency(void **state)
{
    (void)state;
    scenario_t *sc, *sc2;
    sim_t *sim = make(TWO_GROUPS, "ground.noise_rel=0.1", 3, &sc);
    sim_t *same = make(TWO_GROUPS, "ground.noise_rel=0.1", 3, &sc2);
    sim_set_robot_pose(sim, 0, -0.5, -0.5, 0.0);
    sim_set_robot_pose(same, 0, -0.5, -0.5, 0.0);
    double sum = 0, sq = 0;
    int n = 0, varied = 0;
    uint16_t prev = 0;
    for (int s = 0; s < 200; s++) {
        uint16_t g[HAL_GROUND_COUNT], again[HAL_GROUND_COUNT], twin[HAL_GROUND_COUNT];
        read3(sim, 0, g);
        read3(sim, 0, again);
        read3(same, 0, twin);
        for (int k = 0; k < 3; k++) {
            assert_int_equal(g[k], again[k]);
            assert_int_equal(g[k], twin[k]);
            sum += g[k];
            sq += (double)g[k] * g[k];
            n++;
        }
        varied += g[0] != prev;
        prev = g[0];
        sim_step(sim);
        sim_step(same);
    }
    double mean = sum / n, sd = sqrt(sq / n - mean * mean);
    if (fabs(mean - 800.0) > 4.0 * 80.0 / sqrt(n) || fabs(sd - 80.0) > 8.0) {
        fail_msg("ground readings: mean %.1f (800), sd %.1f (80)", mean, sd);
    }
    assert_true(varied > 190);
    done(sim, sc);
    done(same, sc2);
}

/* Controllers that never read the module: the same run with it or
 * without (its stream is drawn only when asked). */
static void test_unread_module_changes_nothing(void **state)
{
    (void)state;
    const char *yaml = "duration: 20\nrobots:\n  - {count: 10, controller: random_walk}\n";
    scenario_t *sa, *sb;
    sim_t *a = make(yaml, NULL, 5, &sa), *b = make(yaml, "robots.0.ground_sensors=true", 5, &sb);
    for (int s = 0; s < 200; s++) {
        sim_step(a);
        sim_step(b);
    }
    assert_true(sim_state_hash(a) == sim_state_hash(b));
    done(a, sa);
    done(b, sb);
}

static void expect_error(const char *set, const char *want)
{
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    assert_int_equal(load_text(TWO_GROUPS, set, sc, err), -1);
    if (strstr(err, want) == NULL) fail_msg("expected an error containing\n  %s\ngot\n  %s", want, err);
    free(sc);
}

static void test_bad_regions(void **state)
{
    (void)state;
    expect_error("ground.regions=[{shape: disc, x: 0, y: 0}]", "ground.regions[0].radius: a disc needs radius > 0");
    expect_error("ground.regions=[{shape: box, x: 0, y: 0, width: 1}]", "ground.regions[0].depth: a box needs depth > 0");
    expect_error("ground.regions=[{shape: disc, x: 3, y: 0, radius: 0.1}]",
                 "ground.regions[0].x: the region's centre is outside the arena");
    expect_error("ground.regions=[{shape: disc, radius: 0.1, reflectance: 2}]",
                 "ground.regions[0].reflectance: 2 is out of range [0, 1]");
    expect_error("robots.1.ground_sensors=1", "robots[1].ground_sensors: expected true/false, got '1'");
    expect_error("ground.flor=0.5", "ground.flor: unknown key 'flor' (did you mean 'floor'?)");
}

/* A file's line is in the message. */
static void test_error_names_the_line(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX];
    scenario_t *sc = calloc(1, sizeof *sc);
    assert_non_null(sc);
    assert_int_equal(load_text("ground:\n  regions:\n    - shape: disc\n      x: 0\n", NULL, sc, err), -1);
    assert_non_null(strstr(err, ":3: ground.regions[0].radius: a disc needs radius > 0"));
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fitted_or_unavailable),
        cmocka_unit_test(test_geometry_left_to_right),
        cmocka_unit_test(test_regions_on_top),
        cmocka_unit_test(test_noise_and_consistency),
        cmocka_unit_test(test_unread_module_changes_nothing),
        cmocka_unit_test(test_bad_regions),
        cmocka_unit_test(test_error_names_the_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
