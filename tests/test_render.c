/*
 * test_render.c - the headless PNG renderer: reads each picture back with
 * libpng and checks palette colours at the image positions where features
 * must be; the atomic write and its errors; two contexts in two threads.
 *
 * Set TEST_RENDER_KEEP=1 to keep the pictures (their directory is printed).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <math.h>
#include <png.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/render.h"

#define W 400
#define H 400
#define PI_F 3.14159265358979323846f

static char g_dir[64];
static int g_keep;

/* ------------------------------------------------------------------ */
/* Helpers                                                             */
/* ------------------------------------------------------------------ */

typedef struct picture {
    int w, h;
    uint8_t *rgb; /* w*h*3, top row first */
} picture_t;

/** Reads an 8-bit RGB PNG.  0 or -1. */
static int read_png(const char *path, picture_t *pic)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return -1;
    /* The file itself must be colour without alpha. */
    if (!(img.format & PNG_FORMAT_FLAG_COLOR) ||
        (img.format & PNG_FORMAT_FLAG_ALPHA)) {
        png_image_free(&img);
        return -1;
    }
    img.format = PNG_FORMAT_RGB;
    pic->w = (int)img.width;
    pic->h = (int)img.height;
    pic->rgb = malloc(PNG_IMAGE_SIZE(img));
    if (!pic->rgb) {
        png_image_free(&img);
        return -1;
    }
    if (!png_image_finish_read(&img, NULL, pic->rgb, 0, NULL)) {
        free(pic->rgb);
        pic->rgb = NULL;
        return -1;
    }
    return 0;
}

/** 0xRRGGBB at pixel (col, row), row 0 at the top; 0xFF000000 outside. */
static uint32_t px(const picture_t *pic, int col, int row)
{
    if (col < 0 || row < 0 || col >= pic->w || row >= pic->h)
        return 0xFF000000u;
    const uint8_t *p = pic->rgb + ((size_t)row * (size_t)pic->w +
                                   (size_t)col) * 3;
    return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}

/** Colour of the pixel under world point (x, y). */
static uint32_t at_world(const render_ctx_t *ctx, const render_scene_t *sc,
                         const picture_t *pic, float x, float y)
{
    float c = -1, r = -1;
    assert_int_equal(render_world_to_pixel(ctx, sc, x, y, &c, &r), 0);
    return px(pic, (int)floorf(c), (int)floorf(r));
}

static void path_in_dir(char *buf, size_t len, const char *name)
{
    snprintf(buf, len, "%s/%s", g_dir, name);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void cleanup(const char *path)
{
    if (!g_keep)
        remove(path);
}

/** Renders `sc` to <dir>/<name> and reads it back. */
static void render_and_read(render_ctx_t *ctx, const render_scene_t *sc,
                            const char *name, picture_t *pic)
{
    char path[256], tmp[300], err[SIM_ERR_MAX] = "";
    path_in_dir(path, sizeof path, name);
    int rc = render_scene_png(ctx, sc, path, err);
    if (rc != 0)
        print_error("render_scene_png: %s\n", err);
    assert_int_equal(rc, 0);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_false(exists(tmp));
    assert_int_equal(read_png(path, pic), 0);
    assert_int_equal(pic->w, W);
    assert_int_equal(pic->h, H);
    cleanup(path);
}

/** A 1 m x 1 m arena with 5 cm walls and nothing in it. */
static render_scene_t empty_scene(void)
{
    render_scene_t sc;
    memset(&sc, 0, sizeof sc);
    sc.arena_w = 1.0f;
    sc.arena_h = 1.0f;
    sc.wall = 0.05f;
    sc.robot_radius = 0.035f;
    return sc;
}

static int setup(void **state)
{
    render_ctx_t *ctx = render_create(W, H, NULL);
    if (!ctx)
        return -1;
    *state = ctx;
    return 0;
}

static int teardown(void **state)
{
    render_destroy(*state);
    return 0;
}

/* ------------------------------------------------------------------ */
/* Geometry                                                            */
/* ------------------------------------------------------------------ */

/* The mapping the other tests rely on, checked against numbers worked out
 * by hand: 400 px, margin 12 px each side, extent 1.1 m -> 376/1.1 px/m,
 * origin at the picture centre, +y up (smaller row). */
static void test_mapping(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    float s = render_scale_px_per_m(ctx, &sc);
    assert_float_equal(s, 376.0f / 1.1f, 1e-3);
    float c, r;
    assert_int_equal(render_world_to_pixel(ctx, &sc, 0, 0, &c, &r), 0);
    assert_float_equal(c, 200.0f, 1e-4);
    assert_float_equal(r, 200.0f, 1e-4);
    assert_int_equal(render_world_to_pixel(ctx, &sc, 0.5f, 0.25f, &c, &r), 0);
    assert_float_equal(c, 200.0f + 0.5f * s, 1e-3);
    assert_float_equal(r, 200.0f - 0.25f * s, 1e-3);

    /* A wide arena keeps its aspect ratio: limited by the width. */
    sc.arena_w = 2.0f;
    sc.arena_h = 0.5f;
    sc.wall = 0.0f;
    assert_float_equal(render_scale_px_per_m(ctx, &sc), 376.0f / 2.0f, 1e-3);

    sc.arena_w = 0.0f;
    assert_int_equal(render_world_to_pixel(ctx, &sc, 0, 0, &c, &r), -1);
    assert_true(render_scale_px_per_m(ctx, &sc) == 0.0f);
}

/* ------------------------------------------------------------------ */
/* A scene with every kind of feature                                  */
/* ------------------------------------------------------------------ */

static void test_scene_colours(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    render_robot_t robot = {.x = -0.2f, .y = -0.2f, .theta = 0.0f};
    render_object_t objs[2] = {
        {.shape = 0, .x = 0.3f, .y = 0.25f, .radius = 0.06f, .colour = 1},
        {.shape = 1, .x = -0.25f, .y = 0.2f, .width = 0.2f, .depth = 0.06f,
         .angle_deg = 90.0f, .colour = 3},
    };
    render_light_t light = {.x = -0.3f, .y = -0.38f};
    /* A task's floor disc (a nest), a ring and a line over everything. */
    draw_shape_t shapes[4] = {
        {.kind = DRAW_DISC, .layer = DRAW_FLOOR, .rgb = 0xB4B4B4u, .x = 0.25f, .y = -0.25f,
         .radius = 0.1f},
        {.kind = DRAW_RING, .layer = DRAW_OVER, .rgb = 0x102030u, .x = 0.0f, .y = 0.3f,
         .radius = 0.1f, .line = 0.01f},
        {.kind = DRAW_LINE, .layer = DRAW_OVER, .rgb = 0x405060u, .x = -0.4f, .y = -0.1f,
         .x2 = -0.1f, .y2 = -0.1f, .line = 0.01f},
        {.kind = DRAW_LABEL, .layer = DRAW_OVER, .rgb = 0x901020u, .x = 0.1f, .y = -0.45f,
         .text = "T=42"},
    };
    sc.shapes = shapes;
    sc.shape_count = 4;
    sc.robots = &robot;
    sc.robot_count = 1;
    sc.objects = objs;
    sc.object_count = 2;
    sc.lights = &light;
    sc.light_count = 1;

    picture_t pic = {0};
    render_and_read(ctx, &sc, "scene.png", &pic);
    float r = 0.035f;

    /* Robot body behind its centre (the heading bar is in front). */
    assert_int_equal(at_world(ctx, &sc, &pic, -0.2f - 0.5f * r, -0.2f),
                     RENDER_RGB_ROBOT);
    /* Red cylinder, its centre and near its edge. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.3f, 0.25f),
                     RENDER_RGB_OBJ_RED);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.3f + 0.05f, 0.25f),
                     RENDER_RGB_OBJ_RED);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.3f + 0.075f, 0.25f),
                     RENDER_RGB_FLOOR);
    /* Box rotated by 90 degrees: 6 cm along x, 20 cm along y. */
    assert_int_equal(at_world(ctx, &sc, &pic, -0.25f, 0.2f + 0.08f),
                     RENDER_RGB_OBJ_BLUE);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.25f + 0.06f, 0.2f),
                     RENDER_RGB_FLOOR);
    /* Floor disc: grey inside, floor just outside its 10 cm radius. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.25f, -0.25f), 0xB4B4B4u);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.25f + 0.09f, -0.25f), 0xB4B4B4u);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.25f + 0.12f, -0.25f),
                     RENDER_RGB_FLOOR);
    /* Ring: on its circle, not at its centre; the line along its length. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.1f, 0.3f), 0x102030u);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.4f), 0x102030u);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.3f), RENDER_RGB_FLOOR);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.25f, -0.1f), 0x405060u);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.25f, -0.13f), RENDER_RGB_FLOOR);
    /* The label: its colour in a box above and right of its corner, and
     * nowhere else. */
    {
        int in = 0, out = 0;
        float c0, r0, c1, r1;
        assert_int_equal(render_world_to_pixel(ctx, &sc, 0.095f, -0.35f, &c0, &r0), 0);
        assert_int_equal(render_world_to_pixel(ctx, &sc, 0.35f, -0.455f, &c1, &r1), 0);
        for (int y = 0; y < pic.h; y++) {
            for (int x = 0; x < pic.w; x++) {
                int box = x >= (int)c0 && x <= (int)c1 && y >= (int)r0 && y <= (int)r1;
                if (px(&pic, x, y) == 0x901020u) {
                    if (box) in++;
                    else out++;
                }
            }
        }
        assert_true(in > 20);
        assert_int_equal(out, 0);
    }
    /* Light marker. */
    assert_int_equal(at_world(ctx, &sc, &pic, -0.3f, -0.38f),
                     RENDER_RGB_LIGHT);
    /* Floor where nothing is. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.0f), RENDER_RGB_FLOOR);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.45f, 0.45f),
                     RENDER_RGB_FLOOR);
    /* Walls on all four sides, in the middle of their 5 cm thickness. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.525f, 0.0f), RENDER_RGB_WALL);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.525f, 0.0f),
                     RENDER_RGB_WALL);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.525f), RENDER_RGB_WALL);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, -0.525f),
                     RENDER_RGB_WALL);
    /* Margin outside the walls, and the picture's corners. */
    assert_int_equal(px(&pic, 2, 200), RENDER_RGB_BACKGROUND);
    assert_int_equal(px(&pic, 0, 0), RENDER_RGB_BACKGROUND);
    assert_int_equal(px(&pic, W - 1, H - 1), RENDER_RGB_BACKGROUND);
    /* Orientation of the picture itself, without the mapping function:
     * the red cylinder (+x, +y) is in the upper-right quadrant. */
    int red_ur = 0, red_other = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (px(&pic, x, y) == RENDER_RGB_OBJ_RED)
                (x >= W / 2 && y < H / 2) ? red_ur++ : red_other++;
    assert_true(red_ur > 100);
    assert_int_equal(red_other, 0);
    free(pic.rgb);
}

/* ------------------------------------------------------------------ */
/* Robots                                                              */
/* ------------------------------------------------------------------ */

/* Where the renderer puts the centre of ring LED i: on the rim, at -45*i
 * degrees from the heading, slightly inside the outline (3/4 of r is well
 * inside the LED dot). */
static void led_pos(const render_robot_t *rb, int i, float r, float *x,
                    float *y)
{
    float a = rb->theta - (float)i * PI_F / 4.0f;
    *x = rb->x + 0.76f * r * cosf(a);
    *y = rb->y + 0.76f * r * sinf(a);
}

static void test_ring_leds(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    /* Turned by 0.6 rad so a wrong sign or a missing rotation shows. */
    render_robot_t rb = {.x = 0.1f, .y = 0.05f, .theta = 0.6f,
                         .leds = (1u << 0) | (1u << 2)};
    sc.robots = &rb;
    sc.robot_count = 1;
    float r = 0.035f, x, y;

    picture_t pic = {0};
    render_and_read(ctx, &sc, "leds.png", &pic);
    led_pos(&rb, 0, r, &x, &y);
    assert_int_equal(at_world(ctx, &sc, &pic, x, y), RENDER_RGB_LED_RED);
    led_pos(&rb, 2, r, &x, &y); /* right-hand side, clockwise */
    assert_int_equal(at_world(ctx, &sc, &pic, x, y), RENDER_RGB_LED_RED);
    led_pos(&rb, 6, r, &x, &y); /* its mirror image: off */
    assert_int_equal(at_world(ctx, &sc, &pic, x, y), RENDER_RGB_ROBOT);
    led_pos(&rb, 4, r, &x, &y); /* back: off */
    assert_int_equal(at_world(ctx, &sc, &pic, x, y), RENDER_RGB_ROBOT);
    free(pic.rgb);

    /* Every LED on its own: red at its place and nowhere else on the rim. */
    for (int i = 0; i < 8; i++) {
        rb.leds = (uint8_t)(1u << i);
        render_and_read(ctx, &sc, "led_i.png", &pic);
        for (int j = 0; j < 8; j++) {
            led_pos(&rb, j, r, &x, &y);
            uint32_t c = at_world(ctx, &sc, &pic, x, y);
            if (j == i)
                assert_int_equal(c, RENDER_RGB_LED_RED);
            else
                assert_int_not_equal(c, RENDER_RGB_LED_RED);
        }
        free(pic.rgb);
    }

    /* All off: no red anywhere. */
    rb.leds = 0;
    render_and_read(ctx, &sc, "leds_off.png", &pic);
    for (int yy = 0; yy < H; yy++)
        for (int xx = 0; xx < W; xx++)
            assert_int_not_equal(px(&pic, xx, yy), RENDER_RGB_LED_RED);
    free(pic.rgb);
}

static void test_heading(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    render_robot_t rbs[2] = {
        {.x = -0.2f, .y = 0.0f, .theta = 0.0f},        /* facing +x */
        {.x = 0.2f, .y = 0.0f, .theta = PI_F / 2.0f},  /* facing +y */
    };
    sc.robots = rbs;
    sc.robot_count = 2;
    float r = 0.035f;

    picture_t pic = {0};
    render_and_read(ctx, &sc, "heading.png", &pic);
    /* Facing +x: the mark on the +x side, body on the -x side. */
    assert_int_equal(at_world(ctx, &sc, &pic, -0.2f + 0.5f * r, 0.0f),
                     RENDER_RGB_HEADING);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.2f - 0.5f * r, 0.0f),
                     RENDER_RGB_ROBOT);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.2f, 0.5f * r),
                     RENDER_RGB_ROBOT);
    /* Facing +y: the mark above the centre in the picture. */
    assert_int_equal(at_world(ctx, &sc, &pic, 0.2f, 0.5f * r),
                     RENDER_RGB_HEADING);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.2f, -0.5f * r),
                     RENDER_RGB_ROBOT);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.2f + 0.5f * r, 0.0f),
                     RENDER_RGB_ROBOT);
    /* Walking left from the first robot's centre along its row: body,
     * then a thin outline, then floor from about 35 mm on. */
    float c, row;
    assert_int_equal(render_world_to_pixel(ctx, &sc, -0.2f, 0.0f, &c, &row),
                     0);
    float r_px = r * render_scale_px_per_m(ctx, &sc);
    int y = (int)floorf(row), x = (int)floorf(c) - 2;
    while (px(&pic, x, y) == RENDER_RGB_ROBOT)
        x--;
    int outline = 0;
    for (; px(&pic, x, y) == RENDER_RGB_OUTLINE; x--)
        outline++;
    assert_in_range(outline, 1, 2);
    assert_int_equal(px(&pic, x, y), RENDER_RGB_FLOOR);
    float edge = c - ((float)x + 1.0f); /* distance to the floor pixel */
    assert_true(fabsf(edge - r_px) <= 1.0f);
    free(pic.rgb);
}

static void test_highlight_and_body_leds(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    render_robot_t rbs[3] = {
        {.x = -0.25f, .y = 0.0f, .fill_rgb = DRAW_RGB_HL_GREEN},
        {.x = 0.0f, .y = 0.0f, .body_led = 1},
        {.x = 0.25f, .y = 0.0f, .front_led = 1, .fill_rgb = DRAW_RGB_HL_YELLOW},
    };
    sc.robots = rbs;
    sc.robot_count = 3;
    float r = 0.035f;

    picture_t pic = {0};
    render_and_read(ctx, &sc, "highlight.png", &pic);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.25f - 0.5f * r, 0.0f),
                     DRAW_RGB_HL_GREEN);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f - 0.2f * r, 0.0f),
                     RENDER_RGB_LED_GREEN);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f - 0.6f * r, 0.0f),
                     RENDER_RGB_ROBOT);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.25f + 0.55f * r, 0.0f),
                     RENDER_RGB_LED_RED);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.25f - 0.5f * r, 0.0f),
                     DRAW_RGB_HL_YELLOW);
    free(pic.rgb);
}

/* In a 40 m arena a 70 mm robot is far below a pixel: still drawn, at the
 * minimum size (radius 3 px), and nothing beyond that. */
static void test_min_robot_size(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    sc.arena_w = 40.0f;
    sc.arena_h = 40.0f;
    sc.wall = 0.1f;
    render_robot_t rb = {.x = 3.0f, .y = 2.0f};
    sc.robots = &rb;
    sc.robot_count = 1;

    picture_t pic = {0};
    render_and_read(ctx, &sc, "tiny.png", &pic);
    float c, rw;
    assert_int_equal(render_world_to_pixel(ctx, &sc, rb.x, rb.y, &c, &rw), 0);
    int cx = (int)floorf(c), cy = (int)floorf(rw), drawn = 0;
    for (int y = cy - 6; y <= cy + 6; y++)
        for (int x = cx - 6; x <= cx + 6; x++) {
            float d = hypotf((float)x + 0.5f - c, (float)y + 0.5f - rw);
            uint32_t p = px(&pic, x, y);
            if (d > RENDER_MIN_ROBOT_RADIUS_PX + 0.5f)
                assert_int_equal(p, RENDER_RGB_FLOOR);
            else if (p != RENDER_RGB_FLOOR)
                drawn++;
        }
    assert_true(drawn >= 20); /* about pi * 3^2 = 28 pixels */
    free(pic.rgb);
}

/* ------------------------------------------------------------------ */
/* Files and errors                                                    */
/* ------------------------------------------------------------------ */

static void test_bad_path(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    char err[SIM_ERR_MAX] = "";
    const char *bad = "/nonexistent-dir-for-test-render/x.png";
    assert_int_equal(render_scene_png(ctx, &sc, bad, err), -1);
    assert_non_null(strstr(err, bad));
    assert_non_null(strstr(err, strerror(ENOENT)));
    assert_false(exists(bad));

    /* The target is a directory: the picture is written, the rename fails,
     * the temporary file is removed and the directory is untouched. */
    char dir[256], tmp[300];
    path_in_dir(dir, sizeof dir, "a-directory");
    assert_int_equal(mkdir(dir, 0755), 0);
    snprintf(tmp, sizeof tmp, "%s.tmp", dir);
    err[0] = '\0';
    assert_int_equal(render_scene_png(ctx, &sc, dir, err), -1);
    assert_non_null(strstr(err, dir));
    assert_non_null(strstr(err, strerror(EISDIR)));
    assert_false(exists(tmp));
    struct stat st;
    assert_int_equal(stat(dir, &st), 0);
    assert_true(S_ISDIR(st.st_mode));
    assert_int_equal(rmdir(dir), 0);

    /* A NULL err is allowed. */
    assert_int_equal(render_scene_png(ctx, &sc, bad, NULL), -1);
}

static void test_invalid_arguments(void **state)
{
    render_ctx_t *ctx = *state;
    char err[SIM_ERR_MAX] = "";
    char path[256];
    path_in_dir(path, sizeof path, "invalid.png");

    assert_null(render_create(0, 100, err));
    assert_non_null(strstr(err, "0x100"));
    assert_null(render_create(100, RENDER_MAX_PX + 1, NULL));

    render_scene_t sc = empty_scene();
    sc.arena_w = 0.0f;
    err[0] = '\0';
    assert_int_equal(render_scene_png(ctx, &sc, path, err), -1);
    assert_non_null(strstr(err, "arena"));
    sc = empty_scene();
    sc.arena_h = NAN;
    assert_int_equal(render_scene_png(ctx, &sc, path, err), -1);

    sc = empty_scene();
    sc.robot_count = 3; /* robots NULL */
    err[0] = '\0';
    assert_int_equal(render_scene_png(ctx, &sc, path, err), -1);
    assert_non_null(strstr(err, "NULL"));

    assert_int_equal(render_scene_png(NULL, &sc, path, err), -1);
    assert_int_equal(render_scene_png(ctx, NULL, path, err), -1);
    assert_int_equal(render_scene_png(ctx, &sc, NULL, err), -1);
    assert_int_equal(render_scene_png(ctx, &sc, "", err), -1);
    assert_false(exists(path));

    /* Non-finite items are skipped, the rest is drawn. */
    sc = empty_scene();
    render_robot_t rbs[2] = {{.x = NAN, .y = 0.0f}, {.x = 0.1f, .y = 0.1f}};
    render_object_t ob = {.shape = 0, .x = 0.0f, .y = 0.0f, .radius = INFINITY};
    sc.robots = rbs;
    sc.robot_count = 2;
    sc.objects = &ob;
    sc.object_count = 1;
    picture_t pic = {0};
    render_and_read(ctx, &sc, "nonfinite.png", &pic);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.1f - 0.02f, 0.1f),
                     RENDER_RGB_ROBOT);
    assert_int_equal(at_world(ctx, &sc, &pic, -0.2f, -0.2f),
                     RENDER_RGB_FLOOR);
    free(pic.rgb);
    render_destroy(NULL);
}

/* Rendering over an existing picture replaces it, leaves no .tmp, and a
 * failed write leaves the old picture in place. */
static void test_overwrite(void **state)
{
    render_ctx_t *ctx = *state;
    render_scene_t sc = empty_scene();
    render_object_t ob = {.shape = 0, .x = 0.0f, .y = 0.0f, .radius = 0.1f,
                          .colour = 2};
    char path[256], err[SIM_ERR_MAX];
    path_in_dir(path, sizeof path, "overwrite.png");
    assert_int_equal(render_scene_png(ctx, &sc, path, err), 0);
    sc.objects = &ob;
    sc.object_count = 1;
    assert_int_equal(render_scene_png(ctx, &sc, path, err), 0);
    picture_t pic = {0};
    assert_int_equal(read_png(path, &pic), 0);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.0f),
                     RENDER_RGB_OBJ_GREEN);
    free(pic.rgb);
    char tmp[300];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_false(exists(tmp));

    /* The picture goes through "<path>.tmp": when that cannot be created
     * (here it is a directory) the call fails and the old picture stays. */
    assert_int_equal(mkdir(tmp, 0755), 0);
    ob.colour = 3;
    err[0] = '\0';
    assert_int_equal(render_scene_png(ctx, &sc, path, err), -1);
    assert_non_null(strstr(err, path));
    assert_int_equal(read_png(path, &pic), 0);
    assert_int_equal(at_world(ctx, &sc, &pic, 0.0f, 0.0f),
                     RENDER_RGB_OBJ_GREEN);
    free(pic.rgb);
    assert_int_equal(rmdir(tmp), 0);
    cleanup(path);
}

/* ------------------------------------------------------------------ */
/* Threads                                                             */
/* ------------------------------------------------------------------ */

#define FRAMES_PER_THREAD 12

typedef struct worker {
    int id;
    render_ctx_t *ctx;  /* NULL: the worker creates and destroys its own */
    int frames;
    int failures;       /* frames that were wrong or failed */
    char err[SIM_ERR_MAX];
} worker_t;

/* Each worker's robot sits at its own place with its own highlight, and
 * moves each frame; a frame is right when its own robot is there and the
 * other worker's place shows floor. */
static void *worker_main(void *arg)
{
    worker_t *wk = arg;
    render_ctx_t *ctx = wk->ctx ? wk->ctx : render_create(W, H, wk->err);
    if (!ctx) {
        wk->failures = wk->frames;
        return NULL;
    }
    for (int f = 0; f < wk->frames; f++) {
        render_scene_t sc = empty_scene();
        float side = wk->id == 0 ? -1.0f : 1.0f;
        render_robot_t rb = {.x = side * 0.25f, .y = -0.3f + 0.05f * (float)f,
                             .theta = PI_F,
                             .fill_rgb = wk->id == 0 ? DRAW_RGB_HL_RED : DRAW_RGB_HL_GREEN,
                             .leds = 0x10};
        sc.robots = &rb;
        sc.robot_count = 1;
        char path[256], name[64];
        snprintf(name, sizeof name, "thread%d.png", wk->id);
        path_in_dir(path, sizeof path, name);
        picture_t pic = {0};
        if (render_scene_png(ctx, &sc, path, wk->err) != 0 ||
            read_png(path, &pic) != 0) {
            wk->failures++;
            continue;
        }
        float c, r, oc, orow;
        render_world_to_pixel(ctx, &sc, rb.x - 0.015f, rb.y + 0.01f, &c, &r);
        render_world_to_pixel(ctx, &sc, -rb.x, rb.y, &oc, &orow);
        uint32_t want = wk->id == 0 ? DRAW_RGB_HL_RED : DRAW_RGB_HL_GREEN;
        /* LED4 is at the back, i.e. +x for a robot facing -x. */
        float lc, lr;
        render_world_to_pixel(ctx, &sc, rb.x + 0.76f * 0.035f, rb.y, &lc, &lr);
        if (px(&pic, (int)c, (int)r) != want ||
            px(&pic, (int)oc, (int)orow) != RENDER_RGB_FLOOR ||
            px(&pic, (int)lc, (int)lr) != RENDER_RGB_LED_RED)
            wk->failures++;
        free(pic.rgb);
        cleanup(path);
    }
    if (!wk->ctx)
        render_destroy(ctx);
    return NULL;
}

static void test_two_threads(void **state)
{
    (void)state;
    worker_t wk[2];
    pthread_t th[2];
    for (int i = 0; i < 2; i++) {
        memset(&wk[i], 0, sizeof wk[i]);
        wk[i].id = i;
        wk[i].frames = FRAMES_PER_THREAD;
        assert_int_equal(pthread_create(&th[i], NULL, worker_main, &wk[i]),
                         0);
    }
    for (int i = 0; i < 2; i++)
        assert_int_equal(pthread_join(th[i], NULL), 0);
    for (int i = 0; i < 2; i++) {
        if (wk[i].failures)
            print_error("worker %d: %s\n", i, wk[i].err);
        assert_int_equal(wk[i].failures, 0);
    }
}

/* One context used by the main thread, then a worker, then main again. */
static void test_context_moves_between_threads(void **state)
{
    render_ctx_t *ctx = *state;
    worker_t wk;
    memset(&wk, 0, sizeof wk);
    wk.id = 1;
    wk.ctx = ctx;
    wk.frames = 2;
    worker_main(&wk);
    assert_int_equal(wk.failures, 0);

    pthread_t th;
    wk.id = 0;
    assert_int_equal(pthread_create(&th, NULL, worker_main, &wk), 0);
    assert_int_equal(pthread_join(th, NULL), 0);
    assert_int_equal(wk.failures, 0);

    wk.id = 1;
    worker_main(&wk);
    assert_int_equal(wk.failures, 0);
}

/* ------------------------------------------------------------------ */

static int group_setup(void **state)
{
    (void)state;
    g_keep = getenv("TEST_RENDER_KEEP") != NULL;
    snprintf(g_dir, sizeof g_dir, "/tmp/test_render_XXXXXX");
    if (!mkdtemp(g_dir))
        return -1;
    if (g_keep)
        printf("test_render: pictures kept in %s\n", g_dir);
    return 0;
}

static int group_teardown(void **state)
{
    (void)state;
    if (!g_keep)
        rmdir(g_dir);
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_mapping, setup, teardown),
        cmocka_unit_test_setup_teardown(test_scene_colours, setup, teardown),
        cmocka_unit_test_setup_teardown(test_ring_leds, setup, teardown),
        cmocka_unit_test_setup_teardown(test_heading, setup, teardown),
        cmocka_unit_test_setup_teardown(test_highlight_and_body_leds, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_min_robot_size, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_path, setup, teardown),
        cmocka_unit_test_setup_teardown(test_invalid_arguments, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_overwrite, setup, teardown),
        cmocka_unit_test(test_two_threads),
        cmocka_unit_test_setup_teardown(test_context_moves_between_threads,
                                        setup, teardown),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
