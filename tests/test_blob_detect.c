/*
 * test_blob_detect.c - CMocka tests of hal/blob_detect on synthetic frames.
 */
#include <stdarg.h>
#include <math.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "blob_detect.h"
#include "blob_detect_lut.h"
#include "blob_detect_old.h"

#define FW 40u
#define FH 40u

/* Big enough for the largest frame accepted plus one column. */
static uint8_t frame[2u * (BLOB_MAX_WIDTH + 1u) * BLOB_MAX_HEIGHT];

static const uint8_t RED[3] = { 255u, 0u, 0u };
static const uint8_t GREEN[3] = { 0u, 255u, 0u };
static const uint8_t BLUE[3] = { 0u, 0u, 255u };
static const uint8_t GREY[3] = { 128u, 128u, 128u };

static void put(uint16_t w, uint16_t x, uint16_t y, const uint8_t rgb[3], uint8_t order)
{
    uint16_t v = blob_rgb565(rgb[0], rgb[1], rgb[2]);
    size_t off = 2u * ((size_t)y * w + x);
    if (order == BLOB_BYTE_ORDER_BIG) {
        frame[off] = (uint8_t)(v >> 8);
        frame[off + 1u] = (uint8_t)(v & 0xFFu);
    } else {
        frame[off] = (uint8_t)(v & 0xFFu);
        frame[off + 1u] = (uint8_t)(v >> 8);
    }
}

static void rect(uint16_t w, uint16_t x0, uint16_t y0, uint16_t rw, uint16_t rh,
                 const uint8_t rgb[3], uint8_t order)
{
    uint16_t x, y;
    for (y = y0; y < y0 + rh; y++) {
        for (x = x0; x < x0 + rw; x++) {
            put(w, x, y, rgb, order);
        }
    }
}

static void fill(uint16_t w, uint16_t h, const uint8_t rgb[3])
{
    rect(w, 0u, 0u, w, h, rgb, BLOB_BYTE_ORDER_BIG);
}

/* The documented bearing of a fractional centre column, rounded. */
static int expected_bearing(double centre, uint16_t w, uint16_t fov)
{
    double b = ((double)w - 1.0 - 2.0 * centre) * fov / (2.0 * w);
    return (int)(b >= 0.0 ? b + 0.5 : b - 0.5);
}

static int expected_width(uint16_t columns, uint16_t w, uint16_t fov)
{
    return (int)((double)columns * fov / w + 0.5);
}

static uint8_t detect(const blob_detect_params_t *p, uint16_t w, uint16_t h,
                      hal_blob_t *out, uint8_t max)
{
    blob_detect_work_t work;
    memset(&work, 0xA5, sizeof work);   /* the detector must not rely on it */
    return blob_detect(p, frame, w, h, &work, out, max);
}

/* ------------------------------------------------------------------ */

static void test_rgb565_and_defaults(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    (void)state;
    assert_int_equal(blob_rgb565(255u, 0u, 0u), 0xF800u);
    assert_int_equal(blob_rgb565(0u, 255u, 0u), 0x07E0u);
    assert_int_equal(blob_rgb565(0u, 0u, 255u), 0x001Fu);
    assert_int_equal(blob_rgb565(255u, 255u, 255u), 0xFFFFu);
    assert_int_equal(blob_rgb565(0x12u, 0x34u, 0x56u), ((0x12u >> 3) << 11) | ((0x34u >> 2) << 5) | (0x56u >> 3));
    assert_int_equal(p.fov_mrad, 977u);
    assert_int_equal(p.byte_order, BLOB_BYTE_ORDER_BIG);
    assert_true(p.min_pixels >= 1u);
    assert_int_equal(p.min_column_pixels, 1u);
}

static void test_classify_primaries(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    (void)state;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 0u, 0u)), HAL_COLOUR_RED);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(0u, 255u, 0u)), HAL_COLOUR_GREEN);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(0u, 0u, 255u)), HAL_COLOUR_BLUE);
    /* Imperfect but clear colours, as a real camera gives. */
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(200u, 60u, 50u)), HAL_COLOUR_RED);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(40u, 150u, 60u)), HAL_COLOUR_GREEN);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(30u, 60u, 140u)), HAL_COLOUR_BLUE);
    assert_int_equal(blob_classify_rgb565(NULL, blob_rgb565(255u, 0u, 0u)), HAL_COLOUR_NONE);
    /* Full-scale 5/6/5 channels expand to exactly 255. */
    p.min_value = 255u;
    assert_int_equal(blob_classify_rgb565(&p, 0xF800u), HAL_COLOUR_RED);
    assert_int_equal(blob_classify_rgb565(&p, 0x07E0u), HAL_COLOUR_GREEN);
    assert_int_equal(blob_classify_rgb565(&p, 0x001Fu), HAL_COLOUR_BLUE);
    assert_int_equal(blob_classify_rgb565(&p, 0xF000u), HAL_COLOUR_NONE);   /* r5 = 30: 247 */
}

static void test_classify_rejects_neutral(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    unsigned v;
    (void)state;
    for (v = 0u; v <= 255u; v++) {   /* every grey from black to white */
        assert_int_equal(blob_classify_rgb565(&p, blob_rgb565((uint8_t)v, (uint8_t)v, (uint8_t)v)),
                         HAL_COLOUR_NONE);
    }
    /* Near-greys with a slight tint, pastel, dim colour, secondary colours. */
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(140u, 120u, 120u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 215u, 215u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(50u, 0u, 0u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 255u, 0u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(0u, 255u, 255u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 0u, 255u)), HAL_COLOUR_NONE);
    /* Each threshold acts on its own. */
    p = blob_detect_default_params();
    p.min_value = 0u; p.min_margin = 1u; p.min_saturation_q8 = 0u;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(50u, 0u, 0u)), HAL_COLOUR_RED);
    p.min_value = 100u;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(50u, 0u, 0u)), HAL_COLOUR_NONE);
    p = blob_detect_default_params();
    p.min_saturation_q8 = 0u; p.min_margin = 100u;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 160u, 160u)), HAL_COLOUR_NONE);
    p.min_margin = 10u;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 160u, 160u)), HAL_COLOUR_RED);
    p.min_saturation_q8 = 128u;   /* (255-160)/255 = 37 % < 50 % */
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 160u, 160u)), HAL_COLOUR_NONE);
    /* With every threshold at 0, tied top channels still are no colour. */
    p.min_value = 0u; p.min_margin = 0u; p.min_saturation_q8 = 0u;
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(128u, 128u, 128u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 255u, 0u)), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, 0u), HAL_COLOUR_NONE);
    assert_int_equal(blob_classify_rgb565(&p, blob_rgb565(255u, 240u, 0u)), HAL_COLOUR_RED);
}

static void test_empty_frames(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    static const uint8_t WHITE[3] = { 255u, 255u, 255u };
    static const uint8_t BLACK[3] = { 0u, 0u, 0u };
    (void)state;
    fill(FW, FH, GREY);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
    fill(FW, FH, WHITE);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
    fill(FW, FH, BLACK);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
    /* A grey frame with white and black patches is still empty. */
    fill(FW, FH, GREY);
    rect(FW, 5u, 5u, 10u, 10u, WHITE, BLOB_BYTE_ORDER_BIG);
    rect(FW, 20u, 20u, 10u, 10u, BLACK, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
}

static void test_centre_red_rectangle(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    fill(FW, FH, GREY);
    rect(FW, 16u, 10u, 8u, 20u, RED, BLOB_BYTE_ORDER_BIG);   /* columns 16..23 */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].colour, HAL_COLOUR_RED);
    assert_int_equal(out[0].pixels, 8u * 20u);
    assert_int_equal(out[0].bearing_mrad, 0);
    assert_int_equal(out[0].width_mrad, expected_width(8u, FW, 977u));   /* 195 */
    assert_int_equal(out[0].width_mrad, 195);
}

static void test_left_blob_positive_bearing(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    hal_blob_t right;
    (void)state;
    fill(FW, FH, GREY);
    rect(FW, 2u, 0u, 6u, 5u, RED, BLOB_BYTE_ORDER_BIG);   /* columns 2..7, centre 4.5 */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_true(out[0].bearing_mrad > 0);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(4.5, FW, 977u));   /* 366.4 */
    assert_int_equal(out[0].bearing_mrad, 366);
    assert_int_equal(out[0].pixels, 30u);

    /* Its mirror image on the right has exactly the opposite bearing. */
    fill(FW, FH, GREY);
    rect(FW, (uint16_t)(FW - 8u), 0u, 6u, 5u, RED, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, &right, 1u), 1u);
    assert_int_equal(right.bearing_mrad, -out[0].bearing_mrad);
    assert_int_equal(right.width_mrad, out[0].width_mrad);

    /* Another field of view scales the bearing. */
    p.fov_mrad = 1954u;
    fill(FW, FH, GREY);
    rect(FW, 2u, 0u, 6u, 5u, RED, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, out, 1u), 1u);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(4.5, FW, 1954u));
}

static void test_bearing_is_pixel_weighted(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    fill(FW, FH, GREY);
    /* Column 10 holds 20 pixels, columns 11..19 one each: centre is
     * (20*10 + 11 + ... + 19) / 29 = 335 / 29 = 11.55, not 14.5. */
    rect(FW, 10u, 0u, 1u, 20u, RED, BLOB_BYTE_ORDER_BIG);
    rect(FW, 11u, 0u, 9u, 1u, RED, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, 29u);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(335.0 / 29.0, FW, 977u));
    assert_int_not_equal(out[0].bearing_mrad, expected_bearing(14.5, FW, 977u));
    assert_int_equal(out[0].width_mrad, expected_width(10u, FW, 977u));
}

static void test_width_matches_column_span(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    uint16_t span;
    (void)state;
    p.min_pixels = 1u;
    for (span = 1u; span <= FW; span++) {
        fill(FW, FH, GREY);
        rect(FW, 0u, 3u, span, 2u, BLUE, BLOB_BYTE_ORDER_BIG);
        assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
        assert_int_equal(out[0].colour, HAL_COLOUR_BLUE);
        assert_int_equal(out[0].pixels, 2u * span);
        assert_int_equal(out[0].width_mrad, expected_width(span, FW, 977u));
        assert_int_equal(out[0].bearing_mrad, expected_bearing((span - 1u) / 2.0, FW, 977u));
    }
    /* The full frame: the field of view, straight ahead. */
    assert_int_equal(out[0].width_mrad, 977u);
    assert_int_equal(out[0].bearing_mrad, 0);
}

static void test_two_red_blobs_sorted(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    fill(FW, FH, GREY);
    rect(FW, 2u, 5u, 5u, 6u, RED, BLOB_BYTE_ORDER_BIG);     /* left, 30 px */
    rect(FW, 25u, 20u, 10u, 6u, RED, BLOB_BYTE_ORDER_BIG);  /* right, 60 px */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 2u);
    assert_int_equal(out[0].colour, HAL_COLOUR_RED);
    assert_int_equal(out[1].colour, HAL_COLOUR_RED);
    assert_int_equal(out[0].pixels, 60u);
    assert_int_equal(out[1].pixels, 30u);
    assert_true(out[0].bearing_mrad < 0);
    assert_true(out[1].bearing_mrad > 0);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(29.5, FW, 977u));
    assert_int_equal(out[1].bearing_mrad, expected_bearing(4.0, FW, 977u));

    /* Blobs one gap column apart are still separate. */
    fill(FW, FH, GREY);
    rect(FW, 10u, 0u, 5u, 4u, RED, BLOB_BYTE_ORDER_BIG);    /* 10..14 */
    rect(FW, 16u, 0u, 5u, 4u, RED, BLOB_BYTE_ORDER_BIG);    /* 16..20 */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 2u);
    /* Equal sizes: smaller bearing (the right one) first. */
    assert_int_equal(out[0].pixels, out[1].pixels);
    assert_true(out[0].bearing_mrad < out[1].bearing_mrad);
    /* Adjacent columns (even on different rows) merge. */
    fill(FW, FH, GREY);
    rect(FW, 10u, 0u, 5u, 4u, RED, BLOB_BYTE_ORDER_BIG);    /* 10..14 */
    rect(FW, 15u, 30u, 5u, 4u, RED, BLOB_BYTE_ORDER_BIG);   /* 15..19 */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, 40u);
    assert_int_equal(out[0].width_mrad, expected_width(10u, FW, 977u));
}

static void test_red_and_green_overlap(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    fill(FW, FH, GREY);
    rect(FW, 10u, 0u, 11u, 10u, RED, BLOB_BYTE_ORDER_BIG);     /* 10..20, 110 px */
    rect(FW, 15u, 20u, 11u, 8u, GREEN, BLOB_BYTE_ORDER_BIG);   /* 15..25, 88 px */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 2u);
    assert_int_equal(out[0].colour, HAL_COLOUR_RED);
    assert_int_equal(out[0].pixels, 110u);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(15.0, FW, 977u));
    assert_int_equal(out[1].colour, HAL_COLOUR_GREEN);
    assert_int_equal(out[1].pixels, 88u);
    assert_int_equal(out[1].bearing_mrad, expected_bearing(20.0, FW, 977u));
    assert_int_equal(out[1].width_mrad, expected_width(11u, FW, 977u));

    /* Same size, same columns: ties broken by colour (red before green). */
    fill(FW, FH, GREY);
    rect(FW, 10u, 0u, 6u, 5u, GREEN, BLOB_BYTE_ORDER_BIG);
    rect(FW, 10u, 10u, 6u, 5u, RED, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 2u);
    assert_int_equal(out[0].colour, HAL_COLOUR_RED);
    assert_int_equal(out[1].colour, HAL_COLOUR_GREEN);
    assert_int_equal(out[0].bearing_mrad, out[1].bearing_mrad);
}

static void test_noise_below_min_pixels(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    uint16_t x;
    (void)state;
    fill(FW, FH, GREY);
    /* Isolated red pixels in every third column: 1-pixel blobs. */
    for (x = 0u; x < FW; x += 3u) {
        put(FW, x, (uint16_t)((x * 7u) % FH), RED, BLOB_BYTE_ORDER_BIG);
    }
    p.min_pixels = 2u;
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
    p.min_pixels = 1u;   /* the same pixels count when allowed */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), HAL_MAX_BLOBS);
    assert_int_equal(out[0].pixels, 1u);

    /* A real blob among the noise is found with its exact size. */
    p.min_pixels = 3u;
    rect(FW, 19u, 10u, 2u, 6u, GREEN, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].colour, HAL_COLOUR_GREEN);
    assert_int_equal(out[0].pixels, 12u);

    /* A blob of exactly min_pixels is kept, one less is dropped. */
    p.min_pixels = 12u;
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    p.min_pixels = 13u;
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
}

static void test_min_column_pixels(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    fill(FW, FH, GREY);
    rect(FW, 10u, 0u, 4u, 8u, RED, BLOB_BYTE_ORDER_BIG);    /* 10..13, 8 per column */
    rect(FW, 14u, 0u, 6u, 2u, RED, BLOB_BYTE_ORDER_BIG);    /* 14..19, 2 per column */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, 44u);
    p.min_column_pixels = 3u;   /* the thin tail no longer belongs to it */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, 32u);
    assert_int_equal(out[0].width_mrad, expected_width(4u, FW, 977u));
    assert_int_equal(out[0].bearing_mrad, expected_bearing(11.5, FW, 977u));
    p.min_column_pixels = 0u;   /* acts as 1: empty columns are not part */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, 44u);
    assert_int_equal(out[0].width_mrad, expected_width(10u, FW, 977u));
    assert_int_equal(out[0].bearing_mrad, expected_bearing((8.0 * 46 + 2.0 * 99) / 44.0, FW, 977u));
}

static void test_byte_order(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    /* A red square stored low byte first. */
    rect(FW, 0u, 0u, FW, FH, GREY, BLOB_BYTE_ORDER_LITTLE);
    rect(FW, 5u, 5u, 10u, 10u, RED, BLOB_BYTE_ORDER_LITTLE);
    /* Read as big-endian, 0xF800 becomes 0x00F8, a blue. */
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].colour, HAL_COLOUR_BLUE);
    p.byte_order = BLOB_BYTE_ORDER_LITTLE;
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].colour, HAL_COLOUR_RED);
    assert_int_equal(out[0].pixels, 100u);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(9.5, FW, 977u));
    /* An unknown byte order is rejected. */
    p.byte_order = 2u;
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS), 0u);
}

static void test_line_frame(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    const uint16_t w = 120u;
    (void)state;
    fill(w, 1u, GREY);
    rect(w, 0u, 0u, 10u, 1u, RED, BLOB_BYTE_ORDER_BIG);      /* 0..9 */
    rect(w, 100u, 0u, 20u, 1u, GREEN, BLOB_BYTE_ORDER_BIG);  /* 100..119 */
    rect(w, 60u, 0u, 2u, 1u, BLUE, BLOB_BYTE_ORDER_BIG);     /* 2 px: dropped */
    assert_int_equal(detect(&p, w, 1u, out, HAL_MAX_BLOBS), 2u);
    assert_int_equal(out[0].colour, HAL_COLOUR_GREEN);
    assert_int_equal(out[0].pixels, 20u);
    assert_int_equal(out[0].bearing_mrad, expected_bearing(109.5, w, 977u));
    assert_int_equal(out[0].width_mrad, expected_width(20u, w, 977u));
    assert_int_equal(out[1].colour, HAL_COLOUR_RED);
    assert_int_equal(out[1].pixels, 10u);
    assert_int_equal(out[1].bearing_mrad, expected_bearing(4.5, w, 977u));
    assert_true(out[1].bearing_mrad > 400);   /* near the left edge, < fov/2 */
    assert_true(out[1].bearing_mrad < 489);
    assert_int_equal(out[1].width_mrad, expected_width(10u, w, 977u));
}

static void test_bad_inputs(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    blob_detect_work_t work;
    hal_blob_t out[HAL_MAX_BLOBS];
    hal_blob_t sentinel;
    (void)state;
    memset(&sentinel, 0x5A, sizeof sentinel);
    out[0] = sentinel;
    /* A red frame one column wider than the maximum: 0, out untouched. */
    fill((uint16_t)(BLOB_MAX_WIDTH + 1u), 1u, RED);
    assert_int_equal(blob_detect(&p, frame, (uint16_t)(BLOB_MAX_WIDTH + 1u), 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, frame, 60000u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_memory_equal(&out[0], &sentinel, sizeof sentinel);
    /* ... but the maximum width itself works. */
    assert_int_equal(blob_detect(&p, frame, BLOB_MAX_WIDTH, 1u, &work, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, BLOB_MAX_WIDTH);
    out[0] = sentinel;
    assert_int_equal(blob_detect(&p, frame, 10u, (uint16_t)(BLOB_MAX_HEIGHT + 1u), &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, frame, 0u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, frame, 1u, 0u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(NULL, frame, 10u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, NULL, 10u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, frame, 10u, 1u, NULL, out, HAL_MAX_BLOBS), 0u);
    assert_int_equal(blob_detect(&p, frame, 10u, 1u, &work, NULL, HAL_MAX_BLOBS), 0u);
    p.fov_mrad = 0u;
    assert_int_equal(blob_detect(&p, frame, 10u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    p.fov_mrad = (uint16_t)(BLOB_MAX_FOV_MRAD + 1u);
    assert_int_equal(blob_detect(&p, frame, 10u, 1u, &work, out, HAL_MAX_BLOBS), 0u);
    assert_memory_equal(&out[0], &sentinel, sizeof sentinel);
    /* The same call with valid parameters does find the blob. */
    p.fov_mrad = BLOB_MAX_FOV_MRAD;
    assert_int_equal(blob_detect(&p, frame, 10u, 1u, &work, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].width_mrad, BLOB_MAX_FOV_MRAD);
}

static void test_largest_frame_arithmetic(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS];
    (void)state;
    p.fov_mrad = BLOB_MAX_FOV_MRAD;
    fill(BLOB_MAX_WIDTH, BLOB_MAX_HEIGHT, RED);
    assert_int_equal(detect(&p, BLOB_MAX_WIDTH, BLOB_MAX_HEIGHT, out, HAL_MAX_BLOBS), 1u);
    assert_int_equal(out[0].pixels, BLOB_MAX_WIDTH * BLOB_MAX_HEIGHT);
    assert_int_equal(out[0].bearing_mrad, 0);
    assert_int_equal(out[0].width_mrad, BLOB_MAX_FOV_MRAD);
    /* A full-height stripe at the far left. */
    fill(BLOB_MAX_WIDTH, BLOB_MAX_HEIGHT, GREY);
    rect(BLOB_MAX_WIDTH, 0u, 0u, 1u, BLOB_MAX_HEIGHT, BLUE, BLOB_BYTE_ORDER_BIG);
    rect(BLOB_MAX_WIDTH, BLOB_MAX_WIDTH - 1u, 0u, 1u, BLOB_MAX_HEIGHT, GREEN, BLOB_BYTE_ORDER_BIG);
    assert_int_equal(detect(&p, BLOB_MAX_WIDTH, BLOB_MAX_HEIGHT, out, HAL_MAX_BLOBS), 2u);
    assert_int_equal(out[0].colour, HAL_COLOUR_GREEN);   /* same size, right first */
    assert_int_equal(out[0].bearing_mrad, expected_bearing(159.0, BLOB_MAX_WIDTH, BLOB_MAX_FOV_MRAD));
    assert_int_equal(out[1].colour, HAL_COLOUR_BLUE);
    assert_int_equal(out[1].bearing_mrad, expected_bearing(0.0, BLOB_MAX_WIDTH, BLOB_MAX_FOV_MRAD));
    assert_int_equal(out[1].bearing_mrad, -out[0].bearing_mrad);
    assert_int_equal(out[1].pixels, BLOB_MAX_HEIGHT);
}

static void test_max_limits_output(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS + 2u];
    hal_blob_t sentinel;
    (void)state;
    memset(&sentinel, 0x5A, sizeof sentinel);
    fill(FW, FH, GREY);
    rect(FW, 0u, 0u, 4u, 4u, GREEN, BLOB_BYTE_ORDER_BIG);    /* 16 */
    rect(FW, 10u, 0u, 5u, 5u, BLUE, BLOB_BYTE_ORDER_BIG);    /* 25 */
    rect(FW, 30u, 0u, 3u, 3u, RED, BLOB_BYTE_ORDER_BIG);     /* 9 */
    out[1] = sentinel;
    assert_int_equal(detect(&p, FW, FH, out, 1u), 1u);
    assert_int_equal(out[0].colour, HAL_COLOUR_BLUE);
    assert_int_equal(out[0].pixels, 25u);
    assert_memory_equal(&out[1], &sentinel, sizeof sentinel);
    out[0] = sentinel;
    assert_int_equal(detect(&p, FW, FH, out, 0u), 0u);
    assert_memory_equal(&out[0], &sentinel, sizeof sentinel);
    assert_int_equal(detect(&p, FW, FH, out, 255u), 3u);
    assert_int_equal(out[1].pixels, 16u);
    assert_int_equal(out[2].pixels, 9u);
}

static void test_more_blobs_than_capacity(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    hal_blob_t out[HAL_MAX_BLOBS + 2u];
    uint16_t i;
    (void)state;
    p.min_pixels = 1u;
    fill(FW, FH, GREY);
    /* 20 one-column blobs at even columns, heights shuffled 1..20. */
    for (i = 0u; i < 20u; i++) {
        uint16_t h = (uint16_t)(((i * 7u) % 20u) + 1u);
        rect(FW, (uint16_t)(2u * i), 0u, 1u, h, (i % 3u == 0u) ? RED : (i % 3u == 1u) ? GREEN : BLUE,
             BLOB_BYTE_ORDER_BIG);
    }
    assert_int_equal(detect(&p, FW, FH, out, HAL_MAX_BLOBS + 2u), BLOB_DETECT_MAX_BLOBS);
    for (i = 0u; i < BLOB_DETECT_MAX_BLOBS; i++) {
        uint16_t h = (uint16_t)(20u - i);
        uint16_t col = 0u;
        uint16_t j;
        for (j = 0u; j < 20u; j++) {
            if (((j * 7u) % 20u) + 1u == h) {
                col = (uint16_t)(2u * j);
            }
        }
        assert_int_equal(out[i].pixels, h);
        assert_int_equal(out[i].bearing_mrad, blob_column_bearing_mrad(977u, FW, col));
    }
}

static void test_column_bearing(void **state)
{
    uint16_t c;
    (void)state;
    for (c = 0u; c < FW; c++) {
        int16_t b = blob_column_bearing_mrad(977u, FW, c);
        assert_int_equal(b, expected_bearing((double)c, FW, 977u));
        assert_int_equal(b, -blob_column_bearing_mrad(977u, FW, (uint16_t)(FW - 1u - c)));
    }
    assert_true(blob_column_bearing_mrad(977u, FW, 0u) > 0);   /* left is positive */
    assert_int_equal(blob_column_bearing_mrad(977u, 1u, 0u), 0);
    assert_int_equal(blob_column_bearing_mrad(977u, FW, FW), 0);
    assert_int_equal(blob_column_bearing_mrad(977u, 0u, 0u), 0);
    assert_int_equal(blob_column_bearing_mrad(977u, (uint16_t)(BLOB_MAX_WIDTH + 1u), 0u), 0);
    assert_int_equal(blob_column_bearing_mrad(BLOB_MAX_FOV_MRAD, BLOB_MAX_WIDTH, 0u),
                     expected_bearing(0.0, BLOB_MAX_WIDTH, BLOB_MAX_FOV_MRAD));
}

/* ------------------------------------------------------------------ */
/* Randomised comparison against a straightforward reference model.    */

typedef struct ref_blob {
    hal_blob_t b;
} ref_blob_t;

static int ref_cmp(const void *pa, const void *pb)
{
    const hal_blob_t *a = &((const ref_blob_t *)pa)->b;
    const hal_blob_t *b = &((const ref_blob_t *)pb)->b;
    if (a->pixels != b->pixels) return (a->pixels > b->pixels) ? -1 : 1;
    if (a->bearing_mrad != b->bearing_mrad) return (a->bearing_mrad < b->bearing_mrad) ? -1 : 1;
    return (int)a->colour - (int)b->colour;
}

/* The documented bearing as an exact rational, rounded half away from 0. */
static int exact_bearing(int64_t s, int64_t n, int64_t w, int64_t fov)
{
    int64_t num = ((w - 1) * n - 2 * s) * fov;
    int64_t den = 2 * w * n;
    return (int)(num >= 0 ? (num + den / 2) / den : -((-num + den / 2) / den));
}

static size_t reference(const blob_detect_params_t *p, uint16_t w, uint16_t h, ref_blob_t *ref)
{
    static uint16_t counts[BLOB_MAX_WIDTH][3];
    size_t n = 0u;
    uint16_t x, y;
    unsigned k;
    memset(counts, 0, sizeof counts);
    for (x = 0u; x < w; x++) {
        for (y = 0u; y < h; y++) {
            size_t off = 2u * ((size_t)y * w + x);
            uint16_t v = (uint16_t)((frame[off] << 8) | frame[off + 1u]);
            uint8_t c = blob_classify_rgb565(p, v);
            if (c != HAL_COLOUR_NONE) counts[x][c - 1u]++;
        }
    }
    for (k = 0u; k < 3u; k++) {
        x = 0u;
        while (x < w) {
            uint16_t start;
            unsigned long px = 0u;
            int64_t wsum = 0;
            if (counts[x][k] < p->min_column_pixels) { x++; continue; }
            start = x;
            while (x < w && counts[x][k] >= p->min_column_pixels) {
                px += counts[x][k];
                wsum += (int64_t)counts[x][k] * x;
                x++;
            }
            if (px >= p->min_pixels) {
                ref[n].b.colour = (uint8_t)(k + 1u);
                ref[n].b.pixels = (uint16_t)px;
                ref[n].b.bearing_mrad = (int16_t)exact_bearing(wsum, (int64_t)px, w, p->fov_mrad);
                ref[n].b.width_mrad = (uint16_t)expected_width((uint16_t)(x - start), w, p->fov_mrad);
                n++;
            }
        }
    }
    qsort(ref, n, sizeof ref[0], ref_cmp);
    return n;
}

static void test_random_frames_match_reference(void **state)
{
    static ref_blob_t ref[3u * BLOB_MAX_WIDTH];
    static const uint8_t *const palette[4] = { RED, GREEN, BLUE, GREY };
    uint32_t seed = 12345u;
    unsigned trial;
    (void)state;
    for (trial = 0u; trial < 2000u; trial++) {
        blob_detect_params_t p = blob_detect_default_params();
        hal_blob_t out[HAL_MAX_BLOBS];
        uint16_t w, h;
        unsigned nrect, i;
        size_t nref;
        uint8_t n;
#define RND(m) ((seed = seed * 1103515245u + 12345u), (uint16_t)((seed >> 16) % (m)))
        w = (uint16_t)(1u + RND(BLOB_MAX_WIDTH));
        h = (uint16_t)(1u + RND(48u));
        p.fov_mrad = (uint16_t)(1u + RND(BLOB_MAX_FOV_MRAD));
        p.min_column_pixels = (uint16_t)(1u + RND(3u));
        p.min_pixels = (uint16_t)RND(12u);
        fill(w, h, GREY);
        nrect = RND(10u);
        for (i = 0u; i < nrect; i++) {
            uint16_t x0 = RND(w), y0 = RND(h);
            uint16_t rw = (uint16_t)(1u + RND((uint16_t)(w - x0)));
            uint16_t rh = (uint16_t)(1u + RND((uint16_t)(h - y0)));
            rect(w, x0, y0, rw, rh, palette[RND(4u)], BLOB_BYTE_ORDER_BIG);
        }
#undef RND
        nref = reference(&p, w, h, ref);
        n = detect(&p, w, h, out, HAL_MAX_BLOBS);
        assert_int_equal(n, nref < HAL_MAX_BLOBS ? nref : HAL_MAX_BLOBS);
        for (i = 0u; i < n; i++) {
            assert_int_equal(out[i].colour, ref[i].b.colour);
            assert_int_equal(out[i].pixels, ref[i].b.pixels);
            assert_int_equal(out[i].bearing_mrad, ref[i].b.bearing_mrad);
            assert_int_equal(out[i].width_mrad, ref[i].b.width_mrad);
        }
    }
}

/* ------------------------------------------------------------------ */
/* The lookup-table detector against the classifier and the old detector. */

/* The tables (blob_detect_lut.h) hold the classes of the default
 * thresholds: were the defaults changed without regenerating them, the
 * robot would silently fall back to the slower classifier path. */
static void test_lut_thresholds_are_the_defaults(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    (void)state;
    assert_int_equal(p.min_value, BLOB_LUT_MIN_VALUE);
    assert_int_equal(p.min_margin, BLOB_LUT_MIN_MARGIN);
    assert_int_equal(p.min_saturation_q8, BLOB_LUT_MIN_SATURATION_Q8);
}

/* Every one of the 65,536 pixel values: the tables, and blob_detect() on a
 * one-pixel frame in both byte orders (the table path), give
 * blob_classify_rgb565()'s class, which is still the old classifier's. */
static void test_lut_every_pixel(void **state)
{
    blob_detect_params_t p = blob_detect_default_params();
    uint32_t v;
    (void)state;
    p.min_pixels = 1u;
    for (v = 0u; v < 65536u; v++) {
        uint16_t px = (uint16_t)v;
        uint8_t want = blob_classify_rgb565(&p, px);
        uint8_t order;
        assert_int_equal(want, old_classify_rgb565(&p, px));
        assert_int_equal(blob_lut_class[blob_lut_row[px >> 5]][px & 0x1Fu], want);
        for (order = 0u; order < 2u; order++) {
            hal_blob_t out[HAL_MAX_BLOBS];
            uint8_t n;
            p.byte_order = order;
            frame[order] = (uint8_t)(px >> 8);
            frame[1u - order] = (uint8_t)(px & 0xFFu);
            n = detect(&p, 1u, 1u, out, HAL_MAX_BLOBS);
            assert_int_equal(n, want != HAL_COLOUR_NONE);
            if (n != 0u) {
                assert_int_equal(out[0].colour, want);
                assert_int_equal(out[0].pixels, 1u);
            }
        }
    }
}

static uint32_t old_seed;

static uint32_t rnd32(void)
{
    old_seed = old_seed * 1664525u + 1013904223u;
    return old_seed;
}

static uint16_t rnd(uint32_t m)
{
    return (uint16_t)((rnd32() >> 8) % m);
}

/* A pixel near the classifier's thresholds: a dominant channel and two
 * others a random amount below it, so that margin and saturation decide. */
static uint16_t near_threshold_pixel(void)
{
    uint8_t ch[3];
    uint8_t m = (uint8_t)(40u + rnd(216u));
    uint8_t k = (uint8_t)rnd(3u);
    uint8_t i;
    for (i = 0u; i < 3u; i++) {
        uint16_t below = rnd(120u);
        ch[i] = (i == k) ? m : (uint8_t)(below >= m ? 0u : (unsigned)m - below);
    }
    return blob_rgb565(ch[0], ch[1], ch[2]);
}

/* Fills a w x h frame with one of several kinds of content. */
static void random_frame(uint16_t w, uint16_t h, uint8_t kind)
{
    size_t i, n = (size_t)w * h;
    uint16_t x, y;
    uint16_t palette[6];
    palette[0] = blob_rgb565(255u, 0u, 0u);
    palette[1] = blob_rgb565(0u, 255u, 0u);
    palette[2] = blob_rgb565(0u, 0u, 255u);
    palette[3] = blob_rgb565(128u, 128u, 128u);
    palette[4] = near_threshold_pixel();
    palette[5] = (uint16_t)rnd32();
    for (i = 0u; i < n; i++) {
        uint16_t v;
        switch (kind) {
        case 0: v = (uint16_t)(rnd32() >> 8); break;              /* noise */
        case 1: v = near_threshold_pixel(); break;
        default: v = palette[3]; break;
        }
        frame[2u * i] = (uint8_t)(v >> 8);
        frame[2u * i + 1u] = (uint8_t)v;
    }
    if (kind == 2u) {           /* rectangles of palette colours */
        unsigned r, nr = rnd(12u);
        for (r = 0u; r < nr; r++) {
            uint16_t x0 = rnd(w), y0 = rnd(h);
            uint16_t rw = (uint16_t)(1u + rnd((uint32_t)(w - x0)));
            uint16_t rh = (uint16_t)(1u + rnd((uint32_t)(h - y0)));
            uint16_t v = palette[rnd(6u)];
            for (y = y0; y < y0 + rh; y++) {
                for (x = x0; x < x0 + rw; x++) {
                    frame[2u * ((size_t)y * w + x)] = (uint8_t)(v >> 8);
                    frame[2u * ((size_t)y * w + x) + 1u] = (uint8_t)v;
                }
            }
        }
    } else if (kind == 3u) {    /* stripes: many runs, many equal blobs */
        uint16_t period = (uint16_t)(1u + rnd(4u));
        for (x = 0u; x < w; x++) {
            uint16_t v = ((x / period) % 2u == 0u) ? palette[x % 3u] : palette[3];
            for (y = 0u; y < h; y++) {
                frame[2u * ((size_t)y * w + x)] = (uint8_t)(v >> 8);
                frame[2u * ((size_t)y * w + x) + 1u] = (uint8_t)v;
            }
        }
    }
}

/* The new detector's blobs are the old one's, field by field, in order. */
static void assert_same_blobs(const hal_blob_t *a, uint8_t na, const hal_blob_t *b, uint8_t nb)
{
    uint8_t i;
    assert_int_equal(na, nb);
    for (i = 0u; i < na; i++) {
        assert_int_equal(a[i].colour, b[i].colour);
        assert_int_equal(a[i].pixels, b[i].pixels);
        assert_int_equal(a[i].bearing_mrad, b[i].bearing_mrad);
        assert_int_equal(a[i].width_mrad, b[i].width_mrad);
    }
}

/* blob_detect() against the copy of the detector before the tables
 * (tests/blob_detect_old.h) over random and structured frames and
 * parameters: the same count, the same blobs, in the same order. */
static void test_matches_old_detector(void **state)
{
    static const uint16_t sizes[][2] = {
        { 40u, 20u }, { 40u, 40u }, { 120u, 1u }, { 1u, 1u }, { 160u, 160u }, { 160u, 1u }, { 1u, 160u }
    };
    unsigned trial;
    (void)state;
    old_seed = 2024u;
    for (trial = 0u; trial < 6000u; trial++) {
        blob_detect_params_t p = blob_detect_default_params();
        blob_detect_work_t w_new, w_old;
        hal_blob_t out_new[HAL_MAX_BLOBS], out_old[HAL_MAX_BLOBS];
        uint16_t w, h;
        uint8_t n_new, n_old, max;
        uint8_t kind = (uint8_t)(trial % 4u);

        if (trial % 3u == 0u) {
            w = sizes[(trial / 3u) % 7u][0];
            h = sizes[(trial / 3u) % 7u][1];
            if (w == 160u && h == 160u && trial % 5u != 0u) {
                w = 40u;   /* the largest frame now and then only: it is slow */
            }
        } else {
            w = (uint16_t)(1u + rnd(BLOB_MAX_WIDTH));
            h = (uint16_t)(1u + rnd(48u));
        }
        p.fov_mrad = (trial % 2u == 0u) ? BLOB_DEFAULT_FOV_MRAD : (uint16_t)(1u + rnd(BLOB_MAX_FOV_MRAD));
        p.byte_order = (uint8_t)rnd(2u);
        p.min_column_pixels = rnd(5u);
        p.min_pixels = (trial % 5u == 0u) ? rnd(400u) : rnd(12u);
        if (trial % 4u == 1u) {   /* other thresholds: the classifier path */
            p.min_value = (uint8_t)rnd(256u);
            p.min_margin = (uint8_t)rnd(256u);
            p.min_saturation_q8 = (uint8_t)rnd(256u);
            if (rnd(2u) == 0u) {
                p.min_margin = (uint8_t)rnd(60u);
                p.min_saturation_q8 = (uint8_t)rnd(100u);
            }
        }
        max = (uint8_t)((trial % 7u == 0u) ? rnd(HAL_MAX_BLOBS + 2u) : HAL_MAX_BLOBS);
        random_frame(w, h, kind);
        memset(&w_new, 0x5A, sizeof w_new);
        memset(&w_old, 0xA5, sizeof w_old);
        n_new = blob_detect(&p, frame, w, h, &w_new, out_new, max);
        n_old = old_blob_detect(&p, frame, w, h, &w_old, out_old, max);
        assert_same_blobs(out_new, n_new, out_old, n_old);
    }
}

/* The per-blob arithmetic (16-bit divisions and restoring divisions now)
 * at its extremes: every run of columns of a full-height single-colour
 * block, in the widest and tallest frame, at the widest and the default
 * field of view, against the old 32-bit arithmetic. */
static void test_blob_arithmetic_extremes_match_old(void **state)
{
    static const uint16_t fovs[] = { 1u, 2u, 977u, 1000u, 6282u, BLOB_MAX_FOV_MRAD };
    static const uint16_t widths[] = { 1u, 2u, 3u, 40u, 159u, BLOB_MAX_WIDTH };
    unsigned fi, wi;
    (void)state;
    for (fi = 0u; fi < sizeof fovs / sizeof fovs[0]; fi++) {
        for (wi = 0u; wi < sizeof widths / sizeof widths[0]; wi++) {
            uint16_t w = widths[wi], h = (w == BLOB_MAX_WIDTH) ? BLOB_MAX_HEIGHT : 3u;
            uint16_t x0, x1;
            for (x0 = 0u; x0 < w; x0 = (uint16_t)(x0 + 1u + x0 / 4u)) {
                for (x1 = x0; x1 < w; x1 = (uint16_t)(x1 + 1u + (x1 - x0) / 3u)) {
                    blob_detect_params_t p = blob_detect_default_params();
                    blob_detect_work_t wk;
                    hal_blob_t a[HAL_MAX_BLOBS], b[HAL_MAX_BLOBS];
                    uint8_t na, nb;
                    p.fov_mrad = fovs[fi];
                    p.min_pixels = 1u;
                    fill(w, h, GREY);
                    rect(w, x0, 0u, (uint16_t)(x1 - x0 + 1u), h, RED, BLOB_BYTE_ORDER_BIG);
                    /* a sloped edge: weighted centres off the column grid */
                    rect(w, x0, 0u, 1u, (uint16_t)(h - h / 3u), GREY, BLOB_BYTE_ORDER_BIG);
                    na = blob_detect(&p, frame, w, h, &wk, a, HAL_MAX_BLOBS);
                    nb = old_blob_detect(&p, frame, w, h, &wk, b, HAL_MAX_BLOBS);
                    assert_same_blobs(a, na, b, nb);
                }
            }
        }
    }
}

/* blob_colour_stats: every pixel's statistics, a class's alone, and the
 * refusals.  A grey frame with a red rectangle: the channels' means and sds
 * are those of a two-valued distribution, computed here in double. */
static void test_colour_stats(void **state)
{
    (void)state;
    blob_detect_params_t p = blob_detect_default_params();
    hal_colour_stats_t st;
    const double n_red = 10.0 * 8.0, n = (double)FW * FH;
    /* 255 and 128 survive RGB565 exactly (bit replication of 11111 and 10000
     * gives 255 and 132 in 5 bits, 130 in 6: the expanded values). */
    const double grey5 = 132.0, grey6 = 130.0;
    double mean_r, sd_r;
    fill(FW, FH, GREY);
    rect(FW, 5u, 5u, 10u, 8u, RED, BLOB_BYTE_ORDER_BIG);

    assert_int_equal(blob_colour_stats(&p, frame, FW, FH, HAL_COLOUR_RED, &st), 0);
    assert_int_equal(st.pixels, 80);
    assert_int_equal(st.mean[0], 255);
    assert_int_equal(st.mean[1], 0);
    assert_int_equal(st.sd[0], 0);

    assert_int_equal(blob_colour_stats(&p, frame, FW, FH, HAL_COLOUR_NONE, &st), 0);
    assert_int_equal(st.pixels, FW * FH);
    mean_r = (n_red * 255.0 + (n - n_red) * grey5) / n;
    assert_int_equal(st.mean[0], (int)floor(mean_r + 0.5));
    assert_int_equal(st.mean[1], (int)floor(((n - n_red) * grey6) / n + 0.5));
    /* The sd is taken about the rounded mean, rounded down. */
    sd_r = sqrt((n_red * pow(255.0 - st.mean[0], 2) + (n - n_red) * pow(grey5 - st.mean[0], 2)) / n);
    assert_int_equal(st.sd[0], (int)floor(sd_r));

    assert_int_equal(blob_colour_stats(&p, frame, FW, FH, HAL_COLOUR_GREEN, &st), 0);
    assert_int_equal(st.pixels, 0);
    assert_int_equal(st.mean[1], 0);

    assert_int_equal(blob_colour_stats(&p, frame, FW, FH, HAL_COLOUR_COUNT, &st), -1);
    assert_int_equal(st.pixels, 0);
    assert_int_equal(blob_colour_stats(&p, frame, 0u, FH, HAL_COLOUR_NONE, &st), -1);
    assert_int_equal(blob_colour_stats(&p, NULL, FW, FH, HAL_COLOUR_NONE, &st), -1);
    assert_int_equal(blob_colour_stats(&p, frame, FW, FH, HAL_COLOUR_NONE, NULL), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rgb565_and_defaults),
        cmocka_unit_test(test_classify_primaries),
        cmocka_unit_test(test_classify_rejects_neutral),
        cmocka_unit_test(test_empty_frames),
        cmocka_unit_test(test_centre_red_rectangle),
        cmocka_unit_test(test_left_blob_positive_bearing),
        cmocka_unit_test(test_bearing_is_pixel_weighted),
        cmocka_unit_test(test_width_matches_column_span),
        cmocka_unit_test(test_two_red_blobs_sorted),
        cmocka_unit_test(test_red_and_green_overlap),
        cmocka_unit_test(test_noise_below_min_pixels),
        cmocka_unit_test(test_min_column_pixels),
        cmocka_unit_test(test_byte_order),
        cmocka_unit_test(test_line_frame),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_largest_frame_arithmetic),
        cmocka_unit_test(test_max_limits_output),
        cmocka_unit_test(test_more_blobs_than_capacity),
        cmocka_unit_test(test_column_bearing),
        cmocka_unit_test(test_random_frames_match_reference),
        cmocka_unit_test(test_lut_thresholds_are_the_defaults),
        cmocka_unit_test(test_lut_every_pixel),
        cmocka_unit_test(test_matches_old_detector),
        cmocka_unit_test(test_blob_arithmetic_extremes_match_old),
        cmocka_unit_test(test_colour_stats),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
