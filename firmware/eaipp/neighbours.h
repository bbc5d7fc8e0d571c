/*
 * neighbours.h - what a robot knows of the robots it hears (EAIPP, seed 003):
 * one entry per sender id with the last range and bearing the turret
 * measured and the last value heard of each field of eaipp_msg.h, and how
 * many control periods ago the sender was last heard.
 *
 * A robot not heard for `timeout` periods is forgotten (neighbours_age),
 * so that a robot which left, stopped sending or went out of range stops
 * counting as a node, an explorer or a parent.  The table is bounded
 * (NEIGHBOURS_MAX entries, 12 bytes each): when it is full, a frame of a
 * node or a source (a STATE saying so, a GRADIENT or a ROOT) replaces the
 * moving robot (lost, explorer, exiting) heard longest ago, if any; any
 * other new sender replaces the moving robot heard longest ago, if not heard
 * this period; a node's frame then replaces the entry heard longest ago if
 * not heard this period; otherwise the frame is dropped.
 *
 * Fields arrive in different message kinds; `heard` says which have arrived
 * since the entry was made (NB_HEARD_*), so that a neighbour whose state is
 * known but whose gradient is not yet is not taken for one with gradient 0.
 */
#ifndef FW_EAIPP_NEIGHBOURS_H
#define FW_EAIPP_NEIGHBOURS_H

#include <stdint.h>

#include "eaipp/eaipp_msg.h"

/** Most robots a table holds (the paper's neighbourhoods at 0.7 R spacing
 *  hold a handful of nodes; explorers crowd around branch ends). */
#define NEIGHBOURS_MAX 16u

/** Bits of neighbour_t.heard. */
#define NB_HEARD_STATE 0x01u
#define NB_HEARD_GRADIENT 0x02u
#define NB_HEARD_ROOT 0x04u
#define NB_HEARD_EXIT 0x08u

typedef struct neighbour {
    uint8_t id;            /**< sender id, 0..127 */
    uint8_t age;           /**< control periods since last heard (0: this one) */
    uint8_t heard;         /**< NB_HEARD_* bits */
    uint8_t state;         /**< eaipp_msg_state_t */
    uint8_t flags;         /**< bit 0 Source_Type of the STATE frame, bit 1
                                Flag_Contraction, bit 2 Source_Type of the
                                GRADIENT frame */
    uint8_t gradient;      /**< 0..62 or EAIPP_GRADIENT_MAX */
    uint8_t root;          /**< Root_ID */
    uint8_t exit_units;    /**< EXIT: distance to the nest / 20 mm */
    uint16_t range_mm;     /**< last measured range */
    int16_t bearing_mrad;  /**< last measured bearing, CCW positive */
} neighbour_t;

#define NB_FLAG_STATE_SOURCE 0x01u
#define NB_FLAG_CONTRACTION 0x02u
#define NB_FLAG_GRADIENT_SOURCE 0x04u

typedef struct neighbours {
    neighbour_t n[NEIGHBOURS_MAX];
    uint8_t count;
} neighbours_t;

void neighbours_clear(neighbours_t *t);

/** Files the decoded frame `m` (valid) heard at `range_mm`, `bearing_mrad`
 *  under its sender; returns the entry, or 0 (NULL) when the table is full
 *  of robots heard this period. */
neighbour_t *neighbours_hear(neighbours_t *t, const eaipp_msg_t *m, uint16_t range_mm,
                             int16_t bearing_mrad);

/** One control period passes: every entry ages by one and those not heard
 *  for `timeout` periods or more are removed.  Call once a step, before
 *  reading the step's messages. */
void neighbours_age(neighbours_t *t, uint8_t timeout);

/** The entry of sender `id`, or 0. */
const neighbour_t *neighbours_find(const neighbours_t *t, uint8_t id);

/** 1 if the neighbour's state is known and is `state`. */
uint8_t neighbour_is(const neighbour_t *nb, uint8_t state);

/** Source_Type of its gradient (GRADIENT frame). */
uint8_t neighbour_gradient_source(const neighbour_t *nb);

/** Its Flag_Contraction (STATE frame). */
uint8_t neighbour_contraction(const neighbour_t *nb);

#endif
