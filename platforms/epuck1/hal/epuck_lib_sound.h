/*
 * epuck_lib_sound.h - GCtronic e-puck library, codec module (library/codec/):
 * the speaker through the Si3000 codec, 7200 samples/s.  Declarations only;
 * see epuck_lib.h.
 *
 * e_play_sound(offset, length) starts playing `length` 16-bit words of the
 * library's sound table (the symbol e_sound_sample, normally
 * codec/e_const_sound.s: five recorded voices) from word `offset` on; the
 * DCI interrupt sends them 4 at a time and stops when the count reaches 0.
 * It plays only from that table: it cannot be given a pointer.  Facts the
 * HAL relies on (codec/e_sub_dci_kickoff.s, e_isr_dci.s):
 *  - the pointer is advanced before each word is read: the word AT
 *    `offset` is never played, words offset+1 .. offset+length are;
 *  - `length` must be a multiple of 4: the count drops by 4 per interrupt
 *    and only stops at exactly 0 (otherwise playback runs on through
 *    program memory);
 *  - a new call restarts playback at once (no queue), whether or not the
 *    previous sound has ended.
 * So the e-puck images link OUR table as e_sound_sample instead of the
 * library's (tools/make/firmware.mk: hal/tone_tables.c's
 * tone_speaker_table, by a linker alias), and play band b with
 * e_play_sound((b - 1) * TONE_SPK_STRIDE, length).
 */
#ifndef EPUCK_LIB_SOUND_H
#define EPUCK_LIB_SOUND_H

/* codec/e_sound.h: powers the speaker amplifier and sets up the codec
 * (busy-waits, once, at start). */
void e_init_sound(void);
/* codec/e_sound.h */
void e_play_sound(int sound_offset, int sound_length);

#endif
