/*
 * pfias_msg.h - PFIAS's chain signalling as 16-bit range-and-bearing
 * turret messages.
 *
 * In Nouyan, Campo and Dorigo's path formation (PFIAS, Swarm Intelligence
 * 2008) the s-bots signal with coloured LEDs seen by an omnidirectional
 * camera: a chain member lights one of three colours (blue, green, red in
 * turn from the nest outwards), so that a robot seeing two consecutive
 * members knows which way the nest is; the nest and the prey show colours
 * of their own (the nest blue, the prey red on the swarm-bots pages;
 * docs/notes/i15_baselines.md).  The e-puck's front camera sees 40 x 20
 * pixels over ~56 degrees and cannot tell eight neighbours' colours all
 * round, so here each robot broadcasts what its LEDs would show, once per
 * control period, and the turret gives range and bearing: "I see a green
 * chain member at 0.45 m, 30 degrees left" becomes "I heard a chain frame
 * of colour 1 from 450 mm at +524 mrad".  Perception is limited to the
 * paper's radius R by the receiver (pfias_params_t.range_mm), not by the
 * turret's longer reach.
 *
 * Frame (uint16), bits 15-13 = kind:
 *   kind 0  invalid (a zero frame is invalid).
 *   kind 1  NEST      "I am the nest":  bits 8-0 sender id & 511.
 *   kind 2  FOOD      "I am the food" (the paper's prey): bits 8-0 id.
 *   kind 3  EXPLORER  bits 8-0 id.
 *   kind 4  CHAIN     a chain member: bits 12-11 colour (0 blue, 1 green,
 *                     2 red; 3 is invalid), bit 10 tail (no successor in
 *                     view), bit 9 prey (this member perceives the food),
 *                     bits 8-0 id.
 *   kinds 5-7 unused: decode as invalid.
 * Bits a kind does not use are zero; a frame with any of them set is
 * invalid (so that a stray frame of another controller's codec is not
 * believed).  Over libIrcom's 8 bits the kind bits are dropped and every
 * frame decodes as invalid.
 *
 * The codec also writes TSASR's frames (firmware/tsasr/tsasr_msg.h, the
 * format PFIAS_FMT_RETREAT): the same layout with bit 8 the elimination's
 * retreat flag (chain frames), and so 8-bit ids.  The chain controller
 * (pfias.c) sends and reads the format of its params' `elim`.
 */
#ifndef FW_PFIAS_MSG_H
#define FW_PFIAS_MSG_H

#include <stdint.h>

typedef enum pfias_kind {
    PFIAS_MSG_INVALID = 0,
    PFIAS_MSG_NEST = 1,
    PFIAS_MSG_FOOD = 2,
    PFIAS_MSG_EXPLORER = 3,
    PFIAS_MSG_CHAIN = 4
} pfias_kind_t;

/** The three colours of the chain's cyclic pattern, in order from the nest. */
#define PFIAS_COLOURS 3u
#define PFIAS_BLUE 0u
#define PFIAS_GREEN 1u
#define PFIAS_RED 2u

/** Ids a frame carries (9 bits). */
#define PFIAS_ID_MASK 0x01FFu

/** Frame formats: PFIAS's, and TSASR's (bit 8 the retreat flag, 8-bit ids). */
#define PFIAS_FMT_PFIAS 0u
#define PFIAS_FMT_RETREAT 1u

/** A decoded frame. */
typedef struct pfias_msg {
    uint8_t kind;     /**< pfias_kind_t; PFIAS_MSG_INVALID if malformed */
    uint8_t colour;   /**< chain frames: 0..2 */
    uint8_t tail;     /**< chain frames: 1 = last member of its chain */
    uint8_t prey;     /**< chain frames: 1 = perceives the food */
    uint8_t retreat;  /**< chain frames of PFIAS_FMT_RETREAT: 1 = being eliminated (else 0) */
    uint16_t id;      /**< sender id & 511 (PFIAS_FMT_RETREAT: & 255) */
} pfias_msg_t;

uint16_t pfias_msg_nest(uint16_t id);
uint16_t pfias_msg_food(uint16_t id);
uint16_t pfias_msg_explorer(uint16_t id);
/** Chain frame; a colour above 2 is reduced mod 3. */
uint16_t pfias_msg_chain(uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey);

/** Decodes `frame` into `out` and returns its kind (PFIAS_MSG_INVALID, with
 *  `out` all zero, for anything malformed). */
uint8_t pfias_msg_decode(uint16_t frame, pfias_msg_t *out);

/** The codec of either format `fmt` (PFIAS_FMT_*): a NEST, FOOD or EXPLORER
 *  frame of `kind`; a chain frame (`retreat` is sent in PFIAS_FMT_RETREAT
 *  only); the decoder, as pfias_msg_decode. */
uint16_t pfias_fmt_frame(uint8_t fmt, uint8_t kind, uint16_t id);
uint16_t pfias_fmt_chain(uint8_t fmt, uint16_t id, uint8_t colour, uint8_t tail, uint8_t prey,
                         uint8_t retreat);
uint8_t pfias_fmt_decode(uint8_t fmt, uint16_t frame, pfias_msg_t *out);
/** `id` as frames of format `fmt` carry it. */
uint16_t pfias_fmt_id(uint8_t fmt, uint16_t id);

/** The colour that follows `colour` away from the nest (0 -> 1 -> 2 -> 0). */
uint8_t pfias_next_colour(uint8_t colour);
/** The colour that precedes `colour` (towards the nest). */
uint8_t pfias_prev_colour(uint8_t colour);

#endif
