/*
 * schema.c - the strict loader of descriptor tables over a YAML tree
 * (schema.h).
 */
#include "schema.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- errors */

/* snprintf that may cut: messages and key paths are bounded on purpose
 * (and, unlike snprintf, GCC does not warn about it). */
__attribute__((format(printf, 3, 4)))
static void format_into(char *buf, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, len, fmt, ap);
    va_end(ap);
}

int schema_fail(const loader_t *ld, const ynode_t *node, const char *path, const char *fmt, ...)
{
    char msg[SIM_ERR_MAX], where[SCHEMA_PATH_MAX + 300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (node != NULL && node->origin != NULL) {
        format_into(where, sizeof where, "--set %s", node->origin);
    } else if (node != NULL && node->line > 0) {
        format_into(where, sizeof where, "%s:%d", ld->file, node->line);
    } else {
        format_into(where, sizeof where, "%s", ld->file);
    }
    if (path[0] != '\0') {
        format_into(ld->err, ld->err_size, "%s: %s: %s", where, path, msg);
    } else {
        format_into(ld->err, ld->err_size, "%s: %s", where, msg);
    }
    return -1;
}

int schema_wrong_type(const loader_t *ld, const ynode_t *v, const char *path, const char *expected)
{
    char got[64];
    ytree_describe(v, got, sizeof got);
    return schema_fail(ld, v, path, "expected %s, got %s", expected, got);
}

/* A long unknown key is cut so that the message stays readable. */
void schema_join(char out[SCHEMA_PATH_MAX], const char *parent, const char *key)
{
    if (parent[0] == '\0') {
        format_into(out, SCHEMA_PATH_MAX, "%.64s", key);
    } else {
        format_into(out, SCHEMA_PATH_MAX, "%s.%.64s", parent, key);
    }
}

void schema_display_path(char out[SCHEMA_PATH_MAX], const char *dotted)
{
    size_t n = 0;
    out[0] = '\0';
    while (*dotted != '\0' && n + 1 < SCHEMA_PATH_MAX) {
        size_t len = strcspn(dotted, ".");
        int index = len > 0 && strspn(dotted, "0123456789") == len;
        int w = snprintf(out + n, SCHEMA_PATH_MAX - n, index ? "[%.*s]" : n ? ".%.*s" : "%.*s", (int)len, dotted);
        n = w < 0 ? n : n + (size_t)w < SCHEMA_PATH_MAX ? n + (size_t)w : SCHEMA_PATH_MAX - 1;
        dotted += len + (dotted[len] == '.');
    }
}

void schema_index_path(char out[SCHEMA_PATH_MAX], const char *path, size_t i)
{
    format_into(out, SCHEMA_PATH_MAX, "%s[%zu]", path, i);
}

/* Integral values up to 2^53 (exact in a double) print in full, others with %g. */
static void format_number(double v, char *buf, size_t len)
{
    if (fabs(v) <= 9007199254740992.0 && v == (double)(long long)v) {  /* exact below 2^53 */
        snprintf(buf, len, "%.0f", v);
    } else {
        snprintf(buf, len, "%g", v);
    }
}

static void format_range(const param_desc_t *d, char *buf, size_t len)
{
    char lo[32], hi[32];
    size_t used = 0;
    const char *const *c;
    switch (d->type) {
    case PARAM_BOOL:
        snprintf(buf, len, "true|false");
        return;
    case PARAM_STRING:
        snprintf(buf, len, "<= %zu chars", d->size - 1);
        return;
    case PARAM_ANGLE:
        format_number(d->min, lo, sizeof lo);
        format_number(d->max, hi, sizeof hi);
        snprintf(buf, len, "[%s, %s]|random", lo, hi);
        return;
    case PARAM_ENUM:
        buf[0] = '\0';
        for (c = d->choices; *c != NULL && used < len; c++) {
            used += (size_t)snprintf(buf + used, len - used, "%s%s", c == d->choices ? "" : "|", *c);
        }
        return;
    default:
        format_number(d->min, lo, sizeof lo);
        if (d->type == PARAM_U64 && d->max >= (double)UINT64_MAX) {
            snprintf(hi, sizeof hi, "%" PRIu64, UINT64_MAX);
        } else {
            format_number(d->max, hi, sizeof hi);
        }
        snprintf(buf, len, "[%s, %s]", lo, hi);
    }
}

static int out_of_range(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                        const char *path)
{
    char range[64];
    format_range(d, range, sizeof range);
    return schema_fail(ld, v, path, "%.40s is out of range %s", v->text, range);
}

/* Optimal string alignment distance (typos: one edit or swap is 1). */
static size_t edit_distance(const char *a, const char *b)
{
    unsigned char d[33][33];
    size_t la = strlen(a), lb = strlen(b), i, j;
    if (la > 32 || lb > 32) {
        return 99;
    }
    for (i = 0; i <= la; i++) {
        for (j = 0; j <= lb; j++) {
            size_t best;
            if (i == 0 || j == 0) {
                d[i][j] = (unsigned char)(i + j);
                continue;
            }
            best = (size_t)d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if ((size_t)d[i - 1][j] + 1 < best) best = (size_t)d[i - 1][j] + 1;
            if ((size_t)d[i][j - 1] + 1 < best) best = (size_t)d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                (size_t)d[i - 2][j - 2] + 1 < best) {
                best = (size_t)d[i - 2][j - 2] + 1;
            }
            d[i][j] = (unsigned char)best;
        }
    }
    return d[la][lb];
}

void schema_consider(const char *word, const char *candidate, const char **best, size_t *dist)
{
    size_t d = edit_distance(word, candidate);
    if (d <= 2 && d < *dist) {
        *best = candidate;
        *dist = d;
    }
}

void schema_list_key(char *buf, size_t len, const char *key)
{
    size_t used = strlen(buf);
    if (used < len) {
        snprintf(buf + used, len - used, "%s%s", used ? ", " : "", key);
    }
}

/* ---------------------------------------------------------------- scalars */

static int all_digits(const char *s)
{
    const char *p = s;
    while (*p >= '0' && *p <= '9') {
        p++;
    }
    return p != s && *p == '\0';
}

static int is_plain(const ynode_t *v)
{
    return v != NULL && v->kind == YNODE_SCALAR && !v->quoted;
}

static int fill_bool(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    static const char *const words[] = { "false", "False", "FALSE", "true", "True", "TRUE" };
    size_t i;
    (void)d;
    for (i = 0; is_plain(v) && i < sizeof words / sizeof words[0]; i++) {
        if (strcmp(v->text, words[i]) == 0) {
            uint8_t b = i >= 3;
            memcpy(dst, &b, sizeof b);
            return 0;
        }
    }
    return schema_wrong_type(ld, v, path, "true/false");
}

/* Stores `i` as the C type of `d`; returns -1 if it does not fit. */
static int store_int(const param_desc_t *d, intmax_t i, void *dst)
{
    uint8_t u8 = (uint8_t)i;
    uint16_t u16 = (uint16_t)i;
    int16_t i16 = (int16_t)i;
    uint32_t u32 = (uint32_t)i;
    if (d->type == PARAM_U8 && i >= 0 && i <= UINT8_MAX) {
        memcpy(dst, &u8, sizeof u8);
    } else if (d->type == PARAM_U16 && i >= 0 && i <= UINT16_MAX) {
        memcpy(dst, &u16, sizeof u16);
    } else if (d->type == PARAM_I16 && i >= INT16_MIN && i <= INT16_MAX) {
        memcpy(dst, &i16, sizeof i16);
    } else if (d->type == PARAM_U32 && i >= 0 && i <= (intmax_t)UINT32_MAX) {
        memcpy(dst, &u32, sizeof u32);
    } else {
        return -1;
    }
    return 0;
}

static int fill_u64(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                    const char *path, void *dst)
{
    const char *s = v->text;
    uintmax_t u;
    uint64_t x;
    /* strtoumax accepts "-5" and wraps it; only "-0" is in range. */
    if (s[0] == '-' && strspn(s + 1, "0") != strlen(s + 1)) {
        return out_of_range(ld, d, v, path);
    }
    errno = 0;
    u = strtoumax(s, NULL, 10);
    if (errno == ERANGE || u > UINT64_MAX || (double)u < d->min || (double)u > d->max) {
        return out_of_range(ld, d, v, path);
    }
    x = (uint64_t)u;
    memcpy(dst, &x, sizeof x);
    return 0;
}

static int fill_integer(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                        const char *path, void *dst)
{
    intmax_t i;
    if (!is_plain(v) || !all_digits(v->text + (v->text[0] == '-' || v->text[0] == '+'))) {
        return schema_wrong_type(ld, v, path, "an integer");
    }
    if (d->type == PARAM_U64) {
        return fill_u64(ld, d, v, path, dst);
    }
    errno = 0;
    i = strtoimax(v->text, NULL, 10);
    if (errno == ERANGE || (double)i < d->min || (double)i > d->max ||
        store_int(d, i, dst) != 0) {
        return out_of_range(ld, d, v, path);
    }
    return 0;
}

static int fill_real(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    const char *s = v != NULL ? v->text : NULL;
    char *end;
    double x;
    /* strtod would also take hex, "nan", "inf" and leading blanks. */
    if (!is_plain(v) || strspn(s, "0123456789+-.eE") != strlen(s) ||
        strpbrk(s, "0123456789") == NULL) {
        return schema_wrong_type(ld, v, path, "a number");
    }
    errno = 0;
    x = strtod(s, &end);
    if (*end != '\0') {
        return schema_wrong_type(ld, v, path, "a number");
    }
    if (!isfinite(x) || x < d->min || x > d->max) {
        return out_of_range(ld, d, v, path);
    }
    if (d->type == PARAM_FLOAT || d->type == PARAM_ANGLE) {
        float f = (float)x;
        memcpy(dst, &f, sizeof f);
    } else {
        memcpy(dst, &x, sizeof x);
    }
    return 0;
}

static int fill_string(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                       const char *path, void *dst)
{
    size_t len;
    if (v == NULL || v->kind != YNODE_SCALAR || ytree_is_null(v)) {
        return schema_wrong_type(ld, v, path, "a string");
    }
    len = strlen(v->text);
    if (len == 0) {
        return schema_fail(ld, v, path, "expected a non-empty string");
    }
    if (len >= d->size) {
        return schema_fail(ld, v, path, "'%.40s...' is longer than %zu characters", v->text,
                    d->size - 1);
    }
    memcpy(dst, v->text, len + 1);
    return 0;
}

static int fill_enum(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                     const char *path, void *dst)
{
    char range[120], choices[128], got[64];
    const char *best = NULL;
    size_t dist = 3;
    int i;
    format_range(d, range, sizeof range);
    format_into(choices, sizeof choices, "one of %s", range);
    if (v == NULL || v->kind != YNODE_SCALAR) {
        return schema_wrong_type(ld, v, path, choices);
    }
    for (i = 0; d->choices[i] != NULL; i++) {
        if (strcmp(v->text, d->choices[i]) == 0) {
            if (d->size == 1) {   /* a uint8_t field (firmware parameters) */
                uint8_t b = (uint8_t)i;
                memcpy(dst, &b, 1);
            } else {
                memcpy(dst, &i, sizeof i);
            }
            return 0;
        }
        schema_consider(v->text, d->choices[i], &best, &dist);
    }
    ytree_describe(v, got, sizeof got);
    if (best != NULL) {
        return schema_fail(ld, v, path, "expected %s, got %s (did you mean '%s'?)", choices, got, best);
    }
    return schema_fail(ld, v, path, "expected %s, got %s", choices, got);
}

/* Degrees in [min, max], or the word "random" (stored as NaN). */
static int fill_angle(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                      const char *path, void *dst)
{
    if (is_plain(v) && strcmp(v->text, "random") == 0) {
        float nan_value = NAN;
        memcpy(dst, &nan_value, sizeof nan_value);
        return 0;
    }
    if (!is_plain(v) || strspn(v->text, "0123456789+-.eE") != strlen(v->text)) {
        return schema_wrong_type(ld, v, path, "an angle in degrees or 'random'");
    }
    return fill_real(ld, d, v, path, dst);
}

static int fill_one(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                    const char *path, void *dst)
{
    switch (d->type) {
    case PARAM_BOOL:
        return fill_bool(ld, d, v, path, dst);
    case PARAM_FLOAT:
    case PARAM_DOUBLE:
        return fill_real(ld, d, v, path, dst);
    case PARAM_ANGLE:
        return fill_angle(ld, d, v, path, dst);
    case PARAM_STRING:
        return fill_string(ld, d, v, path, dst);
    case PARAM_ENUM:
        return fill_enum(ld, d, v, path, dst);
    default:
        return fill_integer(ld, d, v, path, dst);
    }
}

/* An array key: a sequence of exactly d->count numbers, each checked as a
 * scalar of the key's type and range.  Elements are written only once all
 * are good, so a bad element leaves the array as it was. */
static int fill_array(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                      const char *path, void *dst)
{
    uint8_t tmp[PARAM_ARRAY_MAX_BYTES];
    char got[64], at[SCHEMA_PATH_MAX];
    size_t i;
    if (v == NULL || v->kind != YNODE_SEQUENCE) {
        ytree_describe(v, got, sizeof got);
        return schema_fail(ld, v, path, "expected a sequence of %u numbers (e.g. [0, 1, ...]), got %s",
                           (unsigned)d->count, got);
    }
    if (v->count != d->count) {
        return schema_fail(ld, v, path, "expected exactly %u numbers, got %zu", (unsigned)d->count,
                           v->count);
    }
    if ((size_t)d->count * d->size > sizeof tmp) {
        return schema_fail(ld, v, path, "array of %zu bytes: larger than the loader's %u",
                           (size_t)d->count * d->size, (unsigned)PARAM_ARRAY_MAX_BYTES);
    }
    for (i = 0; i < v->count; i++) {
        const ynode_t *item = v->items[i];
        schema_index_path(at, path, i);
        if (item == NULL || item->kind != YNODE_SCALAR) {
            return schema_wrong_type(ld, item != NULL ? item : v, at, "a number");
        }
        if (fill_one(ld, d, item, at, tmp + i * d->size) != 0) {
            return -1;
        }
    }
    memcpy(dst, tmp, (size_t)d->count * d->size);
    return 0;
}

int schema_fill_scalar(const loader_t *ld, const param_desc_t *d, const ynode_t *v,
                       const char *path, void *base)
{
    void *dst = (char *)base + d->offset;
    return d->count > 0 ? fill_array(ld, d, v, path, dst) : fill_one(ld, d, v, path, dst);
}

/* ---------------------------------------------------------------- mappings */

static const param_desc_t *find_param(const param_desc_t *d, const char *key)
{
    for (; d != NULL && d->key != NULL; d++) {
        if (strcmp(d->key, key) == 0) {
            return d;
        }
    }
    return NULL;
}

static const child_t *find_child(const child_t *c, const char *key)
{
    for (; c != NULL && c->key != NULL; c++) {
        if (strcmp(c->key, key) == 0) {
            return c;
        }
    }
    return NULL;
}

static int unknown_key(const loader_t *ld, const ynode_t *key, const char *path,
                       const schema_t *schema)
{
    char valid[400] = "";
    const char *best = NULL, *other;
    size_t dist = 3, i;
    const param_desc_t *d;
    const child_t *c;
    for (d = schema->params; d != NULL && d->key != NULL; d++) {
        schema_consider(key->text, d->key, &best, &dist);
        schema_list_key(valid, sizeof valid, d->key);
    }
    for (c = schema->children; c != NULL && c->key != NULL; c++) {
        if (c->kind != CHILD_DEFERRED) {
            schema_consider(key->text, c->key, &best, &dist);
            schema_list_key(valid, sizeof valid, c->key);
        }
    }
    for (i = 0; schema->other_key != NULL && (other = schema->other_key(i)) != NULL; i++) {
        schema_consider(key->text, other, &best, &dist);
        schema_list_key(valid, sizeof valid, other);
    }
    /* Keys filled after the others (a group's params) come last. */
    for (c = schema->children; c != NULL && c->key != NULL; c++) {
        if (c->kind == CHILD_DEFERRED) {
            schema_consider(key->text, c->key, &best, &dist);
            schema_list_key(valid, sizeof valid, c->key);
        }
    }
    if (best != NULL) {
        return schema_fail(ld, key, path, "unknown key '%.64s' (did you mean '%s'?)", key->text, best);
    }
    if (valid[0] == '\0') {
        return schema_fail(ld, key, path, "unknown key '%.64s' (no keys are allowed here)", key->text);
    }
    return schema_fail(ld, key, path, "unknown key '%.64s' (valid keys: %s)", key->text, valid);
}

int schema_fill_known(const loader_t *ld, const ypair_t *pair, const char *path, const schema_t *schema,
                      void *base)
{
    const param_desc_t *d = find_param(schema->params, pair->key->text);
    const child_t *c;
    if (d != NULL) {
        return schema_fill_scalar(ld, d, pair->value, path, base) == 0 ? 1 : -1;
    }
    c = find_child(schema->children, pair->key->text);
    if (c == NULL) {
        return 0;
    }
    switch (c->kind) {
    case CHILD_MAPPING:
        return schema_fill_mapping(ld, pair->value, path, c->schema, base) == 0 ? 1 : -1;
    case CHILD_SEQUENCE:
        return schema_fill_sequence(ld, pair->value, path, c->seq, base) == 0 ? 1 : -1;
    default:
        return 1;   /* the parent fills it */
    }
}

const char *schema_key_at(const schema_t *schema, size_t i)
{
    for (const param_desc_t *d = schema->params; d != NULL && d->key != NULL; d++) {
        if (i-- == 0) {
            return d->key;
        }
    }
    for (const child_t *c = schema->children; c != NULL && c->key != NULL; c++) {
        if (i-- == 0) {
            return c->key;
        }
    }
    return NULL;
}

static int fill_entry(const loader_t *ld, const ypair_t *pair, const char *path,
                      const schema_t *schema, void *base)
{
    int rc = schema_fill_known(ld, pair, path, schema, base);
    if (rc == 0) {
        rc = schema->other != NULL ? schema->other(ld, pair, path, base) : 0;
        return rc != 0 ? (rc < 0 ? -1 : 0) : unknown_key(ld, pair->key, path, schema);
    }
    return rc < 0 ? -1 : 0;
}

static int duplicate_key(const loader_t *ld, const ynode_t *map, size_t i, const char *path)
{
    const ynode_t *key = map->pairs[i].key;
    size_t j;
    for (j = 0; j < i; j++) {
        const ynode_t *first = map->pairs[j].key;
        if (strcmp(first->text, key->text) == 0) {
            if (first->line > 0) {
                return schema_fail(ld, key, path, "duplicate key '%.64s' (first on line %d)", key->text,
                                   first->line);
            }
            return schema_fail(ld, key, path, "duplicate key '%.64s'", key->text);
        }
    }
    return 0;
}

int schema_fill_mapping(const loader_t *ld, const ynode_t *node, const char *path,
                        const schema_t *schema, void *base)
{
    size_t i;
    if (ytree_is_null(node)) {
        return 0;
    }
    if (node->kind != YNODE_MAPPING) {
        return schema_wrong_type(ld, node, path, "a mapping");
    }
    for (i = 0; i < node->count; i++) {
        char child[SCHEMA_PATH_MAX];
        schema_join(child, path, node->pairs[i].key->text);
        if (duplicate_key(ld, node, i, child) != 0 ||
            fill_entry(ld, &node->pairs[i], child, schema, base) != 0) {
            return -1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- sequences */

int schema_fill_sequence(const loader_t *ld, const ynode_t *node, const char *path,
                         const seq_desc_t *seq, void *base)
{
    char *array = (char *)base + seq->array_offset;
    uint32_t count = 0;
    size_t n;
    if (ytree_is_null(node)) {
        return 0;   /* an empty section changes nothing; [] empties the list */
    }
    if (node->kind != YNODE_SEQUENCE) {
        return schema_wrong_type(ld, node, path, "a sequence");
    }
    n = node->count;
    if (seq->on_heap) {
        /* Sized by the file, not by the worst case; entries past max are
         * refused below before anything is written to them. */
        size_t cap = n < seq->max ? n : seq->max;
        void **slot = (void **)(void *)array;
        void *grown = realloc(*slot, (cap ? cap : 1) * seq->elem_size);
        if (grown == NULL) {
            return schema_fail(ld, node, path, "out of memory for %zu %s", cap, seq->noun);
        }
        *slot = grown;
        array = grown;
    }
    for (; count < n; count++) {
        const ynode_t *item = node->items[count];
        void *elem = array + (size_t)count * seq->elem_size;
        char ipath[SCHEMA_PATH_MAX];
        schema_index_path(ipath, path, count);
        if (count >= seq->max) {
            return schema_fail(ld, item, ipath, "too many %s (at most %zu)", seq->noun, seq->max);
        }
        if (item == NULL || item->kind != YNODE_MAPPING) {
            return schema_wrong_type(ld, item, ipath, "a mapping");
        }
        memcpy(elem, seq->defaults, seq->elem_size);
        if (seq->init != NULL) {
            seq->init(elem);
        }
        if (schema_fill_mapping(ld, item, ipath, seq->schema, elem) != 0 ||
            (seq->check != NULL && seq->check(ld, item, ipath, elem) != 0)) {
            return -1;
        }
    }
    memcpy((char *)base + seq->count_offset, &count, sizeof count);
    return 0;
}

const ynode_t *schema_node_of(const ynode_t *item, const char *key)
{
    const ynode_t *v = ytree_get(item, key);
    return v != NULL ? v : item;
}

const ynode_t *schema_find(const ynode_t *root, const char *dotted)
{
    const ynode_t *node = root;
    char seg[SCHEMA_PATH_MAX];
    while (node != NULL && *dotted != '\0') {
        size_t len = strcspn(dotted, ".");
        const ynode_t *next = NULL;
        format_into(seg, sizeof seg, "%.*s", (int)len, dotted);
        if (node->kind == YNODE_MAPPING) {
            next = ytree_get(node, seg);
        } else if (node->kind == YNODE_SEQUENCE && seg[0] >= '0' && seg[0] <= '9') {
            size_t i = (size_t)strtoul(seg, NULL, 10);
            next = i < node->count ? node->items[i] : NULL;
        }
        if (next == NULL) {
            return node;
        }
        node = next;
        dotted += len + (dotted[len] == '.');
    }
    return node;
}

/* ---------------------------------------------------------------- --help */

static const char *type_name(param_type_t t)
{
    switch (t) {
    case PARAM_BOOL: return "bool";
    case PARAM_FLOAT:
    case PARAM_DOUBLE: return "number";
    case PARAM_ANGLE: return "angle";
    case PARAM_STRING: return "string";
    case PARAM_ENUM: return "enum";
    default: return "int";
    }
}

static void format_value(const param_desc_t *d, const void *base, char *buf, size_t len);

/* An array's default as "[a, b, c, ...]": its first elements, as many as fit. */
static void format_array(const param_desc_t *d, const void *base, char *buf, size_t len)
{
    param_desc_t one = *d;
    size_t used = 1, i;
    one.count = 0;
    snprintf(buf, len, "[");
    for (i = 0; i < d->count; i++) {
        char v[32];
        one.offset = d->offset + i * d->size;
        format_value(&one, base, v, sizeof v);
        if (used + strlen(v) + 6 >= len) {
            snprintf(buf + used, len - used, "...]");
            return;
        }
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? "," : "", v);
    }
    snprintf(buf + used, len - used, "]");
}

static void format_value(const param_desc_t *d, const void *base, char *buf, size_t len)
{
    const char *p = (const char *)base + d->offset;
    if (d->count > 0) {
        format_array(d, base, buf, len);
        return;
    }
    union { uint8_t u8; uint16_t u16; int16_t i16; uint32_t u32; uint64_t u64; float f;
            double d; int i; } v;
    memcpy(&v, p, d->type == PARAM_STRING ? 0 : d->size);
    switch (d->type) {
    case PARAM_BOOL: snprintf(buf, len, "%s", v.u8 ? "true" : "false"); break;
    case PARAM_U8: snprintf(buf, len, "%u", (unsigned)v.u8); break;
    case PARAM_U16: snprintf(buf, len, "%u", (unsigned)v.u16); break;
    case PARAM_I16: snprintf(buf, len, "%d", (int)v.i16); break;
    case PARAM_U32: snprintf(buf, len, "%" PRIu32, v.u32); break;
    case PARAM_U64: snprintf(buf, len, "%" PRIu64, v.u64); break;
    case PARAM_FLOAT:   /* NaN: unset, the key's doc says what then */
        if (isnan(v.f)) snprintf(buf, len, "-");
        else format_number(v.f, buf, len);
        break;
    case PARAM_ANGLE:
        if (isnan(v.f)) snprintf(buf, len, "random");
        else format_number(v.f, buf, len);
        break;
    case PARAM_DOUBLE: format_number(v.d, buf, len); break;
    case PARAM_STRING: snprintf(buf, len, "%s", p[0] ? p : "-"); break;
    case PARAM_ENUM: snprintf(buf, len, "%s", d->choices[d->size == 1 ? v.u8 : v.i]); break;
    }
}

void schema_format_value(const param_desc_t *d, const void *base, char *buf, size_t len)
{
    format_value(d, base, buf, len);
}

void schema_format_range(const param_desc_t *d, char *buf, size_t len)
{
    format_range(d, buf, len);
}

int schema_fill_text(const param_desc_t *d, const char *text, const char *where, void *base, char *err,
                     size_t err_size)
{
    uint8_t tmp[64];
    loader_t ld = { where, err, err_size };
    ynode_t v;
    memset(&v, 0, sizeof v);
    v.kind = YNODE_SCALAR;
    v.text = (char *)text;
    if (d->count > 0 || d->size > sizeof tmp) {
        return schema_fail(&ld, NULL, d->key, "an array or a long string is not set from one value");
    }
    if (fill_one(&ld, d, &v, d->key, tmp) != 0) {
        return -1;
    }
    memcpy((char *)base + d->offset, tmp, d->size);
    return 0;
}

void schema_print_params(FILE *f, const char *prefix, const param_desc_t *d, const void *base)
{
    for (; d != NULL && d->key != NULL; d++) {
        char path[SCHEMA_PATH_MAX], def[48], range[128];
        schema_join(path, prefix, d->key);
        char type[24];
        format_value(d, base, def, sizeof def);
        format_range(d, range, sizeof range);
        if (d->count > 0) {
            snprintf(type, sizeof type, "%s[%u]", type_name(d->type), (unsigned)d->count);
        } else {
            snprintf(type, sizeof type, "%s", type_name(d->type));
        }
        fprintf(f, "  %-34s %-6s %-12s %-22s %s\n", path, type, def, range, d->doc);
    }
}

void schema_print(FILE *f, const char *prefix, const schema_t *schema, const void *base,
                  void (*deferred)(FILE *f, const char *path))
{
    const child_t *c;
    schema_print_params(f, prefix, schema->params, base);
    for (c = schema->children; c != NULL && c->key != NULL; c++) {
        char path[SCHEMA_PATH_MAX], elem[SCHEMA_PATH_MAX];
        schema_join(path, prefix, c->key);
        switch (c->kind) {
        case CHILD_SEQUENCE:
            fprintf(f, "  %-34s %-6s %-12s <= %-19zu %s; each entry:\n", path, "list", "-",
                    c->seq->max, c->doc);
            format_into(elem, sizeof elem, "%s[]", path);
            schema_print(f, elem, c->seq->schema, c->seq->defaults, deferred);
            break;
        case CHILD_DEFERRED:
            if (deferred != NULL) {
                deferred(f, path);
            }
            break;
        default:
            schema_print(f, path, c->schema, base, deferred);
        }
    }
}
