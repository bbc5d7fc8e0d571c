/*
 * test_legend.c - one colour key for every view (sim_host/core/legend.h):
 * a run's legend is its tasks' tables (robot fills, the default body's key,
 * then the floor areas, outlines and items), a PNG frame draws each robot
 * in the colour of its key and every key's swatch in the band above the
 * arena.  (The scene telemetry's copy of the legend: test_telemetry_scene.)
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "sim_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/legend.h"
#include "core/render.h"
#include "core/sim_render.h"
#include "hal.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "swarmsim/task.h"
#include "tasks/foraging/foraging.h"
#include "units.h"

#define BASE "../sim_host/scenarios/foraging_base.yaml"
#define GATHER "../sim_host/scenarios/phototaxis_gather.yaml"
#define WALK "../sim_host/scenarios/random_walk.yaml"
#define W 800
#define H 800

static void done(sim_t *sim, scenario_t *sc)
{
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* The keys of a legend are these labels of these kinds, in this order. */
static void expect_keys(const draw_key_t *keys, uint32_t n, const char *const *labels, const uint8_t *kinds)
{
    uint32_t want = 0;
    while (labels[want]) want++;
    assert_int_equal(n, want);
    for (uint32_t k = 0; k < n; k++) {
        assert_string_equal(keys[k].label, labels[k]);
        assert_int_equal(keys[k].kind, kinds[k]);
    }
}

static const draw_key_t *key_named(const draw_key_t *keys, uint32_t n, const char *label)
{
    for (uint32_t k = 0; k < n; k++)
        if (!strcmp(keys[k].label, label)) return &keys[k];
    fail_msg("no legend key %s", label);
    return NULL;
}

/* Foraging: its robot states, then its nest (an area) and its food (the
 * items, drawn as the cameras' red); the waiting robots' default body. */
static void test_foraging_keys(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(BASE);
    sim_t *sim = fixture_sim(sc, 1);
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n = legend_collect(sim, keys);
    static const char *const labels[] = { "waiting", "searching", "returning", "beacon", "nest", "food", NULL };
    static const uint8_t kinds[] = { DRAW_KEY_ROBOT, DRAW_KEY_ROBOT, DRAW_KEY_ROBOT, DRAW_KEY_ROBOT,
                                     DRAW_KEY_AREA, DRAW_KEY_ITEM };
    expect_keys(keys, n, labels, kinds);
    assert_int_equal(render_key_rgb(&keys[0]), RENDER_RGB_ROBOT);
    assert_int_equal(render_key_rgb(&keys[1]), DRAW_RGB_HL_GREEN);
    assert_int_equal(render_key_rgb(&keys[5]), RENDER_RGB_OBJ_RED);
    /* The food key is the colour the task gives its items. */
    const sim_item_t *items;
    uint32_t count = foraging_task.items(sim_task(sim, &foraging_task), &items);
    assert_true(count > 0);
    assert_int_equal(items[0].colour, keys[5].colour);
    done(sim, sc);
}

/* The walkthrough's task: its two robot keys and its goal (an outline). */
static void test_gather_keys(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(GATHER);
    sim_t *sim = fixture_sim(sc, 1);
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n = legend_collect(sim, keys);
    static const char *const labels[] = { "outside", "in goal", "goal", NULL };
    static const uint8_t kinds[] = { DRAW_KEY_ROBOT, DRAW_KEY_ROBOT, DRAW_KEY_RING };
    expect_keys(keys, n, labels, kinds);
    done(sim, sc);
}

/* No task: one key, the default body's. */
static void test_no_task_key(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(WALK);
    sim_t *sim = fixture_sim(sc, 1);
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n = legend_collect(sim, keys);
    static const char *const labels[] = { "robot", NULL };
    static const uint8_t kinds[] = { DRAW_KEY_ROBOT };
    expect_keys(keys, n, labels, kinds);
    assert_int_equal(render_key_rgb(&keys[0]), RENDER_RGB_ROBOT);
    done(sim, sc);
}

static uint32_t px(const uint8_t *rgb, int col, int row)
{
    const uint8_t *p = rgb + ((size_t)row * W + (size_t)col) * 3;
    return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}

/* The share of the ring of a robot's body between 0.35 and 0.75 of its
 * radius r (px) from its centre (where no LED is) that has colour want. */
static double body_share(const uint8_t *rgb, float cx, float cy, float r, uint32_t want)
{
    int n = 0, hit = 0;
    for (int y = (int)floorf(cy - r); y <= (int)ceilf(cy + r); y++) {
        for (int x = (int)floorf(cx - r); x <= (int)ceilf(cx + r); x++) {
            float d = hypotf((float)x + 0.5f - cx, (float)y + 0.5f - cy);
            if (d < 0.35f * r || d > 0.75f * r || x < 0 || y < 0 || x >= W || y >= H) continue;
            n++;
            hit += px(rgb, x, y) == want;
        }
    }
    return n ? (double)hit / n : 0.0;
}

/* Pixels of colour want in the rows above `rows`. */
static int band_count(const uint8_t *rgb, int rows, uint32_t want)
{
    int n = 0;
    for (int y = 0; y < rows; y++)
        for (int x = 0; x < W; x++) n += px(rgb, x, y) == want;
    return n;
}

/* A frame of seed 000's base run at 30 s: every robot's body in the colour
 * of its key (the searching ones the legend's "searching", the waiting ones
 * the default body), and the band shows every key's swatch: the robot
 * states', the nest's grey and the food's red. */
static void test_frame_draws_the_legend(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(BASE);
    sim_t *sim = fixture_sim(sc, 2);
    for (int k = 0; k < 300; k++) sim_step(sim);
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n_keys = legend_collect(sim, keys);
    uint32_t n = sim_robot_count(sim);
    draw_shape_t *shapes = calloc(4096, sizeof *shapes);
    uint32_t *fill = calloc(n, sizeof *fill);
    uint8_t *rgb = malloc((size_t)W * H * 3);
    assert_true(shapes && fill && rgb);
    drawing_t d = { shapes, 0, 4096, fill, n };
    foraging_task.draw(sim_task(sim, &foraging_task), sim, &d);

    char err[SIM_ERR_MAX] = "";
    render_ctx_t *ctx = render_create(W, H, err);
    if (!ctx) fail_msg("%s", err);
    if (sim_render_rgb(sim, ctx, rgb, err) != 0) fail_msg("%s", err);
    float c0, r0, c1, r1;
    assert_int_equal(sim_render_world_to_pixel(sim, ctx, 0.0f, 0.0f, &c0, &r0), 0);
    assert_int_equal(sim_render_world_to_pixel(sim, ctx, EPUCK_BODY_RADIUS_M, 0.0f, &c1, &r1), 0);
    float radius = c1 - c0;
    assert_true(radius > 4.0f);
    uint32_t searching = key_named(keys, n_keys, "searching")->rgb;
    uint32_t waiting = render_key_rgb(key_named(keys, n_keys, "waiting"));
    uint32_t seen_searching = 0, seen_waiting = 0, matched = 0;
    for (uint32_t i = 0; i < n; i++) {
        double x, y, th;
        sim_robot_pose(sim, i, &x, &y, &th);
        float col, row;
        assert_int_equal(sim_render_world_to_pixel(sim, ctx, (float)x, (float)y, &col, &row), 0);
        uint32_t want = fill[i] ? fill[i] : RENDER_RGB_ROBOT;
        /* A robot's colour is one of the legend's robot keys. */
        int keyed = 0;
        for (uint32_t k = 0; k < n_keys; k++) keyed |= keys[k].kind == DRAW_KEY_ROBOT && render_key_rgb(&keys[k]) == want;
        assert_true(keyed);
        double share = body_share(rgb, col, row, radius, want);
        matched += share > 0.5;
        if (share > 0.5) {
            seen_searching += want == searching;
            seen_waiting += want == waiting;
        }
    }
    /* Some bodies are partly under a neighbour's id or the nest's label. */
    assert_true(matched >= n - n / 10);
    assert_true(seen_searching > 0);
    assert_true(seen_waiting > 0);

    /* The band: everything above the arena's top wall. */
    float top_col, top_row;
    assert_int_equal(sim_render_world_to_pixel(sim, ctx, 0.0f, sc->arena.height / 2.0f + sc->arena.wall_thickness,
                                               &top_col, &top_row), 0);
    for (uint32_t k = 0; k < n_keys; k++) {
        int got = band_count(rgb, (int)top_row - 1, render_key_rgb(&keys[k]));
        if (got < 6) fail_msg("key %s: %d pixels of %06X in the band", keys[k].label, got, render_key_rgb(&keys[k]));
    }
    render_destroy(ctx);
    free(shapes);
    free(fill);
    free(rgb);
    done(sim, sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_foraging_keys),
        cmocka_unit_test(test_gather_keys),
        cmocka_unit_test(test_no_task_key),
        cmocka_unit_test(test_frame_draws_the_legend),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
