/*
 * test_telemetry_scene.c - the picture of a run as telemetry
 * (sim_host/core/telemetry_scene.c): SCENE carries the scenario's arena,
 * obstacles and lamps; TASK_DRAWING carries exactly what the tasks draw for
 * the PNG frames (shapes, items, robot fills), at the start, with every
 * RUN_INFO, and at the swarm-state rate whenever it changed (no change
 * missed, none sent twice); a run without tasks sends an empty drawing only
 * with RUN_INFO.  SCENE also carries the run's legend, the PNG frames'.
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

#include <lcm/lcm.h>

#include "core/legend.h"
#include "core/render.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "core/telemetry.h"
#include "core/telemetry_scene.h"
#include "swarmlcm_scene_t.h"
#include "swarmlcm_task_drawing_t.h"
#include "tasks/foraging/foraging.h"
#include "tasks/gather/gather.h"
#include "units.h"

#define GATHER "../sim_host/scenarios/phototaxis_gather.yaml"
#define BASE "../sim_host/scenarios/foraging_base.yaml"
#define WALK "../sim_host/scenarios/random_walk.yaml"
#define SHAPES 64
#define ROBOTS 64

/* What a memq subscriber saw.  The last messages are kept decoded from
 * their bytes (lcm-gen's _copy memcpy()s from NULL for empty arrays, which
 * UBSan reports). */
typedef struct seen {
    uint32_t scenes, drawings;
    swarmlcm_scene_t *scene;              /* the last, kept */
    swarmlcm_task_drawing_t *drawing;     /* the last */
    int64_t drawing_utime;
    uint32_t repeated;                    /* drawings equal to the one before, sent outside a RUN_INFO step */
} seen_t;

static int same_drawing(const swarmlcm_task_drawing_t *a, const swarmlcm_task_drawing_t *b)
{
    if (a->n_shapes != b->n_shapes || a->n_items != b->n_items || a->n_fills != b->n_fills) return 0;
    for (int k = 0; k < a->n_shapes; k++) {
        const swarmlcm_scene_shape_t *p = &a->shapes[k], *q = &b->shapes[k];
        if (p->kind != q->kind || p->layer != q->layer || p->rgb != q->rgb || p->x != q->x || p->y != q->y
            || p->radius != q->radius || p->line != q->line || strcmp(p->text, q->text) != 0) return 0;
    }
    for (int k = 0; k < a->n_items; k++) {
        if (a->items[k].x != b->items[k].x || a->items[k].y != b->items[k].y || a->items[k].rgb != b->items[k].rgb)
            return 0;
    }
    for (int k = 0; k < a->n_fills; k++) {
        if (a->fill_robot[k] != b->fill_robot[k] || a->fill_rgb[k] != b->fill_rgb[k]) return 0;
    }
    return 1;
}

static void free_scene(swarmlcm_scene_t *m)
{
    if (m) swarmlcm_scene_t_decode_cleanup(m);
    free(m);
}

static void free_drawing(swarmlcm_task_drawing_t *m)
{
    if (m) swarmlcm_task_drawing_t_decode_cleanup(m);
    free(m);
}

static void on_scene(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_scene_t *m, void *u)
{
    (void)ch;
    (void)m;
    seen_t *s = u;
    swarmlcm_scene_t *keep = calloc(1, sizeof *keep);
    assert_non_null(keep);
    assert_true(swarmlcm_scene_t_decode(rb->data, 0, (int)rb->data_size, keep) > 0);
    s->scenes++;
    free_scene(s->scene);
    s->scene = keep;
}

static void on_drawing(const lcm_recv_buf_t *rb, const char *ch, const swarmlcm_task_drawing_t *m, void *u)
{
    (void)ch;
    seen_t *s = u;
    swarmlcm_task_drawing_t *keep = calloc(1, sizeof *keep);
    assert_non_null(keep);
    assert_true(swarmlcm_task_drawing_t_decode(rb->data, 0, (int)rb->data_size, keep) > 0);
    s->drawings++;
    if (s->drawing) s->repeated += m->utime % 10000000 != 0 && same_drawing(s->drawing, m);
    free_drawing(s->drawing);
    s->drawing = keep;
    s->drawing_utime = m->utime;
}

/* The drawing the PNG frames would get now, from the task's own hook. */
static void task_draws(const sim_t *sim, const task_def_t *def, drawing_t *d)
{
    d->count = 0;
    memset(d->robot_rgb, 0, d->robot_count * sizeof *d->robot_rgb);
    def->draw(sim_task(sim, def), sim, d);
}

/* Robot fills of a drawing_t as (robot, rgb) pairs; returns how many. */
static int fills_of(const drawing_t *d, int32_t robot[ROBOTS], int32_t rgb[ROBOTS])
{
    int n = 0;
    for (uint32_t i = 0; i < d->robot_count; i++) {
        if (d->robot_rgb[i]) {
            robot[n] = (int32_t)i;
            rgb[n++] = (int32_t)d->robot_rgb[i];
        }
    }
    return n;
}

typedef struct bus {
    telemetry_t *t;
    lcm_t *lcm;
    seen_t seen;
    swarmlcm_scene_t_subscription_t *sub_scene;
    swarmlcm_task_drawing_t_subscription_t *sub_drawing;
} bus_t;

static void open_bus(bus_t *b, const sim_t *sim)
{
    telemetry_options_t opt;
    char err[SIM_ERR_MAX];
    memset(b, 0, sizeof *b);
    telemetry_default_options(&opt);
    opt.url = "memq://";
    if (telemetry_open(&opt, sim, NULL, &b->t, err) != 0) fail_msg("%s", err);
    b->lcm = telemetry_lcm(b->t);
    b->sub_scene = swarmlcm_scene_t_subscribe(b->lcm, TELEMETRY_CHANNEL_SCENE, on_scene, &b->seen);
    b->sub_drawing = swarmlcm_task_drawing_t_subscribe(b->lcm, TELEMETRY_CHANNEL_TASK_DRAWING, on_drawing, &b->seen);
}

static void drain(bus_t *b)
{
    while (lcm_handle_timeout(b->lcm, 0) > 0) {
    }
}

static void close_bus(bus_t *b)
{
    char err[SIM_ERR_MAX];
    swarmlcm_scene_t_unsubscribe(b->lcm, b->sub_scene);
    swarmlcm_task_drawing_t_unsubscribe(b->lcm, b->sub_drawing);
    assert_int_equal(telemetry_close(b->t, 1, err), 0);
    free_scene(b->seen.scene);
    free_drawing(b->seen.drawing);
}

/* SCENE's legend is the PNG frames' (legend.h), in the colours they draw
 * its keys in; returns how many keys. */
static int32_t check_legend(const swarmlcm_scene_t *s, const sim_t *sim)
{
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n = legend_collect(sim, keys);
    assert_int_equal(s->n_keys, n);
    for (uint32_t k = 0; k < n; k++) {
        assert_int_equal(s->key_kind[k], keys[k].kind);
        assert_int_equal((uint32_t)s->key_rgb[k], render_key_rgb(&keys[k]));
        assert_string_equal(s->key_label[k], keys[k].label);
    }
    assert_int_equal(s->robot_rgb, RENDER_RGB_ROBOT);
    return s->n_keys;
}

/* The walkthrough's scenario: its arena, obstacle and lamp in SCENE; in
 * TASK_DRAWING after every step, what the gather task draws (the goal ring,
 * its label, the robots inside), sent at each step where it changed. */
static void test_gather_scene_and_drawing(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(GATHER);
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 1, err);
    if (!sim) fail_msg("%s", err);
    bus_t b;
    open_bus(&b, sim);
    draw_shape_t shapes[SHAPES];
    uint32_t rgb[ROBOTS];
    drawing_t d = { shapes, 0, SHAPES, rgb, sim_robot_count(sim) };
    int32_t fill_robot[ROBOTS], fill_rgb[ROBOTS], prev_robot[ROBOTS];
    char prev_label[DRAW_TEXT_MAX + 1] = "";
    int prev_fills = -1;
    uint32_t changes = 0, expected = 1;
    const uint64_t steps = 600;

    telemetry_begin(b.t, sim, steps);
    drain(&b);
    assert_int_equal(b.seen.scenes, 1);
    assert_int_equal(b.seen.drawings, 1);
    for (uint64_t k = 0; k <= steps; k++) {
        if (k > 0) {
            sim_step(sim);
            telemetry_step(b.t, sim);
            drain(&b);
        }
        /* The task's own drawing now equals the last TASK_DRAWING. */
        task_draws(sim, &gather_task, &d);
        const swarmlcm_task_drawing_t *m = b.seen.drawing;
        assert_int_equal(m->n_shapes, 2);
        assert_int_equal(m->n_items, 0);
        assert_int_equal(m->shapes[0].kind, DRAW_RING);
        assert_int_equal(m->shapes[0].layer, DRAW_FLOOR);
        assert_int_equal((uint32_t)m->shapes[0].rgb, shapes[0].rgb);
        assert_true(m->shapes[0].x == 0.5f && m->shapes[0].y == 0.5f && m->shapes[0].radius == 0.45f);
        assert_true(m->shapes[0].line == shapes[0].line);
        assert_int_equal(m->shapes[1].kind, DRAW_LABEL);
        assert_int_equal(m->shapes[1].layer, DRAW_OVER);
        assert_true(m->shapes[1].x == shapes[1].x && m->shapes[1].y == shapes[1].y);
        assert_string_equal(m->shapes[1].text, shapes[1].text);
        int n = fills_of(&d, fill_robot, fill_rgb);
        assert_int_equal(m->n_fills, n);
        for (int f = 0; f < n; f++) {
            assert_int_equal(m->fill_robot[f], fill_robot[f]);
            assert_int_equal(m->fill_rgb[f], fill_rgb[f]);
        }
        /* Sent at this very step when it changed (the swarm-state rate is
         * every step here), and with every RUN_INFO (each 10 s). */
        int changed = n != prev_fills || memcmp(prev_robot, fill_robot, (size_t)n * sizeof *fill_robot) != 0
                      || strcmp(prev_label, shapes[1].text) != 0;
        if (k > 0 && (changed || k % 100 == 0)) {
            assert_int_equal(b.seen.drawing_utime, (int64_t)k * 100000);
            changes += (uint32_t)changed;
            expected++;
        }
        prev_fills = n;
        memcpy(prev_robot, fill_robot, (size_t)n * sizeof *fill_robot);
        snprintf(prev_label, sizeof prev_label, "%s", shapes[1].text);
    }
    assert_true(changes >= 3);   /* robots came into the goal */
    assert_int_equal(b.seen.repeated, 0);
    assert_int_equal(b.seen.drawings, expected);
    assert_int_equal(b.seen.scenes, 1 + steps / 100);

    const swarmlcm_scene_t *s = b.seen.scene;
    assert_int_equal(s->version, 2);
    assert_int_equal(s->run, 1);
    assert_true(s->arena_width == 3.0f && s->arena_height == 3.0f);
    assert_true(s->wall_thickness == sc->arena.wall_thickness && s->wall_thickness > 0.0f);
    assert_true(s->robot_radius == EPUCK_BODY_RADIUS_M);
    assert_int_equal(s->n_obstacles, 1);
    assert_int_equal(s->obstacles[0].shape, SHAPE_CYLINDER);
    assert_true(s->obstacles[0].x == -0.2f && s->obstacles[0].y == -0.1f && s->obstacles[0].radius == 0.1f);
    assert_int_equal(s->obstacles[0].rgb, RENDER_RGB_OBJ_NONE);
    assert_int_equal(s->n_lights, 1);
    assert_true(s->lights[0].x == 0.5f && s->lights[0].y == 0.5f && s->lights[0].height == 0.3f);
    assert_int_equal(check_legend(s, sim), 3);   /* outside, in goal, the goal */
    assert_string_equal(s->key_label[2], "goal");
    close_bus(&b);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* Foraging: the items the cameras see (in the world and coloured) as the
 * PNG frames draw them, each step. */
static void test_foraging_items(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(BASE);
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 2, err);
    if (!sim) fail_msg("%s", err);
    bus_t b;
    open_bus(&b, sim);
    telemetry_begin(b.t, sim, 300);
    drain(&b);
    for (uint64_t k = 0; k < 300; k++) {
        sim_step(sim);
        telemetry_step(b.t, sim);
        drain(&b);
        const sim_item_t *items;
        uint32_t n = foraging_task.items(sim_task(sim, &foraging_task), &items), shown = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (!isfinite(items[i].x) || items[i].colour == HAL_COLOUR_NONE) continue;
            assert_true(shown < (uint32_t)b.seen.drawing->n_items);
            const swarmlcm_scene_item_t *it = &b.seen.drawing->items[shown++];
            assert_true(it->x == items[i].x && it->y == items[i].y && it->radius == items[i].radius);
            assert_true(it->rgb == RENDER_RGB_OBJ_RED || it->rgb == RENDER_RGB_OBJ_GREEN || it->rgb == RENDER_RGB_OBJ_BLUE);
        }
        assert_int_equal(shown, b.seen.drawing->n_items);
        assert_true(shown > 0);
    }
    /* The legend has the nest and the food, the food in its items' colour. */
    const swarmlcm_scene_t *s = b.seen.scene;
    int32_t n_keys = check_legend(s, sim);
    assert_int_equal(n_keys, 6);
    assert_string_equal(s->key_label[4], "nest");
    assert_int_equal(s->key_kind[4], DRAW_KEY_AREA);
    assert_string_equal(s->key_label[5], "food");
    assert_int_equal(s->key_kind[5], DRAW_KEY_ITEM);
    assert_int_equal(s->key_rgb[5], b.seen.drawing->items[0].rgb);
    assert_int_equal(b.seen.repeated, 0);
    close_bus(&b);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* No task: an empty drawing, sent only at the start and with RUN_INFO. */
static void test_no_task_draws_nothing(void **state)
{
    (void)state;
    scenario_t *sc = fixture_load(WALK);
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create(sc, 1, err);
    if (!sim) fail_msg("%s", err);
    bus_t b;
    open_bus(&b, sim);
    telemetry_begin(b.t, sim, 300);
    for (uint64_t k = 0; k < 300; k++) {
        sim_step(sim);
        telemetry_step(b.t, sim);
    }
    drain(&b);
    assert_int_equal(b.seen.drawings, 1 + 300 / 100);
    assert_int_equal(b.seen.scenes, 1 + 300 / 100);
    assert_int_equal(b.seen.drawing->n_shapes + b.seen.drawing->n_items + b.seen.drawing->n_fills, 0);
    assert_int_equal(b.seen.drawing_utime, 300 * 100000);
    assert_int_equal(check_legend(b.seen.scene, sim), 1);   /* the default body: "robot" */
    close_bus(&b);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gather_scene_and_drawing),
        cmocka_unit_test(test_foraging_items),
        cmocka_unit_test(test_no_task_draws_nothing),
    };
    return cmocka_run_group_tests_name("telemetry_scene", tests, NULL, NULL);
}
