/*
 * test_task_alloc.c - seed 000's task-allocation equations (firmware/task_alloc)
 * against hand-computed values, and the ARTM/FRTM thresholds.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "foraging/task_alloc.h"

/* Floats are 32-bit: compare to about 6 significant digits. */
#define EPS 1e-5

static void test_stimulus_eq2(void **state)
{
    (void)state;
    /* S = F_d - F: the seed's start, F_d = 20, F(0) = 5 -> 15. */
    assert_float_equal(ta_stimulus(20.0f, 5.0f), 15.0, EPS);
    /* Nest above the target: negative stimulus. */
    assert_float_equal(ta_stimulus(20.0f, 25.0f), -5.0, EPS);
    /* The beacon's resolution, 1/16 token: 20 - 19.9375 = 0.0625. */
    assert_float_equal(ta_stimulus(20.0f, 19.9375f), 0.0625, EPS);
}

static void test_traffic_density_eq4(void **state)
{
    (void)state;
    /* (20 - 6) / (4 * 4) = 14 / 16 = 0.875 robots/m^2. */
    assert_float_equal(ta_traffic_density(20u, 6u, 4.0f), 0.875, EPS);
    /* Section 4.3/4.4-like: (30 - 12) / (3 * 3) = 18 / 9 = 2. */
    assert_float_equal(ta_traffic_density(30u, 12u, 3.0f), 2.0, EPS);
    /* Everyone waiting: nobody foraging, k = 0. */
    assert_float_equal(ta_traffic_density(20u, 20u, 4.0f), 0.0, 0.0);
    /* N_W > N_r (stale reports) is guarded, not negative. */
    assert_float_equal(ta_traffic_density(20u, 25u, 4.0f), 0.0, 0.0);
    /* A degenerate arena gives 0, not inf. */
    assert_float_equal(ta_traffic_density(20u, 0u, 0.0f), 0.0, 0.0);
}

static void test_mean_oae_eq5(void **state)
{
    (void)state;
    /* 37 OAEs in T2 over 20 robots: 1.85. */
    assert_float_equal(ta_mean_oae(37u, 20u), 1.85, EPS);
    assert_float_equal(ta_mean_oae(0u, 20u), 0.0, 0.0);
    assert_float_equal(ta_mean_oae(5u, 0u), 0.0, 0.0);
}

static void test_drtm_threshold_eq6(void **state)
{
    (void)state;
    /* alpha 3, beta 2, k 0.875, M_A 1.85: 2.625 + 3.7 = 6.325. */
    assert_float_equal(ta_drtm_threshold(3.0f, 2.0f, 0.875f, 1.85f), 6.325, EPS);
    /* At the start all robots wait and no OAE happened: theta = 0, raw,
     * not clipped to the ARTM range. */
    assert_float_equal(ta_drtm_threshold(3.0f, 2.0f, ta_traffic_density(20u, 20u, 4.0f),
                                         ta_mean_oae(0u, 20u)), 0.0, 0.0);
}

static void test_probability_eq7_values(void **state)
{
    (void)state;
    /* S 15, theta 3.3, n 2: 225 / (225 + 10.89) = 0.95383441... */
    assert_float_equal(ta_probability(15.0f, 3.3f, 2u), 0.9538344, EPS);
    /* n 9: 15^9 = 38443359375, 3.3^9 = 46411.4844: 0.99999879... */
    assert_float_equal(ta_probability(15.0f, 3.3f, 9u), 0.9999988, EPS);
    /* S 2, theta 3.3, n 2: 4 / (4 + 10.89) = 0.26863667... */
    assert_float_equal(ta_probability(2.0f, 3.3f, 2u), 0.2686367, EPS);
    /* n 9: 512 / (512 + 46411.4844) = 0.01091138... */
    assert_float_equal(ta_probability(2.0f, 3.3f, 9u), 0.0109114, EPS);
    /* S 3.3, theta 5, n 4: 118.5921 / (118.5921 + 625) = 0.15948542... */
    assert_float_equal(ta_probability(3.3f, 5.0f, 4u), 0.1594854, EPS);
}

static void test_probability_eq7_cases(void **state)
{
    uint8_t n;
    (void)state;
    /* S <= 0: the nest has enough, nobody leaves, whatever theta. */
    assert_float_equal(ta_probability(0.0f, 3.3f, 2u), 0.0, 0.0);
    assert_float_equal(ta_probability(-4.0f, 3.3f, 2u), 0.0, 0.0);
    assert_float_equal(ta_probability(-4.0f, 0.0f, 2u), 0.0, 0.0);
    /* DRTM at the start: theta = 0 and S > 0 -> everyone wants to go. */
    assert_float_equal(ta_probability(15.0f, 0.0f, 2u), 1.0, 0.0);
    assert_float_equal(ta_probability(0.0625f, 0.0f, 9u), 1.0, 0.0);
    /* Figure 2: P = 0.5 where theta = S, for any n. */
    for (n = 2u; n <= 9u; n++) {
        assert_float_equal(ta_probability(3.3f, 3.3f, n), 0.5, EPS);
        assert_float_equal(ta_probability(7.0f, 7.0f, n), 0.5, EPS);
    }
    /* No overflow or NaN at extremes (S^9 of 1e5 overflows a float). */
    assert_float_equal(ta_probability(1.0e5f, 1.0f, 9u), 1.0, EPS);
    assert_float_equal(ta_probability(1.0e-6f, 10.0f, 9u), 0.0, EPS);
    assert_float_equal(ta_probability(1.0f, 1.0e5f, 9u), 0.0, EPS);
}

static void test_probability_larger_n_is_steeper(void **state)
{
    uint8_t n;
    (void)state;
    for (n = 2u; n < 9u; n++) {
        /* Below the threshold a larger n responds less ... */
        assert_true(ta_probability(2.0f, 3.3f, (uint8_t)(n + 1u)) < ta_probability(2.0f, 3.3f, n));
        /* ... above it more. */
        assert_true(ta_probability(5.0f, 3.3f, (uint8_t)(n + 1u)) > ta_probability(5.0f, 3.3f, n));
    }
    /* And P rises with S for a fixed theta. */
    assert_true(ta_probability(4.0f, 3.3f, 3u) > ta_probability(3.0f, 3.3f, 3u));
}

static void test_roulette_frequency(void **state)
{
    rng_t rng;
    uint32_t i, hits = 0u;
    (void)state;
    rng_seed(&rng, 12345u);
    /* p = 0.25 over 100000 draws: 25000, sd = sqrt(1e5 * 0.25 * 0.75) = 137;
     * accept +-600 (4.4 sd). */
    for (i = 0; i < 100000u; i++) {
        hits += ta_roulette(&rng, 0.25f);
    }
    assert_in_range(hits, 24400u, 25600u);
    /* p = 0.9: 90000 +- 4.4 * 95. */
    hits = 0u;
    for (i = 0; i < 100000u; i++) {
        hits += ta_roulette(&rng, 0.9f);
    }
    assert_in_range(hits, 89580u, 90420u);
}

static void test_roulette_certain_and_impossible(void **state)
{
    rng_t rng;
    uint32_t i, hits0 = 0u, hits1 = 0u;
    (void)state;
    rng_seed(&rng, 7u);
    for (i = 0; i < 10000u; i++) {
        hits0 += ta_roulette(&rng, 0.0f);
        hits0 += ta_roulette(&rng, -0.5f);
        hits1 += ta_roulette(&rng, 1.0f);
        hits1 += ta_roulette(&rng, 1.5f);
    }
    assert_int_equal(hits0, 0);
    assert_int_equal(hits1, 20000);
}

static void test_artm_update(void **state)
{
    (void)state;
    /* Stimulus rises (15 -> 16): the threshold falls, more robots forage. */
    assert_float_equal(ta_artm_update(3.3f, 16.0f, 15.0f, 0.5f, 1.0f, 10.0f), 2.8, EPS);
    /* Stimulus falls (15 -> 14): the threshold rises. */
    assert_float_equal(ta_artm_update(3.3f, 14.0f, 15.0f, 0.5f, 1.0f, 10.0f), 3.8, EPS);
    /* Unchanged stimulus (a robot's first decision uses S_prev = S). */
    assert_float_equal(ta_artm_update(3.3f, 15.0f, 15.0f, 0.5f, 1.0f, 10.0f), 3.3, EPS);
    /* Clipped to [1, 10]. */
    assert_float_equal(ta_artm_update(1.2f, 16.0f, 15.0f, 0.5f, 1.0f, 10.0f), 1.0, EPS);
    assert_float_equal(ta_artm_update(9.8f, 14.0f, 15.0f, 0.5f, 1.0f, 10.0f), 10.0, EPS);
    assert_float_equal(ta_artm_update(1.0f, 100.0f, -100.0f, 0.5f, 1.0f, 10.0f), 1.0, EPS);
}

static void test_artm_walks_between_bounds(void **state)
{
    float theta = 3.3f;
    int i;
    (void)state;
    /* A stimulus rising for 18 decisions drives theta down to 1 and keeps it
     * there; a falling one takes it to 10 in (10 - 1) / 0.5 = 18 steps. */
    for (i = 0; i < 18; i++) {
        theta = ta_artm_update(theta, (float)(i + 1), (float)i, 0.5f, 1.0f, 10.0f);
    }
    assert_float_equal(theta, 1.0, EPS);
    for (i = 0; i < 17; i++) {
        theta = ta_artm_update(theta, (float)-i - 1.0f, (float)-i, 0.5f, 1.0f, 10.0f);
    }
    assert_float_equal(theta, 9.5, EPS);
    theta = ta_artm_update(theta, -100.0f, -18.0f, 0.5f, 1.0f, 10.0f);
    assert_float_equal(theta, 10.0, EPS);
}

static void test_frtm_fixed(void **state)
{
    float theta = 3.3f;
    int i;
    (void)state;
    /* FRTM = ARTM with the adaptation off: theta stays theta0 whatever the
     * stimulus does ... */
    for (i = 0; i < 10; i++) {
        theta = ta_artm_update(theta, (float)(i * 3 % 7), (float)(i * 5 % 7), 0.0f, 1.0f, 10.0f);
    }
    assert_float_equal(theta, 3.3, 0.0);
    /* ... so P depends on S only: 0.5 at S = theta0, 0 for S <= 0. */
    assert_float_equal(ta_probability(3.3f, theta, 5u), 0.5, EPS);
    assert_float_equal(ta_probability(-1.0f, theta, 5u), 0.0, 0.0);
    assert_string_equal(ta_policy_names[TA_FRTM], "frtm");
    assert_string_equal(ta_policy_names[TA_DRTM], "drtm");
    assert_string_equal(ta_policy_names[TA_ARTM], "artm");
    assert_null(ta_policy_names[TA_POLICY_COUNT]);   /* the list's end */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stimulus_eq2),
        cmocka_unit_test(test_traffic_density_eq4),
        cmocka_unit_test(test_mean_oae_eq5),
        cmocka_unit_test(test_drtm_threshold_eq6),
        cmocka_unit_test(test_probability_eq7_values),
        cmocka_unit_test(test_probability_eq7_cases),
        cmocka_unit_test(test_probability_larger_n_is_steeper),
        cmocka_unit_test(test_roulette_frequency),
        cmocka_unit_test(test_roulette_certain_and_impossible),
        cmocka_unit_test(test_artm_update),
        cmocka_unit_test(test_artm_walks_between_bounds),
        cmocka_unit_test(test_frtm_fixed),
    };
    return cmocka_run_group_tests_name("task_alloc", tests, NULL, NULL);
}
