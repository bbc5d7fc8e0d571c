/*
 * test_eaipp_msg.c - EAIPP's 16-bit messages (firmware/eaipp/eaipp_msg) and
 * the neighbour table (firmware/eaipp/neighbours): every frame decodes and
 * every valid one re-encodes to itself; round trips of every field value;
 * the table files fields under senders, ages them out, stays bounded.
 * Time: well under a second.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "eaipp/eaipp_msg.h"
#include "eaipp/neighbours.h"

static uint16_t reencode(const eaipp_msg_t *m)
{
    switch (m->kind) {
    case EAIPP_MSG_STATE: return eaipp_msg_state(m->id, m->state, m->source, m->contraction);
    case EAIPP_MSG_GRADIENT: return eaipp_msg_gradient(m->id, m->source, m->gradient);
    case EAIPP_MSG_ROOT: return eaipp_msg_root(m->id, m->root);
    default: return eaipp_msg_exit(m->id, (uint16_t)(m->exit_units * EAIPP_MSG_EXIT_MM),
                                   (uint8_t)(m->exit_units != EAIPP_MSG_EXIT_UNKNOWN));
    }
}

static void test_every_frame(void **state)
{
    uint32_t f, valid = 0, invalid = 0;
    (void)state;
    for (f = 0; f <= 0xFFFFu; f++) {
        eaipp_msg_t m;
        uint8_t v = eaipp_msg_decode((uint16_t)f, &m);
        assert_int_equal(v, m.valid);
        assert_int_equal(m.id, f >> 9);
        assert_int_equal(m.kind, (f >> 7) & 3u);
        if (v) {
            valid++;
            assert_int_equal(reencode(&m), f);
        } else {
            invalid++;
            assert_int_equal(m.kind, EAIPP_MSG_STATE);
        }
    }
    /* STATE: 6 states x 2 x 2 valid of 128 payloads; the other kinds all. */
    assert_int_equal(valid, 128u * (24u + 3u * 128u));
    assert_int_equal(invalid, 128u * (128u - 24u));
}

static void test_round_trips(void **state)
{
    uint16_t id;
    (void)state;
    for (id = 0; id < 128u; id++) {
        uint8_t s, src, c, g;
        uint16_t r, d;
        eaipp_msg_t m;
        for (s = 0; s < EAIPP_ST_COUNT; s++) {
            for (src = 0; src < 2u; src++) {
                for (c = 0; c < 2u; c++) {
                    assert_true(eaipp_msg_decode(eaipp_msg_state(id, s, src, c), &m));
                    assert_int_equal(m.id, id);
                    assert_int_equal(m.kind, EAIPP_MSG_STATE);
                    assert_int_equal(m.state, s);
                    assert_int_equal(m.source, src);
                    assert_int_equal(m.contraction, c);
                }
            }
        }
        for (src = 0; src < 2u; src++) {
            for (g = 0; g <= EAIPP_GRADIENT_MAX; g++) {
                assert_true(eaipp_msg_decode(eaipp_msg_gradient(id, src, g), &m));
                assert_int_equal(m.kind, EAIPP_MSG_GRADIENT);
                assert_int_equal(m.source, src);
                assert_int_equal(m.gradient, g);
            }
        }
        for (r = 0; r < 128u; r++) {
            assert_true(eaipp_msg_decode(eaipp_msg_root(id, r), &m));
            assert_int_equal(m.kind, EAIPP_MSG_ROOT);
            assert_int_equal(m.root, r);
            assert_int_equal(m.id, id);
        }
        for (d = 0; d < 2600u; d += 7u) {
            uint16_t want = (uint16_t)((d + 10u) / 20u);
            assert_true(eaipp_msg_decode(eaipp_msg_exit(id, d, 1u), &m));
            assert_int_equal(m.kind, EAIPP_MSG_EXIT);
            assert_int_equal(m.exit_units, want > 126u ? 126u : want);
        }
        assert_true(eaipp_msg_decode(eaipp_msg_exit(id, 500u, 0u), &m));
        assert_int_equal(m.exit_units, EAIPP_MSG_EXIT_UNKNOWN);
    }
}

static void test_saturation_and_masking(void **state)
{
    eaipp_msg_t m;
    (void)state;
    /* Gradients beyond 62 are "none"; ids and roots keep 7 bits. */
    assert_true(eaipp_msg_decode(eaipp_msg_gradient(3u, 0u, 200u), &m));
    assert_int_equal(m.gradient, EAIPP_GRADIENT_MAX);
    assert_true(eaipp_msg_decode(eaipp_msg_root(130u, 129u), &m));
    assert_int_equal(m.id, 2u);
    assert_int_equal(m.root, 1u);
    assert_true(eaipp_msg_decode(eaipp_msg_exit(1u, 65535u, 1u), &m));
    assert_int_equal(m.exit_units, 126u);
    /* State 6 and 7, and the spare bits, are invalid. */
    assert_false(eaipp_msg_decode((uint16_t)(6u << 4), &m));
    assert_false(eaipp_msg_decode((uint16_t)(7u << 4), &m));
    assert_false(eaipp_msg_decode(0x0001u, &m));
    assert_false(eaipp_msg_decode(0x0002u, &m));
}

static void hear(neighbours_t *t, uint16_t frame, uint16_t range, int16_t bearing)
{
    eaipp_msg_t m;
    assert_true(eaipp_msg_decode(frame, &m));
    assert_non_null(neighbours_hear(t, &m, range, bearing));
}

static void test_table_files_fields(void **state)
{
    neighbours_t t;
    const neighbour_t *nb;
    (void)state;
    neighbours_clear(&t);
    hear(&t, eaipp_msg_state(5u, EAIPP_ST_NODE, EAIPP_SOURCE_FOOD, 1u), 400u, 100);
    nb = neighbours_find(&t, 5u);
    assert_non_null(nb);
    assert_true(neighbour_is(nb, EAIPP_ST_NODE));
    assert_true(neighbour_contraction(nb));
    assert_int_equal(nb->heard, NB_HEARD_STATE);
    assert_int_equal(nb->gradient, EAIPP_GRADIENT_MAX);   /* not heard yet: none */
    hear(&t, eaipp_msg_gradient(5u, EAIPP_SOURCE_FOOD, 4u), 410u, -200);
    hear(&t, eaipp_msg_root(5u, 77u), 420u, 300);
    assert_int_equal(t.count, 1u);
    nb = neighbours_find(&t, 5u);
    assert_int_equal(nb->gradient, 4u);
    assert_true(neighbour_gradient_source(nb));
    assert_int_equal(nb->root, 77u);
    assert_int_equal(nb->range_mm, 420u);        /* the latest measurement */
    assert_int_equal(nb->bearing_mrad, 300);
    assert_true(neighbour_is(nb, EAIPP_ST_NODE)); /* other kinds keep the state */
    assert_true(neighbour_contraction(nb));
    hear(&t, eaipp_msg_state(5u, EAIPP_ST_NODE, EAIPP_SOURCE_FOOD, 0u), 420u, 300);
    assert_false(neighbour_contraction(neighbours_find(&t, 5u)));
    assert_true(neighbour_gradient_source(neighbours_find(&t, 5u)));
    assert_null(neighbours_find(&t, 6u));
}

static void test_table_ages_out(void **state)
{
    neighbours_t t;
    uint8_t k;
    (void)state;
    neighbours_clear(&t);
    hear(&t, eaipp_msg_state(1u, EAIPP_ST_EXPLORER, 0u, 0u), 300u, 0);
    hear(&t, eaipp_msg_state(2u, EAIPP_ST_EXPLORER, 0u, 0u), 300u, 0);
    /* Robot 2 keeps talking, robot 1 falls silent: gone after 5 periods. */
    for (k = 1; k <= 5u; k++) {
        neighbours_age(&t, 5u);
        hear(&t, eaipp_msg_gradient(2u, 0u, 1u), 300u, 0);
        if (k < 5u) {
            assert_non_null(neighbours_find(&t, 1u));
            assert_int_equal(neighbours_find(&t, 1u)->age, k);
        }
    }
    assert_null(neighbours_find(&t, 1u));
    assert_non_null(neighbours_find(&t, 2u));
    assert_int_equal(t.count, 1u);
}

static void test_table_bounded(void **state)
{
    neighbours_t t;
    eaipp_msg_t m;
    uint16_t id;
    (void)state;
    neighbours_clear(&t);
    for (id = 0; id < NEIGHBOURS_MAX; id++) {
        hear(&t, eaipp_msg_state(id, EAIPP_ST_NODE, 0u, 0u), (uint16_t)(100u + id), 0);
    }
    /* Full of robots heard this period: a newcomer is dropped. */
    assert_true(eaipp_msg_decode(eaipp_msg_state(100u, EAIPP_ST_NODE, 0u, 0u), &m));
    assert_null(neighbours_hear(&t, &m, 100u, 0));
    assert_int_equal(t.count, NEIGHBOURS_MAX);
    /* A period later, all but robot 3 heard again: the newcomer takes 3's place. */
    neighbours_age(&t, 10u);
    for (id = 0; id < NEIGHBOURS_MAX; id++) {
        if (id != 3u) {
            hear(&t, eaipp_msg_state(id, EAIPP_ST_NODE, 0u, 0u), 100u, 0);
        }
    }
    assert_non_null(neighbours_hear(&t, &m, 100u, 0));
    assert_null(neighbours_find(&t, 3u));
    assert_non_null(neighbours_find(&t, 100u));
    assert_int_equal(neighbours_find(&t, 100u)->heard, NB_HEARD_STATE);
    assert_int_equal(t.count, NEIGHBOURS_MAX);
}

/* A crowd: nodes and sources keep their places against moving robots. */
static void test_table_nodes_first(void **state)
{
    neighbours_t t;
    eaipp_msg_t m;
    uint16_t id;
    (void)state;
    neighbours_clear(&t);
    for (id = 0; id < NEIGHBOURS_MAX; id++) {
        hear(&t, eaipp_msg_state(id, id == 5u ? EAIPP_ST_NODE : EAIPP_ST_EXPLORER, 0u, 0u), 100u, 0);
    }
    /* Full of robots heard this period: a node's GRADIENT frame takes an
     * explorer's place; an explorer's frame is dropped. */
    assert_true(eaipp_msg_decode(eaipp_msg_gradient(100u, 0u, 4u), &m));
    assert_non_null(neighbours_hear(&t, &m, 100u, 0));
    assert_non_null(neighbours_find(&t, 100u));
    assert_non_null(neighbours_find(&t, 5u));             /* the node stays */
    assert_true(eaipp_msg_decode(eaipp_msg_state(101u, EAIPP_ST_EXPLORER, 0u, 0u), &m));
    assert_null(neighbours_hear(&t, &m, 100u, 0));
    /* A period later, the explorer takes the place of an explorer, not of
     * the nodes, even though they were not heard again either. */
    neighbours_age(&t, 10u);
    assert_non_null(neighbours_hear(&t, &m, 100u, 0));
    assert_non_null(neighbours_find(&t, 5u));
    assert_non_null(neighbours_find(&t, 100u));
    assert_non_null(neighbours_find(&t, 101u));
    /* Full of nodes: an explorer is dropped even when they are old. */
    neighbours_clear(&t);
    for (id = 0; id < NEIGHBOURS_MAX; id++) {
        hear(&t, eaipp_msg_state(id, EAIPP_ST_NODE, 0u, 0u), 100u, 0);
    }
    neighbours_age(&t, 10u);
    assert_null(neighbours_hear(&t, &m, 100u, 0));
    assert_int_equal(t.count, NEIGHBOURS_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_frame),
        cmocka_unit_test(test_round_trips),
        cmocka_unit_test(test_saturation_and_masking),
        cmocka_unit_test(test_table_files_fields),
        cmocka_unit_test(test_table_ages_out),
        cmocka_unit_test(test_table_bounded),
        cmocka_unit_test(test_table_nodes_first),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
