/*
 * tsasr_msg.h - TSASR's chain signalling as 16-bit range-and-bearing turret
 * messages (firmware/tsasr/tsasr.h).
 *
 * TSASR (Luo, Guo, Ye et al., IJARS 17(3), 2020) builds on robot chains in
 * the manner of PFIAS (firmware/pfias/): a chain member shows one of three
 * colours in turn from the nest outwards, so that a robot perceiving two
 * consecutive members knows which way the nest is.  As for PFIAS
 * (pfias_msg.h) each robot broadcasts, once per control period, what its
 * lights would show, and the turret gives range and bearing; the receiver
 * ignores frames from beyond the perception radius R.  What TSASR adds to
 * the frame is the elimination mechanism's flag (docs/notes/i15_tsasr.md:
 * a reconstruction): a member that is being eliminated says so, so that
 * explorers do not extend it and its predecessor can follow it.
 *
 * Frame (uint16), bits 15-13 = kind:
 *   kind 0  invalid (a zero frame is invalid).
 *   kind 1  NEST      "I am the nest":  bits 7-0 sender id & 255.
 *   kind 2  FOOD      "I am the food" (the target): bits 7-0 id.
 *   kind 3  EXPLORER  bits 7-0 id.
 *   kind 4  CHAIN     a chain member: bits 12-11 colour (0 blue, 1 green,
 *                     2 red; 3 is invalid), bit 10 tail (no successor in
 *                     view), bit 9 prey (this member perceives the
 *                     target), bit 8 retreat (this member is being
 *                     eliminated), bits 7-0 id.
 *   kinds 5-7 unused: decode as invalid.
 * Bits a kind does not use are zero; a frame with any of them set is
 * invalid.  Over libIrcom's 8 bits the kind bits are dropped and every
 * frame decodes as invalid.
 *
 * PFIAS's codec writes and reads this format too (pfias_msg.h,
 * PFIAS_FMT_RETREAT): the names below are its, for TSASR.
 */
#ifndef FW_TSASR_MSG_H
#define FW_TSASR_MSG_H

#include <stdint.h>

#include "pfias/pfias_msg.h"

typedef pfias_kind_t tsasr_kind_t;
#define TSASR_MSG_INVALID PFIAS_MSG_INVALID
#define TSASR_MSG_NEST PFIAS_MSG_NEST
#define TSASR_MSG_FOOD PFIAS_MSG_FOOD
#define TSASR_MSG_EXPLORER PFIAS_MSG_EXPLORER
#define TSASR_MSG_CHAIN PFIAS_MSG_CHAIN

/** The three colours of the chain's cyclic pattern, in order from the nest. */
#define TSASR_COLOURS PFIAS_COLOURS
#define TSASR_BLUE PFIAS_BLUE
#define TSASR_GREEN PFIAS_GREEN
#define TSASR_RED PFIAS_RED

/** Ids a frame carries (8 bits). */
#define TSASR_ID_MASK 0x00FFu

/** A decoded frame (its `retreat`: chain frames, 1 = being eliminated;
 *  its `id`: sender id & 255). */
typedef pfias_msg_t tsasr_msg_t;

uint16_t tsasr_msg_nest(uint16_t id);
uint16_t tsasr_msg_food(uint16_t id);
uint16_t tsasr_msg_explorer(uint16_t id);
/** Chain frame; a colour above 2 is reduced mod 3. */
uint16_t tsasr_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey, uint8_t retreat);

/** Decodes `frame` into `out` and returns its kind (TSASR_MSG_INVALID, with
 *  `out` all zero, for anything malformed). */
uint8_t tsasr_msg_decode(uint16_t frame, tsasr_msg_t *out);

/** The colour that follows `colour` away from the nest (0 -> 1 -> 2 -> 0),
 *  and the one that precedes it (towards the nest): PFIAS's. */
#define tsasr_next_colour pfias_next_colour
#define tsasr_prev_colour pfias_prev_colour

#endif
