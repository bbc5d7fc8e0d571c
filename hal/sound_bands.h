/*
 * sound_bands.h - the tones of the sound bands on the e-puck1, and the
 * sampling rates of its microphones and speaker they are chosen for.
 *
 * Band k (1..3, hal.h's HAL_SOUND_BANDS - 1) is one sine tone.  The
 * simulator does not use frequencies (its sound model is per band); these
 * numbers are for the robot: the speaker tables and the detector's
 * coefficients (hal/tone_tables.c, generated from this file by
 * tools/sound/gen_tone_tables.py: regenerate it after a change here).
 *
 * Why these frequencies (1160, 1960, 2720 Hz):
 *  - all below the speaker codec's Nyquist limit (3600 Hz at 7200 Hz) and
 *    below ~3 kHz, where the codec's reconstruction filter starts to cut
 *    [?]; far below the microphones' Nyquist limit (8192 Hz);
 *  - each a multiple of 40 Hz, so a whole number of periods fits in every
 *    control period that is a multiple of 25 ms (180 speaker samples per
 *    25 ms): the speaker restarts its table at phase 0 every period
 *    without a click;
 *  - 760 to 800 Hz apart: 4.4 to 4.7 bins of the detector's 96-sample
 *    block (170.7 Hz per bin), well outside its Hann window's main lobe
 *    (+-2 bins): the bands' cross-talk is below 1 % (test_tone_detect.c);
 *  - above the steppers' step rate at RepAtt's cruise speed (776 steps/s)
 *    and between its harmonics (1552, 2328, 3104 Hz), 1.6 bins or more
 *    from each; a harmonic of band 1 (2320 Hz) falls between bands 2 and 3.
 *    Motor noise at other speeds sweeps through every band: a level is a
 *    relative measure, compared over time by the controller.
 * The speaker's response at 1160 Hz and the codec clock are not measured
 * on a robot [?]: these are parameters, change them here.
 */
#ifndef SOUND_BANDS_H
#define SOUND_BANDS_H

/** Bands with a tone (band 0 is silence). */
#define SOUND_BAND_COUNT 3u

/** Tone of band 1, Hz (RepAtt: repulsion). */
#define SOUND_BAND1_HZ 1160u
/** Tone of band 2, Hz (RepAtt: attraction). */
#define SOUND_BAND2_HZ 1960u
/** Tone of band 3, Hz (unused by RepAtt). */
#define SOUND_BAND3_HZ 2720u

/** Microphone sampling rate, Hz: the e-puck library's A/D scan
 *  (a_d/advance_ad_scan, e_ad_conv.h MIC_SAMP_FREQ) in ALL_ADC mode, the
 *  mode the HAL starts it in (every channel; MICRO_ONLY would sample the
 *  mics alone at ~33 kHz). */
#define SOUND_MIC_RATE_HZ 16384u
/** Samples per microphone the library keeps (MIC_SAMP_NB): a ring buffer
 *  of 100 samples, 6.1 ms. */
#define SOUND_MIC_RING 100u
/** Speaker sampling rate, Hz: the Si3000 codec's frame rate as the
 *  library's codec module sets it up (e_init_codec_slave.s). */
#define SOUND_SPK_RATE_HZ 7200u

/** Samples the detector analyses per microphone and step: the newest 96 of
 *  the ring (5.86 ms), the 4 oldest left as a margin for the A/D interrupt,
 *  which overwrites the oldest sample every 61 us while the HAL copies. */
#define TONE_DETECT_N 96u

/** Speaker samples per band in the table: 100 ms at 7200 Hz, the longest
 *  control period a tone covers without a gap (the default period). */
#define TONE_SPK_LEN 720u
/** Words per band in the table: one pad word (never played) + TONE_SPK_LEN. */
#define TONE_SPK_STRIDE 721u
/** Peak of the speaker samples (16-bit codec words; about half of full
 *  scale, like the library's own recordings) [?]. */
#define TONE_SPK_AMPLITUDE 16000u

#endif
