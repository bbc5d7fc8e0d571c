/*
 * blob_detect.c - colour blob detector over RGB565 frames (see the header).
 *
 * Integer-only, correct with 16-bit int: every product that can exceed
 * 32767 is computed in uint32_t/int32_t after a cast.  Bounds used below
 * (W <= 160, H <= 160, fov <= 6283):
 *   pixels of a blob     N <= W * H              = 25,600   (uint16_t)
 *   weighted column sum  S <= N * (W - 1)        = 4,070,400 (uint32_t)
 *   byte offset in frame     <= 2 W H + 2 W      = 51,520   (size_t >= 16 bit)
 *   |(W - 1) N - 2 S|    <= (W - 1) N          = 4,070,400 (uint32_t)
 *   columns * fov            <= 160 * 6283       = 1,005,280 (int32_t)
 *
 * Cost on the dsPIC (16-bit, no FPU; see docs/hardware/footprint.md, "CPU per control step"):
 * the per-pixel loop uses only 8- and 16-bit operations and, with the
 * default thresholds, two table lookups instead of the classifier; the
 * per-blob arithmetic uses no 32-bit division (XC16 turns a 32-bit '/' or
 * '%' into a call of a software routine of some hundreds of cycles, where
 * a 16/16 division is one 19-cycle REPEAT/DIV.U).
 */
#include <stddef.h>

#include "blob_detect.h"
#include "blob_detect_lut.h"
#include "tone_detect.h"        /* tone_detect_isqrt: the frame statistics' sd */

/* The working memory must stay small on every target (documented sizes). */
typedef char blob_detect_work_is_small[(sizeof(blob_detect_work_t) <= 128u) ? 1 : -1];

blob_detect_params_t blob_detect_default_params(void)
{
    blob_detect_params_t p;
    p.fov_mrad = BLOB_DEFAULT_FOV_MRAD;
    p.byte_order = (uint8_t)BLOB_BYTE_ORDER_BIG;
    p.min_value = 64u;
    p.min_margin = 40u;
    p.min_saturation_q8 = 64u;
    p.min_column_pixels = 1u;
    p.min_pixels = 3u;
    return p;
}

uint16_t blob_rgb565(uint8_t r, uint8_t g, uint8_t b)
{
    uint16_t v = (uint16_t)((uint16_t)(r & 0xF8u) << 8);
    v = (uint16_t)(v | (uint16_t)((uint16_t)(g & 0xFCu) << 3));
    v = (uint16_t)(v | (uint16_t)(b >> 3));
    return v;
}

/* Rounded quotient, halves away from zero; den > 0. */
static int32_t div_round(int32_t num, int32_t den)
{
    if (num >= 0) {
        return (num + den / 2) / den;
    }
    return -((-num + den / 2) / den);
}

uint8_t blob_classify_rgb565(const blob_detect_params_t *p, uint16_t pixel)
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

int16_t blob_column_bearing_mrad(uint16_t fov_mrad, uint16_t width, uint16_t column)
{
    int32_t num;

    if (width == 0u || width > BLOB_MAX_WIDTH || column >= width || fov_mrad > BLOB_MAX_FOV_MRAD) {
        return 0;
    }
    num = ((int32_t)width - (int32_t)1 - (int32_t)2 * (int32_t)column) * (int32_t)fov_mrad;
    return (int16_t)div_round(num, (int32_t)2 * (int32_t)width);
}

/* Nonzero when blob `a` comes before blob `b` in the output order. */
static int blob_before(const hal_blob_t *a, const hal_blob_t *b)
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
static void keep_blob(blob_detect_work_t *w, const hal_blob_t *nb)
{
    uint8_t pos = w->count;
    uint8_t i;

    while (pos > 0u && blob_before(nb, &w->blobs[pos - 1u])) {
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

/* floor(*num / den) for a quotient known to be below 2^bits (bits 1..15),
 * leaving the remainder in *num: restoring division, one quotient bit per
 * step with 32-bit subtractions and shifts by one only.  This is what the
 * dsPIC's DIV.UD does in hardware, but C cannot ask for it portably, and a
 * plain 32-bit '/' is a library call on a 16-bit target.  The divisor is
 * scaled by a 16 x 16 -> 32-bit product (one MUL.UU), not by a variable
 * 32-bit shift (another library call). */
static uint16_t udiv_small(uint32_t *num, uint16_t den, uint8_t bits)
{
    uint16_t bit = (uint16_t)(1u << (bits - 1u));
    uint32_t d = (uint32_t)den * (uint32_t)bit;
    uint32_t n = *num;
    uint16_t q = 0u;

    while (bit != 0u) {
        if (n >= d) {
            n -= d;
            q = (uint16_t)(q | bit);
        }
        d >>= 1;
        bit = (uint16_t)(bit >> 1);
    }
    *num = n;
    return q;
}

/* Bearing, in mrad, of the weighted centre column S / N (S = sum of
 * count_c * c, N = sum of count_c) in a frame `width` columns wide:
 *     ((W - 1) N - 2 S) * fov / (2 W N)
 * rounded to nearest, halves away from zero, computed exactly.
 * With D = |(W - 1) N - 2 S| = q N + rem, A = floor(D fov / N) is
 * q fov + floor(rem fov / N), and since A + W is an integer,
 *     floor(D fov / (2 W N) + 1/2) = floor((A + W) / (2 W)).
 * Quotient bounds for udiv_small: 0 <= S <= (W - 1) N, so D <= (W - 1) N
 * and q <= W - 1 <= 159 < 2^8; floor(rem fov / N) < fov <= 6283 < 2^13;
 * (A + W) / (2 W) < fov / 2 + 1 <= 3142.5 < 2^12.  Every product is
 * 16 x 16 -> 32 bits: rem fov < N fov <= 25,600 * 6283 = 1.6e8,
 * A + W <= 159 * 6283 + 6282 + 160 = 1,005,439. */
static int16_t centre_bearing(uint32_t s, uint16_t n, uint16_t width, uint16_t fov)
{
    uint32_t lhs = (uint32_t)(width - 1u) * (uint32_t)n;
    uint32_t rhs = 2u * s;
    uint32_t d = (lhs >= rhs) ? lhs - rhs : rhs - lhs;
    uint16_t q = udiv_small(&d, n, 8u);                 /* d is now rem */
    uint32_t x = (uint32_t)(uint16_t)d * (uint32_t)fov;
    uint16_t frac = udiv_small(&x, n, 13u);
    uint32_t a = (uint32_t)q * (uint32_t)fov + (uint32_t)frac + (uint32_t)width;
    uint16_t mag = udiv_small(&a, (uint16_t)(2u * width), 12u);
    return (lhs >= rhs) ? (int16_t)mag : (int16_t)-(int16_t)mag;
}

/* Width in mrad of `columns` columns of a frame `width` columns wide:
 * columns * fov / W rounded to nearest, with 16-bit divisions only: with
 * fov = f W + g (0 <= g < W),
 *     floor((columns fov + floor(W / 2)) / W)
 *         = columns f + floor((columns g + floor(W / 2)) / W),
 * where columns g + W / 2 <= 160 * 159 + 80 = 25,520 and columns f <= fov. */
static uint16_t run_width_mrad(uint16_t columns, uint16_t width, uint16_t fov)
{
    uint16_t f = (uint16_t)(fov / width);
    uint16_t g = (uint16_t)(fov % width);
    return (uint16_t)(columns * f +
                      (uint16_t)((uint16_t)(columns * g + (uint16_t)(width / 2u)) / width));
}

/* Closes the run of colour `colour` whose last column is `end`. */
static void close_run(const blob_detect_params_t *p, blob_detect_work_t *w,
                      uint8_t colour, uint16_t width, uint16_t end)
{
    blob_detect_run_t *run = &w->runs[colour - 1u];
    hal_blob_t nb;

    /* A blob with fewer pixels than the last of a full list cannot enter it
     * (pixels decide first), so its bearing is not worth computing. */
    if (run->pixels >= p->min_pixels &&
        (w->count < BLOB_DETECT_MAX_BLOBS ||
         run->pixels >= w->blobs[BLOB_DETECT_MAX_BLOBS - 1u].pixels)) {
        nb.colour = colour;
        nb.bearing_mrad = centre_bearing(run->weighted, run->pixels, width, p->fov_mrad);
        nb.width_mrad = run_width_mrad((uint16_t)(end - run->start + 1u), width, p->fov_mrad);
        nb.pixels = run->pixels;
        keep_blob(w, &nb);
    }
    run->pixels = 0u;
    run->weighted = 0u;
}

/* Classification by table (the default thresholds, which the robot image
 * uses): counts the red, green and blue pixels of the `height` pixels from
 * byte offset `off`, one every `stride` bytes; `ih`/`il` are the offsets
 * of a pixel's high and low bytes (the byte order).  The class of pixel p
 * is blob_lut_class[blob_lut_row[p >> 5]][p & 0x1F] (blob_detect_lut.h,
 * generated by tools/vision/gen_blob_lut.py from the classifier's rules),
 * so a pixel costs two byte loads and a counter increment, without a
 * comparison or a branch, instead of blob_classify_rgb565()'s channel
 * expansion, sort and product.  Exact: tests/test_blob_detect.c checks all
 * 65,536 pixel values.  Counter 0 counts the unclassified pixels and is
 * dropped.  The locals are uint_fast16_t: 16 bits on the dsPIC, the
 * register width on a host, so neither needs extensions or truncations. */
static void count_column_lut(const uint8_t *rgb565, size_t off, size_t stride, uint16_t height,
                             uint8_t ih, uint8_t il, uint16_t counts[3])
{
    uint16_t by_class[HAL_COLOUR_COUNT] = { 0u, 0u, 0u, 0u };
    const uint8_t *hp = rgb565 + ih;
    const uint8_t *lp = rgb565 + il;
    uint16_t r;

    for (r = height; r != 0u; r--) {
        uint_fast16_t lo = lp[off];
        uint_fast16_t row = BLOB_LUT_READ(&blob_lut_row[((uint_fast16_t)hp[off] << 3) | (lo >> 5)]);
        by_class[BLOB_LUT_READ(&blob_lut_class[row][lo & 0x1Fu])]++;
        off += stride;
    }
    counts[0] = by_class[HAL_COLOUR_RED];
    counts[1] = by_class[HAL_COLOUR_GREEN];
    counts[2] = by_class[HAL_COLOUR_BLUE];
}

/* The same counts with the classifier itself, for any thresholds (about
 * three times the tables' cost in x86-64 instructions, the CPU report's
 * measure). */
static void count_column_generic(const blob_detect_params_t *p, const uint8_t *rgb565,
                                 size_t off, size_t stride, uint16_t height,
                                 uint8_t ih, uint8_t il, uint16_t counts[3])
{
    uint16_t r;

    counts[0] = 0u;
    counts[1] = 0u;
    counts[2] = 0u;
    for (r = height; r != 0u; r--) {
        uint16_t pixel = (uint16_t)((uint16_t)((uint16_t)rgb565[off + ih] << 8) | rgb565[off + il]);
        uint8_t colour = blob_classify_rgb565(p, pixel);
        if (colour != (uint8_t)HAL_COLOUR_NONE) {
            counts[colour - 1u]++;
        }
        off += stride;
    }
}

uint8_t blob_detect(const blob_detect_params_t *p, const uint8_t *rgb565,
                    uint16_t width, uint16_t height,
                    blob_detect_work_t *work, hal_blob_t *out, uint8_t max)
{
    uint16_t min_col;
    size_t stride;
    uint16_t c;
    uint8_t k, n, ih, il;
    int by_table;

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
    ih = (p->byte_order == (uint8_t)BLOB_BYTE_ORDER_LITTLE) ? 1u : 0u;
    il = (uint8_t)(1u - ih);
    by_table = p->min_value == BLOB_LUT_MIN_VALUE && p->min_margin == BLOB_LUT_MIN_MARGIN &&
               p->min_saturation_q8 == BLOB_LUT_MIN_SATURATION_Q8;

    work->count = 0u;
    for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
        work->runs[k].pixels = 0u;
        work->runs[k].weighted = 0u;
        work->runs[k].start = 0u;
    }

    for (c = 0u; c < width; c++) {
        uint16_t counts[HAL_COLOUR_COUNT - 1u];
        size_t off = (size_t)c * 2u;

        if (by_table) {
            count_column_lut(rgb565, off, stride, height, ih, il, counts);
        } else {
            count_column_generic(p, rgb565, off, stride, height, ih, il, counts);
        }
        for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
            blob_detect_run_t *run = &work->runs[k];
            if (counts[k] >= min_col) {
                if (run->pixels == 0u) {
                    run->start = c;
                }
                run->pixels = (uint16_t)(run->pixels + counts[k]);
                /* 16 x 16 -> 32-bit product: one MUL.UU on the dsPIC. */
                run->weighted += (uint32_t)counts[k] * (uint32_t)c;
            } else if (run->pixels != 0u) {
                close_run(p, work, (uint8_t)(k + 1u), width, (uint16_t)(c - 1u));
            }
        }
    }
    for (k = 0u; k < HAL_COLOUR_COUNT - 1u; k++) {
        if (work->runs[k].pixels != 0u) {
            close_run(p, work, (uint8_t)(k + 1u), width, (uint16_t)(width - 1u));
        }
    }

    n = (work->count < max) ? work->count : max;
    for (k = 0u; k < n; k++) {
        out[k] = work->blobs[k];
    }
    return n;
}

/* A pixel's channels expanded to 0..255 as blob_classify_rgb565 expands
 * them (the header), which keeps its own copy inline: a call there costs
 * every image with a camera flash, for the statistics' sake. */
static void expand_rgb565(uint16_t pixel, uint8_t ch[3])
{
    uint8_t r5 = (uint8_t)((pixel >> 11) & 0x1Fu);
    uint8_t g6 = (uint8_t)((pixel >> 5) & 0x3Fu);
    uint8_t b5 = (uint8_t)(pixel & 0x1Fu);
    ch[0] = (uint8_t)((uint8_t)(r5 << 3) | (uint8_t)(r5 >> 2));
    ch[1] = (uint8_t)((uint8_t)(g6 << 2) | (uint8_t)(g6 >> 4));
    ch[2] = (uint8_t)((uint8_t)(b5 << 3) | (uint8_t)(b5 >> 2));
}

/* 1 and pixel k's channels in ch when the statistics of `colour` count it
 * (every pixel for HAL_COLOUR_NONE, else the classifier's), else 0; the
 * pixel assembled from its two bytes in the frame's order. */
static uint8_t counted_pixel(const blob_detect_params_t *p, const uint8_t *rgb565, size_t k, uint8_t colour,
                             uint8_t ch[3])
{
    uint8_t ih = (p->byte_order == (uint8_t)BLOB_BYTE_ORDER_LITTLE) ? 1u : 0u;
    uint16_t px = (uint16_t)((uint16_t)((uint16_t)rgb565[2u * k + ih] << 8) | rgb565[2u * k + (1u - ih)]);
    if (colour != (uint8_t)HAL_COLOUR_NONE && blob_classify_rgb565(p, px) != colour) {
        return 0u;
    }
    expand_rgb565(px, ch);
    return 1u;
}

/* Two passes: the means, then the squared deviations from them, so every
 * sum stays within 32 bits (25,600 x 255^2 < 2^31) and nothing cancels.
 * The 32-bit divisions are library calls on the dsPIC: a frame's statistics
 * are a calibration's, not a control step's. */
int8_t blob_colour_stats(const blob_detect_params_t *p, const uint8_t *rgb565,
                         uint16_t width, uint16_t height, uint8_t colour, hal_colour_stats_t *out)
{
    uint32_t sum[3] = { 0u, 0u, 0u };
    size_t n_px, k;
    uint16_t n = 0u;
    uint8_t ch[3], i;

    if (out == NULL) {
        return -1;
    }
    for (i = 0u; i < 3u; i++) {
        out->mean[i] = 0u;
        out->sd[i] = 0u;
    }
    out->pixels = 0u;
    if (p == NULL || rgb565 == NULL || colour >= (uint8_t)HAL_COLOUR_COUNT ||
        width == 0u || width > BLOB_MAX_WIDTH || height == 0u || height > BLOB_MAX_HEIGHT) {
        return -1;
    }
    n_px = (size_t)width * (size_t)height;
    for (k = 0u; k < n_px; k++) {
        if (counted_pixel(p, rgb565, k, colour, ch) == 0u) {
            continue;
        }
        for (i = 0u; i < 3u; i++) {
            sum[i] += ch[i];
        }
        n++;
    }
    if (n == 0u) {
        return 0;
    }
    for (i = 0u; i < 3u; i++) {
        out->mean[i] = (uint8_t)((sum[i] + n / 2u) / n);
        sum[i] = 0u;
    }
    for (k = 0u; k < n_px; k++) {
        if (counted_pixel(p, rgb565, k, colour, ch) == 0u) {
            continue;
        }
        for (i = 0u; i < 3u; i++) {
            int16_t d = (int16_t)((int16_t)ch[i] - (int16_t)out->mean[i]);
            sum[i] += (uint32_t)((int32_t)d * (int32_t)d);
        }
    }
    for (i = 0u; i < 3u; i++) {
        out->sd[i] = (uint8_t)tone_detect_isqrt(sum[i] / n);
    }
    out->pixels = n;
    return 0;
}
