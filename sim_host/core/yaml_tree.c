/*
 * yaml_tree.c - builds a ynode_t tree from libyaml's event stream, and
 * edits it with `--set` overrides.  See yaml_tree.h.
 */
#include "yaml_tree.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "swarmsim/base.h"

/* Scenarios nest three levels; the limit only keeps hostile input from
 * exhausting the stack of the recursive builder and checker. */
#define YTREE_MAX_DEPTH 64
/* Longest key path an override may name, in segments. */
#define OVERRIDE_MAX_SEGMENTS 16
/* Largest sequence index an override may name. */
#define OVERRIDE_MAX_INDEX 1000000UL

/* ---------------------------------------------------------------- nodes */

static ynode_t *node_new(ynode_kind_t kind, int line, const char *origin)
{
    ynode_t *node = calloc(1, sizeof *node);
    if (node != NULL) {
        node->kind = kind;
        node->line = line;
        node->origin = origin;
    }
    return node;
}

static ynode_t *scalar_new(const char *text, size_t len, int quoted, int line,
                           const char *origin)
{
    ynode_t *node = node_new(YNODE_SCALAR, line, origin);
    if (node == NULL) {
        return NULL;
    }
    node->text = malloc(len + 1);
    if (node->text == NULL) {
        free(node);
        return NULL;
    }
    memcpy(node->text, text, len);
    node->text[len] = '\0';
    node->quoted = quoted;
    return node;
}

ynode_t *ytree_new_mapping(int line, const char *origin)
{
    return node_new(YNODE_MAPPING, line, origin);
}

void ytree_free(ynode_t *node)
{
    size_t i;
    if (node == NULL) {
        return;
    }
    for (i = 0; i < node->count; i++) {
        if (node->kind == YNODE_MAPPING) {
            ytree_free(node->pairs[i].key);
            ytree_free(node->pairs[i].value);
        } else if (node->kind == YNODE_SEQUENCE) {
            ytree_free(node->items[i]);
        }
    }
    free(node->pairs);
    free(node->items);
    free(node->text);
    free(node);
}

/* Makes room for one more entry; returns -1 when out of memory. */
static int reserve(ynode_t *node)
{
    size_t cap;
    if (node->count < node->cap) {
        return 0;
    }
    cap = node->cap ? node->cap * 2 : 4;
    if (node->kind == YNODE_MAPPING) {
        ypair_t *pairs = realloc(node->pairs, cap * sizeof *pairs);
        if (pairs == NULL) {
            return -1;
        }
        node->pairs = pairs;
    } else {
        ynode_t **items = realloc(node->items, cap * sizeof *items);
        if (items == NULL) {
            return -1;
        }
        node->items = items;
    }
    node->cap = cap;
    return 0;
}

/* Takes ownership of key and value, even on failure. */
static int map_push(ynode_t *map, ynode_t *key, ynode_t *value)
{
    if (reserve(map) != 0) {
        ytree_free(key);
        ytree_free(value);
        return -1;
    }
    map->pairs[map->count].key = key;
    map->pairs[map->count].value = value;
    map->count++;
    return 0;
}

/* Takes ownership of item, even on failure. */
static int seq_push(ynode_t *seq, ynode_t *item)
{
    if (reserve(seq) != 0) {
        ytree_free(item);
        return -1;
    }
    seq->items[seq->count++] = item;
    return 0;
}

const ynode_t *ytree_get(const ynode_t *map, const char *key)
{
    size_t i;
    if (map == NULL || map->kind != YNODE_MAPPING) {
        return NULL;
    }
    for (i = 0; i < map->count; i++) {
        if (strcmp(map->pairs[i].key->text, key) == 0) {
            return map->pairs[i].value;
        }
    }
    return NULL;
}

int ytree_is_null(const ynode_t *node)
{
    static const char *const nulls[] = { "", "~", "null", "Null", "NULL" };
    size_t i;
    if (node == NULL) {
        return 1;
    }
    if (node->kind != YNODE_SCALAR || node->quoted) {
        return 0;
    }
    for (i = 0; i < sizeof nulls / sizeof nulls[0]; i++) {
        if (strcmp(node->text, nulls[i]) == 0) {
            return 1;
        }
    }
    return 0;
}

void ytree_describe(const ynode_t *node, char *buf, size_t len)
{
    const int max = 40;
    if (node == NULL || (node->kind == YNODE_SCALAR && !node->quoted && node->text[0] == '\0')) {
        snprintf(buf, len, "nothing");
    } else if (node->kind == YNODE_MAPPING) {
        snprintf(buf, len, "a mapping");
    } else if (node->kind == YNODE_SEQUENCE) {
        snprintf(buf, len, "a sequence");
    } else {
        const char *cut = strlen(node->text) > (size_t)max ? "..." : "";
        snprintf(buf, len, node->quoted ? "the string \"%.*s%s\"" : "'%.*s%s'",
                 max, node->text, cut);
    }
}

/* ---------------------------------------------------------------- parsing */

typedef struct builder {
    yaml_parser_t parser;
    const char *file;    /* for messages: the file, or NULL for a --set value */
    const char *origin;  /* the --set text, or NULL */
    char *err;
    size_t errlen;
    int depth;
} builder_t;

static int fail_at(builder_t *b, int line, const char *fmt, ...)
{
    char msg[SIM_ERR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (b->origin != NULL) {
        snprintf(b->err, b->errlen, "--set %s: value: %s", b->origin, msg);
    } else if (line > 0) {
        snprintf(b->err, b->errlen, "%s:%d: %s", b->file, line, msg);
    } else {
        snprintf(b->err, b->errlen, "%s: %s", b->file, msg);
    }
    return -1;
}

static int parser_error(builder_t *b)
{
    const yaml_parser_t *p = &b->parser;
    const char *problem = p->problem ? p->problem : "unknown problem";
    switch (p->error) {
    case YAML_MEMORY_ERROR:
        return fail_at(b, 0, "out of memory while reading YAML");
    case YAML_READER_ERROR:
        return fail_at(b, 0, "cannot read: %s (at byte %zu)", problem, p->problem_offset);
    default:
        if (p->context != NULL && b->origin == NULL) {
            return fail_at(b, (int)p->problem_mark.line + 1,
                           "YAML syntax error: %s (%s starting on line %d)", problem,
                           p->context, (int)p->context_mark.line + 1);
        }
        return fail_at(b, (int)p->problem_mark.line + 1, "YAML syntax error: %s", problem);
    }
}

static int next_event(builder_t *b, yaml_event_t *ev)
{
    return yaml_parser_parse(&b->parser, ev) ? 0 : parser_error(b);
}

static int event_line(const builder_t *b, const yaml_event_t *ev)
{
    return b->origin != NULL ? 0 : (int)ev->start_mark.line + 1;
}

static int build_node(builder_t *b, const yaml_event_t *ev, ynode_t **out);

static int build_sequence(builder_t *b, int line, ynode_t **out)
{
    ynode_t *seq = node_new(YNODE_SEQUENCE, line, b->origin);
    if (seq == NULL) {
        return fail_at(b, line, "out of memory");
    }
    for (;;) {
        yaml_event_t ev;
        ynode_t *item;
        int rc;
        if (next_event(b, &ev) != 0) {
            break;
        }
        if (ev.type == YAML_SEQUENCE_END_EVENT) {
            yaml_event_delete(&ev);
            *out = seq;
            return 0;
        }
        rc = build_node(b, &ev, &item);
        yaml_event_delete(&ev);
        if (rc != 0) {
            break;
        }
        if (seq_push(seq, item) != 0) {
            fail_at(b, line, "out of memory");
            break;
        }
    }
    ytree_free(seq);
    return -1;
}

/* Reads one `key: value` entry whose key event is `ev` into `map`. */
static int build_entry(builder_t *b, const yaml_event_t *ev, ynode_t *map)
{
    yaml_event_t vev;
    ynode_t *key, *value;
    int rc;
    if (ev->type != YAML_SCALAR_EVENT) {
        return fail_at(b, event_line(b, ev), "a mapping key must be a scalar");
    }
    if (build_node(b, ev, &key) != 0) {
        return -1;
    }
    if (next_event(b, &vev) != 0) {
        ytree_free(key);
        return -1;
    }
    rc = build_node(b, &vev, &value);
    yaml_event_delete(&vev);
    if (rc != 0) {
        ytree_free(key);
        return -1;
    }
    return map_push(map, key, value) == 0 ? 0 : fail_at(b, key->line, "out of memory");
}

static int build_mapping(builder_t *b, int line, ynode_t **out)
{
    ynode_t *map = node_new(YNODE_MAPPING, line, b->origin);
    if (map == NULL) {
        return fail_at(b, line, "out of memory");
    }
    for (;;) {
        yaml_event_t ev;
        int rc;
        if (next_event(b, &ev) != 0) {
            break;
        }
        if (ev.type == YAML_MAPPING_END_EVENT) {
            yaml_event_delete(&ev);
            *out = map;
            return 0;
        }
        rc = build_entry(b, &ev, map);
        yaml_event_delete(&ev);
        if (rc != 0) {
            break;
        }
    }
    ytree_free(map);
    return -1;
}

/* Builds the node that starts with `ev` (owned by the caller). */
static int build_node(builder_t *b, const yaml_event_t *ev, ynode_t **out)
{
    int line = event_line(b, ev);
    int rc;
    *out = NULL;
    switch (ev->type) {
    case YAML_SCALAR_EVENT:
        if (ev->data.scalar.tag != NULL) {
            return fail_at(b, line, "YAML tags (%s) are not supported", ev->data.scalar.tag);
        }
        if (memchr(ev->data.scalar.value, '\0', ev->data.scalar.length) != NULL) {
            return fail_at(b, line, "a NUL character in a value");
        }
        *out = scalar_new((const char *)ev->data.scalar.value, ev->data.scalar.length,
                          ev->data.scalar.style != YAML_PLAIN_SCALAR_STYLE, line, b->origin);
        return *out != NULL ? 0 : fail_at(b, line, "out of memory");
    case YAML_SEQUENCE_START_EVENT:
    case YAML_MAPPING_START_EVENT:
        if ((ev->type == YAML_SEQUENCE_START_EVENT ? ev->data.sequence_start.tag
                                                   : ev->data.mapping_start.tag) != NULL) {
            return fail_at(b, line, "YAML tags are not supported");
        }
        if (b->depth >= YTREE_MAX_DEPTH) {
            return fail_at(b, line, "nested deeper than %d levels", YTREE_MAX_DEPTH);
        }
        b->depth++;
        rc = ev->type == YAML_SEQUENCE_START_EVENT ? build_sequence(b, line, out)
                                                   : build_mapping(b, line, out);
        b->depth--;
        return rc;
    case YAML_ALIAS_EVENT:
        return fail_at(b, line, "YAML aliases (*%s) are not supported", ev->data.alias.anchor);
    default:
        return fail_at(b, line, "unexpected YAML structure");
    }
}

/* Reads the next event, which must be of `type`. */
static int expect_event(builder_t *b, yaml_event_type_t type)
{
    yaml_event_t ev;
    int rc;
    if (next_event(b, &ev) != 0) {
        return -1;
    }
    rc = ev.type == type ? 0 : fail_at(b, event_line(b, &ev), "unexpected YAML structure");
    yaml_event_delete(&ev);
    return rc;
}

/* stream-start, then nothing or one document, then stream-end. */
static int build_stream(builder_t *b, ynode_t **root)
{
    yaml_event_t ev;
    int rc;
    *root = NULL;
    if (expect_event(b, YAML_STREAM_START_EVENT) != 0 || next_event(b, &ev) != 0) {
        return -1;
    }
    if (ev.type == YAML_STREAM_END_EVENT) {
        yaml_event_delete(&ev);
        return 0;
    }
    yaml_event_delete(&ev);  /* the document start */
    if (next_event(b, &ev) != 0) {
        return -1;
    }
    rc = build_node(b, &ev, root);
    yaml_event_delete(&ev);
    if (rc != 0 || expect_event(b, YAML_DOCUMENT_END_EVENT) != 0 || next_event(b, &ev) != 0) {
        return -1;
    }
    rc = ev.type == YAML_STREAM_END_EVENT
             ? 0
             : fail_at(b, event_line(b, &ev), "only one YAML document is allowed");
    yaml_event_delete(&ev);
    return rc;
}

/* Runs build_stream on an initialised parser and cleans up. */
static int parse_with(builder_t *b, ynode_t **root)
{
    int rc = build_stream(b, root);
    yaml_parser_delete(&b->parser);
    if (rc != 0) {
        ytree_free(*root);
        *root = NULL;
    }
    return rc;
}

int ytree_parse_file(const char *path, ynode_t **root, char *err, size_t errlen)
{
    builder_t b;
    struct stat st;
    FILE *file;
    int rc;
    *root = NULL;
    file = fopen(path, "rb");
    if (file == NULL) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    /* fopen succeeds on a directory; reading it fails less clearly. */
    if (fstat(fileno(file), &st) == 0 && S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(EISDIR));
        fclose(file);
        return -1;
    }
    memset(&b, 0, sizeof b);
    b.file = path;
    b.err = err;
    b.errlen = errlen;
    if (!yaml_parser_initialize(&b.parser)) {
        fclose(file);
        return fail_at(&b, 0, "out of memory");
    }
    yaml_parser_set_input_file(&b.parser, file);
    rc = parse_with(&b, root);
    fclose(file);
    return rc;
}

/* Parses an override's value; an empty value is an empty plain scalar. */
static int parse_value(const char *value, const char *origin, ynode_t **out, char *err,
                       size_t errlen)
{
    builder_t b;
    memset(&b, 0, sizeof b);
    b.origin = origin;
    b.err = err;
    b.errlen = errlen;
    if (!yaml_parser_initialize(&b.parser)) {
        return fail_at(&b, 0, "out of memory");
    }
    yaml_parser_set_input_string(&b.parser, (const unsigned char *)value, strlen(value));
    if (parse_with(&b, out) != 0) {
        return -1;
    }
    if (*out == NULL) {
        *out = scalar_new("", 0, 0, 0, origin);
        if (*out == NULL) {
            return fail_at(&b, 0, "out of memory");
        }
    }
    return 0;
}

/* ---------------------------------------------------------------- overrides */

typedef struct segment {
    const char *start;
    size_t len;
    int bracketed;  /* written "[N]" */
} segment_t;

typedef struct override {
    const char *text;
    char *err;
    size_t errlen;
    segment_t seg[OVERRIDE_MAX_SEGMENTS];
    size_t nseg;
    char where[256];  /* display path of the node reached so far */
} override_t;

static int ofail(override_t *o, const char *fmt, ...)
{
    char msg[384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    snprintf(o->err, o->errlen, "--set %s: %s", o->text, msg);
    return -1;
}

static int all_digits(const char *s, size_t len)
{
    size_t i;
    for (i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9') {
            return 0;
        }
    }
    return len > 0;
}

static int add_segment(override_t *o, const char *start, size_t len, int bracketed)
{
    if (len == 0 || (bracketed && !all_digits(start, len))) {
        return -1;
    }
    if (o->nseg == OVERRIDE_MAX_SEGMENTS) {
        return -1;
    }
    o->seg[o->nseg].start = start;
    o->seg[o->nseg].len = len;
    o->seg[o->nseg].bracketed = bracketed;
    o->nseg++;
    return 0;
}

/* Splits "a.b[2].c" (ending at `end`) into segments. */
static int split_path(override_t *o, const char *p, const char *end)
{
    o->nseg = 0;
    while (p < end) {
        const char *s = p;
        int bracketed = (*p == '[');
        if (bracketed) {
            s = ++p;
            while (p < end && *p != ']') {
                p++;
            }
            if (p == end || add_segment(o, s, (size_t)(p - s), 1) != 0) {
                return -1;
            }
            p++;  /* the ']' */
        } else {
            while (p < end && *p != '.' && *p != '[') {
                p++;
            }
            if (add_segment(o, s, (size_t)(p - s), 0) != 0) {
                return -1;
            }
        }
        if (p < end && *p == '.') {
            p++;
            if (p == end) {
                return -1;  /* a trailing '.' */
            }
        } else if (p < end && *p != '[') {
            return -1;  /* "[1]x" */
        }
    }
    return o->nseg > 0 ? 0 : -1;
}

static void where_append(override_t *o, const segment_t *seg, int as_index)
{
    size_t used = strlen(o->where);
    const char *fmt = as_index ? "[%.*s]" : (used ? ".%.*s" : "%.*s");
    snprintf(o->where + used, sizeof o->where - used, fmt, (int)seg->len, seg->start);
}

/* The slot of key `seg` in `map`, adding the key (with a NULL value). */
static ynode_t **map_slot(override_t *o, ynode_t *map, const segment_t *seg)
{
    size_t i;
    ynode_t *key;
    where_append(o, seg, 0);
    for (i = 0; i < map->count; i++) {
        const char *k = map->pairs[i].key->text;
        if (strlen(k) == seg->len && memcmp(k, seg->start, seg->len) == 0) {
            return &map->pairs[i].value;
        }
    }
    key = scalar_new(seg->start, seg->len, 0, 0, o->text);
    if (key == NULL || map_push(map, key, NULL) != 0) {
        ofail(o, "out of memory");
        return NULL;
    }
    return &map->pairs[map->count - 1].value;
}

/* The slot of index `seg` in `seq`; index == count appends a NULL entry. */
static ynode_t **seq_slot(override_t *o, ynode_t *seq, const segment_t *seg)
{
    unsigned long index;
    if (!all_digits(seg->start, seg->len) || seg->len > 7) {
        ofail(o, "%s: expected an index into the sequence, got '%.*s'", o->where,
              (int)seg->len, seg->start);
        return NULL;
    }
    index = strtoul(seg->start, NULL, 10);
    where_append(o, seg, 1);
    if (index > seq->count || index > OVERRIDE_MAX_INDEX) {
        ofail(o, "%s: index out of range (the sequence has %zu entries)", o->where, seq->count);
        return NULL;
    }
    if (index == seq->count && seq_push(seq, NULL) != 0) {
        ofail(o, "out of memory");
        return NULL;
    }
    return &seq->items[index];
}

/* Makes `*slot` a container for segment `next` if it is absent or null. */
static int ensure_container(override_t *o, ynode_t **slot, const segment_t *next)
{
    char got[64];
    ynode_t *node;
    if (*slot != NULL && !ytree_is_null(*slot)) {
        if ((*slot)->kind != YNODE_SCALAR) {
            return 0;
        }
        ytree_describe(*slot, got, sizeof got);
        return ofail(o, "%s: expected a mapping, got %s", o->where, got);
    }
    node = node_new(all_digits(next->start, next->len) ? YNODE_SEQUENCE : YNODE_MAPPING, 0,
                    o->text);
    if (node == NULL) {
        return ofail(o, "out of memory");
    }
    ytree_free(*slot);
    *slot = node;
    return 0;
}

/* Walks the segments from `*root`, creating what is missing, and stores
 * `value` (taking ownership on success only). */
static int place_value(override_t *o, ynode_t **root, ynode_t *value)
{
    ynode_t **slot = root;
    size_t i;
    if (*root == NULL || ytree_is_null(*root)) {
        ytree_free(*root);
        *root = ytree_new_mapping(0, NULL);
        if (*root == NULL) {
            return ofail(o, "out of memory");
        }
    } else if ((*root)->kind == YNODE_SCALAR) {
        return ofail(o, "the document is not a mapping");
    }
    for (i = 0; i < o->nseg; i++) {
        ynode_t *container = *slot;
        if (container->kind == YNODE_SEQUENCE) {
            slot = seq_slot(o, container, &o->seg[i]);
        } else if (o->seg[i].bracketed) {
            return ofail(o, "%s: expected a sequence, got a mapping", o->where);
        } else {
            slot = map_slot(o, container, &o->seg[i]);
        }
        if (slot == NULL) {
            return -1;
        }
        if (i + 1 < o->nseg && ensure_container(o, slot, &o->seg[i + 1]) != 0) {
            return -1;
        }
    }
    ytree_free(*slot);
    *slot = value;
    return 0;
}

int ytree_apply_override(ynode_t **root, const char *text, char *err, size_t errlen)
{
    override_t o;
    const char *eq;
    ynode_t *value = NULL;
    memset(&o, 0, sizeof o);
    o.text = text != NULL ? text : "";
    o.err = err;
    o.errlen = errlen;
    eq = strchr(o.text, '=');
    if (eq == NULL) {
        return ofail(&o, "expected key.path=value");
    }
    if (split_path(&o, o.text, eq) != 0) {
        return ofail(&o, "malformed key path '%.*s' (expected e.g. robots.count or "
                         "objects.0.x, at most %d parts)",
                     (int)(eq - o.text), o.text, OVERRIDE_MAX_SEGMENTS);
    }
    if (parse_value(eq + 1, o.text, &value, err, errlen) != 0) {
        return -1;
    }
    if (place_value(&o, root, value) != 0) {
        ytree_free(value);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------ writing */

static int emit(yaml_emitter_t *e, yaml_event_t *ev)
{
    return yaml_emitter_emit(e, ev) ? 0 : -1;   /* the emitter frees ev */
}

static int emit_node(yaml_emitter_t *e, const ynode_t *n)
{
    yaml_event_t ev;
    if (n == NULL) {
        yaml_scalar_event_initialize(&ev, NULL, NULL, (yaml_char_t *)"~", 1, 1, 1, YAML_PLAIN_SCALAR_STYLE);
        return emit(e, &ev);
    }
    switch (n->kind) {
    case YNODE_SCALAR:
        /* A quoted scalar stays quoted (a string); a plain one stays plain
         * where YAML allows, so numbers and booleans read back as such.
         * Where it does not (a line break in it), libyaml quotes it, and
         * quoted_implicit lets it do so without the tag "!" that we cannot
         * read back: such text is a string to the schema anyway. */
        yaml_scalar_event_initialize(&ev, NULL, NULL, (yaml_char_t *)n->text, (int)strlen(n->text),
                                     !n->quoted, 1,
                                     n->quoted ? YAML_DOUBLE_QUOTED_SCALAR_STYLE : YAML_ANY_SCALAR_STYLE);
        return emit(e, &ev);
    case YNODE_MAPPING:
        yaml_mapping_start_event_initialize(&ev, NULL, NULL, 1, YAML_BLOCK_MAPPING_STYLE);
        if (emit(e, &ev) != 0) return -1;
        for (size_t i = 0; i < n->count; i++) {
            if (emit_node(e, n->pairs[i].key) != 0 || emit_node(e, n->pairs[i].value) != 0) return -1;
        }
        yaml_mapping_end_event_initialize(&ev);
        return emit(e, &ev);
    case YNODE_SEQUENCE:
        yaml_sequence_start_event_initialize(&ev, NULL, NULL, 1, YAML_BLOCK_SEQUENCE_STYLE);
        if (emit(e, &ev) != 0) return -1;
        for (size_t i = 0; i < n->count; i++) {
            if (emit_node(e, n->items[i]) != 0) return -1;
        }
        yaml_sequence_end_event_initialize(&ev);
        return emit(e, &ev);
    }
    return -1;
}

static int write_to_file(void *data, unsigned char *buffer, size_t size)
{
    return fwrite(buffer, 1, size, (FILE *)data) == size;
}

int ytree_write(FILE *f, const ynode_t *root, char *err, size_t errlen)
{
    yaml_emitter_t e;
    yaml_event_t ev;
    if (!yaml_emitter_initialize(&e)) {
        snprintf(err, errlen, "YAML writer: out of memory");
        return -1;
    }
    yaml_emitter_set_output(&e, write_to_file, f);
    yaml_emitter_set_unicode(&e, 1);
    yaml_emitter_set_width(&e, 100);
    yaml_stream_start_event_initialize(&ev, YAML_UTF8_ENCODING);
    int rc = emit(&e, &ev);
    if (rc == 0) {
        yaml_document_start_event_initialize(&ev, NULL, NULL, NULL, 1);
        rc = emit(&e, &ev);
    }
    if (rc == 0) rc = emit_node(&e, root);
    if (rc == 0) {
        yaml_document_end_event_initialize(&ev, 1);
        rc = emit(&e, &ev);
    }
    if (rc == 0) {
        yaml_stream_end_event_initialize(&ev);
        rc = emit(&e, &ev);
    }
    if (rc != 0) {
        snprintf(err, errlen, "YAML writer: %s", e.problem ? e.problem : "write error");
    }
    yaml_emitter_delete(&e);
    return rc;
}
