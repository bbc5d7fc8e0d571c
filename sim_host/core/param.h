/*
 * param.h - descriptors of plain-old-data parameter structs, so that one
 * strict loader can fill any of them from a scenario file and `--set`.
 */
#ifndef SIM_PARAM_H
#define SIM_PARAM_H

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
    PARAM_ENUM     /**< int, one of `choices` (NULL-terminated), stored as its index */
} param_type_t;

/** One scalar key of a parameter struct. */
typedef struct param_desc {
    const char *key;        /**< YAML key */
    param_type_t type;
    size_t offset;          /**< offsetof in the struct */
    size_t size;            /**< sizeof the member (strings: buffer size) */
    double min, max;        /**< inclusive range for numbers */
    const char *const *choices; /**< PARAM_ENUM only */
    const char *doc;        /**< one line, with the unit */
} param_desc_t;

#define PARAM_END { NULL, PARAM_BOOL, 0, 0, 0.0, 0.0, NULL, NULL }

#endif
