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
 */
#ifndef FW_TSASR_MSG_H
#define FW_TSASR_MSG_H

#include <stdint.h>

typedef enum tsasr_kind {
    TSASR_MSG_INVALID = 0,
    TSASR_MSG_NEST = 1,
    TSASR_MSG_FOOD = 2,
    TSASR_MSG_EXPLORER = 3,
    TSASR_MSG_CHAIN = 4
} tsasr_kind_t;

/** The three colours of the chain's cyclic pattern, in order from the nest. */
#define TSASR_COLOURS 3u
#define TSASR_BLUE 0u
#define TSASR_GREEN 1u
#define TSASR_RED 2u

/** Ids a frame carries (8 bits). */
#define TSASR_ID_MASK 0x00FFu

/** A decoded frame. */
typedef struct tsasr_msg {
    uint8_t kind;     /**< tsasr_kind_t; TSASR_MSG_INVALID if malformed */
    uint8_t colour;   /**< chain frames: 0..2 */
    uint8_t tail;     /**< chain frames: 1 = no successor in view */
    uint8_t prey;     /**< chain frames: 1 = perceives the target */
    uint8_t retreat;  /**< chain frames: 1 = being eliminated */
    uint16_t id;      /**< sender id & 255 */
} tsasr_msg_t;

uint16_t tsasr_msg_nest(uint16_t id);
uint16_t tsasr_msg_food(uint16_t id);
uint16_t tsasr_msg_explorer(uint16_t id);
/** Chain frame; a colour above 2 is reduced mod 3. */
uint16_t tsasr_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey, uint8_t retreat);

/** Decodes `frame` into `out` and returns its kind (TSASR_MSG_INVALID, with
 *  `out` all zero, for anything malformed). */
uint8_t tsasr_msg_decode(uint16_t frame, tsasr_msg_t *out);

/** The colour that follows `colour` away from the nest (0 -> 1 -> 2 -> 0). */
uint8_t tsasr_next_colour(uint8_t colour);
/** The colour that precedes `colour` (towards the nest). */
uint8_t tsasr_prev_colour(uint8_t colour);

#endif
