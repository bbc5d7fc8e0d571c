/*
 * schema.h - checks a YAML tree (yaml_tree.h) against descriptor tables
 * (param.h) and fills plain structs from it: the strict loader behind
 * scenarios and, later, sweep files.  Every error names the file and line
 * (or the --set) the bad value came from, and the key path.
 *
 * Decisions:
 *  - An empty mapping (or a null one: `robots:` with nothing after it)
 *    changes nothing; absent keys keep their value.
 *  - Integers are decimal with an optional sign: "2.5", "1e3", "0x10", "5m"
 *    and quoted "5" are errors, as is a value outside the key's range or
 *    its C type.  Numbers accept integers, decimals and exponents but not
 *    nan/inf/.inf, hex or trailing garbage.  Booleans are true/false (any
 *    case YAML 1.2 allows), not yes/no/on/off/1/0.
 *  - Strings may be plain or quoted but not empty or null.
 *  - A given sequence replaces the default one; each entry starts from the
 *    entry defaults.
 *  - An array key (PARAM_ARRAY_FIELD) takes a sequence of exactly its
 *    element count, each element checked like a scalar of its type and
 *    range (errors name "key[i]"); a bad element changes nothing.  One
 *    element can be overridden with --set key.I=V where the file gives the
 *    array, the whole array anywhere with --set key=[v0, v1, ...].
 */
#ifndef SIM_SCHEMA_H
#define SIM_SCHEMA_H

#include <stddef.h>
#include <stdio.h>

#include "common/param.h"
#include "swarmsim/base.h"
#include "yaml_tree.h"

#define SCHEMA_PATH_MAX 256
/** Largest array key (param.h's PARAM_ARRAY_FIELD) the loader fills, bytes:
 *  a controller's whole params block (SCENARIO_CONTROLLER_PARAMS_MAX). */
#define PARAM_ARRAY_MAX_BYTES 512u

typedef struct loader {
    const char *file;
    char *err;         /**< the caller's buffer */
    size_t err_size;
} loader_t;

typedef struct schema schema_t;
typedef struct seq_desc seq_desc_t;

/** Fills what a key's value holds when no table can say it (a group's
 *  params depend on its controller).  Returns 0 or -1 (error set). */
typedef int (*fill_fn)(const loader_t *ld, const ynode_t *node, const char *path, void *base);

typedef enum child_kind {
    CHILD_MAPPING,     /**< a nested struct, offsets from the same base */
    CHILD_SEQUENCE,    /**< an array and its count in the base */
    CHILD_DEFERRED     /**< filled by the parent's own code (e.g. params after controller) */
} child_kind_t;

/** A key whose value is a mapping or a sequence. */
typedef struct child {
    const char *key;
    child_kind_t kind;
    const schema_t *schema;  /**< CHILD_MAPPING */
    const seq_desc_t *seq;   /**< CHILD_SEQUENCE */
    const char *doc;
} child_t;

#define CHILD_END { NULL, CHILD_MAPPING, NULL, NULL, NULL }

struct schema {
    const param_desc_t *params;  /**< scalar keys, offsets from the base */
    const child_t *children;     /**< NULL, or ends with a NULL key */
    /** Keys no table names (a task's section): returns 1 when it filled
     *  one, 0 when it does not know it, -1 on error.  NULL: none. */
    int (*other)(const loader_t *ld, const ypair_t *pair, const char *path, void *base);
    /** The i-th key `other` knows, for messages and suggestions; NULL past
     *  the end. */
    const char *(*other_key)(size_t i);
};

typedef int (*elem_check_fn)(const loader_t *ld, const ynode_t *item, const char *path,
                             void *elem);

struct seq_desc {
    const char *noun;      /**< "objects" */
    size_t max;
    size_t elem_size;
    const void *defaults;  /**< one element with every default */
    const schema_t *schema;
    size_t array_offset;   /**< of the array in the base (or of a pointer to it: on_heap) */
    size_t count_offset;   /**< of its uint32_t count in the base */
    elem_check_fn check;   /**< after an entry is filled (or NULL) */
    int on_heap;           /**< the base holds a pointer, reallocated to the sequence's
                                length (the owner frees it) */
    void (*init)(void *elem);  /**< after an entry takes the defaults, before its keys
                                    (what `defaults` cannot hold), or NULL */
};

/** "FILE:LINE: path: message" (or "--set TEXT: path: message" for a value
 *  an override wrote) into ld->err.  Always returns -1. */
__attribute__((format(printf, 4, 5)))
int schema_fail(const loader_t *ld, const ynode_t *node, const char *path, const char *fmt, ...);

/** "expected <what>, got <the value>". */
int schema_wrong_type(const loader_t *ld, const ynode_t *v, const char *path, const char *expected);

/** "parent.key" (or "key" at the top level). */
void schema_join(char out[SCHEMA_PATH_MAX], const char *parent, const char *key);
/** "path[i]" */
void schema_index_path(char out[SCHEMA_PATH_MAX], const char *path, size_t i);

/** The value node of `key` in mapping `item`, or `item` itself (for a
 *  line to point at). */
const ynode_t *schema_node_of(const ynode_t *item, const char *key);

/** The node a dotted path names below `root` ("robots.0.count"), or the
 *  deepest node on the way (for a line to point at). */
const ynode_t *schema_find(const ynode_t *root, const char *dotted);

/** A dotted path as messages show it: "robots.0.faults.1.kind" gives
 *  "robots[0].faults[1].kind". */
void schema_display_path(char out[SCHEMA_PATH_MAX], const char *dotted);

/** Fills `pair` when `schema` knows its key (a scalar or a child): 1 when
 *  it did, 0 when the key is not the schema's, -1 on error (set).  For
 *  keys a schema_t.other hook hands to another schema (the models'). */
int schema_fill_known(const loader_t *ld, const ypair_t *pair, const char *path, const schema_t *schema,
                      void *base);
/** The i-th key of `schema` (its scalars, then its children), NULL past
 *  the end: for schema_t.other_key. */
const char *schema_key_at(const schema_t *schema, size_t i);

/** The value of field `d` of `base` as a scenario writes it ("300", "0.5",
 *  "true", an enum's word). */
void schema_format_value(const param_desc_t *d, const void *base, char *buf, size_t len);
/** What `d` takes, as messages show it ("[0, 1000]", "a|b", "true|false"). */
void schema_format_range(const param_desc_t *d, char *buf, size_t len);
/** Fills field `d` of `base` from one plain scalar `text`, checked as a
 *  scenario's value is (its type, its range): 0, or -1 with
 *  "WHERE: KEY: what" in err and the field unchanged.  Scalars only. */
int schema_fill_text(const param_desc_t *d, const char *text, const char *where, void *base, char *err,
                     size_t err_size);

/** Appends `key` to a ", "-separated list in buf. */
void schema_list_key(char *buf, size_t len, const char *key);

/** Keeps in *best the candidate closest to `word` within two edits. */
void schema_consider(const char *word, const char *candidate, const char **best, size_t *dist);

int schema_fill_mapping(const loader_t *ld, const ynode_t *node, const char *path,
                        const schema_t *schema, void *base);
int schema_fill_sequence(const loader_t *ld, const ynode_t *node, const char *path,
                         const seq_desc_t *seq, void *base);
/** One key of a table: a scalar, or an array (param_desc_t.count). */
int schema_fill_scalar(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                       const char *path, void *base);

/** --help: every key of `params` under `prefix` with type, default (read
 *  from `base`), range and meaning. */
void schema_print_params(FILE *f, const char *prefix, const param_desc_t *params, const void *base);
/** The same for a schema and its children; `deferred` prints a
 *  CHILD_DEFERRED (or is NULL). */
void schema_print(FILE *f, const char *prefix, const schema_t *schema, const void *base,
                  void (*deferred)(FILE *f, const char *path));

#endif
