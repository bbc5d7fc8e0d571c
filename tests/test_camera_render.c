/*
 * test_camera_render.c - the rendered camera (camera.model: rendered: an
 * OSMesa frame through hal/blob_detect.c) against the geometric model, and
 * the camera's frame timing (camera.fps).  About 2 s (10 s under ASan).
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
#include "units.h"
#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
/* The camera's keys and model names, set in code (an internal header). */
#include "models/camera/camera.h"

#define PI 3.14159265358979
/* One column of the 40-column, 56 deg frame, mrad. */
#define COLUMN_MRAD (977.0 / 40.0)
/* A food token of seed 000 (foraging's token_radius and token_height). */
#define TOKEN_R 0.0175f
#define TOKEN_H 0.042f

/* Idle robots (the tests drive them), in a 3 m arena, blobs fresh every
 * step (fps 0) unless a test says otherwise. */
static scenario_t *camera_scenario(int model, uint32_t robots)
{
    scenario_t *sc = fixture_idle_scenario(robots, 3.0f);
    sc->groups[0].placement.shape = PLACE_RECTANGLE;   /* spots clear of the objects */
    camera_config_mut(sc)->model = model;
    camera_config_mut(sc)->fps = 0.0f;
    return sc;
}

static void add_cylinder(scenario_t *sc, float x, float y, float r, float h, int colour)
{
    assert_int_equal(scenario_add_object(sc, &(object_def_t){ .shape = SHAPE_CYLINDER, .x = x, .y = y,
                                                             .radius = r, .height = h, .colour = colour }), 0);
}

static uint8_t blobs_of(sim_t *sim, uint32_t i, hal_blob_t *b)
{
    sim_step(sim);   /* a fresh step: the camera is sampled once per step */
    return hal_camera_blobs(sim_robot_hal(sim, i), b, HAL_MAX_BLOBS);
}

/* The widest blob of `colour`, or NULL. */
static const hal_blob_t *widest(const hal_blob_t *b, uint8_t n, uint8_t colour)
{
    const hal_blob_t *w = NULL;
    for (uint8_t k = 0; k < n; k++) {
        if (b[k].colour == colour && (!w || b[k].width_mrad > w->width_mrad)) w = &b[k];
    }
    return w;
}

static uint8_t count_colour(const hal_blob_t *b, uint8_t n, uint8_t colour)
{
    uint8_t c = 0;
    for (uint8_t k = 0; k < n; k++) c += b[k].colour == colour;
    return c;
}

/* A token straight ahead, 0.3 m from the lens, gives a blob at bearing 0
 * of width 2 asin(r / d) = 117 mrad: exactly in the geometric model; in
 * whole columns (24.4 mrad) in the rendered one, so within 1.5 columns and
 * within half a column of bearing 0. */
static void test_token_ahead_both_models(void **state)
{
    (void)state;
    for (int model = CAMERA_GEOMETRIC; model <= CAMERA_RENDERED; model++) {
        scenario_t *sc = camera_scenario(model, 2);
        add_cylinder(sc, 0.3f + EPUCK_BODY_RADIUS_M, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
        sim_t *sim = fixture_sim(sc, 3);
        sim_set_robot_pose(sim, 1, -1.0, -1.0, 0.0);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        hal_blob_t b[HAL_MAX_BLOBS];
        uint8_t n = blobs_of(sim, 0, b);
        const hal_blob_t *t = widest(b, n, HAL_COLOUR_RED);
        assert_non_null(t);
        double expect = 2000.0 * asin(TOKEN_R / 0.3);
        print_message("%s: bearing %d mrad, width %u mrad (expected 0 and %.0f), %u px\n",
                      camera_kind_names[model], t->bearing_mrad, t->width_mrad, expect, t->pixels);
        double tol_w = model == CAMERA_GEOMETRIC ? 2.0 : 1.5 * COLUMN_MRAD;
        double tol_b = model == CAMERA_GEOMETRIC ? 2.0 : 0.5 * COLUMN_MRAD;
        assert_true(fabs(t->width_mrad - expect) <= tol_w);
        assert_true(fabs((double)t->bearing_mrad) <= tol_b);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* Two tokens 5 mm apart at 0.3 m (17 mrad, under a column): one blob on
 * the robot and in the rendered model, two in the geometric model. */
static void test_side_by_side_merge_when_rendered(void **state)
{
    (void)state;
    for (int model = CAMERA_GEOMETRIC; model <= CAMERA_RENDERED; model++) {
        scenario_t *sc = camera_scenario(model, 2);
        float x = 0.3f + EPUCK_BODY_RADIUS_M, gap = 0.005f;
        add_cylinder(sc, x, TOKEN_R + gap / 2, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
        add_cylinder(sc, x, -TOKEN_R - gap / 2, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
        sim_t *sim = fixture_sim(sc, 3);
        sim_set_robot_pose(sim, 1, -1.0, -1.0, 0.0);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        hal_blob_t b[HAL_MAX_BLOBS];
        uint8_t n = blobs_of(sim, 0, b);
        uint8_t red = count_colour(b, n, HAL_COLOUR_RED);
        print_message("%s: %u red blob(s), widest %u mrad\n", camera_kind_names[model], red,
                      widest(b, n, HAL_COLOUR_RED)->width_mrad);
        if (model == CAMERA_GEOMETRIC) {
            assert_int_equal(red, 2);
        } else {
            assert_int_equal(red, 1);
            assert_true(b[0].width_mrad > 2000.0 * asin(TOKEN_R / 0.3) + COLUMN_MRAD);
            assert_true(abs(b[0].bearing_mrad) <= COLUMN_MRAD / 2);
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* A token behind another robot is not seen; moved aside, it is. */
static void test_occluded_token_not_seen(void **state)
{
    (void)state;
    for (int model = CAMERA_GEOMETRIC; model <= CAMERA_RENDERED; model++) {
        scenario_t *sc = camera_scenario(model, 2);
        add_cylinder(sc, 0.5f, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
        sim_t *sim = fixture_sim(sc, 3);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        sim_set_robot_pose(sim, 1, 0.25, 0.0, 0.0);
        hal_blob_t b[HAL_MAX_BLOBS];
        uint8_t n = blobs_of(sim, 0, b);
        assert_int_equal(count_colour(b, n, HAL_COLOUR_RED), 0);
        sim_set_robot_pose(sim, 1, 0.25, 0.3, 0.0);
        n = blobs_of(sim, 0, b);
        assert_int_equal(count_colour(b, n, HAL_COLOUR_RED), 1);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* Over headings -24..24 deg and distances 0.15..0.55 m, wherever the
 * geometric model sees the whole token in view, the rendered model sees it
 * too, at the same bearing within one column (24 mrad): half a column of
 * quantisation, plus the pixel-weighted centre of a token whose columns
 * show it partly (20 mrad the largest seen on Mesa 22.3); a token cut by
 * the frame's edge is excluded. */
#define BEARING_TOL_MRAD 24
static void test_models_agree_on_bearing(void **state)
{
    (void)state;
    scenario_t *sg = camera_scenario(CAMERA_GEOMETRIC, 2), *sr = camera_scenario(CAMERA_RENDERED, 2);
    add_cylinder(sg, 0.0f, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
    add_cylinder(sr, 0.0f, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
    sim_t *g = fixture_sim(sg, 3), *r = fixture_sim(sr, 3);
    sim_set_robot_pose(g, 1, -1.0, -1.0, 0.0);
    sim_set_robot_pose(r, 1, -1.0, -1.0, 0.0);
    int compared = 0, worst = 0;
    for (int deg = -24; deg <= 24; deg += 3) {
        for (double d = 0.15; d < 0.56; d += 0.1) {
            /* Robot d from the token, turned `deg` away from facing it. */
            double x = -(d + EPUCK_BODY_RADIUS_M), th = deg * PI / 180.0;
            sim_set_robot_pose(g, 0, x, 0.0, th);
            sim_set_robot_pose(r, 0, x, 0.0, th);
            hal_blob_t bg[HAL_MAX_BLOBS], br[HAL_MAX_BLOBS];
            uint8_t ng = blobs_of(g, 0, bg), nr = blobs_of(r, 0, br);
            const hal_blob_t *tg = widest(bg, ng, HAL_COLOUR_RED), *tr = widest(br, nr, HAL_COLOUR_RED);
            if (!tg || abs(tg->bearing_mrad) + tg->width_mrad / 2 > 977 / 2 - COLUMN_MRAD) {
                continue;   /* not wholly in view */
            }
            assert_non_null(tr);
            int diff = abs(tg->bearing_mrad - tr->bearing_mrad);
            worst = diff > worst ? diff : worst;
            assert_true(diff <= BEARING_TOL_MRAD);
            compared++;
        }
    }
    print_message("%d poses compared, largest bearing difference %d mrad\n", compared, worst);
    assert_true(compared >= 40);
    sim_destroy(g);
    sim_destroy(r);
    scenario_free(sg);
    free(sg);
    scenario_free(sr);
    free(sr);
}

/* Frames at camera.fps with their age: nothing before the first frame
 * completes; afterwards a change in front of the lens reaches the blobs
 * one to two frame periods later (capture, then completion), and the
 * blobs stay as they were in between.  5 fps = 2 control steps a frame. */
static void test_frames_at_their_rate_and_age(void **state)
{
    (void)state;
    for (int model = CAMERA_GEOMETRIC; model <= CAMERA_RENDERED; model++) {
        scenario_t *sc = camera_scenario(model, 2);
        camera_config_mut(sc)->fps = 5.0f;
        add_cylinder(sc, 0.3f, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
        sim_t *sim = fixture_sim(sc, 3);
        sim_set_robot_pose(sim, 1, -1.0, -1.0, 0.0);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, 0.0);
        hal_blob_t b[HAL_MAX_BLOBS];
        int first = -1;
        for (int s = 0; s < 10 && first < 0; s++) {
            if (count_colour(b, blobs_of(sim, 0, b), HAL_COLOUR_RED) == 1) first = s;
        }
        /* The first frame completes 1 to 2 periods (2 to 4 steps) in. */
        assert_true(first >= 1 && first <= 4);
        sim_set_robot_pose(sim, 0, 0.0, 0.0, PI);   /* now facing away */
        int gone = -1;
        for (int s = 0; s < 10 && gone < 0; s++) {
            if (count_colour(b, blobs_of(sim, 0, b), HAL_COLOUR_RED) == 0) gone = s;
        }
        print_message("%s: first frame after %d step(s), the turn seen after %d\n",
                      camera_kind_names[model], first + 1, gone + 1);
        assert_true(gone >= 1 && gone <= 4);
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* The rendered model is deterministic: seed 000's base condition with it
 * (and pixel noise) twice, the same state and the same blobs. */
static void test_rendered_runs_are_deterministic(void **state)
{
    (void)state;
    scenario_t *sc = calloc(1, sizeof *sc);
    char err[SIM_ERR_MAX];
    scenario_override_t set[] = { { .text = "camera.model=rendered" }, { .text = "camera.noise=6" } };
    assert_int_equal(scenario_load("../sim_host/scenarios/foraging_base.yaml", set, 2, sc, err), 0);
    uint64_t hash[2];
    hal_blob_t blobs[2][21][HAL_MAX_BLOBS];
    uint8_t count[2][21];
    memset(blobs, 0, sizeof blobs);
    for (int run = 0; run < 2; run++) {
        sim_t *sim = fixture_sim(sc, 11);
        for (int s = 0; s < 400; s++) sim_step(sim);
        for (uint32_t i = 0; i < sim_robot_count(sim); i++) {
            count[run][i] = hal_camera_blobs(sim_robot_hal(sim, i), blobs[run][i], HAL_MAX_BLOBS);
        }
        hash[run] = sim_state_hash(sim);
        sim_destroy(sim);
    }
    assert_true(hash[0] == hash[1]);
    int seen = 0;
    for (uint32_t i = 0; i < 21; i++) {   /* field by field: hal_blob_t has padding */
        assert_int_equal(count[0][i], count[1][i]);
        for (uint8_t k = 0; k < count[0][i]; k++) {
            const hal_blob_t *x = &blobs[0][i][k], *y = &blobs[1][i][k];
            assert_int_equal(x->colour, y->colour);
            assert_int_equal(x->bearing_mrad, y->bearing_mrad);
            assert_int_equal(x->width_mrad, y->width_mrad);
            assert_int_equal(x->pixels, y->pixels);
        }
        seen += count[0][i];
    }
    assert_true(seen > 0);
    scenario_free(sc);
    free(sc);
}

/* Seed 000's lighting in sc: its nest lamp, and with `arena` its 4 x 4 m
 * arena too. */
static void under_nest_lamp(scenario_t *sc, int arena)
{
    scenario_t *base = calloc(1, sizeof *base);
    char err[SIM_ERR_MAX];
    assert_non_null(base);
    assert_int_equal(scenario_load("../sim_host/scenarios/foraging_base.yaml", NULL, 0, base, err), 0);
    if (arena) {
        sc->arena = base->arena;
    }
    sc->light_count = base->light_count;
    memcpy(sc->lights, base->lights, sizeof sc->lights);
    scenario_free(base);
    free(base);
}

/* Every colour class of a scenario's objects is detected under seed 000's
 * lighting (its nest lamp, 0.1 m up at the centre): red, green and blue
 * cylinders on the lamp's side and in the shade of their own body, and a
 * robot's lit green body LED and red ring LEDs. */
static void test_colour_classes_under_scenario_lighting(void **state)
{
    (void)state;
    static const uint8_t classes[] = { HAL_COLOUR_RED, HAL_COLOUR_GREEN, HAL_COLOUR_BLUE };
    for (int c = 0; c < 3; c++) {
        scenario_t *sc = camera_scenario(CAMERA_RENDERED, 2);
        under_nest_lamp(sc, 1);
        add_cylinder(sc, 1.0f, 0.0f, TOKEN_R, TOKEN_H, classes[c]);
        sim_t *sim = fixture_sim(sc, 3);
        sim_set_robot_pose(sim, 1, -1.8, -1.8, 0.0);
        /* Looking at it from the lamp's side (its lit face) and from beyond
         * it (its shaded face), near and far. */
        static const double from[][3] = { { 0.6, 0.0, 0.0 }, { 0.3, 0.0, 0.0 }, { 1.4, 0.0, PI },
                                          { 1.7, 0.0, PI }, { 1.0, 0.4, -PI / 2 } };
        for (size_t p = 0; p < sizeof from / sizeof from[0]; p++) {
            sim_set_robot_pose(sim, 0, from[p][0], from[p][1], from[p][2]);
            hal_blob_t b[HAL_MAX_BLOBS];
            uint8_t n = blobs_of(sim, 0, b);
            assert_int_equal(count_colour(b, n, classes[c]), 1);
            assert_int_equal(n, 1);   /* and nothing else: floor, walls, robots are no class */
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
    /* A robot's LEDs at 8 cm: the green body LED, the red ring LEDs. */
    scenario_t *sc = camera_scenario(CAMERA_RENDERED, 2);
    under_nest_lamp(sc, 0);
    sim_t *sim = fixture_sim(sc, 3);
    sim_set_robot_pose(sim, 0, 0.5, 0.0, 0.0);
    sim_set_robot_pose(sim, 1, 0.5 + 0.08 + 2 * EPUCK_BODY_RADIUS_M, 0.0, PI);
    hal_blob_t b[HAL_MAX_BLOBS];
    uint8_t n = blobs_of(sim, 0, b);
    assert_int_equal(n, 0);   /* its body: no class */
    hal_set_body_led(sim_robot_hal(sim, 1), 1);
    n = blobs_of(sim, 0, b);
    assert_int_equal(count_colour(b, n, HAL_COLOUR_GREEN), 1);
    hal_set_body_led(sim_robot_hal(sim, 1), 0);
    for (uint8_t k = 0; k < HAL_LED_COUNT; k++) hal_set_led(sim_robot_hal(sim, 1), k, 1);
    n = blobs_of(sim, 0, b);
    assert_true(count_colour(b, n, HAL_COLOUR_RED) >= 1);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* How far the robot's detector sees a food token: the rendered model, a
 * token straight ahead under seed 000's lamp, from its lit side and its
 * shaded side, at growing distances in 5 cm steps.  The detector keeps blobs
 * of at least min_pixels (3) pixels; a 3.5 x 4.2 cm token covers about
 * 1.6 x 1.7 pixels of the 40 x 20 frame at 0.9 m.  The geometric model's
 * default camera.range (to the token's nearest point) stands for that
 * reach: they agree within one step. */
static void test_detector_reach_is_the_geometric_range(void **state)
{
    (void)state;
    scenario_t *sc = camera_scenario(CAMERA_RENDERED, 2);   /* the default camera.range */
    under_nest_lamp(sc, 1);
    float tx = 0.3f;
    add_cylinder(sc, tx, 0.0f, TOKEN_R, TOKEN_H, HAL_COLOUR_RED);
    sim_t *sim = fixture_sim(sc, 3);
    sim_set_robot_pose(sim, 1, -1.8, -1.8, 0.0);
    for (int side = 0; side < 2; side++) {   /* 0: from the lamp's side, 1: from beyond */
        double last_seen = 0.0;
        for (int cm = 40; cm <= 160; cm += 5) {
            double lens = cm / 100.0;   /* lens to the token's centre */
            double x = side == 0 ? tx - lens - EPUCK_BODY_RADIUS_M : tx + lens + EPUCK_BODY_RADIUS_M;
            sim_set_robot_pose(sim, 0, x, 0.0, side == 0 ? 0.0 : PI);
            hal_blob_t b[HAL_MAX_BLOBS];
            uint8_t n = blobs_of(sim, 0, b);
            if (count_colour(b, n, HAL_COLOUR_RED) > 0) last_seen = lens;
        }
        double reach = last_seen - TOKEN_R;   /* to the token's nearest point, as camera.range */
        print_message("reach %s: %.3f m (default camera.range %.2f m)\n", side ? "shaded" : "lit", reach,
                      (double)camera_config_mut(sc)->range);
        assert_true(fabs(reach - camera_config_mut(sc)->range) <= 0.05 + 1e-6);
    }
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_token_ahead_both_models),
        cmocka_unit_test(test_side_by_side_merge_when_rendered),
        cmocka_unit_test(test_occluded_token_not_seen),
        cmocka_unit_test(test_models_agree_on_bearing),
        cmocka_unit_test(test_frames_at_their_rate_and_age),
        cmocka_unit_test(test_rendered_runs_are_deterministic),
        cmocka_unit_test(test_colour_classes_under_scenario_lighting),
        cmocka_unit_test(test_detector_reach_is_the_geometric_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
