/*
 * param.h - descriptors of plain-old-data structs (a controller's params, a
 * task's section of a scenario, the scenario itself), so that one strict
 * loader fills any of them from a scenario file and `--set`, and prints
 * them for --help.
 *
 * Descriptor tables cannot lie about their fields: PARAM_FIELD and its
 * siblings take the field's C type and make a mismatch a build error (a
 * bit-field of negative width, named for the mistake), so a PARAM_U32 on
 * an int16_t field does not compile (tests/firmware/hygiene.sh proves it
 * on a probe).  They need a GCC-compatible compiler (gcc, clang, avr-gcc,
 * XC16): __builtin_types_compatible_p.
 *
 *     { .key = "alpha", PARAM_FIELD(forager_params_t, alpha, float),
 *       .min = 0, .max = 1000, .doc = "eq 6 weight of k, per robot/m^2" },
 *
 * An array of numbers (a controller's weights, a genome) is one key whose
 * value is a YAML sequence of exactly as many numbers as the field has
 * elements, each checked against the key's one range:
 *
 *     { .key = "weights", PARAM_ARRAY_FIELD(net_params_t, weights, int16_t),
 *       .min = -2048, .max = 2047, .doc = "synaptic weights, Q8 (1/256)" },
 *
 * The tables are const data: on the robot they cost flash only if an image
 * refers to them (the simulator's loader does; images do not).
 */
#ifndef FW_PARAM_H
#define FW_PARAM_H

#include <stddef.h>
#include <stdint.h>

typedef enum param_type {
    PARAM_BOOL,    /**< uint8_t, YAML true/false */
    PARAM_U8,      /**< uint8_t  */
    PARAM_U16,     /**< uint16_t */
    PARAM_I16,     /**< int16_t  */
    PARAM_U32,     /**< uint32_t */
    PARAM_U64,     /**< uint64_t */
    PARAM_FLOAT,   /**< float  */
    PARAM_DOUBLE,  /**< double */
    PARAM_STRING,  /**< char[size] */
    PARAM_ENUM,    /**< int, one of `choices` (NULL-terminated), stored as its index */
    PARAM_ANGLE    /**< float, degrees, or the word "random" (stored as NaN) */
} param_type_t;

/** One key of a parameter struct: a scalar, or an array of numbers. */
typedef struct param_desc {
    const char *key;        /**< YAML key */
    param_type_t type;      /**< of the value (an array: of each element) */
    size_t offset;          /**< offsetof in the struct */
    size_t size;            /**< sizeof the member (strings: buffer size; arrays:
                                 one element) */
    double min, max;        /**< inclusive range for numbers (each element) */
    const char *const *choices; /**< PARAM_ENUM only */
    const char *doc;        /**< one line, with the unit */
    uint16_t count;         /**< 0: a scalar; n > 0: an array of n numbers of
                                 `type` (PARAM_ARRAY_FIELD) */
    uint8_t live;           /**< 1: a controller's key that may be set while the run
                                 goes (control_t `set`): its init copies it into the
                                 state's params (CONTROLLER_LIVE_PARAMS) and derives
                                 nothing else from it, so each step reads the new
                                 value (tests/sim/test_live_params.c proves it for
                                 every key so marked).  Scalars only. */
} param_desc_t;

/** Ends a table. */
#define PARAM_END { NULL, PARAM_BOOL, 0, 0, 0.0, 0.0, NULL, NULL, 0, 0 }

/** 1 if field `f` of struct `T` has C type `ctype`, else 0. */
#define FIELD_HAS_TYPE(T, f, ctype) \
    __builtin_types_compatible_p(__typeof__(((T *)0)->f), ctype)

/** offsetof(T, f), and a build error unless the field's type is `ctype`:
 *  "negative width in bit-field 'descriptor_type_differs_from_the_field_type'",
 *  with a note pointing at the descriptor's line. */
#define FIELD_OFFSET_AS(T, f, ctype) \
    (offsetof(T, f) + 0u * sizeof(struct { \
        int descriptor_type_differs_from_the_field_type : FIELD_HAS_TYPE(T, f, ctype) ? 1 : -1; }))

#define FIELD_SIZE(T, f) sizeof(((T *)0)->f)

/* The param_type_t of each C type PARAM_FIELD accepts. */
#define PARAM_TYPE_uint8_t PARAM_U8
#define PARAM_TYPE_uint16_t PARAM_U16
#define PARAM_TYPE_int16_t PARAM_I16
#define PARAM_TYPE_uint32_t PARAM_U32
#define PARAM_TYPE_uint64_t PARAM_U64
#define PARAM_TYPE_float PARAM_FLOAT
#define PARAM_TYPE_double PARAM_DOUBLE

/** A number: `ctype` is one of uint8_t, uint16_t, int16_t, uint32_t,
 *  uint64_t, float, double, and must be the field's type. */
#define PARAM_FIELD(T, f, ctype) \
    .type = PARAM_TYPE_##ctype, .offset = FIELD_OFFSET_AS(T, f, ctype), .size = FIELD_SIZE(T, f)
/** An array field `ctype f[n]` of struct `T`, `ctype` one of PARAM_FIELD's
 *  number types: the YAML value is a sequence of exactly n numbers.  A
 *  scalar field, or an array of another type, is a build error. */
#define PARAM_ARRAY_FIELD(T, f, ctype) \
    .type = PARAM_TYPE_##ctype, \
    .offset = FIELD_OFFSET_AS(T, f, ctype[FIELD_SIZE(T, f) / sizeof(ctype)]), \
    .size = sizeof(ctype), .count = (uint16_t)(FIELD_SIZE(T, f) / sizeof(ctype))
/** true/false in a uint8_t field. */
#define PARAM_BOOL_FIELD(T, f) \
    .type = PARAM_BOOL, .offset = FIELD_OFFSET_AS(T, f, uint8_t), .size = FIELD_SIZE(T, f)
/** One of `list` (NULL-terminated words) in an int field, stored as the index. */
#define PARAM_ENUM_FIELD(T, f, list) \
    .type = PARAM_ENUM, .offset = FIELD_OFFSET_AS(T, f, int), .size = FIELD_SIZE(T, f), .choices = (list)
/** One of `list` in a uint8_t field (firmware parameters: fixed width). */
#define PARAM_ENUM_U8_FIELD(T, f, list) \
    .type = PARAM_ENUM, .offset = FIELD_OFFSET_AS(T, f, uint8_t), .size = FIELD_SIZE(T, f), .choices = (list)
/** A string in a char array field. */
#define PARAM_STRING_FIELD(T, f) \
    .type = PARAM_STRING, .offset = FIELD_OFFSET_AS(T, f, char[FIELD_SIZE(T, f)]), .size = FIELD_SIZE(T, f)
/** Degrees or "random" (NaN) in a float field. */
#define PARAM_ANGLE_FIELD(T, f) \
    .type = PARAM_ANGLE, .offset = FIELD_OFFSET_AS(T, f, float), .size = FIELD_SIZE(T, f)

#endif
