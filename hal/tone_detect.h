/*
 * tone_detect.h - how loud each sound band is in a block of microphone
 * samples: a fixed-point Goertzel filter per band (Q14 coefficients, 32-bit
 * state), one pass over the block for all bands.
 *
 * Platform-neutral robot code: integer only (no FPU, no float), correct
 * with 16-bit int, no allocation, no static state (the caller's stack holds
 * 2 x 4 bytes per band).  platforms/epuck1/hal runs it on the newest TONE_DETECT_N
 * samples of each microphone (hal/sound_bands.h).
 *
 * The block: TONE_DETECT_N samples of one microphone, oldest first, any
 * int16 values (the e-puck's A/D gives 0..4095 with the microphone's offset
 * near the middle).  Its mean is removed (the offset), then a Hann window
 * (tone_window_q15) confines each tone to +-2 bins of 16384 / 96 =
 * 170.7 Hz, so the bands (760 Hz or more apart) do not leak into each
 * other.
 *
 * Level counts: level = 1000 x the peak amplitude, in A/D counts, of a tone
 * at the band's frequency (a tone of amplitude 100 counts reads 100,000).
 * Within 1 % from 100 counts of amplitude up (the block's own rounding to
 * whole counts costs 3 % at 20 counts, 8 % at 5).  Off the band's
 * frequency the level falls: ~51 % at 1 bin (171 Hz) away, ~0 at 2 bins,
 * then the Hann window's sidelobes, below 3 % (-31 dB) and falling 18 dB
 * per octave: a tone at another band's frequency reads below 0.5 % of its
 * own level (the cross-talk; test bound 1 %).  White noise of standard
 * deviation sigma counts reads on average 1000 x 2.2 sigma / sqrt(N) =
 * 222 sigma (Rayleigh mean of the window's noise bandwidth); silence, any
 * constant, reads 0.
 *
 * Overflow: for every input (full int16 range, clipping included) the
 * state stays below 2^26 and every product below 2^31 (tests/
 * test_tone_detect.c drives it with full-scale input under UBSan).  A
 * full-scale int16 square wave at a band reads about 4.2e7; the largest
 * possible level is below 2^32.
 */
#ifndef TONE_DETECT_H
#define TONE_DETECT_H

#include <stdint.h>

#include "tone_tables.h"

/** Levels of `n_bands` bands (coefficients `bands[0..n_bands-1]`, at most
 *  SOUND_BAND_COUNT) in the block `samples[0..TONE_DETECT_N-1]`, into
 *  `levels[0..n_bands-1]` (level counts, see above). */
void tone_detect_block(const int16_t *samples, const tone_band_coeffs_t *bands, uint8_t n_bands,
                       uint32_t *levels);

/** floor(sqrt(v)), for any 32-bit v. */
uint16_t tone_detect_isqrt(uint32_t v);

#endif
