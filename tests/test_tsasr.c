/*
 * test_tsasr.c - the TSASR baseline (firmware/tsasr, a reconstruction) on a
 * fake HAL: its turret codec (with the retreat flag), the sources, joining
 * (at a chainless nest, at a tail, not at a retreating tail), the prey rule,
 * the elimination mechanism's timing (the tail's timer, its reset by a
 * successor, the retreat and the leave, the cascade down the chain and its
 * absence), PFIAS's random leave, the frames and lights, and replay after
 * a reset.  Runs in well under a second.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "tsasr/tsasr.h"
#include "tsasr/tsasr_msg.h"

#define CHAIN_INIT tsasr_init
#define CHAIN_STEP tsasr_step
#define CHAIN_DECODE tsasr_msg_decode
#include "chain_fixture.h"

#define ELIM 50u        /* elim_steps in the timing tests */
#define RETREAT 5u      /* retreat_steps in the timing tests */
#define FORGET 3u       /* forget_steps (the default): heard at t, gone at t + FORGET + 1 */

static void params(tsasr_params_t *p, uint16_t p_join, uint16_t p_leave)
{
    tsasr_default_params(p);
    p->p_join = p_join;
    p->p_leave = p_leave;
    p->elim_steps = ELIM;
    p->retreat_steps = RETREAT;
}

static void start(uint16_t p_join, uint16_t p_leave)
{
    tsasr_params_t p;
    params(&p, p_join, p_leave);
    start_with(&p);
}

/* ------------------------------------------------------------ codec */

static void test_codec_round_trip(void **state)
{
    tsasr_msg_t m;
    (void)state;
    assert_int_equal(tsasr_msg_decode(tsasr_msg_nest(3u), &m), TSASR_MSG_NEST);
    assert_int_equal(m.id, 3u);
    assert_int_equal(tsasr_msg_decode(tsasr_msg_food(300u), &m), TSASR_MSG_FOOD);
    assert_int_equal(m.id, 300u & TSASR_ID_MASK);
    assert_int_equal(tsasr_msg_decode(tsasr_msg_explorer(255u), &m), TSASR_MSG_EXPLORER);
    assert_int_equal(m.id, 255u);
    assert_int_equal(tsasr_msg_decode(tsasr_msg_chain(9u, TSASR_RED, 1u, 0u, 0u), &m), TSASR_MSG_CHAIN);
    assert_int_equal(m.colour, TSASR_RED);
    assert_int_equal(m.tail, 1u);
    assert_int_equal(m.prey, 0u);
    assert_int_equal(m.retreat, 0u);
    assert_int_equal(m.id, 9u);
    assert_int_equal(tsasr_msg_decode(tsasr_msg_chain(9u, TSASR_GREEN, 0u, 1u, 0u), &m), TSASR_MSG_CHAIN);
    assert_int_equal(m.colour, TSASR_GREEN);
    assert_int_equal(m.tail, 0u);
    assert_int_equal(m.prey, 1u);
    assert_int_equal(tsasr_msg_decode(tsasr_msg_chain(200u, TSASR_BLUE, 1u, 0u, 1u), &m), TSASR_MSG_CHAIN);
    assert_int_equal(m.colour, TSASR_BLUE);
    assert_int_equal(m.retreat, 1u);
    assert_int_equal(m.tail, 1u);
    assert_int_equal(m.id, 200u);
    /* a colour above 2 is reduced mod 3 */
    assert_int_equal(tsasr_msg_decode(tsasr_msg_chain(1u, 4u, 0u, 0u, 0u), &m), TSASR_MSG_CHAIN);
    assert_int_equal(m.colour, TSASR_GREEN);
    assert_int_equal(tsasr_next_colour(TSASR_RED), TSASR_BLUE);
    assert_int_equal(tsasr_prev_colour(TSASR_BLUE), TSASR_RED);
}

static void test_codec_rejects_malformed(void **state)
{
    tsasr_msg_t m;
    uint16_t f;
    (void)state;
    assert_int_equal(tsasr_msg_decode(0u, &m), TSASR_MSG_INVALID);
    for (f = 5u; f <= 7u; f++) {
        assert_int_equal(tsasr_msg_decode((uint16_t)(f << 13), &m), TSASR_MSG_INVALID);
    }
    /* colour 3 */
    assert_int_equal(tsasr_msg_decode((uint16_t)((4u << 13) | (3u << 11)), &m), TSASR_MSG_INVALID);
    assert_int_equal(m.kind, TSASR_MSG_INVALID);
    assert_int_equal(m.colour, 0u);
    /* a nest, food or explorer frame with a chain flag (tail, prey, retreat, id bit 8) set */
    assert_int_equal(tsasr_msg_decode((uint16_t)(tsasr_msg_nest(1u) | 0x0400u), &m), TSASR_MSG_INVALID);
    assert_int_equal(tsasr_msg_decode((uint16_t)(tsasr_msg_food(1u) | 0x0100u), &m), TSASR_MSG_INVALID);
    assert_int_equal(tsasr_msg_decode((uint16_t)(tsasr_msg_explorer(1u) | 0x0200u), &m), TSASR_MSG_INVALID);
    assert_int_equal(m.retreat, 0u);
    /* over libIrcom's 8 bits every frame loses its kind */
    assert_int_equal(tsasr_msg_decode((uint16_t)(tsasr_msg_chain(5u, 1u, 1u, 1u, 1u) & 0xFFu), &m),
                     TSASR_MSG_INVALID);
}

/* ------------------------------------------------------------ sources, lost */

static void test_sources_broadcast_their_role(void **state)
{
    tsasr_params_t p;
    int i;
    (void)state;
    tsasr_default_params(&p);
    p.role = TSASR_ROLE_NEST;
    start_with(&p);
    for (i = 0; i < 400; i++) {   /* past elim_steps: a source never changes */
        hear(tsasr_msg_chain(2u, TSASR_BLUE, 1u, 0u, 0u), 450u, 0);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "source");
    assert_int_equal(last_sent().kind, TSASR_MSG_NEST);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    p.role = TSASR_ROLE_FOOD;
    start_with(&p);
    step();
    assert_int_equal(last_sent().kind, TSASR_MSG_FOOD);
    assert_int_equal(last_sent().id, 7u);
}

static void test_lost_walks_silently_until_it_perceives_the_nest(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    for (i = 0; i < 20; i++) {
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "lost");
    assert_int_equal(H.out_count, 0u);
    assert_true(H.left != 0 || H.right != 0);
    hear(tsasr_msg_nest(1u), 700u, 0);   /* beyond R */
    step();
    assert_string_equal(tsasr_state_name(&C), "lost");
    hear(tsasr_msg_nest(1u), 590u, 0);
    step();
    assert_string_equal(tsasr_state_name(&C), "explorer");
    assert_int_equal(last_sent().kind, TSASR_MSG_EXPLORER);
    assert_int_equal(C.ref, TSASR_REF_NEST);
}

/* ------------------------------------------------------------ joining */

static void test_joins_a_chainless_nest_on_the_link_circle(void **state)
{
    int i;
    (void)state;
    start(0u, 0u);
    for (i = 0; i < 200; i++) {
        hear(tsasr_msg_nest(1u), 450u, 1000);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "explorer");   /* p_join = 0: never */

    start(ALWAYS, 0u);
    hear(tsasr_msg_nest(1u), 200u, 0);   /* inside the link circle: not yet */
    step();
    hear(tsasr_msg_nest(1u), 200u, 0);
    step();
    assert_string_equal(tsasr_state_name(&C), "explorer");
    for (i = 0; i < 5 && C.state != TSASR_MEMBER; i++) {
        hear(tsasr_msg_nest(1u), 450u, 0);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.colour, TSASR_BLUE);
    assert_int_equal(C.joins, 1u);
    assert_int_equal(H.left, 0);
    assert_int_equal(H.right, 0);
    hear(tsasr_msg_nest(1u), 450u, 0);
    step();
    assert_int_equal(last_sent().kind, TSASR_MSG_CHAIN);
    assert_int_equal(last_sent().colour, TSASR_BLUE);
    assert_int_equal(last_sent().tail, 1u);
    assert_int_equal(last_sent().retreat, 0u);
}

static void test_joins_at_the_tail_with_the_next_colour(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    /* Two members in view: no joining yet; the reference steps out to green. */
    for (i = 0; i < 30; i++) {
        hear(tsasr_msg_chain(4u, TSASR_GREEN, 1u, 0u, 0u), 450u, 0);
        hear(tsasr_msg_chain(5u, TSASR_BLUE, 0u, 0u, 0u), 500u, 3000);
        step();
        assert_string_equal(tsasr_state_name(&C), "explorer");
    }
    /* Only the tail in view, on the link circle. */
    for (i = 0; i < 5 && C.state != TSASR_MEMBER; i++) {
        hear(tsasr_msg_chain(4u, TSASR_GREEN, 1u, 0u, 0u), 450u, 0);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.colour, TSASR_RED);
}

static void test_not_at_a_member_that_is_not_the_tail(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    for (i = 0; i < 100; i++) {
        hear(tsasr_msg_chain(4u, TSASR_GREEN, 0u, 0u, 0u), 450u, 0);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "explorer");
}

static void test_retreating_tail_is_not_extended_and_turns_explorers_back(void **state)
{
    int i;
    (void)state;
    start(ALWAYS, 0u);
    for (i = 0; i < 100; i++) {
        hear(tsasr_msg_chain(4u, TSASR_GREEN, 1u, 0u, 1u), 450u, 0);
        step();
        assert_string_equal(tsasr_state_name(&C), "explorer");
    }
    assert_int_equal(C.outward, 0u);   /* going back towards the nest */
    assert_int_equal(C.joins, 0u);
}

static void test_prey_rule_joins_a_retreating_tail_and_never_leaves(void **state)
{
    int i;
    (void)state;
    start(0u, ALWAYS);   /* p_join = 0: only the prey rule can make it join */
    hear(tsasr_msg_chain(4u, TSASR_RED, 1u, 0u, 1u), 500u, 0);
    step();
    hear(tsasr_msg_chain(4u, TSASR_RED, 1u, 0u, 1u), 500u, 0);
    hear(tsasr_msg_food(8u), 400u, 500);
    step();
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.colour, TSASR_BLUE);
    assert_int_equal(C.prey, 1u);
    for (i = 0; i < 4 * (int)ELIM; i++) {   /* p_leave = 1 and past the elimination time */
        hear(tsasr_msg_chain(4u, TSASR_RED, 0u, 0u, 0u), 500u, 0);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.retreat, 0u);
    assert_int_equal(C.leaves, 0u);
    assert_int_equal(last_sent().prey, 1u);
    assert_int_equal(last_sent().tail, 1u);
}

static void test_prey_rule_needs_at_most_one_member(void **state)
{
    int i;
    (void)state;
    start(0u, 0u);
    for (i = 0; i < 20; i++) {
        hear(tsasr_msg_chain(4u, TSASR_RED, 1u, 0u, 0u), 500u, 0);
        hear(tsasr_msg_chain(6u, TSASR_GREEN, 0u, 0u, 0u), 500u, 3000);
        hear(tsasr_msg_food(8u), 400u, 500);
        step();
    }
    assert_string_equal(tsasr_state_name(&C), "explorer");
}

/* ------------------------------------------------------------ elimination */

/* A member made by joining a chainless nest, with the given parameters. */
static void make_member_with(const tsasr_params_t *p)
{
    int i;
    start_with(p);
    for (i = 0; i < 10 && C.state != TSASR_MEMBER; i++) {
        hear(tsasr_msg_nest(1u), 450u, 0);
        step();
    }
    assert_int_equal(C.state, TSASR_MEMBER);
}

static void make_member(uint16_t p_leave)
{
    tsasr_params_t p;
    params(&p, ALWAYS, p_leave);
    make_member_with(&p);
}

/* One step of a member beside the nest, with an optional successor frame. */
static void member_step(uint16_t successor)
{
    hear(tsasr_msg_nest(1u), 450u, 0);
    if (successor != 0u) {
        hear(successor, 450u, 3000);
    }
    step();
}

static void test_tail_is_eliminated_after_elim_steps_then_retreat_steps(void **state)
{
    uint32_t i;
    (void)state;
    make_member(0u);
    for (i = 1u; i < ELIM; i++) {
        member_step(0u);
        assert_int_equal(C.retreat, 0u);
        assert_int_equal(last_sent().retreat, 0u);
    }
    member_step(0u);   /* the ELIM-th step as the tail: found nothing in time */
    assert_int_equal(C.retreat, 1u);
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(last_sent().retreat, 1u);
    assert_int_equal(last_sent().tail, 1u);
    assert_int_equal(H.leds, 0xFFu);   /* all ring LEDs while retreating */
    for (i = 1u; i < RETREAT; i++) {
        member_step(0u);
        assert_string_equal(tsasr_state_name(&C), "member");
        assert_int_equal(H.left, 0);
        assert_int_equal(H.right, 0);
    }
    member_step(0u);
    assert_string_equal(tsasr_state_name(&C), "explorer");
    assert_int_equal(C.outward, 0u);              /* back along the chain */
    assert_int_equal(C.ref, TSASR_REF_NEST);
    assert_int_equal(C.eliminations, 1u);
    assert_int_equal(C.leaves, 1u);
    assert_int_equal(last_sent().kind, TSASR_MSG_EXPLORER);
}

static void test_a_successor_resets_the_timer(void **state)
{
    uint32_t i;
    const uint16_t green = tsasr_msg_chain(3u, TSASR_GREEN, 1u, 0u, 0u);
    (void)state;
    make_member(0u);
    for (i = 0u; i < 3u * ELIM; i++) {   /* the chain goes on past it: never */
        member_step(green);
    }
    assert_int_equal(C.tail, 0u);
    assert_int_equal(C.retreat, 0u);
    assert_int_equal(last_sent().tail, 0u);
    /* The successor leaves at random (no retreat flag): it is the tail again
     * once it has forgotten it, and its timer starts from zero there. */
    for (i = 0u; i < FORGET; i++) {
        member_step(0u);
        assert_int_equal(C.tail, 0u);
    }
    for (i = 1u; i < ELIM; i++) {
        member_step(0u);
        assert_int_equal(C.tail, 1u);
        assert_int_equal(C.retreat, 0u);
    }
    member_step(0u);
    assert_int_equal(C.retreat, 1u);
}

static void test_the_elimination_cascades_down_the_chain(void **state)
{
    uint32_t i;
    const uint16_t retreating = tsasr_msg_chain(3u, TSASR_GREEN, 1u, 0u, 1u);
    (void)state;
    make_member(0u);
    /* While its successor retreats it waits (it is not the tail). */
    for (i = 0u; i < 2u * ELIM; i++) {
        member_step(retreating);
        assert_int_equal(C.tail, 0u);
        assert_int_equal(C.retreat, 0u);
    }
    /* The successor has left: it retreats as soon as it is the tail ... */
    for (i = 0u; i < FORGET; i++) {
        member_step(0u);
        assert_int_equal(C.retreat, 0u);
    }
    member_step(0u);
    assert_int_equal(C.tail, 1u);
    assert_int_equal(C.retreat, 1u);
    /* ... and leaves retreat_steps later. */
    for (i = 1u; i < RETREAT; i++) {
        member_step(0u);
        assert_int_equal(C.state, TSASR_MEMBER);
    }
    member_step(0u);
    assert_string_equal(tsasr_state_name(&C), "explorer");
    assert_int_equal(C.eliminations, 1u);
}

static void test_without_cascade_the_new_tail_restarts_its_timer(void **state)
{
    uint32_t i;
    tsasr_params_t p;
    (void)state;
    params(&p, ALWAYS, 0u);
    p.elim_cascade = 0u;
    make_member_with(&p);
    for (i = 0u; i < 10u; i++) {
        member_step(tsasr_msg_chain(3u, TSASR_GREEN, 1u, 0u, 1u));
    }
    for (i = 0u; i < FORGET + ELIM - 1u; i++) {
        member_step(0u);
        assert_int_equal(C.retreat, 0u);
    }
    member_step(0u);
    assert_int_equal(C.retreat, 1u);
}

static void test_a_new_successor_cancels_the_retreat(void **state)
{
    uint32_t i;
    (void)state;
    make_member(0u);
    for (i = 0u; i < ELIM; i++) {
        member_step(0u);
    }
    assert_int_equal(C.retreat, 1u);
    /* An explorer reached the target past it (the prey rule): it stays. */
    member_step(tsasr_msg_chain(3u, TSASR_GREEN, 1u, 1u, 0u));
    assert_int_equal(C.retreat, 0u);
    for (i = 0u; i < 2u * ELIM; i++) {
        member_step(tsasr_msg_chain(3u, TSASR_GREEN, 1u, 1u, 0u));
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.eliminations, 0u);
}

static void test_a_tail_at_the_target_is_never_eliminated(void **state)
{
    uint32_t i;
    (void)state;
    make_member(ALWAYS);
    for (i = 0u; i < 4u * ELIM; i++) {
        hear(tsasr_msg_food(8u), 500u, 1000);
        member_step(0u);
    }
    /* The food out of view again: the member keeps its prey mark. */
    for (i = 0u; i < 4u * ELIM; i++) {
        member_step(0u);
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    assert_int_equal(C.prey, 1u);
    assert_int_equal(C.retreat, 0u);
    assert_int_equal(last_sent().prey, 1u);
}

static void test_explorer_reset_variant_holds_the_timer(void **state)
{
    uint32_t i;
    tsasr_params_t p;
    (void)state;
    /* Default: an explorer about the tail does not stop the clock. */
    make_member(0u);
    for (i = 0u; i < ELIM; i++) {
        hear(tsasr_msg_explorer(9u), 300u, 0);
        member_step(0u);
    }
    assert_int_equal(C.retreat, 1u);
    /* elim_explorer_resets: it does, and the count starts again after. */
    params(&p, ALWAYS, 0u);
    p.elim_explorer_resets = 1u;
    make_member_with(&p);
    for (i = 0u; i < 3u * ELIM; i++) {
        hear(tsasr_msg_explorer(9u), 300u, 0);
        member_step(0u);
    }
    assert_int_equal(C.retreat, 0u);
    for (i = 0u; i < FORGET + ELIM - 1u; i++) {
        member_step(0u);
        assert_int_equal(C.retreat, 0u);
    }
    member_step(0u);
    assert_int_equal(C.retreat, 1u);
}

/* ------------------------------------------------------------ PFIAS's leave */

static void test_random_leave_only_without_explorers(void **state)
{
    int i;
    (void)state;
    make_member(ALWAYS);
    for (i = 0; i < (int)ELIM / 2; i++) {
        hear(tsasr_msg_explorer(9u), 300u, 0);
        member_step(0u);
    }
    assert_string_equal(tsasr_state_name(&C), "member");
    for (i = 0; i < 5 && C.state == TSASR_MEMBER; i++) {
        member_step(0u);
    }
    assert_string_equal(tsasr_state_name(&C), "explorer");
    assert_int_equal(C.outward, 0u);
    assert_int_equal(C.ref, TSASR_REF_NEST);
    assert_int_equal(C.leaves, 1u);
    assert_int_equal(C.eliminations, 0u);   /* at random, not by elimination */
}

static void test_member_cut_off_from_the_nest_leaves(void **state)
{
    int i;
    (void)state;
    make_member(0u);
    for (i = 0; i < 3 + 30; i++) {   /* forget_steps, then lost_steps */
        step();
        assert_string_equal(tsasr_state_name(&C), "member");
    }
    step();
    assert_string_equal(tsasr_state_name(&C), "explorer");
    assert_int_equal(C.eliminations, 0u);
}

/* ------------------------------------------------------------ motion, replay */

static void test_explorer_moves_about_its_reference(void **state)
{
    (void)state;
    start(0u, 0u);
    hear(tsasr_msg_nest(1u), 590u, 0);
    step();
    assert_true(H.left + H.right > 0);   /* far: AD pulls it forward */
    hear(tsasr_msg_nest(1u), 450u, 0);
    step();
    assert_true(H.left == -H.right);     /* on the circle: MP only, a turn */
    assert_true(H.left != 0);
}

static void test_reset_replays_the_same_run(void **state)
{
    uint16_t a[400], b[400];
    int i, r;
    tsasr_params_t p;
    (void)state;
    params(&p, 20000u, 300u);
    for (r = 0; r < 2; r++) {
        uint16_t *out = r == 0 ? a : b;
        start_with(&p);
        if (r == 1) {
            tsasr_reset(&C);
        }
        for (i = 0; i < 400; i++) {
            hear(tsasr_msg_nest(1u), 450u, (int16_t)((i % 60) * 50));
            if (i > 20 && i < 40) {
                hear(tsasr_msg_explorer(9u), 300u, 0);
            }
            step();
            out[i] = (uint16_t)(C.state * 1000u + C.retreat * 100u + (uint16_t)H.left);
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
        cmocka_unit_test(test_joins_at_the_tail_with_the_next_colour),
        cmocka_unit_test(test_not_at_a_member_that_is_not_the_tail),
        cmocka_unit_test(test_retreating_tail_is_not_extended_and_turns_explorers_back),
        cmocka_unit_test(test_prey_rule_joins_a_retreating_tail_and_never_leaves),
        cmocka_unit_test(test_prey_rule_needs_at_most_one_member),
        cmocka_unit_test(test_tail_is_eliminated_after_elim_steps_then_retreat_steps),
        cmocka_unit_test(test_a_successor_resets_the_timer),
        cmocka_unit_test(test_the_elimination_cascades_down_the_chain),
        cmocka_unit_test(test_without_cascade_the_new_tail_restarts_its_timer),
        cmocka_unit_test(test_a_new_successor_cancels_the_retreat),
        cmocka_unit_test(test_a_tail_at_the_target_is_never_eliminated),
        cmocka_unit_test(test_explorer_reset_variant_holds_the_timer),
        cmocka_unit_test(test_random_leave_only_without_explorers),
        cmocka_unit_test(test_member_cut_off_from_the_nest_leaves),
        cmocka_unit_test(test_explorer_moves_about_its_reference),
        cmocka_unit_test(test_reset_replays_the_same_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
