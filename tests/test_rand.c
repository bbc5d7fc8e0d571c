/* test_rand.c - the simulator's random streams: moments of the normal
 * deviates, independence of seeds, and the firmware generator's range. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "swarmsim/rand.h"
#include "common/rng.h"
/* The models' names (sim_rand_purpose): the list is internal. */
#include "models/model.h"

static void test_normal_moments_and_tails(void **state)
{
    (void)state;
    sim_rand_t r;
    sim_rand_seed(&r, 7, 0, RAND_SENSORS);
    const int n = 2000000;
    double sum = 0, sq = 0, quad = 0;
    int beyond2 = 0, beyond3 = 0, beyond_r = 0;
    for (int k = 0; k < n; k++) {
        double x = sim_rand_normal(&r);
        sum += x;
        sq += x * x;
        quad += x * x * x * x;
        beyond2 += fabs(x) > 2.0;
        beyond3 += fabs(x) > 3.0;
        beyond_r += fabs(x) > 3.5;   /* past the ziggurat's base layer */
    }
    double mean = sum / n, var = sq / n - mean * mean;
    assert_true(fabs(mean) < 0.003);
    assert_true(fabs(var - 1.0) < 0.005);
    assert_true(fabs(quad / n - 3.0) < 0.03);             /* kurtosis 3 */
    assert_true(fabs((double)beyond2 / n - 0.0455) < 0.001);
    assert_true(fabs((double)beyond3 / n - 0.0027) < 0.0002);
    assert_true(fabs((double)beyond_r / n - 0.000465) < 0.0001);
}

static void test_streams_differ_and_repeat(void **state)
{
    (void)state;
    sim_rand_t a, b, c;
    sim_rand_seed(&a, 1, 3, RAND_SENSORS);
    sim_rand_seed(&b, 1, 3, RAND_SENSORS);
    sim_rand_seed(&c, 1, 3, RAND_IRCOM);
    for (int k = 0; k < 100; k++) {
        uint64_t x = sim_rand_u64(&a);
        assert_true(x == sim_rand_u64(&b));
        assert_true(x != sim_rand_u64(&c));
    }
    assert_true(sim_rand_seed32(1, 0, RAND_CONTROLLER) != sim_rand_seed32(1, 1, RAND_CONTROLLER));
}

/* A purpose from a name lies above the numbered ones, is the same for the
 * same name, and no two shipped models' names share one (a model that
 * seeds from its name gets streams of its own). */
static void test_purposes_of_names(void **state)
{
    (void)state;
    uint64_t seen[SIM_MODEL_COUNT];
    assert_true(sim_rand_purpose("ground") == sim_rand_purpose("ground"));
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        uint64_t p = sim_rand_purpose(sim_models[id]->name);
        assert_true(p >= 128u && p <= 255u && p > RAND_CAMERA);
        for (uint32_t k = 0; k < id; k++) {
            if (seen[k] == p) fail_msg("models %s and %s share stream purpose %u", sim_models[k]->name,
                                       sim_models[id]->name, (unsigned)p);
        }
        seen[id] = p;
    }
    sim_rand_t a, b;
    sim_rand_seed(&a, 1, 3, sim_rand_purpose("ground"));
    sim_rand_seed(&b, 1, 3, RAND_SENSORS);
    assert_true(sim_rand_u64(&a) != sim_rand_u64(&b));
}

static void test_firmware_rng_ranges(void **state)
{
    (void)state;
    rng_t g;
    rng_seed(&g, 0);   /* 0 is a valid seed */
    int seen[8] = { 0 };
    uint32_t hits = 0;
    for (int k = 0; k < 80000; k++) {
        int32_t v = rng_range(&g, 2, 9);
        assert_true(v >= 2 && v <= 9);
        seen[v - 2]++;
        hits += rng_chance(&g, 16384);   /* 25 % */
    }
    for (int k = 0; k < 8; k++) assert_true(seen[k] > 9000 && seen[k] < 11000);
    assert_true(hits > 19000 && hits < 21000);
    assert_int_equal(rng_below(&g, 0), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_normal_moments_and_tails),
        cmocka_unit_test(test_streams_differ_and_repeat),
        cmocka_unit_test(test_purposes_of_names),
        cmocka_unit_test(test_firmware_rng_ranges),
    };
    return cmocka_run_group_tests_name("rand", tests, NULL, NULL);
}
