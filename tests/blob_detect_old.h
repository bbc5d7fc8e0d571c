/*
 * blob_detect_old.h - a verbatim copy (functions renamed old_*, made static)
 * of hal/blob_detect.c as it was before the lookup-table detector (commit
 * 50d378f): the per-pixel classifier, 32-bit divisions per blob.  The unit
 * test (tests/test_blob_detect.c) and the fuzz target
 * (tests/fuzz/blob_detect.c) check that today's blob_detect() returns
 * exactly what this one does, blob for blob and in the same order, on any
 * frame and parameters.  Test code only: do not fix or speed it up.
 */
#ifndef TESTS_BLOB_DETECT_OLD_H
#define TESTS_BLOB_DETECT_OLD_H

#include <stddef.h>
#include <stdint.h>

#include "blob_detect.h"

/* Rounded quotient, halves away from zero; den > 0. */
static int32_t old_div_round(int32_t num, int32_t den)
{
    if (num >= 0) {
        return (num + den / 2) / den;
    }
    return -((-num + den / 2) / den);
}

static uint8_t old_classify_rgb565(const blob_detect_params_t *p, uint16_t pixel)
{
    uint8_t r5, g6, b5;
    uint8_t ch[3];
    uint8_t best = 0u, m, s;
    uint16_t diff;
    uint8_t i;

    if (p == NULL) {
        return (uint8_t)HAL_COLOUR_NONE;
    }
    r5 = (uint8_t)((pixel >> 11) & 0x1Fu);
    g6 = (uint8_t)((pixel >> 5) & 0x3Fu);
    b5 = (uint8_t)(pixel & 0x1Fu);
    ch[0] = (uint8_t)((uint8_t)(r5 << 3) | (uint8_t)(r5 >> 2));
    ch[1] = (uint8_t)((uint8_t)(g6 << 2) | (uint8_t)(g6 >> 4));
    ch[2] = (uint8_t)((uint8_t)(b5 << 3) | (uint8_t)(b5 >> 2));

    for (i = 1u; i < 3u; i++) {
        if (ch[i] > ch[best]) {
            best = i;
        }
    }
    m = ch[best];
    s = 0u;
    for (i = 0u; i < 3u; i++) {
        if (i != best && ch[i] > s) {
            s = ch[i];
        }
    }
    diff = (uint16_t)(m - s);   /* 0..255; 0 when two channels tie */

    if (m < p->min_value || diff == 0u || diff < p->min_margin) {
        return (uint8_t)HAL_COLOUR_NONE;
    }
    /* (m - s) * 256 >= sat * m; both sides <= 65280, exact in uint16_t. */
    if ((uint16_t)(diff << 8) < (uint16_t)((uint16_t)p->min_saturation_q8 * (uint16_t)m)) {
        return (uint8_t)HAL_COLOUR_NONE;
    }
    return (uint8_t)(HAL_COLOUR_RED + best);
}

/* Nonzero when blob `a` comes before blob `b` in the output order. */
static int old_blob_before(const hal_blob_t *a, const hal_blob_t *b)
{
    if (a->pixels != b->pixels) {
        return a->pixels > b->pixels;
    }
    if (a->bearing_mrad != b->bearing_mrad) {
        return a->bearing_mrad < b->bearing_mrad;
    }
    return a->colour < b->colour;
}

/* Inserts `nb` into the ordered list of the best blobs, dropping the last
 * one when the list is full and `nb` comes before it. */
static void old_keep_blob(blob_detect_work_t *w, const hal_blob_t *nb)
{
    uint8_t pos = w->count;
    uint8_t i;

    while (pos > 0u && old_blob_before(nb, &w->blobs[pos - 1u])) {
        pos--;
    }
    if (pos >= BLOB_DETECT_MAX_BLOBS) {
        return;
    }
    i = (w->count < BLOB_DETECT_MAX_BLOBS) ? w->count : (uint8_t)(BLOB_DETECT_MAX_BLOBS - 1u);
    for (; i > pos; i--) {
        w->blobs[i] = w->blobs[i - 1u];
    }
    w->blobs[pos] = *nb;
    if (w->count < BLOB_DETECT_MAX_BLOBS) {
        w->count++;
    }
}

/* Bearing, in mrad, of the weighted centre column S / N (S = sum of
 * count_c * c, N = sum of count_c) in a frame `width` columns wide:
 *     ((W - 1) N - 2 S) * fov / (2 W N)
 * rounded to nearest, halves away from zero, computed exactly in 32 bits.
 * With D = |(W - 1) N - 2 S| = q N + rem, A = floor(D fov / N) is
 * q fov + floor(rem fov / N), and since A + W is an integer,
 *     floor(D fov / (2 W N) + 1/2) = floor((A + W) / (2 W)).
 * Bounds: q <= W - 1, so A < 160 * 6283; rem fov < N fov
 * <= 25,600 * 6283 = 1.6e8. */
static int16_t old_centre_bearing(uint32_t s, uint16_t n, uint16_t width, uint16_t fov)
{
    uint32_t lhs = (uint32_t)(width - 1u) * (uint32_t)n;
    uint32_t rhs = 2u * s;
    uint32_t d = (lhs >= rhs) ? lhs - rhs : rhs - lhs;
    uint32_t a = (d / n) * (uint32_t)fov + ((d % n) * (uint32_t)fov) / n;
    uint32_t mag = (a + (uint32_t)width) / (2u * (uint32_t)width);
    return (lhs >= rhs) ? (int16_t)mag : (int16_t)-(int32_t)mag;
}

/* Closes the run of colour `colour` whose last column is `end`. */
static void old_close_run(const blob_detect_params_t *p, blob_detect_work_t *w,
                      uint8_t colour, uint16_t width, uint16_t end)
{
    blob_detect_run_t *run = &w->runs[colour - 1u];
    hal_blob_t nb;
    uint16_t columns;

    if (run->pixels >= p->min_pixels) {
        columns = (uint16_t)(end - run->start + 1u);
        nb.colour = colour;
        nb.bearing_mrad = old_centre_bearing(run->weighted, run->pixels, width, p->fov_mrad);
        nb.width_mrad = (uint16_t)old_div_round((int32_t)columns * (int32_t)p->fov_mrad,
                                            (int32_t)width);
        nb.pixels = run->pixels;
        old_keep_blob(w, &nb);
    }
    run->pixels = 0u;
    run->weighted = 0u;
}

static uint8_t old_blob_detect(const blob_detect_params_t *p, const uint8_t *rgb565,
                               uint16_t width, uint16_t height,
                               blob_detect_work_t *work, hal_blob_t *out, uint8_t max)
{
    uint16_t min_col;
    size_t stride;
    uint16_t c, r;
    uint8_t k, n;

    if (p == NULL || rgb565 == NULL || work == NULL || out == NULL) {
        return 0u;
    }
    if (width == 0u || width > BLOB_MAX_WIDTH || height == 0u || height > BLOB_MAX_HEIGHT) {
        return 0u;
    }
    if (p->fov_mrad == 0u || p->fov_mrad > BLOB_MAX_FOV_MRAD ||
        p->byte_order > (uint8_t)BLOB_BYTE_ORDER_LITTLE) {
        return 0u;
    }
    min_col = (p->min_column_pixels == 0u) ? 1u : p->min_column_pixels;
    stride = (size_t)width * 2u;

    work->count = 0u;
    for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
        work->runs[k].pixels = 0u;
        work->runs[k].weighted = 0u;
        work->runs[k].start = 0u;
    }

    for (c = 0u; c < width; c++) {
        uint16_t counts[HAL_COLOUR_COUNT - 1u] = { 0u, 0u, 0u };
        size_t off = (size_t)c * 2u;

        for (r = 0u; r < height; r++) {
            uint8_t hi = rgb565[off];
            uint8_t lo = rgb565[off + 1u];
            uint16_t pixel;
            uint8_t colour;

            if (p->byte_order == (uint8_t)BLOB_BYTE_ORDER_LITTLE) {
                uint8_t tmp = hi;
                hi = lo;
                lo = tmp;
            }
            pixel = (uint16_t)((uint16_t)((uint16_t)hi << 8) | lo);
            colour = old_classify_rgb565(p, pixel);
            if (colour != (uint8_t)HAL_COLOUR_NONE) {
                counts[colour - 1u]++;
            }
            off += stride;
        }

        for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
            blob_detect_run_t *run = &work->runs[k];
            if (counts[k] >= min_col) {
                if (run->pixels == 0u) {
                    run->start = c;
                }
                run->pixels = (uint16_t)(run->pixels + counts[k]);
                run->weighted += (uint32_t)counts[k] * (uint32_t)c;
            } else if (run->pixels != 0u) {
                old_close_run(p, work, (uint8_t)(k + 1u), width, (uint16_t)(c - 1u));
            }
        }
    }
    for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
        if (work->runs[k].pixels != 0u) {
            old_close_run(p, work, (uint8_t)(k + 1u), width, (uint16_t)(width - 1u));
        }
    }

    n = (work->count < max) ? work->count : max;
    for (k = 0u; k < n; k++) {
        out[k] = work->blobs[k];
    }
    return n;
}

#endif /* TESTS_BLOB_DETECT_OLD_H */
