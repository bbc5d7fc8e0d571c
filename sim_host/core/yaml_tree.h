/*
 * yaml_tree.h - a small generic tree of a YAML document (mappings,
 * sequences, scalars), each node remembering where it came from, and the
 * `--set key.path=value` overrides that edit it.
 *
 * The scenario loader (scenario.c) parses a file into this tree, applies the
 * overrides, then checks the tree against its schema.  Keeping the parse and
 * the check apart lets an override create keys absent from the file and lets
 * every later error name the line (or the --set) the bad value came from.
 */
#ifndef SIM_YAML_TREE_H
#define SIM_YAML_TREE_H

#include <stddef.h>
#include <stdio.h>

typedef enum ynode_kind { YNODE_SCALAR, YNODE_MAPPING, YNODE_SEQUENCE } ynode_kind_t;

typedef struct ynode ynode_t;

/** One `key: value` entry of a mapping; the key is a scalar node. */
typedef struct ypair {
    ynode_t *key;
    ynode_t *value;
} ypair_t;

struct ynode {
    ynode_kind_t kind;
    int line;            /**< 1-based line in the file; 0 if made by --set */
    const char *origin;  /**< NULL: from the file; else the --set text */
    char *text;          /**< scalar: its value, NUL-terminated */
    int quoted;          /**< scalar: quoted or block style, so a string */
    size_t count, cap;   /**< entries of a mapping or a sequence */
    ypair_t *pairs;      /**< mapping entries, in file order */
    ynode_t **items;     /**< sequence entries */
};

/**
 * Parses the YAML file `path` into `*root` (NULL for a file with no
 * document).  Returns 0, or -1 with "FILE:LINE: what" in `err`.
 * Aliases, explicit tags, non-scalar keys and more than one document are
 * errors: a scenario needs none of them and each would complicate the check.
 */
int ytree_parse_file(const char *path, ynode_t **root, char *err, size_t errlen);

/**
 * Applies one override "key.path=value" to the tree at `*root` (which may be
 * NULL).  Path segments are separated by '.'; a numeric segment (or "[N]")
 * indexes a sequence, and index == length appends.  Missing keys and
 * containers are created; whether a key is valid is left to the schema.
 * The value is parsed as YAML (a scalar, or a flow "[]"/"{}" to replace a
 * whole section).  New nodes keep `text` as their origin, so `text` must
 * outlive the tree.  Returns 0, or -1 with "--set TEXT: path: what" in `err`.
 */
int ytree_apply_override(ynode_t **root, const char *text, char *err, size_t errlen);

/** Writes the tree as a YAML document (block style; quoted scalars stay
 *  quoted, plain ones plain where YAML allows), so that parsing it again
 *  gives the same tree.  Returns 0, or -1 with a message in `err`. */
int ytree_write(FILE *f, const ynode_t *root, char *err, size_t errlen);

/** An empty mapping node (NULL if out of memory). */
ynode_t *ytree_new_mapping(int line, const char *origin);

/** Frees `node` and everything under it; NULL is fine. */
void ytree_free(ynode_t *node);

/** The value of the first entry `key` of mapping `map`, or NULL. */
const ynode_t *ytree_get(const ynode_t *map, const char *key);

/** True for NULL and for an unquoted "", "~", "null", "Null" or "NULL". */
int ytree_is_null(const ynode_t *node);

/** A short description for messages: 'text', the string "text", nothing,
 *  a mapping, a sequence.  Long scalars are cut with "...". */
void ytree_describe(const ynode_t *node, char *buf, size_t len);

#endif
