/*
 * test_live_params.c - the contract of a controller key marked `live`
 * (param.h), which a run under control sets while it goes (control_t
 * `set`): for every registered controller and every such key, a state
 * initialised with one value and then given another in its params copy
 * (CONTROLLER_LIVE_PARAMS) is byte for byte the state initialised with the
 * other.  (LIVE_DISCOVER=1 lists the unmarked keys that would hold.)
 * A step is a function of the state and the sensors, so from then
 * on the robot behaves as if it had started with the new value: a key its
 * init derives something from (a threshold squared, an embedded
 * controller's own copy) fails here and must not be marked live.  The
 * values tried are each end of the key's range and its default.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "registry.h"

#define PARAMS_MAX 4096

/* Writes `v` into the field `d` describes (its C type). */
static void put(const param_desc_t *d, void *base, double v)
{
    uint8_t *dst = (uint8_t *)base + d->offset;
    switch (d->type) {
    case PARAM_BOOL:
    case PARAM_U8: { uint8_t x = (uint8_t)v; memcpy(dst, &x, 1); break; }
    case PARAM_U16: { uint16_t x = (uint16_t)v; memcpy(dst, &x, 2); break; }
    case PARAM_I16: { int16_t x = (int16_t)v; memcpy(dst, &x, 2); break; }
    case PARAM_U32: { uint32_t x = (uint32_t)v; memcpy(dst, &x, 4); break; }
    case PARAM_U64: { uint64_t x = (uint64_t)v; memcpy(dst, &x, 8); break; }
    case PARAM_FLOAT:
    case PARAM_ANGLE: { float x = (float)v; memcpy(dst, &x, 4); break; }
    case PARAM_DOUBLE: memcpy(dst, &v, 8); break;
    case PARAM_ENUM:
        if (d->size == 1) {
            uint8_t x = (uint8_t)v;
            memcpy(dst, &x, 1);
        } else {
            int x = (int)v;
            memcpy(dst, &x, sizeof x);
        }
        break;
    default: break;
    }
}

/* The ends of d's range as values of its type. */
static void ends(const param_desc_t *d, double out[2])
{
    if (d->type == PARAM_BOOL) {
        out[0] = 0, out[1] = 1;
    } else if (d->type == PARAM_ENUM) {
        size_t n = 0;
        while (d->choices[n]) n++;
        out[0] = 0, out[1] = (double)(n - 1);
    } else {
        out[0] = d->min, out[1] = d->max;
    }
}

/* 1 when init(a) then `v` written into the state's copy equals init(v). */
static int live_holds(const controller_def_t *def, const param_desc_t *d, double v)
{
    uint8_t *pa = calloc(1, PARAMS_MAX), *pb = calloc(1, PARAMS_MAX);
    uint8_t *sa = calloc(1, def->state_size), *sb = calloc(1, def->state_size);
    assert_true(pa && pb && sa && sb);
    def->default_params(pa);
    def->default_params(pb);
    put(d, pb, v);
    def->init(sa, pa, 12345u);
    def->init(sb, pb, 12345u);
    put(d, sa + def->params_offset, v);
    int same = memcmp(sa, sb, def->state_size) == 0;
    free(pa), free(pb), free(sa), free(sb);
    return same;
}

static void test_every_live_key_is_read_from_the_state(void **state)
{
    (void)state;
    unsigned live = 0;
    const controller_def_t *def;
    for (size_t i = 0; (def = registry_controller_at(i)) != NULL; i++) {
        assert_true(def->params_size <= PARAMS_MAX);
        for (const param_desc_t *d = def->params; d && d->key; d++) {
            if (!d->live) {
                if (getenv("LIVE_DISCOVER") && def->params_in_state && d->count == 0 && d->type != PARAM_STRING) {
                    double w[2];
                    ends(d, w);
                    printf("%s %s.%s\n", live_holds(def, d, w[0]) && live_holds(def, d, w[1]) ? "PASS" : "fail", def->name, d->key);
                }
                continue;
            }
            live++;
            if (!def->params_in_state || d->count != 0 || d->type == PARAM_STRING) {
                fail_msg("%s.%s is marked live, but %s", def->name, d->key,
                         !def->params_in_state ? "its def has no CONTROLLER_LIVE_PARAMS" : "it is not a number");
            }
            double v[2];
            ends(d, v);
            for (int k = 0; k < 2; k++) {
                if (!live_holds(def, d, v[k])) {
                    fail_msg("%s.%s is marked live, but its init derives something from it (value %g)",
                             def->name, d->key, v[k]);
                }
            }
        }
    }
    /* The foraging and random-walk scenarios have keys to set. */
    assert_true(live >= 4);
    print_message("%u live keys hold\n", live);
}

/* A probe of this test's own check: a key the init derives something from
 * is caught.  random_walk's speed, written somewhere else than the copy,
 * differs from a state initialised with it. */
static void test_the_check_catches_a_derived_key(void **state)
{
    (void)state;
    const controller_def_t *def = registry_controller("random_walk");
    assert_non_null(def);
    const param_desc_t *d = def->params;
    while (d->key && strcmp(d->key, "speed_steps_s") != 0) d++;
    assert_non_null(d->key);
    controller_def_t wrong = *def;
    wrong.params_offset = def->params_offset + 2u;   /* not where the steps read it */
    assert_false(live_holds(&wrong, d, 0.0));
    assert_true(live_holds(def, d, 0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_live_key_is_read_from_the_state),
        cmocka_unit_test(test_the_check_catches_a_derived_key),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
