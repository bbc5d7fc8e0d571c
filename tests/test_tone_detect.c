/*
 * test_tone_detect.c - CMocka tests of hal/tone_detect (the e-puck's
 * fixed-point Goertzel detector) and of the generated tables of
 * hal/tone_tables.c, on synthetic microphone blocks: each band alone, two
 * tones, noise, silence, clipping and full-scale input (run under UBSan by
 * `make asan-tests`: no overflow), amplitude linearity.  About 0.1 s.
 *
 * Blocks look like the e-puck's A/D: 12-bit counts around an offset of
 * 2048, TONE_DETECT_N samples at SOUND_MIC_RATE_HZ.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "sound_bands.h"
#include "tone_detect.h"
#include "tone_tables.h"

#define PI 3.14159265358979323846
#define N TONE_DETECT_N
#define OFFSET 2048.0
#define NB SOUND_BAND_COUNT
/** Cross-talk bound: a tone at one band's frequency reads below this share
 *  of its own level in every other band. */
#define CROSSTALK 0.01

static const double BAND_HZ[NB] = { SOUND_BAND1_HZ, SOUND_BAND2_HZ, SOUND_BAND3_HZ };

/* A small deterministic generator (xorshift32) for phases and noise. */
static uint32_t rng_state = 12345u;
static uint32_t rnd32(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static double uniform(void) { return (rnd32() >> 8) / 16777216.0; }
static double gauss(void)
{
    double u1 = uniform() + 1e-12, u2 = uniform();
    return sqrt(-2.0 * log(u1)) * cos(2.0 * PI * u2);
}

static int16_t clamp12(double v)
{
    long r = lround(v);
    return (int16_t)(r < 0 ? 0 : (r > 4095 ? 4095 : r));
}

/* block[i] = OFFSET + sum of tones (amplitude, frequency, phase) + noise */
static void make_block(int16_t *block, const double *amp, const double *hz, const double *phase,
                       int tones, double noise_sd)
{
    unsigned i;
    int k;
    for (i = 0; i < N; i++) {
        double v = OFFSET;
        for (k = 0; k < tones; k++) {
            v += amp[k] * sin(2.0 * PI * hz[k] * i / SOUND_MIC_RATE_HZ + phase[k]);
        }
        if (noise_sd > 0.0) {
            v += noise_sd * gauss();
        }
        block[i] = clamp12(v);
    }
}

static void levels_of(const int16_t *block, uint32_t *lv)
{
    tone_detect_block(block, tone_band_coeffs, (uint8_t)NB, lv);
}

static void test_tables_match_their_definition(void **state)
{
    (void)state;
    unsigned i, b;
    double wsum = 0.0;
    for (i = 0; i < N; i++) {
        double w = 32767.0 * (0.5 - 0.5 * cos(2.0 * PI * i / (N - 1)));
        assert_true(fabs(tone_window_q15[i] - w) <= 0.5 + 1e-9);
        wsum += tone_window_q15[i];
    }
    assert_true(fabs(tone_level_scale_q8 - 2000.0 * 32768.0 / wsum * 256.0) <= 0.5 + 1e-9);
    for (b = 0; b < NB; b++) {
        double om = 2.0 * PI * BAND_HZ[b] / SOUND_MIC_RATE_HZ;
        assert_true(BAND_HZ[b] < SOUND_SPK_RATE_HZ / 2.0);          /* below the codec's Nyquist */
        assert_true(fabs(tone_band_coeffs[b].coeff_q14 - 2.0 * cos(om) * 16384.0) <= 0.5 + 1e-9);
        assert_true(fabs(tone_band_coeffs[b].cos_q14 - cos(om) * 16384.0) <= 0.5 + 1e-9);
        assert_true(fabs(tone_band_coeffs[b].sin_q14 - sin(om) * 16384.0) <= 0.5 + 1e-9);
        /* the overflow bound of tone_detect.c assumes sin(w) >= 0.43 */
        assert_true(sin(om) >= 0.43);
        /* speaker: pad word, then a whole number of periods */
        assert_int_equal(tone_speaker_table[b][0], 0);
        assert_int_equal(((unsigned long)BAND_HZ[b] * TONE_SPK_LEN) % SOUND_SPK_RATE_HZ, 0);
        /* ... and a whole number in 25 ms (180 samples): seamless restarts */
        assert_int_equal(((unsigned long)BAND_HZ[b] * 180u) % SOUND_SPK_RATE_HZ, 0);
        for (i = 0; i < TONE_SPK_LEN; i++) {
            double v = TONE_SPK_AMPLITUDE * sin(2.0 * PI * BAND_HZ[b] * i / SOUND_SPK_RATE_HZ);
            assert_true(fabs(tone_speaker_table[b][i + 1u] - v) <= 0.5 + 1e-9);
        }
    }
    assert_int_equal(TONE_SPK_STRIDE, TONE_SPK_LEN + 1u);
    assert_true(N <= SOUND_MIC_RING);
}

static void test_each_band_alone(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    unsigned b, o, rep;
    double worst = 0.0;
    for (b = 0; b < NB; b++) {
        for (rep = 0; rep < 20; rep++) {
            double a = 500.0, ph = 2.0 * PI * uniform();
            make_block(block, &a, &BAND_HZ[b], &ph, 1, 0.0);
            levels_of(block, lv);
            assert_true(fabs(lv[b] - 500000.0) < 0.02 * 500000.0);
            for (o = 0; o < NB; o++) {
                if (o != b) {
                    double r = (double)lv[o] / lv[b];
                    worst = r > worst ? r : worst;
                    assert_true(r < CROSSTALK);
                }
            }
        }
    }
    print_message("tone_detect: worst cross-talk between bands %.4f %% (bound %.1f %%)\n",
                  100.0 * worst, 100.0 * CROSSTALK);
}

static void test_two_tones(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    unsigned rep;
    for (rep = 0; rep < 20; rep++) {
        double a[2] = { 800.0, 200.0 };
        double hz[2] = { SOUND_BAND1_HZ, SOUND_BAND2_HZ };
        double ph[2] = { 2.0 * PI * uniform(), 2.0 * PI * uniform() };
        make_block(block, a, hz, ph, 2, 0.0);
        levels_of(block, lv);
        assert_true(fabs(lv[0] - 800000.0) < 0.03 * 800000.0);
        assert_true(fabs(lv[1] - 200000.0) < 0.03 * 200000.0 + 0.01 * 800000.0);
        assert_true(lv[2] < CROSSTALK * 800000.0);
        /* bands 2 and 3 together, the louder one second */
        hz[0] = SOUND_BAND2_HZ;
        hz[1] = SOUND_BAND3_HZ;
        a[0] = 150.0;
        a[1] = 1500.0;
        make_block(block, a, hz, ph, 2, 0.0);
        levels_of(block, lv);
        assert_true(fabs(lv[1] - 150000.0) < 0.03 * 150000.0 + CROSSTALK * 1500000.0);
        assert_true(fabs(lv[2] - 1500000.0) < 0.03 * 1500000.0);
        assert_true(lv[0] < CROSSTALK * 1500000.0);
    }
}

static void test_silence_reads_zero(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    unsigned i;
    int16_t dc[] = { 0, 2048, 4095, -32768, 32767 };
    for (i = 0; i < sizeof dc / sizeof dc[0]; i++) {
        unsigned k;
        for (k = 0; k < N; k++) {
            block[k] = dc[i];
        }
        levels_of(block, lv);
        assert_int_equal(lv[0], 0);
        assert_int_equal(lv[1], 0);
        assert_int_equal(lv[2], 0);
    }
}

/* White noise of sd sigma: mean level ~ 2000 sqrt(pi/4) sigma sqrt(sum w^2)
 * / sum w (Rayleigh), ~ 1000 x 2.2 sigma / sqrt(N) for a Hann window. */
static void test_noise_level(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    double sum[NB] = { 0.0, 0.0, 0.0 }, w2 = 0.0, w1 = 0.0, expect;
    unsigned i, b, rep, reps = 400;
    double sigma = 60.0;
    for (i = 0; i < N; i++) {
        w1 += tone_window_q15[i] / 32768.0;
        w2 += (tone_window_q15[i] / 32768.0) * (tone_window_q15[i] / 32768.0);
    }
    expect = 2000.0 * sqrt(PI / 4.0) * sigma * sqrt(w2) / w1;
    for (rep = 0; rep < reps; rep++) {
        make_block(block, NULL, NULL, NULL, 0, sigma);
        levels_of(block, lv);
        for (b = 0; b < NB; b++) {
            sum[b] += lv[b];
        }
    }
    for (b = 0; b < NB; b++) {
        double mean = sum[b] / reps;
        assert_true(fabs(mean - expect) < 0.10 * expect);
    }
    print_message("tone_detect: noise sd %.0f counts reads %.0f (expected %.0f) = 1000 x %.2f sd / sqrt(N)\n",
                  sigma, sum[0] / reps, expect, expect / 1000.0 / sigma * sqrt((double)N));
    /* a tone of the noise's sd stands out: its level is ~4.5x the noise's */
    {
        double a = sigma, ph = 0.3, tone = 0.0, none = 0.0;
        for (rep = 0; rep < reps; rep++) {
            make_block(block, &a, &BAND_HZ[1], &ph, 1, sigma);
            levels_of(block, lv);
            tone += lv[1];
            none += lv[0];
        }
        assert_true(tone / reps > 3.0 * (none / reps));
    }
}

static void test_clipping_and_full_scale(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    unsigned i, b, rep;
    /* a tone clipped by the 12-bit A/D: still its band, the loudest */
    for (b = 0; b < NB; b++) {
        double a = 4000.0, ph = 0.7;
        make_block(block, &a, &BAND_HZ[b], &ph, 1, 0.0);
        levels_of(block, lv);
        for (i = 0; i < NB; i++) {
            if (i != b) {
                assert_true(lv[i] < lv[b] / 10u);
            }
        }
        assert_true(lv[b] > 2000000u);
    }
    /* full-scale int16 square waves at each band: the largest state */
    for (b = 0; b < NB; b++) {
        for (i = 0; i < N; i++) {
            block[i] = sin(2.0 * PI * BAND_HZ[b] * i / SOUND_MIC_RATE_HZ) >= 0.0 ? 32767 : -32768;
        }
        levels_of(block, lv);
        assert_true(lv[b] > 40000000u);   /* 1000 x 4/pi x 32767, give or take the window */
        print_message("tone_detect: full-scale square wave at band %u reads %lu\n", b + 1u,
                      (unsigned long)lv[b]);
    }
    /* the extremes alternating, half full scale, random full-scale input */
    for (i = 0; i < N; i++) {
        block[i] = (i & 1u) ? 32767 : -32768;
    }
    levels_of(block, lv);
    for (i = 0; i < N; i++) {
        block[i] = (i < N / 2u) ? 32767 : -32768;
    }
    levels_of(block, lv);
    for (rep = 0; rep < 200; rep++) {
        for (i = 0; i < N; i++) {
            block[i] = (int16_t)(uint16_t)rnd32();
        }
        levels_of(block, lv);
    }
    /* fewer bands than the table: only those written */
    lv[1] = 77u;
    lv[2] = 77u;
    tone_detect_block(block, tone_band_coeffs, 1u, lv);
    assert_int_equal(lv[1], 77u);
    assert_int_equal(lv[2], 77u);
}

static void test_amplitude_linearity(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    static const double amps[] = { 5.0, 20.0, 100.0, 400.0, 1000.0, 2000.0 };
    unsigned i, b;
    for (b = 0; b < NB; b++) {
        for (i = 0; i < sizeof amps / sizeof amps[0]; i++) {
            double ph = 1.1 + i, per;
            make_block(block, &amps[i], &BAND_HZ[b], &ph, 1, 0.0);
            levels_of(block, lv);
            per = lv[b] / amps[i];
            /* 1000 counts per A/D count of amplitude: within 1 % from
             * 100 counts up; below, the block's own rounding to whole
             * counts (+-0.5) costs up to 3 % at 20 counts, 8 % at 5 */
            assert_true(fabs(per - 1000.0) < (amps[i] < 10.0 ? 80.0 : amps[i] < 50.0 ? 30.0 : 10.0));
        }
    }
}

static void test_off_frequency_falls(void **state)
{
    (void)state;
    int16_t block[N];
    uint32_t lv[NB];
    double a = 1000.0, ph = 0.2, hz;
    double bin = (double)SOUND_MIC_RATE_HZ / N;
    /* 1 bin away: about half; 2 bins: the window's first zero; 2.5 bins:
     * its first sidelobe, -31 dB (< 3 %) */
    hz = SOUND_BAND2_HZ + 1.0 * bin;
    make_block(block, &a, &hz, &ph, 1, 0.0);
    levels_of(block, lv);
    assert_true(lv[1] > 450000u && lv[1] < 560000u);
    hz = SOUND_BAND2_HZ + 2.0 * bin;
    make_block(block, &a, &hz, &ph, 1, 0.0);
    levels_of(block, lv);
    assert_true(lv[1] < 10000u);
    hz = SOUND_BAND2_HZ + 2.5 * bin;
    make_block(block, &a, &hz, &ph, 1, 0.0);
    levels_of(block, lv);
    assert_true(lv[1] < 30000u);
    /* half a bin away: still most of it */
    hz = SOUND_BAND2_HZ + 0.5 * bin;
    make_block(block, &a, &hz, &ph, 1, 0.0);
    levels_of(block, lv);
    assert_true(lv[1] > 700000u && lv[1] < 1000000u);
}

static void test_isqrt(void **state)
{
    (void)state;
    uint32_t v;
    assert_int_equal(tone_detect_isqrt(0u), 0u);
    assert_int_equal(tone_detect_isqrt(1u), 1u);
    assert_int_equal(tone_detect_isqrt(3u), 1u);
    assert_int_equal(tone_detect_isqrt(4u), 2u);
    assert_int_equal(tone_detect_isqrt(0xFFFFFFFFu), 65535u);
    assert_int_equal(tone_detect_isqrt(65535u * 65535u), 65535u);
    assert_int_equal(tone_detect_isqrt(65535u * 65535u - 1u), 65534u);
    for (v = 0; v < 2000u; v++) {
        uint32_t x = rnd32();
        uint32_t r = tone_detect_isqrt(x);
        assert_true((uint64_t)r * r <= x && (uint64_t)(r + 1u) * (r + 1u) > x);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tables_match_their_definition),
        cmocka_unit_test(test_each_band_alone),
        cmocka_unit_test(test_two_tones),
        cmocka_unit_test(test_silence_reads_zero),
        cmocka_unit_test(test_noise_level),
        cmocka_unit_test(test_clipping_and_full_scale),
        cmocka_unit_test(test_amplitude_linearity),
        cmocka_unit_test(test_off_frequency_falls),
        cmocka_unit_test(test_isqrt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
