/*
 * test_render_overlay.c - what the renderer draws besides the arena when a
 * scene asks for it (render_scene_t.overlay): the band with the simulated
 * time and the legend of robot fills, and the robots' ids.  Pictures are
 * compared with the same scene drawn without the overlay, or at another
 * time, so each check fails if the thing it looks for is not drawn.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/render.h"

#define W 400
#define H 400
#define GREEN DRAW_RGB_HL_GREEN
#define YELLOW DRAW_RGB_HL_YELLOW

typedef struct picture {
    uint8_t rgb[W * H * 3]; /* top row first */
} picture_t;

static const draw_key_t three_keys[] = {
    { 0, "waiting", DRAW_KEY_ROBOT, 0 },
    { GREEN, "searching", DRAW_KEY_ROBOT, 0 },
    { YELLOW, "returning", DRAW_KEY_ROBOT, 0 },
};

/* Three robots: one with the default body, two green; keys for those and
 * for a fill no robot has (yellow). */
typedef struct fixture {
    render_ctx_t *ctx;
    render_robot_t robots[3];
    render_scene_t sc;
} fixture_t;

static int setup(void **state)
{
    fixture_t *fx = calloc(1, sizeof *fx);
    if (!fx || !(fx->ctx = render_create(W, H, NULL))) {
        free(fx);
        return -1;
    }
    fx->robots[0] = (render_robot_t){ .x = -0.2f, .y = -0.2f };
    fx->robots[1] = (render_robot_t){ .x = 0.2f, .y = 0.1f, .fill_rgb = GREEN };
    fx->robots[2] = (render_robot_t){ .x = 0.0f, .y = 0.3f, .fill_rgb = GREEN };
    fx->sc = (render_scene_t){
        .arena_w = 1.0f, .arena_h = 1.0f, .wall = 0.05f, .robot_radius = 0.035f,
        .robots = fx->robots, .robot_count = 3, .time_s = 12.3,
        .overlay = 1, .legend = three_keys, .legend_count = 3,
    };
    *state = fx;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *fx = *state;
    render_destroy(fx->ctx);
    free(fx);
    return 0;
}

static picture_t *draw(fixture_t *fx, const render_scene_t *sc)
{
    picture_t *pic = malloc(sizeof *pic);
    assert_non_null(pic);
    char err[SIM_ERR_MAX] = "";
    int rc = render_scene_rgb(fx->ctx, sc, pic->rgb, err);
    if (rc != 0)
        print_error("render_scene_rgb: %s\n", err);
    assert_int_equal(rc, 0);
    return pic;
}

static uint32_t px(const picture_t *pic, int col, int row)
{
    const uint8_t *p = pic->rgb + ((size_t)row * W + (size_t)col) * 3;
    return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}

/* Pixels of colour rgb in rows [r0, r1) and columns [c0, c1). */
static int count(const picture_t *pic, uint32_t rgb, int c0, int r0, int c1, int r1)
{
    int n = 0;
    for (int y = r0 < 0 ? 0 : r0; y < r1 && y < H; y++)
        for (int x = c0 < 0 ? 0 : c0; x < c1 && x < W; x++)
            n += px(pic, x, y) == rgb;
    return n;
}

/* Rows of the two pictures that differ: the first and one past the last. */
static int rows_differ(const picture_t *a, const picture_t *b, int *first, int *last)
{
    *first = -1;
    *last = -1;
    for (int y = 0; y < H; y++) {
        if (memcmp(a->rgb + (size_t)y * W * 3, b->rgb + (size_t)y * W * 3, (size_t)W * 3) != 0) {
            if (*first < 0)
                *first = y;
            *last = y + 1;
        }
    }
    return *first >= 0;
}

/* Without `overlay` nothing of it is drawn, even with a legend given: the
 * top margin is background and the arena is where it always was. */
static void test_off_draws_nothing(void **state)
{
    fixture_t *fx = *state;
    render_scene_t sc = fx->sc;
    sc.overlay = 0;
    assert_true(render_overlay_band_px(fx->ctx, &sc) == 0.0f);
    picture_t *pic = draw(fx, &sc);
    assert_int_equal(count(pic, RENDER_RGB_BACKGROUND, 0, 0, W, 12), W * 12);
    assert_int_equal(count(pic, RENDER_RGB_TEXT, 0, 0, W, H), 0);
    float c, r;
    assert_int_equal(render_world_to_pixel(fx->ctx, &sc, 0, 0, &c, &r), 0);
    assert_float_equal(r, 200.0f, 1e-4);
    free(pic);
}

/* The band: above the arena's wall, with text and a swatch of every key
 * (the default body's colour included; yellow is no robot's, so only its
 * swatch can show it), none of which the plain picture has there. */
static void test_band_has_time_and_legend(void **state)
{
    fixture_t *fx = *state;
    render_scene_t plain = fx->sc;
    plain.overlay = 0;
    int band = (int)ceilf(render_overlay_band_px(fx->ctx, &fx->sc));
    assert_true(band >= 15 && band < H / 4);
    picture_t *with = draw(fx, &fx->sc), *without = draw(fx, &plain);

    assert_true(count(with, RENDER_RGB_TEXT, 0, 0, W, band) > 100);
    assert_true(count(with, GREEN, 0, 0, W, band) > 10);
    assert_true(count(with, YELLOW, 0, 0, W, band) > 10);
    assert_true(count(with, RENDER_RGB_ROBOT, 0, 0, W, band) > 10);
    assert_int_equal(count(without, RENDER_RGB_TEXT, 0, 0, W, band), 0);
    assert_int_equal(count(without, YELLOW, 0, 0, W, H), 0);
    /* The arena is wholly below the band: no wall in it, wall just under. */
    assert_int_equal(count(with, RENDER_RGB_WALL, 0, 0, W, band), 0);
    float c, r;
    assert_int_equal(render_world_to_pixel(fx->ctx, &fx->sc, 0.0f, 0.525f, &c, &r), 0);
    assert_true(r > (float)band);
    assert_int_equal(px(with, (int)c, (int)r), RENDER_RGB_WALL);
    free(with);
    free(without);
}

/* The time stamp: another time changes the band's left part only; the
 * same time gives the same picture. */
static void test_time_stamp(void **state)
{
    fixture_t *fx = *state;
    render_scene_t later = fx->sc;
    later.time_s = 45.6;
    int band = (int)ceilf(render_overlay_band_px(fx->ctx, &fx->sc));
    picture_t *a = draw(fx, &fx->sc), *b = draw(fx, &later), *again = draw(fx, &fx->sc);
    int first, last;
    assert_true(rows_differ(a, b, &first, &last));
    assert_true(first >= 0 && last <= band);
    /* Which columns: the time slot at the left ("T = 12.3 S"). */
    int right = 0;
    for (int y = first; y < last; y++)
        for (int x = 0; x < W; x++)
            if (px(a, x, y) != px(b, x, y) && x > right)
                right = x;
    assert_true(right < W / 3);
    assert_memory_equal(a->rgb, again->rgb, sizeof a->rgb);
    free(a);
    free(b);
    free(again);
}

/* The band's height depends on neither the time nor the counts, so a
 * video's arena never jumps; a changed count changes the legend's text. */
static void test_band_is_stable(void **state)
{
    fixture_t *fx = *state;
    float band = render_overlay_band_px(fx->ctx, &fx->sc);
    render_scene_t sc = fx->sc;
    sc.time_s = 99999.9;
    assert_float_equal(render_overlay_band_px(fx->ctx, &sc), band, 0);
    picture_t *before = draw(fx, &fx->sc);
    fx->robots[0].fill_rgb = YELLOW;   /* waiting 1 -> 0, returning 0 -> 1 */
    fx->robots[0].x = 0.45f;           /* and out of the way of the band check */
    assert_float_equal(render_overlay_band_px(fx->ctx, &fx->sc), band, 0);
    picture_t *after = draw(fx, &fx->sc);
    int first, last;
    assert_true(rows_differ(before, after, &first, &last));
    assert_true(first < (int)band);
    free(before);
    free(after);
}

/* Each robot's id is written up and to the right of it, in the text
 * colour, and only with the overlay. */
static void test_ids(void **state)
{
    fixture_t *fx = *state;
    render_scene_t plain = fx->sc;
    plain.overlay = 0;
    picture_t *with = draw(fx, &fx->sc), *without = draw(fx, &plain);
    float rpx = 0.035f * render_scale_px_per_m(fx->ctx, &fx->sc);
    for (int i = 0; i < 3; i++) {
        float c, r;
        assert_int_equal(render_world_to_pixel(fx->ctx, &fx->sc, fx->robots[i].x, fx->robots[i].y, &c, &r), 0);
        int c0 = (int)(c + 0.7f * rpx), r1 = (int)(r - 0.4f * rpx);
        assert_true(count(with, RENDER_RGB_TEXT, c0, r1 - 12, c0 + 12, r1 + 1) >= 5);
        assert_int_equal(count(without, RENDER_RGB_TEXT, c0, r1 - 12, c0 + 12, r1 + 1), 0);
    }
    free(with);
    free(without);
}

/* The world-to-picture mapping follows the band: a robot's body is where
 * render_world_to_pixel says, in the overlay's smaller arena. */
static void test_mapping_below_band(void **state)
{
    fixture_t *fx = *state;
    render_scene_t plain = fx->sc;
    plain.overlay = 0;
    assert_true(render_scale_px_per_m(fx->ctx, &fx->sc) < render_scale_px_per_m(fx->ctx, &plain));
    picture_t *pic = draw(fx, &fx->sc);
    for (int i = 0; i < 3; i++) {
        float c, r;
        /* Behind the centre: the heading bar points along +x. */
        assert_int_equal(render_world_to_pixel(fx->ctx, &fx->sc, fx->robots[i].x - 0.015f,
                                               fx->robots[i].y, &c, &r), 0);
        uint32_t want = fx->robots[i].fill_rgb ? fx->robots[i].fill_rgb : RENDER_RGB_ROBOT;
        assert_int_equal(px(pic, (int)c, (int)r), want);
    }
    free(pic);
}

/* A narrow picture wraps the legend onto more lines and shows every key. */
static void test_legend_wraps(void **state)
{
    (void)state;
    static const draw_key_t many[] = {
        { 0x101080u, "first state", DRAW_KEY_ROBOT, 0 }, { 0x108010u, "second state", DRAW_KEY_ROBOT, 0 },
        { 0x801010u, "third state", DRAW_KEY_ROBOT, 0 }, { 0x808010u, "fourth state", DRAW_KEY_ROBOT, 0 },
        { 0x108080u, "fifth state", DRAW_KEY_ROBOT, 0 }, { 0x801080u, "sixth state", DRAW_KEY_ROBOT, 0 },
    };
    render_ctx_t *ctx = render_create(240, 240, NULL);
    assert_non_null(ctx);
    render_scene_t sc = { .arena_w = 1.0f, .arena_h = 1.0f, .overlay = 1, .legend = many, .legend_count = 1 };
    float one = render_overlay_band_px(ctx, &sc);
    sc.legend_count = 6;
    float six = render_overlay_band_px(ctx, &sc);
    assert_true(six > 2.0f * one);
    uint8_t *rgb = malloc(240 * 240 * 3);
    assert_non_null(rgb);
    assert_int_equal(render_scene_rgb(ctx, &sc, rgb, NULL), 0);
    for (int k = 0; k < 6; k++) {
        int n = 0;
        for (int i = 0; i < 240 * (int)six; i++) {
            const uint8_t *p = rgb + (size_t)i * 3;
            n += ((uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]) == many[k].rgb;
        }
        assert_true(n > 5);
    }
    free(rgb);
    render_destroy(ctx);
}

/* The raw frame is the PNG's picture, pixel for pixel. */
static void test_rgb_is_the_png(void **state)
{
    fixture_t *fx = *state;
    char path[] = "/tmp/test_render_overlay_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char err[SIM_ERR_MAX] = "";
    assert_int_equal(render_scene_png(fx->ctx, &fx->sc, path, err), 0);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    assert_true(png_image_begin_read_from_file(&img, path));
    img.format = PNG_FORMAT_RGB;
    picture_t *png = malloc(sizeof *png);
    assert_non_null(png);
    assert_int_equal(PNG_IMAGE_SIZE(img), sizeof png->rgb);
    assert_true(png_image_finish_read(&img, NULL, png->rgb, 0, NULL));
    remove(path);
    picture_t *raw = draw(fx, &fx->sc);
    assert_memory_equal(png->rgb, raw->rgb, sizeof raw->rgb);
    free(png);
    free(raw);
}

/* A legend count without its array is refused, and no frame buffer too. */
static void test_bad_arguments(void **state)
{
    fixture_t *fx = *state;
    render_scene_t sc = fx->sc;
    sc.legend = NULL;
    char err[SIM_ERR_MAX] = "";
    uint8_t *rgb = malloc(W * H * 3);
    assert_non_null(rgb);
    assert_int_equal(render_scene_rgb(fx->ctx, &sc, rgb, err), -1);
    assert_non_null(strstr(err, "non-zero"));
    assert_int_equal(render_scene_rgb(fx->ctx, &fx->sc, NULL, err), -1);
    assert_non_null(strstr(err, "frame buffer"));
    free(rgb);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_off_draws_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_band_has_time_and_legend, setup, teardown),
        cmocka_unit_test_setup_teardown(test_time_stamp, setup, teardown),
        cmocka_unit_test_setup_teardown(test_band_is_stable, setup, teardown),
        cmocka_unit_test_setup_teardown(test_ids, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mapping_below_band, setup, teardown),
        cmocka_unit_test(test_legend_wraps),
        cmocka_unit_test_setup_teardown(test_rgb_is_the_png, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_arguments, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
