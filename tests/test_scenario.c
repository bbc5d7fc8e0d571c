/*
 * test_scenario.c - the strict YAML scenario loader (sim_host/core/scenario.c
 * over schema.c): defaults, a full file, every error class with its line,
 * key path and message, `--set` overrides, robot groups (controller,
 * policy, params, placement), task sections and object validation.
 *
 * Each test writes its YAML into a private temporary directory.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/random_walk.h"
#include "swarmsim/scenario.h"
#include "foraging/forager.h"
#include "nnea/nnea.h"
#include "registry.h"
#include "tasks/foraging/foraging.h"
/* The models' configs, set and read in code (their headers are internal). */
#include "models/camera/camera.h"
#include "models/ir/ir.h"
#include "models/host/host.h"
#include "models/ircom/ircom.h"
#include "models/wheels/wheels.h"
#include "models/tracker/tracker.h"

#define MAX_SETS 8

static char tmpdir[256];

typedef struct fixture {
    scenario_t *sc;
    char err[SIM_ERR_MAX];
    char path[512];  /* the file of the last load */
} fixture_t;

/* ---------------------------------------------------------------- helpers */

static int group_setup(void **state)
{
    const char *base = getenv("TMPDIR");
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "%s/test_scenario.XXXXXX",
             base != NULL && base[0] != '\0' ? base : "/tmp");
    return mkdtemp(tmpdir) != NULL ? 0 : -1;
}

static int group_teardown(void **state)
{
    (void)state;
    return rmdir(tmpdir);
}

static int setup(void **state)
{
    fixture_t *fx = calloc(1, sizeof *fx);
    if (fx == NULL) {
        return -1;
    }
    fx->sc = calloc(1, sizeof *fx->sc);   /* holds nothing on the heap yet */
    if (fx->sc == NULL) {
        free(fx);
        return -1;
    }
    *state = fx;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *fx = *state;
    scenario_free(fx->sc);
    free(fx->sc);
    free(fx);
    return 0;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, strlen(text), f), strlen(text));
    assert_int_equal(fclose(f), 0);
}

/* Writes `yaml` to tmpdir/name, loads it with the NULL-terminated `sets`,
 * removes the file and returns scenario_load's result. */
static int load_sets(fixture_t *fx, const char *name, const char *yaml, const char *const *sets)
{
    scenario_override_t overrides[MAX_SETS];
    size_t n = 0;
    int rc;
    while (sets != NULL && sets[n] != NULL) {
        assert_true(n < MAX_SETS);
        overrides[n].text = sets[n];
        n++;
    }
    snprintf(fx->path, sizeof fx->path, "%s/%s", tmpdir, name);
    write_file(fx->path, yaml);
    fx->err[0] = '\0';
    scenario_free(fx->sc);   /* what an earlier load of this fixture held */
    rc = scenario_load(fx->path, overrides, n, fx->sc, fx->err);
    assert_int_equal(unlink(fx->path), 0);
    return rc;
}

static int load(fixture_t *fx, const char *yaml)
{
    return load_sets(fx, "s.yaml", yaml, NULL);
}

/* The error names the file and line (0: no line) and then `rest`. */
static void assert_error_at(const fixture_t *fx, int line, const char *rest)
{
    char want[1024];
    if (line > 0) {
        snprintf(want, sizeof want, "%s:%d: %s", fx->path, line, rest);
    } else {
        snprintf(want, sizeof want, "%s: %s", fx->path, rest);
    }
    if (strstr(fx->err, want) == NULL) {
        print_error("expected an error containing\n  %s\ngot\n  %s\n", want, fx->err);
        fail();
    }
}

static void expect_load_error(fixture_t *fx, const char *yaml, int line, const char *rest)
{
    if (load(fx, yaml) != -1) {
        print_error("loading succeeded:\n%s\n", yaml);
        fail();
    }
    assert_error_at(fx, line, rest);
}

/* An override error: exactly "--set TEXT: rest...". */
static void expect_set_error(fixture_t *fx, const char *yaml, const char *set, const char *rest)
{
    const char *sets[] = { set, NULL };
    char want[1024];
    assert_int_equal(load_sets(fx, "s.yaml", yaml, sets), -1);
    snprintf(want, sizeof want, "--set %s: %s", set, rest);
    if (strncmp(fx->err, want, strlen(want)) != 0) {
        print_error("expected an error starting with\n  %s\ngot\n  %s\n", want, fx->err);
        fail();
    }
}

static const random_walk_params_t *rw_params(const scenario_t *sc)
{
    return (const random_walk_params_t *)sc->groups[0].params.bytes;
}

/* A minimal group: the text of one entry of `robots:`. */
#define RW "robots:\n  - controller: random_walk\n"

/* ---------------------------------------------------------------- defaults */

static void test_defaults(void **state)
{
    scenario_t *sc = ((fixture_t *)*state)->sc;
    scenario_defaults(sc);
    assert_int_equal(sc->seed, 1);
    assert_float_equal(sc->duration, 60.0, 1e-9);
    assert_int_equal(sc->control_period_ms, 100);
    assert_int_equal(sc->physics_substeps, 4);
    assert_float_equal(sc->arena.width, 4.0, 1e-6);
    assert_float_equal(sc->arena.height, 4.0, 1e-6);
    assert_float_equal(sc->arena.wall_thickness, 0.05, 1e-6);
    assert_int_equal(sc->group_count, 1);
    assert_int_equal(sc->groups[0].count, 20);
    assert_int_equal(sc->groups[0].placement.shape, PLACE_RECTANGLE);
    assert_float_equal(sc->groups[0].placement.width, 0.0, 1e-9);   /* the arena */
    assert_true(isnan(sc->groups[0].heading));                       /* random */
    assert_int_equal(sc->groups[0].moves, 1);
    assert_float_equal(sc->groups[0].min_spacing, 0.08, 1e-6);
    assert_int_equal(sc->object_count, 0);
    assert_int_equal(sc->light_count, 0);
    assert_int_equal(sc->task_count, 0);
    assert_int_equal(tracker_config(sc)->enabled, 0);
    assert_string_equal(sc->groups[0].controller, "random_walk");
    assert_string_equal(sc->groups[0].name, "random_walk");
    assert_ptr_equal(sc->groups[0].def, registry_controller("random_walk"));
    assert_int_equal(rw_params(sc)->speed_steps_s, 500);
    assert_int_equal(rw_params(sc)->avoid_exit, 150);
    assert_float_equal(ir_config(sc)->aperture, 15.0, 1e-6);
    assert_float_equal(ir_config(sc)->range, 0.1, 1e-6);
    assert_float_equal(ir_config(sc)->noise_rel, 0.01, 1e-6);
    assert_float_equal(ir_config(sc)->noise_abs, 5.0, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.dark, 4000.0, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.half, 1.0, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.noise_rel, 0.01, 1e-6);
    assert_float_equal(camera_config(sc)->fov, 56.0, 1e-6);
    assert_float_equal(camera_config(sc)->range, 0.9, 1e-6);   /* the detector's reach (test_camera_render) */
    assert_true(isnan(camera_config(sc)->fps));   /* unset: each robot model's (test_robot_model) */
    assert_int_equal(camera_config(sc)->width_px, 40);
    assert_int_equal(camera_config(sc)->height_px, 20);   /* the e-puck image's frame */
    assert_float_equal(ircom_config(sc)->range, 0.25, 1e-6);
    assert_float_equal(ircom_config(sc)->loss, 0.1, 1e-6);
    assert_float_equal(ircom_config(sc)->bearing_noise, 5.0, 1e-6);
    assert_float_equal(ircom_config(sc)->range_noise_rel, 0.1, 1e-6);
    assert_int_equal(ircom_config(sc)->quantise_bearing, 1);
    assert_int_equal(ircom_config(sc)->blocked_by_robots, 0);
    assert_float_equal(wheels_config(sc)->speed_noise_rel, 0.0, 1e-9);
    assert_int_equal(sc->output.timeseries_every, 10);
}

/* An empty file, a comment-only file, a null document (each with an
 * override: alone they are an error, below) and empty sections all give
 * exactly the defaults (plus path and name). */
static void test_empty_documents_give_defaults(void **state)
{
    static const char *const docs[] = {
        "", "# nothing here\n", "---\n", "~\n", "robots:\nobjects:\narena: {}\n",
    };
    static const char *const sets[] = { "seed=1", NULL };
    fixture_t *fx = *state;
    scenario_t *want = malloc(sizeof *want);
    size_t i;
    assert_non_null(want);
    for (i = 0; i < sizeof docs / sizeof docs[0]; i++) {
        assert_int_equal(load_sets(fx, "empty.yaml", docs[i], sets), 0);
        scenario_defaults(want);
        snprintf(want->path, sizeof want->path, "%s", fx->path);
        snprintf(want->name, sizeof want->name, "empty");
        assert_string_equal(fx->sc->path, fx->path);
        assert_string_equal(fx->sc->name, "empty");
        assert_memory_equal(fx->sc, want, sizeof *want);
    }
    scenario_free(want);
    free(want);
}

/* A file that says nothing, with no override, is a mistake (a wrong or
 * truncated file), not a request for the defaults. */
static void test_empty_file_alone_is_an_error(void **state)
{
    static const char *const docs[] = { "", "# nothing here\n", "---\n", "~\n" };
    fixture_t *fx = *state;
    for (size_t i = 0; i < sizeof docs / sizeof docs[0]; i++) {
        expect_load_error(fx, docs[i], 0, "empty scenario: it sets nothing");
    }
}

static void test_name_from_path(void **state)
{
    fixture_t *fx = *state;
    assert_int_equal(load_sets(fx, "foraging.v2.yaml", "seed: 3\n", NULL), 0);
    assert_string_equal(fx->sc->name, "foraging.v2");
    assert_int_equal(load_sets(fx, "noext", "seed: 3\n", NULL), 0);
    assert_string_equal(fx->sc->name, "noext");
    assert_int_equal(load_sets(fx, "x.yaml", "name: given name\n", NULL), 0);
    assert_string_equal(fx->sc->name, "given name");
    expect_load_error(fx, "name: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\n", 1,
                      "name: 'aaaa");
    assert_non_null(strstr(fx->err, "is longer than 63 characters"));
    expect_load_error(fx, "name: ''\n", 1, "name: expected a non-empty string");
}

/* ---------------------------------------------------------------- full file */

static const char full_yaml[] =
    "name: full\n"
    "seed: 9007199254740991\n"
    "duration: 1.5e3\n"
    "control_period_ms: 50\n"
    "physics_substeps: 8\n"
    "arena:\n"
    "  width: 6\n"
    "  height: 3.5\n"
    "  wall_thickness: 0.1\n"
    "robots:\n"
    "  - name: walkers\n"
    "    count: 100000\n"
    "    controller: random_walk\n"
    "    params:\n"
    "      speed_steps_s: 400\n"
    "      turn_speed_steps_s: 200\n"
    "      turn_chance: 655\n"
    "      avoid_enter: 500\n"
    "      avoid_exit: 250\n"
    "    placement: {shape: circle, x: -2, y: 1, radius: 0.6}\n"
    "    heading: 90\n"
    "    min_spacing: 0.1\n"
    "  - controller: forager\n"
    "    policy: artm\n"
    "    count: 2\n"
    "    placement:\n"
    "      shape: poses\n"
    "      poses: [{x: 1, y: 1}, {x: -1, y: 1, heading: -45}]\n"
    "    moves: false\n"
    "objects:\n"
    "  - shape: cylinder\n"
    "    x: 1\n"
    "    y: -1\n"
    "    radius: 0.2\n"
    "    height: 0.3\n"
    "    colour: red\n"
    "  - {shape: box, x: 2, y: 0.5, width: 0.4, depth: 0.2, angle: 30, colour: blue}\n"
    "lights:\n"
    "  - {x: 0.5, y: 0.25, height: 0.4, intensity: 2.5}\n"
    "  - {x: -1, y: -1}\n"

    "ir:\n"
    "  aperture: 20\n"
    "  range: 0.07\n"
    "  noise_rel: 0.05\n"
    "  noise_abs: 10\n"
    "ambient:\n"
    "  dark: 3800\n"
    "  half: 0.5\n"
    "  noise_rel: 0.02\n"
    "camera:\n"
    "  fov: 60\n"
    "  range: 1\n"
    "  width_px: 64\n"
    "  height_px: 48\n"
    "ircom:\n"
    "  range: 0.3\n"
    "  loss: 0.25\n"
    "  bearing_noise: 10\n"
    "  range_noise_rel: 0.2\n"
    "  quantise_bearing: false\n"
    "  blocked_by_robots: True\n"
    "  payload_bits: 16\n"
    "tracker: {enabled: true, noise_mm: 5, noise_deg: 2, dropout: 0.1}\n"
    "foraging:\n"
    "  nest: {x: -2, y: 1, diameter: 1.2}\n"
    "  food_count: 7\n"
    "  information: global\n"
    "wheels:\n"
    "  speed_noise_rel: 0.05\n"
    "output:\n"
    "  timeseries_every: 5\n";

static void test_full_file(void **state)
{
    fixture_t *fx = *state;
    const scenario_t *sc = fx->sc;
    assert_int_equal(load(fx, full_yaml), 0);
    assert_string_equal(sc->name, "full");
    assert_true(sc->seed == SCENARIO_SEED_MAX);
    assert_float_equal(sc->duration, 1500.0, 1e-9);
    assert_int_equal(sc->control_period_ms, 50);
    assert_int_equal(sc->physics_substeps, 8);
    assert_float_equal(sc->arena.width, 6.0, 1e-6);
    assert_float_equal(sc->arena.height, 3.5, 1e-6);
    assert_float_equal(sc->arena.wall_thickness, 0.1, 1e-6);
    assert_int_equal(sc->group_count, 2);
    assert_string_equal(sc->groups[0].name, "walkers");
    assert_int_equal(sc->groups[0].count, 100000);
    assert_int_equal(sc->groups[0].placement.shape, PLACE_CIRCLE);
    assert_float_equal(sc->groups[0].placement.x, -2.0, 1e-6);
    assert_float_equal(sc->groups[0].placement.y, 1.0, 1e-6);
    assert_float_equal(sc->groups[0].placement.radius, 0.6, 1e-6);
    assert_float_equal(sc->groups[0].heading, 90.0, 1e-6);
    assert_float_equal(sc->groups[0].min_spacing, 0.1, 1e-6);
    assert_int_equal(sc->groups[0].moves, 1);
    assert_string_equal(sc->groups[1].name, "forager");        /* its controller's */
    assert_ptr_equal(sc->groups[1].def, &forager_def);
    assert_string_equal(sc->groups[1].policy, "artm");
    assert_int_equal(sc->groups[1].policy_index, 1);
    assert_int_equal(sc->groups[1].moves, 0);
    assert_int_equal(sc->groups[1].placement.shape, PLACE_POSES);
    assert_int_equal(sc->groups[1].placement.pose_count, 2);
    assert_float_equal(sc->groups[1].placement.poses[0].x, 1.0, 1e-6);
    assert_true(isnan(sc->groups[1].placement.poses[0].heading));
    assert_float_equal(sc->groups[1].placement.poses[1].heading, -45.0, 1e-6);
    assert_int_equal(((const forager_params_t *)sc->groups[1].params.bytes)->t1_steps, 50);
    assert_int_equal(scenario_robot_count(sc), 100002);

    assert_int_equal(sc->object_count, 2);
    assert_int_equal(sc->objects[0].shape, SHAPE_CYLINDER);
    assert_float_equal(sc->objects[0].x, 1.0, 1e-6);
    assert_float_equal(sc->objects[0].y, -1.0, 1e-6);
    assert_float_equal(sc->objects[0].radius, 0.2, 1e-6);
    assert_float_equal(sc->objects[0].height, 0.3, 1e-6);
    assert_int_equal(sc->objects[0].colour, 1);
    assert_int_equal(sc->objects[1].shape, SHAPE_BOX);
    assert_float_equal(sc->objects[1].x, 2.0, 1e-6);
    assert_float_equal(sc->objects[1].y, 0.5, 1e-6);
    assert_float_equal(sc->objects[1].width, 0.4, 1e-6);
    assert_float_equal(sc->objects[1].depth, 0.2, 1e-6);
    assert_float_equal(sc->objects[1].angle, 30.0, 1e-6);
    assert_float_equal(sc->objects[1].height, 0.05, 1e-6);  /* entry default */
    assert_int_equal(sc->objects[1].colour, 3);

    assert_int_equal(sc->light_count, 2);
    assert_float_equal(sc->lights[0].x, 0.5, 1e-6);
    assert_float_equal(sc->lights[0].y, 0.25, 1e-6);
    assert_float_equal(sc->lights[0].height, 0.4, 1e-6);
    assert_float_equal(sc->lights[0].intensity, 2.5, 1e-6);
    assert_float_equal(sc->lights[1].x, -1.0, 1e-6);
    assert_float_equal(sc->lights[1].height, 0.1, 1e-6);    /* entry defaults */
    assert_float_equal(sc->lights[1].intensity, 1.0, 1e-6);

    assert_string_equal(sc->groups[0].controller, "random_walk");
    assert_int_equal(rw_params(sc)->speed_steps_s, 400);
    assert_int_equal(rw_params(sc)->turn_speed_steps_s, 200);
    assert_int_equal(rw_params(sc)->turn_chance, 655);
    assert_int_equal(rw_params(sc)->avoid_enter, 500);
    assert_int_equal(rw_params(sc)->avoid_exit, 250);

    assert_float_equal(ir_config(sc)->aperture, 20.0, 1e-6);
    assert_float_equal(ir_config(sc)->range, 0.07, 1e-6);
    assert_float_equal(ir_config(sc)->noise_rel, 0.05, 1e-6);
    assert_float_equal(ir_config(sc)->noise_abs, 10.0, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.dark, 3800.0, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.half, 0.5, 1e-6);
    assert_float_equal(ir_config(sc)->ambient.noise_rel, 0.02, 1e-6);
    assert_float_equal(camera_config(sc)->fov, 60.0, 1e-6);
    assert_float_equal(camera_config(sc)->range, 1.0, 1e-6);
    assert_int_equal(camera_config(sc)->width_px, 64);
    assert_int_equal(camera_config(sc)->height_px, 48);
    assert_float_equal(ircom_config(sc)->range, 0.3, 1e-6);
    assert_float_equal(ircom_config(sc)->loss, 0.25, 1e-6);
    assert_float_equal(ircom_config(sc)->bearing_noise, 10.0, 1e-6);
    assert_float_equal(ircom_config(sc)->range_noise_rel, 0.2, 1e-6);
    assert_int_equal(ircom_config(sc)->quantise_bearing, 0);
    assert_int_equal(ircom_config(sc)->blocked_by_robots, 1);
    assert_float_equal(wheels_config(sc)->speed_noise_rel, 0.05, 1e-6);
    assert_int_equal(tracker_config(sc)->enabled, 1);
    assert_float_equal(tracker_config(sc)->noise_mm, 5.0, 1e-6);
    assert_float_equal(tracker_config(sc)->dropout, 0.1, 1e-6);
    assert_int_equal(sc->output.timeseries_every, 5);
    assert_int_equal(sc->task_count, 1);
    assert_ptr_equal(sc->tasks[0].def, &foraging_task);
    const foraging_config_t *fc = scenario_task_config(sc, &foraging_task);
    assert_non_null(fc);
    assert_float_equal(fc->nest.x, -2.0, 1e-6);
    assert_float_equal(fc->nest.diameter, 1.2, 1e-6);
    assert_int_equal(fc->food_count, 7);
    assert_float_equal(fc->token_energy, 1500.0, 1e-6);   /* default kept */
    assert_int_equal(fc->information, FORAGING_INFO_GLOBAL);
}

/* ---------------------------------------------------------------- errors */

typedef struct bad_case {
    const char *yaml;
    int line;
    const char *rest;  /* what follows "FILE:LINE: " */
} bad_case_t;

static void expect_cases(fixture_t *fx, const bad_case_t *cases, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        expect_load_error(fx, cases[i].yaml, cases[i].line, cases[i].rest);
    }
}

static void test_exact_message_format(void **state)
{
    fixture_t *fx = *state;
    char want[1024];
    assert_int_equal(load(fx, "seed: 4\nrobots:\n  - controller: random_walk\n    count: 2.5\n"), -1);
    snprintf(want, sizeof want, "%s:4: robots[0].count: expected an integer, got '2.5'", fx->path);
    assert_string_equal(fx->err, want);
}

static void test_syntax_errors(void **state)
{
    static const bad_case_t cases[] = {
        { "a: 1\nrobots:\n  - count: [1, 2\n", 4, "YAML syntax error: " },
        { "arena:\n  width: 5\n bad: 1\n", 3, "YAML syntax error: did not find expected key" },
        { "arena:\n  width: 5\n  height: \"grid\n", 4, "YAML syntax error: " },
        { "arena:\n\twidth: 5\n", 2, "YAML syntax error: " },
        { "seed: 1\n---\nseed: 2\n", 2, "only one YAML document is allowed" },
        { "a: &x 1\nb: *x\n", 2, "YAML aliases (*x) are not supported" },
        { "seed: 1\nname: !!str 5\n", 2, "YAML tags" },
        { "? [a]\n: b\n", 1, "a mapping key must be a scalar" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_unknown_keys(void **state)
{
    static const bad_case_t cases[] = {
        { "seed: 1\n" RW "    cuont: 5\n", 4,
          "robots[0].cuont: unknown key 'cuont' (did you mean 'count'?)" },
        { "duraton: 5\n", 1, "duraton: unknown key 'duraton' (did you mean 'duration'?)" },
        { RW "    zzzzzz: 1\n", 3,
          "robots[0].zzzzzz: unknown key 'zzzzzz' (valid keys: name, count, controller, policy, "
          "heading, min_spacing, moves, first_id, placement, robot, faults, ground_sensors, platform, image, platform_robots, "
          "selector, params)" },
        { RW "    placement: {shape: circle, radius: 1, centre: 0}\n", 3,
          "robots[0].placement.centre: unknown key 'centre' (valid keys: shape, x, y," },
        { "objects:\n  - radius: 0.1\n  - radius: 0.1\n    colur: red\n", 4,
          "objects[1].colur: unknown key 'colur' (did you mean 'colour'?)" },
        { RW "    params:\n      speed: 3\n", 4,
          "robots[0].params.speed: unknown key 'speed' (valid keys: speed_steps_s," },
        { "foragign: {}\n", 1, "foragign: unknown key 'foragign' (did you mean 'foraging'?)" },
        { "foraging:\n  nest: {diametre: 1}\n", 2,
          "foraging.nest.diametre: unknown key 'diametre' (did you mean 'diameter'?)" },
        { "controller: {name: forager}\n", 1,
          "controller: unknown key 'controller': robots are groups now: robots: [{count: 20," },
        { "nest: {enabled: true}\n", 1,
          "nest: unknown key 'nest': a nest is no longer a core key: a task that has one declares it" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_wrong_types(void **state)
{
    static const bad_case_t cases[] = {
        { "duration: abc\n", 1, "duration: expected a number, got 'abc'" },
        { "duration:\n", 1, "duration: expected a number, got nothing" },
        { "duration: nan\n", 1, "duration: expected a number, got 'nan'" },
        { "duration: .inf\n", 1, "duration: expected a number, got '.inf'" },
        { "duration: 0x10\n", 1, "duration: expected a number, got '0x10'" },
        { "duration: 1.5s\n", 1, "duration: expected a number, got '1.5s'" },
        { "duration: \"10\"\n", 1, "duration: expected a number, got the string \"10\"" },
        { RW "    count: 2.5\n", 3, "robots[0].count: expected an integer, got '2.5'" },
        { RW "    count: 1e3\n", 3, "robots[0].count: expected an integer, got '1e3'" },
        { RW "    count: 12abc\n", 3, "robots[0].count: expected an integer, got '12abc'" },
        { RW "    count: [1]\n", 3, "robots[0].count: expected an integer, got a sequence" },
        { "seed: \"5\"\n", 1, "seed: expected an integer, got the string \"5\"" },
        { RW "    moves: yes\n", 3, "robots[0].moves: expected true/false, got 'yes'" },
        { "tracker:\n  enabled: 1\n", 2, "tracker.enabled: expected true/false, got '1'" },
        { RW "    heading: north\n", 3,
          "robots[0].heading: expected an angle in degrees or 'random', got 'north'" },
        { "robots: {count: 5}\n", 1, "robots: expected a sequence of groups, got a mapping" },
        { "robots:\n  - 5\n", 2, "robots[0]: expected a mapping, got '5'" },
        { "arena: 5\n", 1, "arena: expected a mapping, got '5'" },
        { "arena: [1, 2]\n", 1, "arena: expected a mapping, got a sequence" },
        { "objects:\n  shape: box\n", 2, "objects: expected a sequence, got a mapping" },
        { "objects:\n  - 5\n", 2, "objects[0]: expected a mapping, got '5'" },
        { "lights:\n  -\n", 2, "lights[0]: expected a mapping, got nothing" },
        { "name: [a]\n", 1, "name: expected a string, got a sequence" },
        { RW "    params: 5\n", 3, "robots[0].params: expected a mapping, got '5'" },
        { "foraging: 5\n", 1, "foraging: expected a mapping, got '5'" },
        { "- a\n- b\n", 1, "expected a mapping of keys at the top level, got a sequence" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_out_of_range(void **state)
{
    static const bad_case_t cases[] = {
        { RW "    count: 200000\n", 3, "robots[0].count: 200000 is out of range [0, 100000]" },
        { RW "    count: -1\n", 3, "robots[0].count: -1 is out of range [0, 100000]" },
        { RW "    count: 99999999999999999999999\n", 3,
          "robots[0].count: 99999999999999999999999 is out of range [0, 100000]" },
        { RW "    heading: 400\n", 3, "robots[0].heading: 400 is out of range [-360, 360]" },
        { "foraging:\n  robot_speed: 1\n", 2,
          "foraging.robot_speed: 1 is out of range [0.001, 0.128]" },
        { "seed: 9007199254740992\n", 1,
          "seed: 9007199254740992 is out of range [0, 9007199254740991]" },
        { "seed: 18446744073709551616\n", 1,
          "seed: 18446744073709551616 is out of range [0, 9007199254740991]" },
        { "seed: -1\n", 1, "seed: -1 is out of range [0, 9007199254740991]" },
        { "arena:\n  width: 0.05\n", 2, "arena.width: 0.05 is out of range [0.1, 1000]" },
        { "duration: 0\n", 1, "duration: 0 is out of range [0.001, 10000000]" },
        { "duration: 1e400\n", 1, "duration: 1e400 is out of range" },
        { "control_period_ms: 0\n", 1, "control_period_ms: 0 is out of range [1, 10000]" },
        { "physics_substeps: 65\n", 1, "physics_substeps: 65 is out of range [1, 64]" },
        { "ircom:\n  loss: 1.5\n", 2, "ircom.loss: 1.5 is out of range [0, 1]" },
        { "output:\n  timeseries_every: 0\n", 2, "output.timeseries_every: 0 is out of range" },
        { "lights:\n  - {x: 0, y: 0, intensity: -1}\n", 2,
          "lights[0].intensity: -1 is out of range [0, 1000000]" },
        { "duration: 0.05\n", 1, "duration: 0.05 s is shorter than one control period (0.1 s)" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_number_forms(void **state)
{
    fixture_t *fx = *state;
    assert_int_equal(load(fx, "seed: 007\nduration: +2\n" RW "    count: +5\n"
                              "arena:\n  width: .5e1\n  height: 3.\n"),
                     0);
    assert_int_equal(fx->sc->seed, 7);
    assert_float_equal(fx->sc->duration, 2.0, 1e-9);
    assert_int_equal(fx->sc->groups[0].count, 5);
    assert_float_equal(fx->sc->arena.width, 5.0, 1e-6);
    assert_float_equal(fx->sc->arena.height, 3.0, 1e-6);
    assert_int_equal(load(fx, "seed: -0\n" RW "    moves: FALSE\n    heading: random\n"), 0);
    assert_int_equal(fx->sc->seed, 0);
    assert_int_equal(fx->sc->groups[0].moves, 0);
    assert_true(isnan(fx->sc->groups[0].heading));
}

static void test_bad_enum(void **state)
{
    static const bad_case_t cases[] = {
        { RW "    placement: {shape: spiral}\n", 3,
          "robots[0].placement.shape: expected one of rectangle|circle|ring|grid|poses, got 'spiral'" },
        { RW "    placement: {shape: gird}\n", 3,
          "robots[0].placement.shape: expected one of rectangle|circle|ring|grid|poses, got 'gird' "
          "(did you mean 'grid'?)" },
        { RW "    placement: {shape: [grid]}\n", 3,
          "robots[0].placement.shape: expected one of rectangle|circle|ring|grid|poses, got a sequence" },
        { "foraging: {information: ideal}\n", 1,
          "foraging.information: expected one of beacon|global, got 'ideal'" },
        { "objects:\n  - shape: sphere\n", 2,
          "objects[0].shape: expected one of cylinder|box, got 'sphere'" },
        { "objects:\n  - radius: 1\n    colour: purple\n", 3,
          "objects[0].colour: expected one of none|red|green|blue, got 'purple'" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_duplicate_keys(void **state)
{
    static const bad_case_t cases[] = {
        { "seed: 1\n" RW "    count: 2\n    count: 3\n", 5,
          "robots[0].count: duplicate key 'count' (first on line 4)" },
        { "foraging: {}\nseed: 2\nforaging: {}\n", 3, "foraging: duplicate key 'foraging' (first on line 1)" },
        { "seed: 1\nseed: 2\n", 2, "seed: duplicate key 'seed' (first on line 1)" },
        { "objects:\n  - {radius: 1, radius: 2}\n", 2,
          "objects[0].radius: duplicate key 'radius'" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_missing_file(void **state)
{
    fixture_t *fx = *state;
    char want[700];
    snprintf(fx->path, sizeof fx->path, "%s/does-not-exist.yaml", tmpdir);
    assert_int_equal(scenario_load(fx->path, NULL, 0, fx->sc, fx->err), -1);
    snprintf(want, sizeof want, "%s: cannot open: No such file or directory", fx->path);
    assert_string_equal(fx->err, want);
    assert_int_equal(scenario_load(tmpdir, NULL, 0, fx->sc, fx->err), -1);
    snprintf(want, sizeof want, "%s: cannot open: Is a directory", tmpdir);
    assert_string_equal(fx->err, want);
}

static void test_invalid_utf8(void **state)
{
    expect_load_error(*state, "name: \xff\xfe\n", 0, "cannot read: ");
}

/* Builds "objects:\n" and `n` one-line entries (entry i is on line i + 2). */
static char *many_objects(size_t n)
{
    static const char entry[] = "  - {x: 0, y: 0, radius: 0.01}\n";
    char *text = malloc(16 + n * (sizeof entry - 1));
    size_t i, used;
    assert_non_null(text);
    used = (size_t)sprintf(text, "objects:\n");
    for (i = 0; i < n; i++) {
        memcpy(text + used, entry, sizeof entry - 1);
        used += sizeof entry - 1;
    }
    text[used] = '\0';
    return text;
}

static void test_too_many_entries(void **state)
{
    fixture_t *fx = *state;
    char *ok = many_objects(SCENARIO_MAX_OBJECTS);
    char *bad = many_objects(SCENARIO_MAX_OBJECTS + 1);
    char lights[2048] = "lights:\n";
    int i;
    assert_int_equal(load(fx, ok), 0);
    assert_int_equal(fx->sc->object_count, SCENARIO_MAX_OBJECTS);
    expect_load_error(fx, bad, SCENARIO_MAX_OBJECTS + 2,
                      "objects[4096]: too many objects (at most 4096)");
    for (i = 0; i <= SCENARIO_MAX_LIGHTS; i++) {
        strcat(lights, "  - {x: 0, y: 0}\n");
    }
    expect_load_error(fx, lights, SCENARIO_MAX_LIGHTS + 2,
                      "lights[16]: too many lights (at most 16)");
    free(ok);
    free(bad);
}

/* Inputs that must fail cleanly (and not crash or leak). */
static void test_hostile_inputs(void **state)
{
    fixture_t *fx = *state;
    char deep[1200], longkey[3000], want[200];
    memset(deep, '[', 500);
    memset(deep + 500, ']', 500);
    deep[1000] = '\0';
    expect_load_error(fx, deep, 1, "nested deeper than 64 levels");
    memset(longkey, 'k', 1000);
    memcpy(longkey + 1000, ": 1\n", 5);
    assert_int_equal(load(fx, longkey), -1);
    memset(want, 'k', 64);  /* the key is cut to 64 characters in messages */
    snprintf(want + 64, sizeof want - 64, ": unknown key '%.64s' (valid keys: name,", longkey);
    assert_error_at(fx, 1, want);
    memset(longkey, 'k', 2000);  /* libyaml: a simple key is at most 1024 chars */
    memcpy(longkey + 2000, ": 1\n", 5);
    expect_load_error(fx, longkey, 1, "YAML syntax error");
    expect_load_error(fx, "objects: [[[1]]]\n", 1, "objects[0]: expected a mapping, got a sequence");
    expect_load_error(fx, "{a: 1\n", 2, "YAML syntax error");
    expect_load_error(fx, "robots: {count: 5}: 3\n", 1, "YAML syntax error");
    expect_load_error(fx, "&a [*a]\n", 1, "YAML aliases (*a) are not supported");
    expect_load_error(fx, "'unterminated\n", 2, "YAML syntax error");
    expect_load_error(fx, "arena: &r {width: 5}\nwheels: *r\n", 2, "YAML aliases (*r)");
}

/* ---------------------------------------------------------------- objects */

static void test_object_shapes(void **state)
{
    static const bad_case_t cases[] = {
        { "objects:\n  - shape: cylinder\n    x: 1\n", 2,
          "objects[0].radius: a cylinder needs radius > 0" },
        { "objects:\n  - radius: 0.1\n  - shape: cylinder\n    x: 1\n    radius: 0\n", 5,
          "objects[1].radius: a cylinder needs radius > 0" },
        { "objects:\n  - {shape: box, width: 0.2, depth: 0.1}\n  - {shape: box, width: 0.2}\n"
          "  - radius: 0.1\n", 3, "objects[1].depth: a box needs depth > 0" },
        { "objects:\n  - shape: box\n    width: 0\n    depth: 1\n", 3,
          "objects[0].width: a box needs width > 0" },
        { "objects:\n  - radius: 0.1\n  - radius: 0.1\n  - radius: 0.1\n  - radius: -1\n", 5,
          "objects[3].radius: -1 is out of range [0, 500]" },
    };
    expect_cases(*state, cases, sizeof cases / sizeof cases[0]);
}

static void test_objects_inside_arena(void **state)
{
    static const bad_case_t cases[] = {
        { "objects:\n  - {x: 0, y: 0, radius: 0.1}\n  - x: 1.95\n    radius: 0.1\n", 3,
          "objects[1]: the cylinder reaches outside the arena (x in [-2, 2], y in [-2, 2] m)" },
        { "objects:\n  - {shape: box, x: 1.9, width: 1, depth: 0.1}\n", 2,
          "objects[0]: the box reaches outside the arena" },
        { "arena:\n  height: 1\nobjects:\n  - {y: -0.6, radius: 0.2}\n", 4,
          "objects[0]: the cylinder reaches outside the arena (x in [-2, 2], y in [-0.5, 0.5] m)" },
        { "lights:\n  - {x: 3, y: 0}\n", 2, "lights[0]: the light is outside the arena" },
        { "robots: []\nforaging:\n  information: global\n  nest:\n    x: 1.9\n    diameter: 0.5\n", 5,
          "foraging.nest: the nest circle reaches outside the arena" },
    };
    fixture_t *fx = *state;
    expect_cases(fx, cases, sizeof cases / sizeof cases[0]);
    /* Touching a wall is fine; a rotated box is checked by its footprint. */
    assert_int_equal(load(fx, "objects:\n  - {x: 1.9, radius: 0.1}\n"
                              "  - {shape: box, x: -1.9, width: 1, depth: 0.1, angle: 90}\n"),
                     0);
    assert_int_equal(fx->sc->object_count, 2);
    assert_float_equal(fx->sc->objects[1].angle, 90.0, 1e-6);
}

/* ---------------------------------------------------------------- overrides */

static void test_override_existing_and_absent(void **state)
{
    static const char *const sets[] = {
        "robots.0.count=7", "tracker.enabled=true", "robots.0.params.speed_steps_s=300",
        "name='with space'", "duration=30", "robots.1.controller=idle", NULL,
    };
    fixture_t *fx = *state;
    assert_int_equal(load_sets(fx, "s.yaml", RW "    count: 5\nduration: 10\n", sets), 0);
    assert_int_equal(fx->sc->groups[0].count, 7);
    assert_int_equal(fx->sc->group_count, 2);                /* appended */
    assert_string_equal(fx->sc->groups[1].controller, "idle");
    assert_int_equal(fx->sc->groups[1].count, 1);            /* entry default */
    assert_int_equal(tracker_config(fx->sc)->enabled, 1);
    assert_int_equal(rw_params(fx->sc)->speed_steps_s, 300);
    assert_int_equal(rw_params(fx->sc)->turn_speed_steps_s, 300);  /* default kept */
    assert_string_equal(fx->sc->name, "with space");
    assert_float_equal(fx->sc->duration, 30.0, 1e-9);
}

static void test_override_later_wins_and_fixes_file(void **state)
{
    static const char *const sets[] = { "robots.0.count=abc", "robots.0.count=9", NULL };
    fixture_t *fx = *state;
    /* The file's bad value is replaced before the check. */
    assert_int_equal(load_sets(fx, "s.yaml", RW "    count: nope\n", sets), 0);
    assert_int_equal(fx->sc->groups[0].count, 9);
}

static void test_override_sequences(void **state)
{
    static const char *const sets[] = {
        "objects.1.x=1.5", "objects[0].radius=0.3", "objects.2.radius=0.1",
        "objects[2].colour=green", "lights.0.y=-1", NULL,
    };
    static const char *const clear[] = { "objects=[]", NULL };
    static const char yaml[] = "objects:\n  - radius: 0.1\n  - {x: 0, radius: 0.2}\n";
    fixture_t *fx = *state;
    assert_int_equal(load_sets(fx, "s.yaml", yaml, sets), 0);
    assert_int_equal(fx->sc->object_count, 3);
    assert_float_equal(fx->sc->objects[0].radius, 0.3, 1e-6);
    assert_float_equal(fx->sc->objects[1].x, 1.5, 1e-6);
    assert_float_equal(fx->sc->objects[1].radius, 0.2, 1e-6);
    assert_float_equal(fx->sc->objects[2].radius, 0.1, 1e-6);  /* appended */
    assert_int_equal(fx->sc->objects[2].colour, 2);
    assert_int_equal(fx->sc->light_count, 1);                 /* created */
    assert_float_equal(fx->sc->lights[0].y, -1.0, 1e-6);
    assert_int_equal(load_sets(fx, "s.yaml", yaml, clear), 0);
    assert_int_equal(fx->sc->object_count, 0);
}

static void test_override_errors(void **state)
{
    fixture_t *fx = *state;
    static const char two[] = "objects:\n  - radius: 0.1\n  - radius: 0.1\n";
    char want[1024];
    const char *sets[] = { "robots.0.count=abc", NULL };
    assert_int_equal(load_sets(fx, "s.yaml", RW "    count: 5\n", sets), -1);
    assert_string_equal(fx->err, "--set robots.0.count=abc: robots[0].count: expected an integer, "
                                 "got 'abc'");
    expect_set_error(fx, "", "robots.0.count", "expected key.path=value");
    expect_set_error(fx, RW, "robots.0.cuont=5",
                     "robots[0].cuont: unknown key 'cuont' (did you mean 'count'?)");
    expect_set_error(fx, "", "foo.bar=1", "foo: unknown key 'foo'");
    expect_set_error(fx, RW, "robots.0.count=200000",
                     "robots[0].count: 200000 is out of range [0, 100000]");
    expect_set_error(fx, two, "objects.5.x=1",
                     "objects[5]: index out of range (the sequence has 2 entries)");
    expect_set_error(fx, two, "objects.x=1", "objects: expected an index into the sequence");
    expect_set_error(fx, two, "objects.2.x=1", "objects[2].radius: a cylinder needs radius > 0");
    expect_set_error(fx, "arena:\n  width: 5\n", "arena.width.x=1",
                     "arena.width: expected a mapping, got '5'");
    expect_set_error(fx, "arena:\n  width: 5\n", "arena[0]=1",
                     "arena: expected a sequence, got a mapping");
    expect_set_error(fx, "arena:\n  width: 5\n", "arena.0=1", "arena.0: unknown key '0'");
    expect_set_error(fx, "", "arena.0=1", "arena: expected a mapping, got a sequence");
    expect_set_error(fx, "", "a..b=1", "malformed key path 'a..b'");
    expect_set_error(fx, "", "=5", "malformed key path ''");
    expect_set_error(fx, "", "robots.=5", "malformed key path");
    expect_set_error(fx, "", "objects[x].radius=1", "malformed key path");
    expect_set_error(fx, "", "name=[", "value: YAML syntax error");
    expect_set_error(fx, "", "name=", "name: expected a string, got nothing");
    expect_set_error(fx, RW, "robots.0.controller=foo",
                     "robots[0].controller: unknown controller 'foo' (valid: calib, random_walk");
    /* A file error keeps its file line even with valid overrides. */
    sets[0] = "seed=2";
    assert_int_equal(load_sets(fx, "s.yaml", "seed: 1\n" RW "    count: x\n", sets), -1);
    snprintf(want, sizeof want, "%s:4: robots[0].count: expected an integer, got 'x'", fx->path);
    assert_string_equal(fx->err, want);
}

/* ---------------------------------------------------------------- groups */

static void test_group_params(void **state)
{
    fixture_t *fx = *state;
    static const char *const sets[] = { "robots.0.params.turn_chance=70000", NULL };
    /* params before controller: still the named controller's keys and defaults. */
    assert_int_equal(load(fx, "robots:\n  - params:\n      speed_steps_s: 200\n"
                              "    controller: random_walk\n"),
                     0);
    assert_int_equal(rw_params(fx->sc)->speed_steps_s, 200);
    assert_int_equal(rw_params(fx->sc)->turn_speed_steps_s, 300);
    assert_int_equal(rw_params(fx->sc)->turn_chance, 1311);
    expect_load_error(fx, "robots:\n  - controller: nosuch\n", 2,
                      "robots[0].controller: unknown controller 'nosuch' (valid: calib, random_walk");
    expect_load_error(fx, "robots:\n  - controller: forgaer\n", 2,
                      "robots[0].controller: unknown controller 'forgaer' (did you mean 'forager'?)");
    expect_load_error(fx, "robots:\n  - count: 3\n", 2,
                      "robots[0].controller: every group needs a controller (one of calib, random_walk");
    expect_load_error(fx, RW "    params:\n      turn_speed_steps_s: 0\n", 4,
                      "robots[0].params.turn_speed_steps_s: 0 is out of range [1, 1000]");
    expect_load_error(fx, RW "    contoller: idle\n", 3,
                      "robots[0].contoller: unknown key 'contoller' (did you mean 'controller'?)");
    assert_int_equal(load_sets(fx, "s.yaml", RW, sets), -1);
    assert_string_equal(fx->err, "--set robots.0.params.turn_chance=70000: "
                                 "robots[0].params.turn_chance: 70000 is out of range "
                                 "[0, 65535]");
}

static void test_group_policy(void **state)
{
    fixture_t *fx = *state;
    assert_int_equal(load(fx, "ircom: {payload_bits: 16}\nforaging: {information: global}\n"
                              "robots:\n  - controller: forager\n"), 0);
    assert_string_equal(fx->sc->groups[0].policy, "drtm");     /* the first */
    assert_int_equal(fx->sc->groups[0].policy_index, 0);
    expect_load_error(fx, "ircom: {payload_bits: 16}\nrobots:\n  - controller: forager\n"
                          "    policy: xtrm\nforaging: {information: global}\n", 4,
                      "robots[0].policy: unknown policy 'xtrm' for controller 'forager' "
                      "(valid: drtm, artm, frtm)");
    expect_load_error(fx, RW "    policy: drtm\n", 3,
                      "robots[0].policy: controller 'random_walk' has no policies");
}

/* Group names: the controller's by default, numbered when taken; a given
 * name must be unique. */
static void test_group_names(void **state)
{
    fixture_t *fx = *state;
    assert_int_equal(load(fx, RW "  - controller: random_walk\n  - {controller: idle, name: x}\n"), 0);
    assert_string_equal(fx->sc->groups[0].name, "random_walk");
    assert_string_equal(fx->sc->groups[1].name, "random_walk_1");
    assert_string_equal(fx->sc->groups[2].name, "x");
    expect_load_error(fx, "robots:\n  - {controller: idle, name: a}\n  - {controller: idle, name: a}\n",
                      3, "robots[1].name: 'a' already names robots[0]");
}

/* The effective scenario (what a run keeps beside its outputs) loads to
 * the same scenario even when a plain value cannot be written plain: a
 * name over lines with a blank one between holds a line break, and
 * libyaml then quotes it, which needs a tag ("!") to stay plain, and the
 * loader refuses tags (found by tests/fuzz/scenario.c). */
static void test_effective_scenario_of_a_multiline_value(void **state)
{
    fixture_t *fx = *state;
    char err[SIM_ERR_MAX], out[600];
    scenario_t *again = malloc(sizeof *again);
    assert_non_null(again);
    snprintf(fx->path, sizeof fx->path, "%s/multiline.yaml", tmpdir);
    write_file(fx->path, "name: my long\n\n  scenario\n" RW);
    assert_int_equal(scenario_load(fx->path, NULL, 0, fx->sc, err), 0);
    assert_string_equal(fx->sc->name, "my long\nscenario");
    snprintf(out, sizeof out, "%s/effective.yaml", tmpdir);
    FILE *f = fopen(out, "wb");
    assert_non_null(f);
    assert_int_equal(scenario_write_effective(fx->path, NULL, 0, f, err), 0);
    assert_int_equal(fclose(f), 0);
    if (scenario_load(out, NULL, 0, again, err) != 0) fail_msg("%s", err);
    assert_string_equal(again->name, fx->sc->name);
    assert_int_equal(unlink(out), 0);
    assert_int_equal(unlink(fx->path), 0);
    scenario_free(again);
    free(again);
}

static void test_placements(void **state)
{
    static const bad_case_t cases[] = {
        { RW "    placement: {shape: circle}\n", 3,
          "robots[0].placement.radius: a circle placement needs radius > 0" },
        { RW "    placement: {shape: ring, inner: 1, outer: 0.5}\n", 3,
          "robots[0].placement.outer: a ring placement needs outer > inner (0.5 <= 1)" },
        { RW "    count: 3\n    placement:\n      shape: poses\n      poses: [{x: 0, y: 0}]\n", 6,
          "robots[0].placement.poses: 1 poses for a group of 3 robots (give one per robot)" },
        { RW "    placement:\n      poses: [{x: 0, y: 0, heading: left}]\n", 4,
          "robots[0].placement.poses[0].heading: expected an angle in degrees or 'random'" },
        { RW "    placement:\n      shape: poses\n      order: space\n      poses: [{x: 0, y: 0}]\n", 5,
          "robots[0].placement.order: order: space renumbers the spots drawn, and a poses group gives "
          "each robot its own pose" },
        { RW "    placement: {order: morton}\n", 3,
          "robots[0].placement.order: expected one of drawn|space, got 'morton'" },
    };
    fixture_t *fx = *state;
    expect_cases(fx, cases, sizeof cases / sizeof cases[0]);
    /* A group of 0 robots needs no poses. */
    assert_int_equal(load(fx, RW "    count: 0\n    placement: {shape: poses}\n"), 0);
    assert_int_equal(load(fx, RW "    placement: {shape: ring, inner: 0.2, outer: 0.6, order: space}\n"), 0);
    assert_int_equal(fx->sc->groups[0].placement.order, PLACE_ORDER_SPACE);
}

/* A controller that sends 16-bit messages on an 8-bit platform, or one
 * without the task that is its world, is a load error, not a run where the
 * foragers never leave the nest. */
static void test_controller_needs(void **state)
{
    fixture_t *fx = *state;
    expect_load_error(fx, "robots:\n  - controller: random_walk\n  - controller: forager\n"
                          "foraging: {information: global}\n", 3,
                      "robots[1].controller: controller 'forager' sends 16-bit IR messages but "
                      "ircom.payload_bits is 8 (set ircom.payload_bits: 16");
    expect_load_error(fx, "ircom: {payload_bits: 16}\nrobots:\n  - controller: random_walk\n"
                          "  - controller: nest_beacon\n", 4,
                      "robots[1].controller: controller 'nest_beacon' needs the foraging task, its "
                      "world");
    assert_int_equal(load(fx, "robots:\n  - controller: forager\n    count: 0\n"), 0);
}

/* A task runs when its section is there; its own checks name its keys. */
static void test_task_sections(void **state)
{
    static const bad_case_t cases[] = {
        { "ircom: {payload_bits: 16}\nrobots:\n  - controller: forager\nforaging:\n  food_count: 3\n",
          5, "foraging.information: 'beacon' needs one robot running nest_beacon at the nest "
          "(the scenario has 0)" },
        { "ircom: {payload_bits: 16}\nrobots:\n  - {controller: nest_beacon}\n"
          "foraging:\n  information: global\n", 5,
          "foraging.information: 'global' replaces the nest beacon by the simulator" },
    };
    fixture_t *fx = *state;
    expect_cases(fx, cases, sizeof cases / sizeof cases[0]);
    assert_int_equal(load(fx, "seed: 2\n"), 0);
    assert_int_equal(fx->sc->task_count, 0);
    assert_null(scenario_task_config(fx->sc, &foraging_task));
    assert_int_equal(load(fx, "robots: []\nforaging: {information: global}\n"), 0);
    assert_int_equal(fx->sc->task_count, 1);
    assert_int_equal(fx->sc->group_count, 0);
    assert_non_null(scenario_task_config(fx->sc, &foraging_task));
}

/* ---------------------------------------------------------------- --help */

/* Array keys (param.h's PARAM_ARRAY_FIELD): a sequence of exactly the
 * field's count, each element typed and ranged with its index in errors;
 * --set replaces the whole array, or one element where the file gives it;
 * --help shows type[count]. */
#define NN "robots:\n  - controller: nnea\n    params:\n"
static void test_array_params(void **state)
{
    fixture_t *fx = *state;
    static const char *const whole[] = { "robots.0.params.b_out=[7, -8, 9]", NULL };
    static const char *const one[] = { "robots.0.params.b_out.1=-300", NULL };
    static const char *const bad_one[] = { "robots.0.params.b_out.2=3000", NULL };
    static const char *const absent_one[] = { "robots.0.params.tau.1=5", NULL };
    const nnea_params_t *p;
    assert_int_equal(load(fx, NN "      b_out: [1, 2, 3]\n      tau: [0, 10, 200, 255]\n"), 0);
    p = (const nnea_params_t *)fx->sc->groups[0].params.bytes;
    assert_int_equal(p->b_out[0], 1);
    assert_int_equal(p->b_out[2], 3);
    assert_int_equal(p->tau[3], 255);
    assert_int_equal(p->speed_steps_s, 388);          /* other keys keep their defaults */
    assert_int_equal(load(fx, NN "      b_out:\n        - -2047\n        - 0\n        - 2047\n"), 0);
    p = (const nnea_params_t *)fx->sc->groups[0].params.bytes;
    assert_int_equal(p->b_out[0], -2047);
    expect_load_error(fx, NN "      b_out: [1, 2]\n", 4, "robots[0].params.b_out: expected exactly 3 numbers, got 2");
    expect_load_error(fx, NN "      b_out: [1, 2, 3, 4]\n", 4,
                      "robots[0].params.b_out: expected exactly 3 numbers, got 4");
    expect_load_error(fx, NN "      b_out: 5\n", 4,
                      "robots[0].params.b_out: expected a sequence of 3 numbers (e.g. [0, 1, ...]), got '5'");
    expect_load_error(fx, NN "      b_out:\n        - 1\n        - 3000\n        - 3\n", 6,
                      "robots[0].params.b_out[1]: 3000 is out of range [-2047, 2047]");
    expect_load_error(fx, NN "      tau: [1, 2.5, 3, 4]\n", 4, "robots[0].params.tau[1]: expected an integer, got '2.5'");
    expect_load_error(fx, NN "      tau: [1, -1, 3, 4]\n", 4, "robots[0].params.tau[1]: -1 is out of range [0, 255]");
    expect_load_error(fx, NN "      tau: [1, [2], 3, 4]\n", 4, "robots[0].params.tau[1]: expected a number, got a sequence");
    /* --set: the whole array, one element of the file's, errors with the index. */
    assert_int_equal(load_sets(fx, "s.yaml", NN "      b_out: [1, 2, 3]\n", whole), 0);
    p = (const nnea_params_t *)fx->sc->groups[0].params.bytes;
    assert_int_equal(p->b_out[0], 7);
    assert_int_equal(p->b_out[1], -8);
    assert_int_equal(p->b_out[2], 9);
    assert_int_equal(load_sets(fx, "s.yaml", NN "      b_out: [1, 2, 3]\n", one), 0);
    p = (const nnea_params_t *)fx->sc->groups[0].params.bytes;
    assert_int_equal(p->b_out[0], 1);
    assert_int_equal(p->b_out[1], -300);
    assert_int_equal(load_sets(fx, "s.yaml", NN "      b_out: [1, 2, 3]\n", bad_one), -1);
    assert_string_equal(fx->err, "--set robots.0.params.b_out.2=3000: robots[0].params.b_out[2]: "
                                 "3000 is out of range [-2047, 2047]");
    assert_int_equal(load_sets(fx, "s.yaml", NN "      b_out: [1, 2, 3]\n", absent_one), -1);
    assert_non_null(strstr(fx->err, "index out of range (the sequence has 0 entries)"));
}

static void test_print_schema(void **state)
{
    static const char *const wanted[] = {
        "seed", "robots[].count", "[0, 100000]", "rectangle|circle|ring|grid|poses",
        "robots[].placement.poses[].heading", "objects[].radius", "lights[].intensity",
        "robots[].params.speed_steps_s", "when controller is forager", "ircom.quantise_bearing",
        "output.timeseries_every", "arena.width", "0.05", "foraging.nest.diameter",
        "foraging.information", "beacon|global", "tracker.dropout",
        "robots[].params.w_in", "int[56]", "[-2047, 2047]",
    };
    char *text = NULL;
    size_t len = 0, i;
    FILE *f = open_memstream(&text, &len);
    (void)state;
    assert_non_null(f);
    scenario_print_schema(f);
    assert_int_equal(fclose(f), 0);
    for (i = 0; i < sizeof wanted / sizeof wanted[0]; i++) {
        if (strstr(text, wanted[i]) == NULL) {
            print_error("schema lacks '%s'\n", wanted[i]);
            free(text);
            fail();
        }
    }
    free(text);
}

/* host.messages: hex decoded into bytes; a robot that does not exist, bad
 * hex and a robot's messages out of time order are errors at their line. */
static void test_host_messages(void **state)
{
    fixture_t *fx = *state;
    static const bad_case_t cases[] = {
        { RW "    count: 2\nhost:\n  messages:\n    - {robot: 2, at: 0, hex: '52'}\n", 6,
          "host.messages[0].robot: robot 2: the run has 2 robots (ids 0 to 1)" },
        { RW "    count: 2\nhost:\n  messages:\n    - {robot: 0, hex: '5'}\n", 6,
          "host.messages[0].hex: 1 hex digits: a message is 1 to 64 bytes, two digits each" },
        { RW "    count: 2\nhost:\n  messages:\n    - {robot: 0, hex: ''}\n", 6,
          "host.messages[0].hex: " },
        { RW "    count: 2\nhost:\n  messages:\n    - {robot: 0, hex: '5x'}\n", 6,
          "host.messages[0].hex: 'x' (digit 2) is not a hex digit" },
        { RW "    count: 2\nhost:\n  messages:\n    - {robot: 1, at: 2, hex: '01'}\n"
             "    - {robot: 0, at: 0, hex: '01'}\n    - {robot: 1, at: 1, hex: '02'}\n", 8,
          "host.messages[2].at: 1 s is before robot 1's message 0 (2 s): list a robot's messages in time order" },
    };
    expect_cases(fx, cases, sizeof cases / sizeof cases[0]);
    assert_int_equal(load_sets(fx, "s.yaml", RW "    count: 2\nhost:\n  messages:\n"
                               "    - {robot: 1, at: 0.5, hex: 'A1b2'}\n", NULL), 0);
    assert_int_equal(host_config(fx->sc)->message_count, 1);
    assert_int_equal(host_config(fx->sc)->messages[0].robot, 1);
    assert_int_equal(host_config(fx->sc)->messages[0].len, 2);
    assert_int_equal(host_config(fx->sc)->messages[0].bytes[0], 0xA1);
    assert_int_equal(host_config(fx->sc)->messages[0].bytes[1], 0xB2);
}

#define T(f) cmocka_unit_test_setup_teardown(f, setup, teardown)

int main(void)
{
    const struct CMUnitTest tests[] = {
        T(test_defaults),
        T(test_empty_file_alone_is_an_error),
        T(test_empty_documents_give_defaults),
        T(test_name_from_path),
        T(test_full_file),
        T(test_exact_message_format),
        T(test_syntax_errors),
        T(test_unknown_keys),
        T(test_wrong_types),
        T(test_out_of_range),
        T(test_number_forms),
        T(test_bad_enum),
        T(test_duplicate_keys),
        T(test_missing_file),
        T(test_invalid_utf8),
        T(test_too_many_entries),
        T(test_hostile_inputs),
        T(test_object_shapes),
        T(test_objects_inside_arena),
        T(test_override_existing_and_absent),
        T(test_override_later_wins_and_fixes_file),
        T(test_override_sequences),
        T(test_override_errors),
        T(test_group_params),
        T(test_group_policy),
        T(test_group_names),
        T(test_effective_scenario_of_a_multiline_value),
        T(test_placements),
        T(test_controller_needs),
        T(test_task_sections),
        T(test_array_params),
        T(test_print_schema),
        T(test_host_messages),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
