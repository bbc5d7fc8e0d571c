/*
 * observable.h - what a controller (or a task) shows: a table of named
 * values read straight from its state struct, each with its type, unit and
 * scale.  The simulator's telemetry and time series and the robot image's
 * telemetry all read the same table, so the robot and the simulator cannot
 * disagree on what a value means.
 *
 *     { .name = "threshold", OBS_FIELD(forager_t, theta, float), .scale = 1.0f,
 *       .unit = "tokens", .doc = "theta of the last decision (eq 6)" },
 *
 * The value shown is field * scale, in `unit` (a fixed-point field carries
 * its scale here: beacon_food_q4 with scale 1/16 is in tokens).  A COUNTER
 * is a running count (obstacle-avoidance events, deposits): the simulator
 * reports its total over the robots in the run's summary (<name>_total and
 * <name>_per_robot) and sends each increment as an event named after it.
 * As with param.h, OBS_FIELD makes a type that does not match its field a
 * build error.
 */
#ifndef FW_OBSERVABLE_H
#define FW_OBSERVABLE_H

#include <stdint.h>

#include "common/param.h"

typedef enum obs_type {
    OBS_U8, OBS_I8, OBS_U16, OBS_I16, OBS_U32, OBS_I32, OBS_FLOAT
} obs_type_t;

typedef enum obs_kind {
    OBS_LEVEL = 0,    /**< a value that goes up and down */
    OBS_COUNTER = 1   /**< a running count from 0 */
} obs_kind_t;

typedef struct observable {
    const char *name;   /**< short, lower case: a CSV column and an LCM field name */
    uint8_t type;       /**< obs_type_t of the field */
    uint8_t kind;       /**< obs_kind_t */
    uint16_t offset;    /**< of the field in the state struct, bytes */
    float scale;        /**< value = field * scale */
    const char *unit;   /**< of the value ("" when it has none) */
    const char *doc;    /**< one line */
} observable_t;

/** Ends a table. */
#define OBS_END { 0, 0, 0, 0, 0.0f, 0, 0 }

#define OBS_TYPE_uint8_t OBS_U8
#define OBS_TYPE_int8_t OBS_I8
#define OBS_TYPE_uint16_t OBS_U16
#define OBS_TYPE_int16_t OBS_I16
#define OBS_TYPE_uint32_t OBS_U32
#define OBS_TYPE_int32_t OBS_I32
#define OBS_TYPE_float OBS_FLOAT

/** Field `f` of state struct `T`, of C type `ctype` (a build error if not). */
#define OBS_FIELD(T, f, ctype) \
    .type = OBS_TYPE_##ctype, .offset = (uint16_t)FIELD_OFFSET_AS(T, f, ctype)

/** Entries of `table` before its OBS_END. */
uint8_t observable_count(const observable_t *table);

/** The value of `obs` in the state struct at `self`: field * scale. */
float observable_read(const observable_t *obs, const void *self);

#endif
