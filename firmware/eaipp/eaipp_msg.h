/*
 * eaipp_msg.h - the 16-bit range-and-bearing messages of EAIPP (seed 003).
 *
 * The paper's robots (marXbots, a range-and-bearing radio) broadcast their
 * state, gradient value, Source_Type, Root_ID, Flag_Contraction and id.  The
 * e-puck's range-and-bearing turret (e-RandB) carries 16 data bits a
 * message, so the fields go in several message kinds that a robot sends in
 * turn (eaipp.c: one or more a control period, as many as the platform
 * takes).  Every message carries the sender's id, so that a receiver files
 * each field under the right neighbour (neighbours.h) and gets the sender's
 * range and bearing from every message, whatever its kind.
 *
 * Frame (uint16):
 *   bits 15-9  sender id, 0..127 (hal_robot_id & 127: robots whose ids
 *              differ by a multiple of 128 are one neighbour to a receiver)
 *   bits  8-7  kind
 *   kind 0  STATE     bits 6-4 state (eaipp_msg_state_t, 0..5; 6 and 7 are
 *                     invalid), bit 3 Source_Type (0 nest, 1 food), bit 2
 *                     Flag_Contraction, bits 1-0 zero (else invalid)
 *   kind 1  GRADIENT  bit 6 Source_Type, bits 5-0 gradient value 0..62;
 *                     63 is GRADIENT_MAX ("no gradient")
 *   kind 2  ROOT      bits 6-0 Root_ID, 0..127
 *   kind 3  EXIT      bits 6-0 the sender's distance to the nest in units
 *                     of EAIPP_MSG_EXIT_MM (20 mm: 0..2.52 m), 127 unknown:
 *                     section 5.1's "exiting" robots of the maze's waiting
 *                     area broadcast it (Lennard-Jones exit)
 *
 * The gradient is 6 bits: a chain of 62 hops at 0.7 R is 26 m at R = 0.6 m,
 * far beyond the arenas (5 x 5 m, and the maze's half-scale 5 x 5 m).  The
 * gradient and its Source_Type share a frame so that a receiver never pairs
 * a new value with an old source.
 */
#ifndef FW_EAIPP_MSG_H
#define FW_EAIPP_MSG_H

#include <stdint.h>

/** Message kinds (bits 8-7). */
typedef enum eaipp_msg_kind {
    EAIPP_MSG_STATE = 0,
    EAIPP_MSG_GRADIENT = 1,
    EAIPP_MSG_ROOT = 2,
    EAIPP_MSG_EXIT = 3,
    EAIPP_MSG_KIND_COUNT = 4
} eaipp_msg_kind_t;

/** What a robot is, as its STATE frames say. */
typedef enum eaipp_msg_state {
    EAIPP_ST_LOST = 0,      /**< Robot_Lost */
    EAIPP_ST_EXPLORER = 1,  /**< Robot_Explorer */
    EAIPP_ST_NODE = 2,      /**< Robot_Node */
    EAIPP_ST_NEST = 3,      /**< Robot_Nest, a fixed gradient source */
    EAIPP_ST_FOOD = 4,      /**< Robot_Food, a fixed gradient source */
    EAIPP_ST_EXITING = 5,   /**< leaving the maze's waiting area (section 5.1) */
    EAIPP_ST_COUNT = 6
} eaipp_msg_state_t;

/** Source_Type: which source a gradient value counts hops from. */
#define EAIPP_SOURCE_NEST 0u
#define EAIPP_SOURCE_FOOD 1u

/** Ids a frame carries (7 bits). */
#define EAIPP_MSG_ID_COUNT 128u
/** The largest gradient value a frame carries; GRADIENT_MAX means none. */
#define EAIPP_GRADIENT_LAST 62u
#define EAIPP_GRADIENT_MAX 63u
/** EXIT frames: distance unit, and the value that means "unknown". */
#define EAIPP_MSG_EXIT_MM 20u
#define EAIPP_MSG_EXIT_UNKNOWN 127u

/** A decoded frame: the fields of its kind, the others zero. */
typedef struct eaipp_msg {
    uint8_t valid;        /**< 1 if the frame is well formed */
    uint8_t id;           /**< sender id, 0..127 */
    uint8_t kind;         /**< eaipp_msg_kind_t */
    uint8_t state;        /**< STATE: eaipp_msg_state_t */
    uint8_t source;       /**< STATE, GRADIENT: EAIPP_SOURCE_* */
    uint8_t contraction;  /**< STATE: Flag_Contraction, 0 or 1 */
    uint8_t gradient;     /**< GRADIENT: 0..62, or EAIPP_GRADIENT_MAX */
    uint8_t root;         /**< ROOT: Root_ID, 0..127 */
    uint8_t exit_units;   /**< EXIT: distance to the nest / 20 mm, 127 unknown */
} eaipp_msg_t;

uint16_t eaipp_msg_state(uint16_t id, uint8_t state, uint8_t source, uint8_t contraction);
/** `gradient` above EAIPP_GRADIENT_LAST is sent as EAIPP_GRADIENT_MAX. */
uint16_t eaipp_msg_gradient(uint16_t id, uint8_t source, uint8_t gradient);
uint16_t eaipp_msg_root(uint16_t id, uint16_t root_id);
/** `distance_mm` rounded to 20 mm units, saturated at 126; `known` 0 sends 127. */
uint16_t eaipp_msg_exit(uint16_t id, uint16_t distance_mm, uint8_t known);

/** Decodes `frame` into `out`; returns out->valid. */
uint8_t eaipp_msg_decode(uint16_t frame, eaipp_msg_t *out);

#endif
