/*
 * test_foraging.c - seed 000's foraging task end to end in the simulator:
 * firmware foragers and the nest beacon on the base condition, checked
 * against ground truth (deliveries, the energy ledger to the unit, the
 * beacon's estimate, a lost token).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "swarmsim/scenario.h"
#include "swarmsim/metrics.h"
#include "swarmsim/sim.h"
#include "foraging/forager.h"
#include "foraging/nest_beacon.h"
#include "tasks/foraging/foraging.h"

#define BASE "../sim_host/scenarios/foraging_base.yaml"

/* The base condition with `policy`; `info` global also drops the beacon
 * group (robots.1). */
static scenario_t *load(const char *policy, const char *info)
{
    scenario_t *sc = malloc(sizeof *sc);
    char err[SIM_ERR_MAX], set_policy[64], set_info[64];
    snprintf(set_policy, sizeof set_policy, "robots.0.policy=%s", policy);
    snprintf(set_info, sizeof set_info, "foraging.information=%s", info);
    scenario_override_t sets[3] = { { set_policy }, { set_info }, { "robots.1.count=0" } };
    assert_non_null(sc);
    if (scenario_load(BASE, sets, strcmp(info, "global") == 0 ? 3 : 2, sc, err) != 0) fail_msg("%s", err);
    return sc;
}

static const foraging_config_t *config(const scenario_t *sc)
{
    const foraging_config_t *c = scenario_task_config(sc, &foraging_task);
    assert_non_null(c);
    return c;
}

static foraging_truth_t truth(const sim_t *sim)
{
    foraging_truth_t t;
    assert_int_equal(foraging_truth(sim, &t), 1);
    return t;
}

/* Foragers are robots 0..N_r-1; the beacon, when there is one, comes next. */
static uint32_t foragers(const scenario_t *sc) { return sc->groups[0].count; }

/* 3000 steps (5 min) of the base condition with DRTM and the beacon:
 * tokens are collected and delivered, each delivery raises the nest level
 * by one token less that step's costs, and the ledger balances. */
static void test_base_run_collects_and_balances(void **state)
{
    (void)state;
    scenario_t *sc = load("drtm", "beacon");
    sim_t *sim = fixture_sim(sc, 7);
    const foraging_config_t *c = config(sc);
    const double E = c->token_energy;
    uint64_t forage_steps = 0, rises = 0;
    double prev = c->initial_food;
    foraging_truth_t f = truth(sim);
    assert_true(fabs(f.food - 5.0) < 1e-12);
    for (int k = 0; k < 3000; k++) {
        uint64_t delivered = f.delivered;
        sim_step(sim);
        f = truth(sim);
        for (uint32_t i = 0; i < foragers(sc); i++) {
            char st = forager_paper_state(((const forager_t *)sim_robot_controller(sim, i))->state);
            forage_steps += st == 'S' || st == 'R';
        }
        if (f.delivered > delivered) {
            /* A delivery: +1 token, minus at most every robot's step cost
             * and a few OAEs and the nest's 5 units. */
            double up = f.food - prev;
            assert_true(up > 1.0 - (20 * 1 + 5 + 10 * 20) / E && up <= 1.0 * (double)(f.delivered - delivered));
            rises++;
        }
        prev = f.food;
    }
    assert_true(f.delivered >= 10);
    assert_true(rises >= 10);
    /* The ledger, recomputed here in energy units: to the unit. */
    uint64_t oaes = 0;
    for (uint32_t i = 0; i < foragers(sc); i++) {
        oaes += ((const forager_t *)sim_robot_controller(sim, i))->walk.oae_count;
    }
    double nest = c->consumption / 60.0 * 300.0 * E;                 /* 2 tokens/min, 5 min */
    double spent = nest + forage_steps * c->move_cost + oaes * c->oae_energy;
    double units = (c->initial_food + (double)f.delivered) * E - spent;
    assert_true(fabs(units - f.food * E) < 1e-6);
    assert_true(fabs(foraging_balance(sim) - f.food) < 1e-12);
    assert_int_equal(nest, 15000.0);
    /* The robots' own deposit counts agree with the deliveries: a robot
     * still backing out counts its deposit a few steps later, and a robot
     * that meets another one carrying a token face to face can take that
     * token, filling its view, for its own (a belief; the metrics come from
     * the simulator's ground truth).  At most one such mistake in 20. */
    uint64_t deposits = 0, backing = 0;
    for (uint32_t i = 0; i < foragers(sc); i++) {
        const forager_t *fg = sim_robot_controller(sim, i);
        deposits += fg->deposits;
        backing += fg->state == FORAGER_DEPOSIT;
    }
    uint64_t slack = f.delivered / 20 + 1;
    if (!(deposits <= f.delivered + slack && deposits + backing + slack >= f.delivered))
        fail_msg("robots counted %llu deposits (%llu backing), the nest got %llu, dropped %llu", (unsigned long long)deposits, (unsigned long long)backing, (unsigned long long)f.delivered, (unsigned long long)f.dropped);
    /* The beacon (robot N_r) estimates the true nest level from reports. */
    assert_ptr_equal(sim_robot_def(sim, foragers(sc)), &nest_beacon_def);
    const nest_beacon_t *b = sim_robot_controller(sim, foragers(sc));
    double beacon_food = nest_beacon_food_q4(b) / 16.0;
    assert_true(fabs(beacon_food - f.food) < 4.0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* A full base run (seed 000's 1200 s) with the beacon: robots leave the nest
 * in seconds (turning away from the lamp; keeping their heading they took
 * about 27 s and crossed the nest again), and the beacon's F(t) tracks the
 * ground truth: no phantom deposits (a token another robot carries is not
 * one's own) leave it above the truth. */
static void test_beacon_tracks_the_truth_and_robots_leave_the_nest(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        scenario_t *sc = load("drtm", "beacon");
        sim_t *sim = fixture_sim(sc, seed);
        for (int k = 0; k < 12000; k++) sim_step(sim);
        double exit_s = fixture_metric(sim, "exit_time_s"), err_mean = fixture_metric(sim, "beacon_error_mean"),
               err_max = fixture_metric(sim, "beacon_error_max");
        if (!(exit_s < 10.0 && err_mean <= 1.0 && err_max <= 3.0)) {
            fail_msg("seed %llu: exit %.2f s, |F_beacon - F| mean %.2f, max %.2f", (unsigned long long)seed,
                     exit_s, err_mean, err_max);
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

/* A robot that loses its token searches again. */
static void test_lost_token_goes_back_to_search(void **state)
{
    (void)state;
    scenario_t *sc = load("drtm", "beacon");
    sim_t *sim = fixture_sim(sc, 8);
    int32_t carrier = -1;
    for (int k = 0; k < 6000 && carrier < 0; k++) {
        sim_step(sim);
        for (uint32_t i = 0; i < foragers(sc) && carrier < 0; i++) {
            const forager_t *fg = sim_robot_controller(sim, i);
            if (fg->state == FORAGER_RETURN && foraging_carried(sim, i) >= 0) {
                carrier = (int32_t)i;
            }
        }
    }
    assert_true(carrier >= 0);
    const forager_t *fg = sim_robot_controller(sim, (uint32_t)carrier);
    assert_int_equal(foraging_drop(sim, (uint32_t)carrier), 1);
    /* lost_steps without the token's blob, counted from the first frame
     * without it: a frame is up to two periods old at 4.3 fps (5 steps). */
    for (int k = 0; k < fg->params.lost_steps + 1 + 5 && fg->state != FORAGER_SEARCH; k++) {
        sim_step(sim);
    }
    assert_int_equal(fg->state, FORAGER_SEARCH);
    assert_int_equal(truth(sim).dropped, 1);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* At the start every robot waits in the nest, and with S(0) = 15 > 0 and
 * theta = 3.3 (DRTM's default: theta0 + eq 6 with k = M_A = 0) P_s is at
 * least 0.95: they all leave within the first draws after T1 steps. */
static void test_everyone_leaves_at_first_decision(void **state)
{
    (void)state;
    scenario_t *sc = load("drtm", "global");
    sim_t *sim = fixture_sim(sc, 9);
    assert_int_equal(sim_robot_count(sim), 20);   /* no beacon */
    for (int k = 0; k < 49; k++) sim_step(sim);
    assert_int_equal(truth(sim).waiting, 20);
    for (int k = 0; k < 3; k++) sim_step(sim);
    assert_int_equal(truth(sim).waiting, 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* When the nest is full (F(0) >= F_d, S <= 0) nobody ever leaves. */
static void test_full_nest_keeps_everyone_home(void **state)
{
    (void)state;
    const char *policies[3] = { "drtm", "artm", "frtm" };
    for (int p = 0; p < 3; p++) {
        scenario_t *sc = load(policies[p], "beacon");
        foraging_config_t *c = (foraging_config_t *)scenario_task_config(sc, &foraging_task);
        c->initial_food = 40.0f;     /* 40 - 600 s x 2/min > 20 */
        c->consumption = 2.0f;
        sim_t *sim = fixture_sim(sc, 10);
        for (int k = 0; k < 3000; k++) {
            sim_step(sim);
            assert_int_equal(truth(sim).waiting, 20);
        }
        sim_destroy(sim);
        scenario_free(sc);
        free(sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_base_run_collects_and_balances),
        cmocka_unit_test(test_beacon_tracks_the_truth_and_robots_leave_the_nest),
        cmocka_unit_test(test_lost_token_goes_back_to_search),
        cmocka_unit_test(test_everyone_leaves_at_first_decision),
        cmocka_unit_test(test_full_nest_keeps_everyone_home),
    };
    return cmocka_run_group_tests_name("foraging", tests, NULL, NULL);
}
