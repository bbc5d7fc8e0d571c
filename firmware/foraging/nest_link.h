/*
 * nest_link.h - the 16-bit IR messages between foragers and the nest beacon.
 *
 * Seed 000's real-robot experiment used a beacon robot in the nest; ours
 * keeps the nest ledger (F(t), N_W, M_A of eqs 2, 4, 5) and tells waiting
 * robots, which report their deposits and obstacle-avoidance events (OAEs)
 * back.  A frame is one hal_ircom message of 16 bits, so both ends need
 * hal_ircom_payload_bits() == 16 (the range-and-bearing turret).  Over
 * libIrcom's 8 bits the top bits are dropped: every frame then decodes as
 * type 0 (invalid) and is ignored, so nothing wrong is believed.
 *
 * Frame (uint16), bits 15-14 = type:
 *   type 0  invalid (a zero frame is invalid).
 *   type 1  robot -> beacon: bits 13-8 robot id (hal_robot_id & 63),
 *           bits 7-0 the robot's cumulative deposit count mod 256.
 *   type 2  robot -> beacon: bits 13-8 robot id,
 *           bits 7-0 the robot's cumulative OAE count mod 256.
 *   type 3  beacon -> robots: bits 13-12 kind, bits 11-0 value:
 *           kind 0  F(t), nest food, signed 12-bit two's complement in
 *                   1/16 token: -128.0 .. +127.9375 (saturated);
 *           kind 1  N_W, robots waiting in the nest, 0..4095 (saturated);
 *           kind 2  M_A in 1/256 OAE per robot, 0 .. 15.996 (saturated);
 *           kind 3  unused: decodes as invalid.
 *
 * A waiting robot alternates its deposit and OAE totals, one a step; a
 * robot out of the nest sends its OAE total every step, so that a beacon in
 * range counts OAEs about when they happen.  Deposit totals go only from
 * the nest: the beacon counts as waiting (N_W) the ids whose deposit totals
 * it heard within its timeout.
 *
 * Reports carry running totals rather than increments so that a lost
 * message costs nothing: the beacon adds the mod-256 difference from the
 * last total it heard from that id (correct while fewer than 256 events go
 * unheard between two heard reports).  Ids are 6 bits: robots whose ids
 * differ by a multiple of 64 share a ledger slot.
 */
#ifndef FW_NEST_LINK_H
#define FW_NEST_LINK_H

#include <stdint.h>

/** Frame types (bits 15-14). */
typedef enum nest_link_type {
    NL_INVALID = 0,
    NL_DEPOSITS = 1,   /**< robot -> beacon: deposit total mod 256 */
    NL_OAES = 2,       /**< robot -> beacon: OAE total mod 256 */
    NL_BEACON = 3      /**< beacon -> robots: one nest quantity */
} nest_link_type_t;

/** Kinds of beacon frame (bits 13-12 of type 3). */
typedef enum nest_link_kind {
    NL_KIND_FOOD = 0,       /**< F(t) in 1/16 token, signed */
    NL_KIND_WAITING = 1,    /**< N_W, robots */
    NL_KIND_MEAN_OAE = 2,   /**< M_A in 1/256 OAE per robot */
    NL_KIND_COUNT = 3
} nest_link_kind_t;

/** Ranges of the 12-bit beacon values. */
#define NL_FOOD_Q4_MIN (-2048)
#define NL_FOOD_Q4_MAX 2047
#define NL_VALUE_MAX 4095u
/** Ids a report can carry (6 bits). */
#define NL_ID_COUNT 64u

/** A decoded frame. */
typedef struct nest_link_frame {
    uint8_t type;       /**< nest_link_type_t; NL_INVALID if malformed */
    uint8_t kind;       /**< nest_link_kind_t, beacon frames only */
    uint8_t robot_id;   /**< 0..63, report frames only */
    int16_t value;      /**< beacon: food in 1/16 token (signed), N_W, or
                             M_A in 1/256; report: the total mod 256 */
} nest_link_frame_t;

/** Fixed-point scales of the beacon's frames: F(t) in 1/NL_FOOD_PER_TOKEN
 *  token, M_A in 1/NL_MEAN_OAE_PER_UNIT OAE per robot. */
#define NL_FOOD_PER_TOKEN 16
#define NL_MEAN_OAE_PER_UNIT 256

/** Beacon frame of F(t), `food_q4` in 1/16 token, saturated to -2048..2047. */
uint16_t nest_link_encode_food(int32_t food_q4);

/** Beacon frame of N_W (robots), saturated to 4095. */
uint16_t nest_link_encode_waiting(uint16_t n_waiting);

/** Beacon frame of M_A, `mean_oae_q8` in 1/256 OAE per robot, saturated to
 *  4095 (15.996). */
uint16_t nest_link_encode_mean_oae(uint32_t mean_oae_q8);

/** Report frame of a robot's cumulative deposit count (sent mod 256). */
uint16_t nest_link_encode_deposits(uint16_t robot_id, uint32_t deposits);

/** Report frame of a robot's cumulative OAE count (sent mod 256). */
uint16_t nest_link_encode_oaes(uint16_t robot_id, uint32_t oaes);

/** Decodes `frame` into `out` and returns its type (NL_INVALID for type 0
 *  and for beacon kind 3; `out` is then all zero). */
uint8_t nest_link_decode(uint16_t frame, nest_link_frame_t *out);

/** Difference `now - before` of two mod-256 totals: the events between two
 *  reports, 0..255. */
uint8_t nest_link_count_diff(uint8_t now, uint8_t before);

#endif
