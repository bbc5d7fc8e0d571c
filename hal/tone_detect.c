/*
 * tone_detect.c - Goertzel tone detector in fixed point (see tone_detect.h).
 *
 * Ranges, for any int16 input (worst cases, checked by the tests):
 *   x - mean          |.| <= 65535              (int32)
 *   (x - mean) * w    |.| <= 65535 * 32767 < 2^31
 *   windowed sample   |.| <= 4 x 65535 (kept x 4: two bits of precision
 *                     below the A/D count, so that truncation does not
 *                     bias small tones)
 *   state s           |.| <= 4 x 65535 x N / sin(w) <= 5.9e7 < 2^26 for
 *                     the bands of sound_bands.h (sin(w) >= 0.43)
 *   c * s / 2^14      computed as c * (s / 2^14) + c * (s mod 2^14) / 2^14:
 *                     two 16 x 16 -> 32-bit products (one instruction each
 *                     on the dsPIC), no 64-bit arithmetic
 *   c * s / 2^14      |.| <= 2 x 5.9e7
 *   re, im            |.| <= 1.2e8 < 2^27; scaled down to 15 bits before
 *                     squaring.
 */
#include "tone_detect.h"

#define Q14 16384

/* Right shifts of negative values: arithmetic (floor) in GCC, XC16 and
 * every compiler the project uses (C99 leaves it to the implementation;
 * it is not undefined).  A shift, not a division: it is the detector's
 * inner loop, and a signed division by 2^k costs a correction for
 * negative values on every compiler. */

/* c * s / 2^14 (floored) without a 64-bit product: s = hi 2^14 + lo,
 * 0 <= lo < 2^14; |hi| < 2^13 and c * lo < 2^29. */
static int32_t mul_q14(int16_t c, int32_t s)
{
    int32_t lo = (int32_t)((uint32_t)s & (uint32_t)(Q14 - 1));
    int32_t hi = s >> 14;
    return (int32_t)c * hi + (((int32_t)c * lo) >> 14);
}

uint16_t tone_detect_isqrt(uint32_t v)
{
    uint32_t root = 0u;
    uint32_t bit = (uint32_t)1u << 30;
    while (bit > v) {
        bit >>= 2;
    }
    while (bit != 0u) {
        if (v >= root + bit) {
            v -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint16_t)root;
}

/* |re + j im| for |re|, |im| < 2^31: both scaled to below 2^15 first so
 * that the sum of squares fits 32 bits. */
static uint32_t magnitude(int32_t re, int32_t im)
{
    uint32_t a = re < 0 ? (uint32_t)0u - (uint32_t)re : (uint32_t)re;
    uint32_t b = im < 0 ? (uint32_t)0u - (uint32_t)im : (uint32_t)im;
    uint8_t shift = 0u;
    while (a >= 32768u || b >= 32768u) {
        a >>= 1;
        b >>= 1;
        shift++;
    }
    return (uint32_t)tone_detect_isqrt(a * a + b * b) << shift;
}

/* amplitude (Q2) x tone_level_scale_q8 / 256 / 4 without overflowing 32
 * bits. */
static uint32_t to_level(uint32_t amplitude_q2)
{
    uint32_t hi = amplitude_q2 >> 10;
    uint32_t lo = amplitude_q2 & 0x3FFu;
    return hi * tone_level_scale_q8 + ((lo * tone_level_scale_q8) >> 10);
}

void tone_detect_block(const int16_t *samples, const tone_band_coeffs_t *bands, uint8_t n_bands,
                       uint32_t *levels)
{
    int32_t s1[SOUND_BAND_COUNT];
    int32_t s2[SOUND_BAND_COUNT];
    int32_t sum = 0;
    int32_t mean;
    uint16_t i;
    uint8_t b;

    if (n_bands > SOUND_BAND_COUNT) {
        n_bands = SOUND_BAND_COUNT;
    }
    for (i = 0; i < TONE_DETECT_N; i++) {
        sum += samples[i];
    }
    mean = sum / (int32_t)TONE_DETECT_N;
    for (b = 0; b < n_bands; b++) {
        s1[b] = 0;
        s2[b] = 0;
    }
    for (i = 0; i < TONE_DETECT_N; i++) {
        /* windowed, x 4 (Q2): keeps two bits below the A/D's count */
        int32_t x = (((int32_t)samples[i] - mean) * tone_window_q15[i]) >> 13;
        for (b = 0; b < n_bands; b++) {
            int32_t s = x + mul_q14(bands[b].coeff_q14, s1[b]) - s2[b];
            s2[b] = s1[b];
            s1[b] = s;
        }
    }
    for (b = 0; b < n_bands; b++) {
        /* X = s1 - e^{-jw} s2 */
        int32_t re = s1[b] - mul_q14(bands[b].cos_q14, s2[b]);
        int32_t im = mul_q14(bands[b].sin_q14, s2[b]);
        levels[b] = to_level(magnitude(re, im));
    }
}
