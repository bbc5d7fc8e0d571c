/* test_grid.c - the robot grid's queries: a gather holds every point in
 * its box, and grid_sort_ids orders distinct ids as a full sort does, at
 * every size around its rank sort's four-wide blocks and its limit. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "swarmsim/grid.h"

static int ascending(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* A small deterministic generator: the test's own, not the simulator's. */
static uint32_t next(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return (uint32_t)(*s >> 33);
}

static void test_sort_ids_matches_a_full_sort(void **state)
{
    (void)state;
    uint64_t seed = 1;
    for (uint32_t n = 0; n <= 70; n++) {
        for (int round = 0; round < 50; round++) {
            uint32_t ids[70], want[70];
            for (uint32_t k = 0; k < n; k++) {
                /* Distinct: a random high part over the position; the
                 * largest allowed id (UINT32_MAX - 1) in some rounds. */
                ids[k] = round % 7 == 0 && k == 0 ? UINT32_MAX - 1 : (next(&seed) % 1000u) * 128u + k;
                want[k] = ids[k];
            }
            qsort(want, n, sizeof *want, ascending);
            grid_sort_ids(ids, n);
            for (uint32_t k = 0; k < n; k++) {
                assert_int_equal(ids[k], want[k]);
            }
        }
    }
}

/* n points uniform over the square of side side_mm (mm) centred on the origin,
 * on a 1 mm lattice. */
static void random_points(float *x, float *y, uint32_t n, uint32_t side_mm, uint64_t *seed)
{
    float half = (float)side_mm / 2000.0f;
    for (uint32_t k = 0; k < n; k++) {
        x[k] = (float)(next(seed) % side_mm) / 1000.0f - half;
        y[k] = (float)(next(seed) % side_mm) / 1000.0f - half;
    }
}

static void test_gather_holds_every_point_in_the_box(void **state)
{
    (void)state;
    enum { N = 500 };
    float x[N], y[N];
    uint64_t seed = 3;
    grid_t g;
    assert_int_equal(grid_init(&g, -5.0f, -5.0f, 10.0f, 10.0f, 0.4f), 0);
    random_points(x, y, N, 10000u, &seed);
    assert_int_equal(grid_build_points(&g, x, y, N), 0);
    for (int q = 0; q < 100; q++) {
        float cx = (float)(next(&seed) % 10000u) / 1000.0f - 5.0f, cy = (float)(next(&seed) % 10000u) / 1000.0f - 5.0f;
        float h = 0.1f + (float)(q % 10) * 0.3f;
        uint32_t out[N], seen[N] = { 0 };
        uint32_t n = grid_gather(&g, cx - h, cy - h, cx + h, cy + h, out, N);
        grid_sort_ids(out, n);
        for (uint32_t k = 0; k < n; k++) {
            assert_true(k == 0 || out[k - 1] < out[k]);   /* each once, ascending */
            seen[out[k]] = 1;
        }
        for (uint32_t k = 0; k < N; k++) {
            if (x[k] >= cx - h && x[k] <= cx + h && y[k] >= cy - h && y[k] <= cy + h) {
                assert_true(seen[k]);
            }
        }
    }
    grid_free(&g);
}

/* Binning: every point in play once, in the cell its coordinates give, a
 * cell's points in ascending index; a point with a NaN coordinate left out;
 * a second binning of fewer points over the first one's storage alike. */
static void test_build_bins_each_point_once_in_index_order(void **state)
{
    (void)state;
    enum { N = 300 };
    float x[N], y[N];
    uint64_t seed = 11;
    grid_t g;
    assert_int_equal(grid_init(&g, -2.0f, -2.0f, 4.0f, 4.0f, 0.5f), 0);
    random_points(x, y, N, 4000u, &seed);
    for (uint32_t k = 3; k < N; k += 7) {
        (k % 2 ? x : y)[k] = NAN;
    }
    const uint32_t sizes[2] = { N, 100 };
    for (int pass = 0; pass < 2; pass++) {
        uint32_t n = sizes[pass], in_play = 0, seen[N] = { 0 };
        assert_int_equal(grid_build_points(&g, x, y, n), 0);
        for (uint32_t k = 0; k < n; k++) {
            in_play += !isnan(x[k]) && !isnan(y[k]);
        }
        uint32_t cells = (uint32_t)(g.nx * g.ny);
        assert_int_equal(g.start[cells], in_play);
        for (uint32_t c = 0; c < cells; c++) {
            for (uint32_t k = g.start[c]; k < g.start[c + 1]; k++) {
                uint32_t id = g.items[k];
                int32_t cx0, cy0, cx1, cy1;
                assert_true(id < n && !seen[id] && !isnan(x[id]) && !isnan(y[id]));
                assert_true(k == g.start[c] || g.items[k - 1] < id);
                grid_range(&g, x[id], y[id], x[id], y[id], &cx0, &cy0, &cx1, &cy1);
                assert_int_equal((uint32_t)(cy0 * g.nx + cx0), c);
                seen[id] = 1;
            }
        }
    }
    grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_build_bins_each_point_once_in_index_order),
        cmocka_unit_test(test_sort_ids_matches_a_full_sort),
        cmocka_unit_test(test_gather_holds_every_point_in_the_box),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
