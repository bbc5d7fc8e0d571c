/*
 * test_eaipp.c - EAIPP's mechanisms on the fake HAL (firmware/eaipp):
 * Algorithm 1 over a hand-built neighbour set, Algorithm 2's timing and
 * flag forwarding, Algorithm 4's distance check, Algorithm 3's wheel law,
 * the lost robot's transitions, the sources, and how long a gradient takes
 * to cross a chain of 10 nodes.  Time: well under a second.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include "fake_hal.h"
#include "eaipp/eaipp.h"
#include "units.h"

static void make(eaipp_t *e, uint8_t role)
{
    eaipp_params_t p;
    eaipp_default_params(&p);
    p.role = role;
    eaipp_init(e, &p, 1u);
}

static void hear(eaipp_t *e, uint16_t frame, uint16_t range, int16_t bearing)
{
    eaipp_msg_t m;
    assert_true(eaipp_msg_decode(frame, &m));
    assert_non_null(neighbours_hear(&e->nb, &m, range, bearing));
}

/* A node neighbour with every field heard. */
static void node(eaipp_t *e, uint8_t id, uint8_t src, uint8_t g, uint8_t root, uint8_t flag, uint16_t range)
{
    hear(e, eaipp_msg_state(id, EAIPP_ST_NODE, src, flag), range, 0);
    hear(e, eaipp_msg_gradient(id, src, g), range, 0);
    hear(e, eaipp_msg_root(id, root), range, 0);
}

static void test_gradient(void **state)
{
    eaipp_t e;
    (void)state;
    make(&e, EAIPP_ROLE_ROBOT);
    e.state = EAIPP_NODE;
    e.id = 50u;
    assert_false(eaipp_gradient_update(&e));          /* nothing heard */
    assert_int_equal(e.gradient, EAIPP_GRADIENT_MAX);
    /* Food-sourced nodes at 1 and 4, a nest-sourced node at 6: the nest
     * gradient wins whatever its value (Algorithm 1's order). */
    node(&e, 10u, EAIPP_SOURCE_FOOD, 1u, 10u, 0u, 400u);
    node(&e, 11u, EAIPP_SOURCE_FOOD, 4u, 10u, 0u, 400u);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.gradient, 2u);
    assert_int_equal(e.source, EAIPP_SOURCE_FOOD);
    assert_int_equal(e.parent, 10u);
    assert_int_equal(e.root, 10u);
    node(&e, 12u, EAIPP_SOURCE_NEST, 6u, 33u, 0u, 400u);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.gradient, 7u);
    assert_int_equal(e.source, EAIPP_SOURCE_NEST);
    assert_int_equal(e.parent, 12u);
    assert_int_equal(e.root, 33u);                     /* the parent's Root_ID */
    assert_int_equal(e.children, 0u);
    /* The nest itself (gradient 0 from its STATE alone) beats node 12. */
    hear(&e, eaipp_msg_state(0u, EAIPP_ST_NEST, EAIPP_SOURCE_NEST, 0u), 300u, 0);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.gradient, 1u);
    assert_int_equal(e.parent, 0u);
    assert_int_equal(e.root, 0u);
    /* Two children (nest-sourced, gradient 2): the branch forks here. */
    node(&e, 20u, EAIPP_SOURCE_NEST, 2u, 50u, 0u, 400u);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.children, 1u);
    assert_int_equal(e.root, 0u);
    node(&e, 21u, EAIPP_SOURCE_NEST, 2u, 50u, 0u, 400u);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.children, 2u);
    assert_int_equal(e.root, 50u);
    /* Explorers and nodes with no gradient heard are no sources. */
    make(&e, EAIPP_ROLE_ROBOT);
    hear(&e, eaipp_msg_state(7u, EAIPP_ST_EXPLORER, 0u, 0u), 300u, 0);
    hear(&e, eaipp_msg_state(8u, EAIPP_ST_NODE, 0u, 0u), 300u, 0);
    assert_false(eaipp_gradient_update(&e));
}

static void test_food_source(void **state)
{
    eaipp_t e;
    (void)state;
    make(&e, EAIPP_ROLE_ROBOT);
    assert_int_equal(e.p.food_source, 0u);             /* the default: the food is the target only */
    e.state = EAIPP_NODE;
    hear(&e, eaipp_msg_state(3u, EAIPP_ST_FOOD, EAIPP_SOURCE_FOOD, 0u), 300u, 0);
    assert_false(eaipp_gradient_update(&e));          /* the food is no source */
    e.state = EAIPP_EXPLORER;
    e.nb.n[0].range_mm = 500u;
    assert_false(eaipp_extension_due(&e));            /* nor the one of Algorithm 4 */
    e.p.food_source = 1u;
    assert_true(eaipp_extension_due(&e));
    e.state = EAIPP_NODE;
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.source, EAIPP_SOURCE_FOOD);
}

/* same_source: an explorer at the end of the nest's network (its one nest
 * node farther than B_UL) that also hears the food's network joins, and
 * the node it becomes takes the nest's gradient (the two are linked);
 * without it the two nodes make two and it does not join. */
static void test_same_source_merge(void **state)
{
    eaipp_t e;
    (void)state;
    make(&e, EAIPP_ROLE_ROBOT);
    assert_int_equal(e.p.same_source, 0u);
    e.p.food_source = 1u;
    e.state = EAIPP_EXPLORER;
    node(&e, 10u, EAIPP_SOURCE_NEST, 4u, 10u, 0u, 500u);   /* the nest's end, beyond B_UL */
    node(&e, 20u, EAIPP_SOURCE_FOOD, 3u, 20u, 0u, 300u);   /* a food node */
    assert_false(eaipp_extension_due(&e));                /* two nodes heard: the printed rule */
    e.p.same_source = 1u;
    assert_true(eaipp_extension_due(&e));                 /* one of its own network */
    e.state = EAIPP_NODE;
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.source, EAIPP_SOURCE_NEST);        /* the nest's network wins */
    assert_int_equal(e.gradient, 5u);
    assert_int_equal(e.parent, 10u);
    /* A second nest node nearer than B_UL: no longer the network's end. */
    e.state = EAIPP_EXPLORER;
    node(&e, 11u, EAIPP_SOURCE_NEST, 5u, 10u, 0u, 200u);
    assert_false(eaipp_extension_due(&e));
    /* Without food_source the option does nothing (the food is no source). */
    make(&e, EAIPP_ROLE_ROBOT);
    e.p.same_source = 1u;
    e.state = EAIPP_EXPLORER;
    node(&e, 10u, EAIPP_SOURCE_NEST, 4u, 10u, 0u, 500u);
    node(&e, 20u, EAIPP_SOURCE_FOOD, 3u, 20u, 0u, 300u);
    assert_false(eaipp_extension_due(&e));
}

/* A branch end: parent 10 (root 5) only, so no child. */
static void branch_end(eaipp_t *e, uint8_t root_of_parent)
{
    make(e, EAIPP_ROLE_ROBOT);
    e->state = EAIPP_NODE;
    e->id = 40u;
    e->p.period1_steps = 20u;
    e->p.period2_steps = 30u;
    node(e, 10u, EAIPP_SOURCE_NEST, 3u, root_of_parent, 0u, 450u);
    assert_true(eaipp_gradient_update(e));
}

static void test_extinction_timing(void **state)
{
    eaipp_t e;
    uint16_t k;
    (void)state;
    /* No explorer: lost after PERIOD_TIME_1 + 1 steps. */
    branch_end(&e, 5u);
    for (k = 1; k <= 20u; k++) {
        eaipp_extinction_step(&e);
        assert_int_equal(e.state, EAIPP_NODE);
    }
    eaipp_extinction_step(&e);
    assert_int_equal(e.state, EAIPP_LOST);
    assert_int_equal(e.leaves, 1u);
    assert_int_equal(e.shun_root, 5u);                 /* will not rejoin that branch */
    /* Explorers around but no child: the flag rises after PERIOD_TIME_2 + 1. */
    branch_end(&e, 5u);
    hear(&e, eaipp_msg_state(60u, EAIPP_ST_EXPLORER, 0u, 0u), 300u, 0);
    for (k = 1; k <= 30u; k++) {
        eaipp_extinction_step(&e);
        assert_int_equal(e.contraction, 0u);
    }
    eaipp_extinction_step(&e);
    assert_int_equal(e.contraction, 1u);
    assert_int_equal(e.state, EAIPP_NODE);
    /* The explorer leaves: PERIOD_TIME_1 later the end node leaves as an
     * explorer, since its parent (10) is not its Root_ID (5). */
    e.nb.count = 0u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 5u, 1u, 450u);
    for (k = 1; k <= 20u; k++) {
        eaipp_extinction_step(&e);
    }
    assert_int_equal(e.state, EAIPP_NODE);
    eaipp_extinction_step(&e);
    assert_int_equal(e.state, EAIPP_EXPLORER);
    /* It retreats along its branch: the node it shuns still keeps it an
     * explorer (not lost), but it does not join it. */
    {
        hal_t hal;
        fake_hal_init(&hal, 40u);
        e.nb.count = 0u;
        fake_hal_push(&hal, eaipp_msg_state(10u, EAIPP_ST_NODE, EAIPP_SOURCE_NEST, 1u), 500u, 0);
        fake_hal_push(&hal, eaipp_msg_gradient(10u, EAIPP_SOURCE_NEST, 3u), 500u, 0);
        fake_hal_push(&hal, eaipp_msg_root(10u, 5u), 500u, 0);
        eaipp_step(&e, &hal);
        assert_int_equal(e.state, EAIPP_EXPLORER);
        assert_int_equal(e.retreating, 1u);
    }
    /* The last node before the fork (parent == Root_ID) stays as a marker. */
    branch_end(&e, 10u);
    e.contraction = 1u;
    for (k = 1; k <= 100u; k++) {
        eaipp_extinction_step(&e);
    }
    assert_int_equal(e.state, EAIPP_NODE);
}

/* A node that left does not rejoin its branch: neither nodes of its old
 * Root_ID nor its old P_Node, whose Root_ID changes when the leaver was one
 * of the two children of a fork; nor the nest when that was its parent. */
static void test_shunning(void **state)
{
    eaipp_t e;
    uint16_t k;
    (void)state;
    branch_end(&e, 10u);                               /* parent 10 is a fork: Root_ID 10 */
    for (k = 0; k <= 20u; k++) {
        eaipp_extinction_step(&e);
    }
    assert_int_equal(e.state, EAIPP_LOST);
    e.state = EAIPP_EXPLORER;
    e.shun_steps = 5u;
    e.nb.count = 0u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 2u, 0u, 500u); /* no longer a fork: Root_ID 2 */
    assert_false(eaipp_extension_due(&e));
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 10u, 0u, 500u);
    assert_false(eaipp_extension_due(&e));
    e.nb.count = 0u;
    node(&e, 11u, EAIPP_SOURCE_NEST, 3u, 10u, 0u, 500u); /* another node of the old branch */
    assert_false(eaipp_extension_due(&e));
    e.nb.count = 0u;
    node(&e, 12u, EAIPP_SOURCE_NEST, 3u, 7u, 0u, 500u);  /* another branch: yes */
    assert_true(eaipp_extension_due(&e));
    e.shun_steps = 0u;                                  /* the shunning is over */
    e.nb.count = 0u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 2u, 0u, 500u);
    assert_true(eaipp_extension_due(&e));
    /* A node next to the nest that left ignores the nest for a while. */
    make(&e, EAIPP_ROLE_ROBOT);
    e.state = EAIPP_NODE;
    e.id = 40u;
    e.p.period1_steps = 20u;
    hear(&e, eaipp_msg_state(0u, EAIPP_ST_NEST, EAIPP_SOURCE_NEST, 0u), 460u, 0);
    hear(&e, eaipp_msg_root(0u, 0u), 460u, 0);
    assert_true(eaipp_gradient_update(&e));
    for (k = 0; k <= 20u; k++) {
        eaipp_extinction_step(&e);
    }
    assert_int_equal(e.state, EAIPP_LOST);
    e.state = EAIPP_EXPLORER;
    assert_false(eaipp_extension_due(&e));
}

static void test_flag_forwarding(void **state)
{
    eaipp_t e;
    (void)state;
    make(&e, EAIPP_ROLE_ROBOT);
    e.state = EAIPP_NODE;
    e.id = 40u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 5u, 0u, 450u);        /* parent */
    node(&e, 41u, EAIPP_SOURCE_NEST, 5u, 5u, 1u, 450u);        /* child, contracting */
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.children, 1u);
    eaipp_extinction_step(&e);
    assert_int_equal(e.contraction, 1u);
    /* A child of another branch (other Root_ID) is not followed. */
    e.nb.count = 0u;
    e.contraction = 0u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 5u, 0u, 450u);
    node(&e, 41u, EAIPP_SOURCE_NEST, 5u, 9u, 1u, 450u);
    assert_true(eaipp_gradient_update(&e));
    eaipp_extinction_step(&e);
    assert_int_equal(e.contraction, 0u);
    /* A fork (two children, Root_ID its own id) does not take a child's flag. */
    e.nb.count = 0u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 3u, 5u, 0u, 450u);
    node(&e, 41u, EAIPP_SOURCE_NEST, 5u, 40u, 1u, 450u);
    node(&e, 42u, EAIPP_SOURCE_NEST, 5u, 40u, 0u, 450u);
    assert_true(eaipp_gradient_update(&e));
    assert_int_equal(e.children, 2u);
    assert_int_equal(e.root, 40u);
    eaipp_extinction_step(&e);
    assert_int_equal(e.contraction, 0u);
}

static void test_extension_distance(void **state)
{
    eaipp_t e;
    (void)state;
    make(&e, EAIPP_ROLE_ROBOT);
    e.state = EAIPP_EXPLORER;
    /* One node at 0.6 R, at B_UL = 0.75 R, just beyond, near R (R = 600 mm):
     * Algorithm 4's "measured_distance > B_UL", no upper bound. */
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 360u);
    assert_false(eaipp_extension_due(&e));
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 450u);
    assert_false(eaipp_extension_due(&e));
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 451u);
    assert_true(eaipp_extension_due(&e));
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 590u);
    assert_true(eaipp_extension_due(&e));
    /* The optional window (b_ul_max): not beyond it. */
    e.p.b_ul_max_mm = 480u;
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 480u);
    assert_true(eaipp_extension_due(&e));
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 510u);
    assert_false(eaipp_extension_due(&e));
    e.p.b_ul_max_mm = 0u;
    /* Contracting branch: no. */
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 1u, 450u);
    assert_false(eaipp_extension_due(&e));
    /* Two nodes heard: no (Algorithm 4 wants exactly one). */
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 450u);
    node(&e, 11u, EAIPP_SOURCE_NEST, 1u, 1u, 0u, 700u);
    assert_false(eaipp_extension_due(&e));
    /* ext_strict: a neighbour whose STATE is not heard yet may be a node:
     * wait; the one node's range must be this period's.  Off: neither. */
    make(&e, EAIPP_ROLE_ROBOT);
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 500u);
    assert_true(eaipp_extension_due(&e));
    hear(&e, eaipp_msg_gradient(12u, EAIPP_SOURCE_NEST, 3u), 550u, 0);
    assert_true(eaipp_extension_due(&e));
    e.p.ext_strict = 1u;
    assert_false(eaipp_extension_due(&e));
    make(&e, EAIPP_ROLE_ROBOT);
    node(&e, 10u, EAIPP_SOURCE_NEST, 2u, 1u, 0u, 500u);
    neighbours_age(&e.nb, 10u);
    assert_true(eaipp_extension_due(&e));
    e.p.ext_strict = 1u;
    assert_false(eaipp_extension_due(&e));
    /* The nest alone counts as the one. */
    make(&e, EAIPP_ROLE_ROBOT);
    hear(&e, eaipp_msg_state(0u, EAIPP_ST_NEST, 0u, 0u), 460u, 0);
    hear(&e, eaipp_msg_state(7u, EAIPP_ST_EXPLORER, 0u, 0u), 100u, 0);
    assert_true(eaipp_extension_due(&e));
}

static void test_wheel_law(void **state)
{
    int16_t l, r;
    int8_t side = 0;
    (void)state;
    eaipp_wheel_law(1.0f, 0.0f, 400u, 400u, &side, &l, &r);          /* straight ahead */
    assert_int_equal(l, 400);
    assert_int_equal(r, 400);
    eaipp_wheel_law(1.0f, 1.0f, 400u, 400u, &side, &l, &r);          /* 45 deg left: left wheel at 1/2 */
    assert_in_range(l, 198, 202);
    assert_int_equal(r, 400);
    assert_int_equal(side, 1);
    eaipp_wheel_law(1.0f, -1.0f, 400u, 400u, &side, &l, &r);         /* 45 deg right */
    assert_int_equal(l, 400);
    assert_in_range(r, 198, 202);
    assert_int_equal(side, -1);
    eaipp_wheel_law(0.0f, 1.0f, 400u, 400u, &side, &l, &r);          /* 90 deg left: pivot on the left wheel */
    assert_true(l >= -2 && l <= 2);
    side = 0;
    eaipp_wheel_law(-1.0f, -0.001f, 400u, 400u, &side, &l, &r);      /* behind: spin in place */
    assert_int_equal(l, 400);
    assert_true(r >= -402 && r <= -396);
    /* Behind, a little to the left then a little to the right: the spin
     * keeps its side (right) instead of dithering. */
    eaipp_wheel_law(-1.0f, 0.1f, 400u, 400u, &side, &l, &r);
    assert_int_equal(l, 400);
    assert_true(r < -300);
    eaipp_wheel_law(-1.0f, -0.1f, 400u, 400u, &side, &l, &r);
    assert_int_equal(l, 400);
    assert_true(r < -300);
    /* Off (hold 0): the sign of the angle decides. */
    eaipp_wheel_law(-1.0f, 0.1f, 400u, 0u, &side, &l, &r);
    assert_true(l < -300);
    assert_int_equal(r, 400);
    /* Well to the side, the angle decides whatever the last side. */
    side = -1;
    eaipp_wheel_law(-1.0f, 1.0f, 400u, 400u, &side, &l, &r);          /* 135 deg left */
    assert_true(l < 0);
    assert_int_equal(r, 400);
}

static void test_direction(void **state)
{
    eaipp_t e;
    uint16_t prox[HAL_IR_COUNT] = { 0 };
    int16_t bearing[HAL_IR_COUNT];
    float vx, vy;
    uint8_t i;
    (void)state;
    for (i = 0; i < HAL_IR_COUNT; i++) bearing[i] = units_ir_bearing_mrad(i);
    make(&e, EAIPP_ROLE_ROBOT);
    /* Gradient 1 to the left, gradient 3 to the right: go right (toward
     * the branch end). */
    node(&e, 10u, 0u, 1u, 1u, 0u, 400u);
    e.nb.n[0].bearing_mrad = 1571;
    node(&e, 11u, 0u, 3u, 1u, 0u, 400u);
    e.nb.n[1].bearing_mrad = -1571;
    eaipp_direction(&e, prox, bearing, &vx, &vy);
    assert_true(vy < -0.9f);
    /* The branch contracts: back toward the low gradient. */
    node(&e, 11u, 0u, 3u, 1u, 1u, 400u);
    node(&e, 10u, 0u, 1u, 1u, 1u, 400u);
    e.nb.n[0].bearing_mrad = 1571;
    e.nb.n[1].bearing_mrad = -1571;
    eaipp_direction(&e, prox, bearing, &vx, &vy);
    assert_true(vy > 0.9f);
    /* Just past the end node of a branch (gradient 2, 0.1 m behind), the
     * node before it (gradient 1) 0.55 m behind: the linear reading (the
     * default) leads on, beyond the end; the inverse one back to the end. */
    e.nb.count = 0u;
    node(&e, 10u, 0u, 2u, 1u, 0u, 100u);
    e.nb.n[0].bearing_mrad = 3141;
    node(&e, 11u, 0u, 1u, 1u, 0u, 550u);
    e.nb.n[1].bearing_mrad = 3141;
    assert_int_equal(e.p.a_distance, EAIPP_A_LINEAR);
    eaipp_direction(&e, prox, bearing, &vx, &vy);
    assert_true(vx > 0.9f);
    e.p.a_distance = EAIPP_A_INVERSE;
    eaipp_direction(&e, prox, bearing, &vx, &vy);
    assert_true(vx < -0.9f);
    /* A wall touching the front sensors dominates: away from it. */
    prox[0] = prox[7] = 2000u;
    eaipp_direction(&e, prox, bearing, &vx, &vy);
    assert_true(vx < -0.5f);
}

static void test_lost_and_sources(void **state)
{
    eaipp_t e;
    hal_t hal;
    eaipp_msg_t m;
    (void)state;
    fake_hal_init(&hal, 9u);
    make(&e, EAIPP_ROLE_ROBOT);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "lost");
    assert_int_equal(hal.left, 388);                   /* straight on */
    assert_int_equal(hal.right, 388);
    fake_hal_end_step(&hal);
    hal.proximity[0] = 1500u;                          /* something ahead-right */
    eaipp_step(&e, &hal);
    assert_true(hal.left < 0 && hal.right > 0);        /* turns left, away */
    fake_hal_end_step(&hal);
    hal.proximity[0] = 0u;
    /* The food alone (not a source, the default): still lost; a node: explorer. */
    fake_hal_push(&hal, eaipp_msg_state(3u, EAIPP_ST_FOOD, 1u, 0u), 300u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "lost");
    fake_hal_end_step(&hal);
    fake_hal_push(&hal, eaipp_msg_state(4u, EAIPP_ST_NODE, 0u, 0u), 300u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "explorer");
    assert_true(eaipp_msg_decode(hal.last_sent, &m));
    assert_int_equal(m.kind, EAIPP_MSG_STATE);
    assert_int_equal(m.state, EAIPP_ST_EXPLORER);
    assert_int_equal(m.id, 9u);
    /* The nest never moves and sends STATE, GRADIENT 0, ROOT = own id in turn. */
    fake_hal_init(&hal, 130u);
    make(&e, EAIPP_ROLE_NEST);
    {
        uint8_t k;
        for (k = 0; k < 3u; k++) {
            eaipp_step(&e, &hal);
            assert_int_equal(hal.left, 0);
            assert_true(eaipp_msg_decode(hal.last_sent, &m));
            assert_int_equal(m.id, 2u);
            assert_int_equal(m.kind, k);
            fake_hal_end_step(&hal);
        }
    }
    assert_true(eaipp_msg_decode(hal.outbox[1], &m));
    assert_int_equal(m.gradient, 0u);
    assert_int_equal(m.source, EAIPP_SOURCE_NEST);
    assert_true(eaipp_msg_decode(hal.outbox[2], &m));
    assert_int_equal(m.root, 2u);
    assert_string_equal(eaipp_state_name(&e), "nest");
}

/* Robot_Lost turns only from what is ahead: a wall behind it (after a turn
 * away from it) must not start another turn, or it spins in the corner. */
static void test_lost_rear_wall(void **state)
{
    eaipp_t e;
    hal_t hal;
    (void)state;
    fake_hal_init(&hal, 9u);
    make(&e, EAIPP_ROLE_ROBOT);
    hal.proximity[3] = hal.proximity[4] = 1500u;       /* behind, +-150 deg */
    hal.proximity[2] = 1500u;                          /* beside, -90 deg */
    eaipp_step(&e, &hal);
    assert_int_equal(hal.left, 388);
    assert_int_equal(hal.right, 388);
    fake_hal_end_step(&hal);
    hal.proximity[7] = 1500u;                          /* ahead-left: turn right */
    eaipp_step(&e, &hal);
    assert_true(hal.left > 0 && hal.right < 0);
}

/* Section 5.1's exit (lj_exit): a lost robot that hears the nest, or an
 * exiting robot, starts exiting; it heads for the nest, or for the exiting
 * neighbour nearest to it, pushed off exiting robots that are too near
 * (Lennard-Jones), broadcasts its distance, and becomes an explorer at the
 * nest.  Off by default. */
static void test_lj_exit(void **state)
{
    eaipp_t e;
    hal_t hal;
    eaipp_msg_t m;
    float vx, vy;
    uint8_t k, exits = 0u;
    (void)state;
    /* Off: the nest makes an explorer, as in the square arena. */
    fake_hal_init(&hal, 9u);
    make(&e, EAIPP_ROLE_ROBOT);
    fake_hal_push(&hal, eaipp_msg_state(0u, EAIPP_ST_NEST, 0u, 0u), 700u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "explorer");
    /* On: an exiting neighbour (its distance 1.0 m, 300 mm to my left). */
    fake_hal_init(&hal, 9u);
    make(&e, EAIPP_ROLE_ROBOT);
    e.p.lj_exit = 1u;
    fake_hal_push(&hal, eaipp_msg_state(20u, EAIPP_ST_EXITING, 0u, 0u), 300u, 1571);
    fake_hal_push(&hal, eaipp_msg_exit(20u, 1000u, 1u), 300u, 1571);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "exiting");
    fake_hal_end_step(&hal);
    fake_hal_push(&hal, eaipp_msg_exit(20u, 1000u, 1u), 300u, 1571);
    eaipp_step(&e, &hal);
    assert_int_equal(e.exit_mm, 1300u);                /* its distance + the range to it */
    assert_true(e.heading_y > 0.5f);                   /* toward it (left) */
    assert_true(hal.right > hal.left);
    for (k = 0; k < hal.out_count; k++) {
        assert_true(eaipp_msg_decode(hal.outbox[k], &m));
        if (m.kind == EAIPP_MSG_EXIT) {
            exits++;
            assert_int_equal(m.exit_units, 65u);       /* 1300 mm / 20 */
        }
    }
    assert_int_equal(exits, 1u);                       /* STATE, then EXIT: one each a period */
    fake_hal_end_step(&hal);
    /* The nest heard at 600 mm ahead wins over the neighbour's 1.3 m. */
    fake_hal_push(&hal, eaipp_msg_state(0u, EAIPP_ST_NEST, 0u, 0u), 600u, 0);
    eaipp_step(&e, &hal);
    assert_int_equal(e.exit_mm, 600u);
    assert_true(eaipp_exit_direction(&e, &vx, &vy));
    assert_true(vx > 0.9f);
    fake_hal_end_step(&hal);
    /* Lennard-Jones: an exiting robot 60 mm ahead pushes harder than the
     * pull to the nest ahead; one at 300 mm (beyond 2^(1/6) sigma = 168 mm)
     * pulls a little. */
    hear(&e, eaipp_msg_state(21u, EAIPP_ST_EXITING, 0u, 0u), 60u, 0);
    assert_true(eaipp_exit_direction(&e, &vx, &vy));
    assert_true(vx < 0.5f);
    hear(&e, eaipp_msg_state(21u, EAIPP_ST_EXITING, 0u, 0u), 300u, 1571);
    assert_true(eaipp_exit_direction(&e, &vx, &vy));
    assert_true(vy > 0.0f && vx > 0.9f);
    /* At the nest: an explorer, and never exiting again. */
    fake_hal_push(&hal, eaipp_msg_state(0u, EAIPP_ST_NEST, 0u, 0u), 200u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "explorer");
    assert_int_equal(e.exited, 1u);
    e.state = EAIPP_LOST;
    e.nb.count = 0u;
    fake_hal_end_step(&hal);
    fake_hal_push(&hal, eaipp_msg_state(20u, EAIPP_ST_EXITING, 0u, 0u), 300u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "lost");
    /* Exiting with nothing to follow: lost again (still to exit). */
    fake_hal_init(&hal, 9u);
    make(&e, EAIPP_ROLE_ROBOT);
    e.p.lj_exit = 1u;
    fake_hal_push(&hal, eaipp_msg_state(20u, EAIPP_ST_EXITING, 0u, 0u), 300u, 0);
    eaipp_step(&e, &hal);
    assert_string_equal(eaipp_state_name(&e), "exiting");
    fake_hal_end_step(&hal);
    eaipp_step(&e, &hal);                              /* 20's distance never heard */
    assert_string_equal(eaipp_state_name(&e), "lost");
    assert_int_equal(e.exited, 0u);
}

/* A chain: robot 0 the nest, 1..10 nodes 450 mm apart, 11 the food; each
 * hears its two neighbours only, `tx` messages a period each, no loss. */
#define CHAIN 12u
static uint32_t steps_to_cross(uint8_t tx)
{
    static hal_t hal[CHAIN];
    static eaipp_t e[CHAIN];
    uint32_t sent[CHAIN] = { 0 };
    uint32_t t, i;
    for (i = 0; i < CHAIN; i++) {
        fake_hal_init(&hal[i], (uint16_t)i);
        hal[i].tx_per_step = tx;
        make(&e[i], i == 0u ? EAIPP_ROLE_NEST : i == CHAIN - 1u ? EAIPP_ROLE_FOOD : EAIPP_ROLE_ROBOT);
        e[i].p.timeout_steps = 250u;   /* a static chain: nobody is forgotten */
        e[i].p.period1_steps = 60000u;
        e[i].p.food_source = 1u;       /* two gradients, to see the nest's override the food's */
        if (i > 0u && i < CHAIN - 1u) e[i].state = EAIPP_NODE;
    }
    /* Warm-up with the nest silent: the food's gradient fills the chain;
     * then the nest speaks, and its gradient (which wins) must reach node
     * 10, ten hops away. */
    for (t = 0; t < 2000u; t++) {
        for (i = 0; i < CHAIN; i++) {
            if (i == 0u && t < 1000u) continue;
            eaipp_step(&e[i], &hal[i]);
        }
        for (i = 0; i < CHAIN; i++) {
            while (sent[i] < hal[i].out_count) {
                uint16_t f = hal[i].outbox[sent[i] % FAKE_OUTBOX_MAX];
                if (i > 0u) fake_hal_push(&hal[i - 1u], f, 450u, 0);
                if (i + 1u < CHAIN) fake_hal_push(&hal[i + 1u], f, 450u, 3142);
                sent[i]++;
            }
            fake_hal_end_step(&hal[i]);
            hal[i].out_count = 0u;
            sent[i] = 0u;
        }
        if (t == 999u) {
            assert_int_equal(e[1].gradient, 10u);        /* food-sourced, ten hops */
            assert_int_equal(e[1].source, EAIPP_SOURCE_FOOD);
        }
        if (t >= 1000u && e[10].source == EAIPP_SOURCE_NEST && e[10].gradient == 10u) {
            return t - 999u;
        }
    }
    return 0u;
}

static void test_chain_crossing(void **state)
{
    uint32_t one, three;
    (void)state;
    one = steps_to_cross(1u);
    three = steps_to_cross(3u);
    printf("# a nest gradient crossed 10 nodes in %u steps (%.1f s at 10 Hz) with one message a period,"
           " %u steps (%.1f s) with three (the EAIPP images' turret rate)\n",
           (unsigned)one, one / 10.0, (unsigned)three, three / 10.0);
    /* One message a period: each hop needs the STATE and GRADIENT frames of
     * a 3-kind cycle, 1 to 3 periods, plus the step it takes to act.  Three
     * a period: every kind every period, one step a hop. */
    assert_in_range(one, 10u, 45u);
    assert_in_range(three, 10u, 15u);
    assert_true(three < one);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gradient),
        cmocka_unit_test(test_food_source),
        cmocka_unit_test(test_same_source_merge),
        cmocka_unit_test(test_extinction_timing),
        cmocka_unit_test(test_shunning),
        cmocka_unit_test(test_flag_forwarding),
        cmocka_unit_test(test_extension_distance),
        cmocka_unit_test(test_wheel_law),
        cmocka_unit_test(test_direction),
        cmocka_unit_test(test_lost_and_sources),
        cmocka_unit_test(test_lost_rear_wall),
        cmocka_unit_test(test_lj_exit),
        cmocka_unit_test(test_chain_crossing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
