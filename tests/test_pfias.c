/*
 * test_pfias.c - the PFIAS baseline (firmware/pfias) on a fake HAL: its
 * turret codec, the sources, joining at a chainless nest and at a tail,
 * the prey rule, tail members leaving (and not leaving), the reference
 * walking along the colour pattern, and the motion about a reference.
 * Runs in well under a second.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "pfias/pfias.h"
#include "pfias/pfias_msg.h"

#define CHAIN_INIT pfias_init
#define CHAIN_STEP pfias_step
#define CHAIN_DECODE pfias_msg_decode
#include "chain_fixture.h"

static void start(uint16_t p_join, uint16_t p_leave)
{
    pfias_params_t p;
    pfias_default_params(&p);
    p.p_join = p_join;
    p.p_leave = p_leave;
    start_with(&p);
}

/* ------------------------------------------------------------ codec */

static void test_codec_round_trip(void **state)
{
    pfias_msg_t m;
    (void)state;
    assert_int_equal(pfias_msg_decode(pfias_msg_nest(3u), &m), PFIAS_MSG_NEST);
    assert_int_equal(m.id, 3u);
    assert_int_equal(pfias_msg_decode(pfias_msg_food(600u), &m), PFIAS_MSG_FOOD);
    assert_int_equal(m.id, 600u & PFIAS_ID_MASK);
    assert_int_equal(pfias_msg_decode(pfias_msg_explorer(511u), &m), PFIAS_MSG_EXPLORER);
    assert_int_equal(m.id, 511u);
    assert_int_equal(pfias_msg_decode(pfias_msg_chain(9u, PFIAS_RED, 1u, 0u), &m), PFIAS_MSG_CHAIN);
    assert_int_equal(m.colour, PFIAS_RED);
    assert_int_equal(m.tail, 1u);
    assert_int_equal(m.prey, 0u);
    assert_int_equal(m.id, 9u);
    assert_int_equal(pfias_msg_decode(pfias_msg_chain(9u, PFIAS_GREEN, 0u, 1u), &m), PFIAS_MSG_CHAIN);
    assert_int_equal(m.colour, PFIAS_GREEN);
    assert_int_equal(m.tail, 0u);
    assert_int_equal(m.prey, 1u);
    assert_int_equal(pfias_next_colour(PFIAS_RED), PFIAS_BLUE);
    assert_int_equal(pfias_prev_colour(PFIAS_BLUE), PFIAS_RED);
}

static void test_codec_rejects_malformed(void **state)
{
    pfias_msg_t m;
    uint16_t f;
    (void)state;
    assert_int_equal(pfias_msg_decode(0u, &m), PFIAS_MSG_INVALID);
    for (f = 5u; f <= 7u; f++) {
        assert_int_equal(pfias_msg_decode((uint16_t)(f << 13), &m), PFIAS_MSG_INVALID);
    }
    /* colour 3 */
    assert_int_equal(pfias_msg_decode((uint16_t)((4u << 13) | (3u << 11)), &m), PFIAS_MSG_INVALID);
    assert_int_equal(m.kind, PFIAS_MSG_INVALID);
    assert_int_equal(m.colour, 0u);
    /* a nest frame with a chain flag set */
    assert_int_equal(pfias_msg_decode((uint16_t)(pfias_msg_nest(1u) | 0x0400u), &m), PFIAS_MSG_INVALID);
    /* over libIrcom's 8 bits every frame loses its kind */
    assert_int_equal(pfias_msg_decode((uint16_t)(pfias_msg_chain(5u, 1u, 1u, 1u) & 0xFFu), &m),
                     PFIAS_MSG_INVALID);
}

/* ------------------------------------------------------------ sources */

static void test_sources_broadcast_their_role(void **state)
{
    pfias_params_t p;
    (void)state;
    pfias_default_params(&p);
    p.role = PFIAS_ROLE_NEST;
    start_with(&p);
    step();
    assert_string_equal(pfias_state_name(&C), "source");
    assert_int_equal(last_sent().kind, PFIAS_MSG_NEST);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    p.role = PFIAS_ROLE_FOOD;
    start_with(&p);
    step();
    assert_int_equal(last_sent().kind, PFIAS_MSG_FOOD);
    assert_int_equal(last_sent().id, 7u);
}

/* ------------------------------------------------------------ lost, explorer */

static void test_lost_walks_silently_until_it_perceives_the_nest(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    for (i = 0; i < 20; i++) {
        step();
    }
    assert_string_equal(pfias_state_name(&C), "lost");
    assert_int_equal(H.out_count, 0u);
    assert_true(H.left != 0 || H.right != 0);
    /* A nest beyond R is not perceived. */
    hear(pfias_msg_nest(1u), 700u, 0);
    step();
    assert_string_equal(pfias_state_name(&C), "lost");
    hear(pfias_msg_nest(1u), 590u, 0);
    step();
    assert_string_equal(pfias_state_name(&C), "explorer");
    assert_int_equal(last_sent().kind, PFIAS_MSG_EXPLORER);
    assert_int_equal(C.ref, PFIAS_REF_NEST);
}

static void test_joins_a_chainless_nest_on_the_link_circle(void **state)
{
    int i;
    (void)state;
    start(0u, 0u);
    for (i = 0; i < 200; i++) {
        hear(pfias_msg_nest(1u), 450u, 1000);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "explorer");   /* P_e->c = 0: never */

    start(ALWAYS, 0u);
    hear(pfias_msg_nest(1u), 200u, 0);   /* inside the link circle: not yet */
    step();
    hear(pfias_msg_nest(1u), 200u, 0);
    step();
    assert_string_equal(pfias_state_name(&C), "explorer");
    for (i = 0; i < 5 && C.state != PFIAS_MEMBER; i++) {
        hear(pfias_msg_nest(1u), 450u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "member");
    assert_int_equal(C.colour, PFIAS_BLUE);
    assert_int_equal(C.joins, 1u);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    hear(pfias_msg_nest(1u), 450u, 0);
    step();
    assert_int_equal(last_sent().kind, PFIAS_MSG_CHAIN);
    assert_int_equal(last_sent().colour, PFIAS_BLUE);
    assert_int_equal(last_sent().tail, 1u);
}

static void test_nest_with_a_chain_is_no_place_to_join(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    hear(pfias_msg_nest(1u), 450u, 0);
    step();
    for (i = 0; i < 50; i++) {
        /* a blue member in view: the explorer walks out along it */
        hear(pfias_msg_nest(1u), 450u, 0);
        hear(pfias_msg_chain(2u, PFIAS_BLUE, 0u, 0u), 580u, 1500);
        hear(pfias_msg_chain(3u, PFIAS_GREEN, 1u, 0u), 590u, 1400);
        step();
        assert_string_equal(pfias_state_name(&C), "explorer");
    }
    assert_int_equal(C.ref, PFIAS_GREEN);   /* blue, then green: the next colours */
}

static void test_joins_at_the_tail_with_the_next_colour(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    /* Found a green member: two members in view, no joining yet. */
    for (i = 0; i < 30; i++) {
        hear(pfias_msg_chain(4u, PFIAS_GREEN, 1u, 0u), 450u, 0);
        hear(pfias_msg_chain(5u, PFIAS_BLUE, 0u, 0u), 500u, 3000);
        step();
        assert_string_equal(pfias_state_name(&C), "explorer");
    }
    /* The blue one out of range: only the tail in view, on the link circle. */
    for (i = 0; i < 5 && C.state != PFIAS_MEMBER; i++) {
        hear(pfias_msg_chain(4u, PFIAS_GREEN, 1u, 0u), 450u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "member");
    assert_int_equal(C.colour, PFIAS_RED);
}

static void test_not_at_a_member_that_is_not_the_tail(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    for (i = 0; i < 100; i++) {
        hear(pfias_msg_chain(4u, PFIAS_GREEN, 0u, 0u), 450u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "explorer");
}

static void test_prey_rule_joins_at_once_and_never_leaves(void **state)
{
    int i;
    (void)state;
    start(0u, ALWAYS);   /* P_e->c = 0: only the prey rule can make it join */
    hear(pfias_msg_chain(4u, PFIAS_RED, 1u, 0u), 500u, 0);
    step();
    hear(pfias_msg_chain(4u, PFIAS_RED, 1u, 0u), 500u, 0);
    hear(pfias_msg_food(8u), 400u, 500);
    step();
    assert_string_equal(pfias_state_name(&C), "member");
    assert_int_equal(C.colour, PFIAS_BLUE);
    assert_int_equal(C.prey, 1u);
    for (i = 0; i < 200; i++) {
        hear(pfias_msg_chain(4u, PFIAS_RED, 0u, 0u), 500u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "member");   /* P_c->e = 1, but prey */
    assert_int_equal(last_sent().prey, 1u);
    assert_int_equal(last_sent().tail, 1u);
}

static void test_prey_rule_needs_at_most_one_member(void **state)
{
    int i;
    (void)state;
    start(0u, 0u);
    for (i = 0; i < 20; i++) {
        hear(pfias_msg_chain(4u, PFIAS_RED, 1u, 0u), 500u, 0);
        hear(pfias_msg_chain(6u, PFIAS_GREEN, 0u, 0u), 500u, 3000);
        hear(pfias_msg_food(8u), 400u, 500);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "explorer");
}

/* A member made by joining a chainless nest. */
static void make_member(uint16_t p_leave)
{
    int i;
    start(ALWAYS, p_leave);
    for (i = 0; i < 10 && C.state != PFIAS_MEMBER; i++) {
        hear(pfias_msg_nest(1u), 450u, 0);
        step();
    }
    assert_int_equal(C.state, PFIAS_MEMBER);
}

static void test_tail_leaves_only_without_explorers(void **state)
{
    int i;
    (void)state;
    make_member(ALWAYS);
    for (i = 0; i < 100; i++) {
        hear(pfias_msg_nest(1u), 450u, 0);
        hear(pfias_msg_explorer(9u), 300u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "member");
    for (i = 0; i < 5 && C.state == PFIAS_MEMBER; i++) {
        hear(pfias_msg_nest(1u), 450u, 0);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "explorer");
    assert_int_equal(C.outward, 0u);   /* back towards the nest */
    assert_int_equal(C.ref, PFIAS_REF_NEST);
    assert_int_equal(C.leaves, 1u);
}

static void test_member_with_a_successor_never_leaves(void **state)
{
    int i;
    (void)state;
    make_member(ALWAYS);
    for (i = 0; i < 300; i++) {
        hear(pfias_msg_nest(1u), 450u, 0);
        hear(pfias_msg_chain(3u, PFIAS_GREEN, 1u, 0u), 450u, 3000);
        step();
    }
    assert_string_equal(pfias_state_name(&C), "member");
    assert_int_equal(C.tail, 0u);
    assert_int_equal(last_sent().tail, 0u);
}

static void test_member_cut_off_from_the_nest_leaves(void **state)
{
    int i;
    (void)state;
    make_member(0u);
    for (i = 0; i < 3 + 30; i++) {   /* forget_steps, then lost_steps */
        step();
        assert_string_equal(pfias_state_name(&C), "member");
    }
    step();
    assert_string_equal(pfias_state_name(&C), "explorer");
}

static void test_reference_walks_back_to_the_nest(void **state)
{
    (void)state;
    make_member(ALWAYS);
    hear(pfias_msg_nest(1u), 450u, 0);
    step();
    assert_int_equal(C.state, PFIAS_EXPLORER);
    assert_int_equal(C.outward, 0u);
    /* At the nest (within the link circle and a quarter) it turns outward. */
    hear(pfias_msg_nest(1u), 500u, 0);
    step();
    assert_int_equal(C.outward, 1u);

    /* Going back from red: green, blue, nest, in the pattern's reverse. */
    start(0u, 0u);
    hear(pfias_msg_chain(4u, PFIAS_RED, 1u, 0u), 500u, 0);
    step();
    C.outward = 0u;
    hear(pfias_msg_chain(4u, PFIAS_RED, 1u, 0u), 500u, 0);
    hear(pfias_msg_chain(5u, PFIAS_GREEN, 0u, 0u), 550u, 3000);
    step();
    assert_int_equal(C.ref, PFIAS_GREEN);
    hear(pfias_msg_chain(6u, PFIAS_BLUE, 0u, 0u), 550u, 3000);
    step();
    assert_int_equal(C.ref, PFIAS_BLUE);
    hear(pfias_msg_nest(1u), 590u, 3000);
    step();
    assert_int_equal(C.ref, PFIAS_REF_NEST);
}

static void test_explorer_without_reference_gets_lost(void **state)
{
    int i;
    (void)state;
    start(0u, 0u);
    hear(pfias_msg_nest(1u), 450u, 0);
    step();
    assert_int_equal(C.state, PFIAS_EXPLORER);
    for (i = 0; i < 3 + 30; i++) {   /* forget_steps, then lost_steps */
        step();
    }
    assert_string_equal(pfias_state_name(&C), "explorer");
    step();
    assert_string_equal(pfias_state_name(&C), "lost");
}

/* ------------------------------------------------------------ motion */

static void test_motion_about_the_reference(void **state)
{
    (void)state;
    start(0u, 0u);
    /* Far ahead (beyond the link): AD pulls forward, MP to one side. */
    hear(pfias_msg_nest(1u), 590u, 0);
    step();
    assert_true(H.left + H.right > 0);
    /* Exactly on the link circle dead ahead: only MP, perpendicular: the
     * robot turns (in place: the sum points 90 degrees off). */
    hear(pfias_msg_nest(1u), 450u, 0);
    step();
    assert_true(H.left == -H.right);
    assert_true(H.left != 0);
    if (C.circle_sign > 0) {
        assert_true(H.right > 0);   /* counter-clockwise about it: turn left */
    } else {
        assert_true(H.right < 0);
    }
    /* On the circle with the reference on its left (circling
     * counter-clockwise, robot tangent): straight on. */
    C.circle_sign = 1;
    hear(pfias_msg_nest(1u), 450u, -1571);
    step();
    assert_true(H.left > 0 && H.right > 0);
    assert_true(H.left - H.right < 40 && H.right - H.left < 40);
}

static void test_avoids_obstacles_ahead(void **state)
{
    (void)state;
    start(0u, 0u);
    hear(pfias_msg_nest(1u), 590u, 0);
    step();
    /* a wall dead ahead on both front sensors: no forward motion */
    H.proximity[0] = 3000u;
    H.proximity[7] = 3000u;
    hear(pfias_msg_nest(1u), 590u, 0);
    step();
    assert_true(H.left + H.right <= 0 || H.left == -H.right);
}

static void test_reset_replays_the_same_run(void **state)
{
    uint16_t a[60], b[60];
    int i, r;
    (void)state;
    for (r = 0; r < 2; r++) {
        uint16_t *out = r == 0 ? a : b;
        start(20000u, 20000u);
        if (r == 1) {
            pfias_reset(&C);
        }
        for (i = 0; i < 60; i++) {
            hear(pfias_msg_nest(1u), 450u, (int16_t)(i * 50));
            if (i > 20) {
                hear(pfias_msg_explorer(9u), 300u, 0);
            }
            step();
            out[i] = (uint16_t)(C.state * 1000 + (uint16_t)H.left);
        }
    }
    assert_memory_equal(a, b, sizeof a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_codec_round_trip),
        cmocka_unit_test(test_codec_rejects_malformed),
        cmocka_unit_test(test_sources_broadcast_their_role),
        cmocka_unit_test(test_lost_walks_silently_until_it_perceives_the_nest),
        cmocka_unit_test(test_joins_a_chainless_nest_on_the_link_circle),
        cmocka_unit_test(test_nest_with_a_chain_is_no_place_to_join),
        cmocka_unit_test(test_joins_at_the_tail_with_the_next_colour),
        cmocka_unit_test(test_not_at_a_member_that_is_not_the_tail),
        cmocka_unit_test(test_prey_rule_joins_at_once_and_never_leaves),
        cmocka_unit_test(test_prey_rule_needs_at_most_one_member),
        cmocka_unit_test(test_tail_leaves_only_without_explorers),
        cmocka_unit_test(test_member_with_a_successor_never_leaves),
        cmocka_unit_test(test_member_cut_off_from_the_nest_leaves),
        cmocka_unit_test(test_reference_walks_back_to_the_nest),
        cmocka_unit_test(test_explorer_without_reference_gets_lost),
        cmocka_unit_test(test_motion_about_the_reference),
        cmocka_unit_test(test_avoids_obstacles_ahead),
        cmocka_unit_test(test_reset_replays_the_same_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
