/*
 * test_pool.c - the run's worker threads (sim_host/core/pool.h): every item
 * of a parallel-for runs exactly once, on a worker the pool names, at 1 to
 * 4 threads, polling or not (SWARMSIM_POOL_SPIN_US), with many short phases
 * in a row as a step has them; the CPUs counted are those the affinity mask
 * allows.  (About 0.1 s.)
 */
#define _GNU_SOURCE 1   /* sched_getaffinity, CPU_COUNT */
#include <sched.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "core/pool.h"

enum { ITEMS = 5000, PHASES = 300 };

typedef struct marks {
    uint32_t threads;
    _Atomic uint32_t seen[ITEMS];
    _Atomic uint32_t bad_worker;
} marks_t;

static void mark(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    marks_t *m = ctx;
    if (worker >= m->threads) {
        m->bad_worker++;
    }
    for (uint32_t i = begin; i < end; i++) {
        m->seen[i]++;
    }
}

/* PHASES parallel-fors of ITEMS items in chunks of at least `chunk`. */
static void run_phases(uint32_t threads, uint32_t chunk)
{
    pool_t *p = pool_create(threads);
    assert_non_null(p);
    assert_int_equal(pool_threads(p), threads);
    marks_t *m = calloc(1, sizeof *m);
    assert_non_null(m);
    m->threads = threads;
    for (int k = 0; k < PHASES; k++) {
        pool_for(p, ITEMS, chunk, mark, m);
    }
    for (uint32_t i = 0; i < ITEMS; i++) {
        if (m->seen[i] != PHASES) {
            fail_msg("%u threads, chunk %u: item %u ran %u times in %d phases", threads, chunk, i, m->seen[i],
                     PHASES);
        }
    }
    assert_int_equal(m->bad_worker, 0);
    free(m);
    pool_destroy(p);
}

static void test_every_item_once(void **state)
{
    (void)state;
    static const char *const spin[] = { NULL, "0", "1000" };
    for (size_t s = 0; s < sizeof spin / sizeof spin[0]; s++) {
        if (spin[s]) {
            setenv(POOL_SPIN_ENV, spin[s], 1);
        } else {
            unsetenv(POOL_SPIN_ENV);
        }
        for (uint32_t threads = 1; threads <= 4; threads++) {
            run_phases(threads, 1);
            run_phases(threads, 64);
            run_phases(threads, ITEMS);   /* one chunk: run in place */
        }
    }
    unsetenv(POOL_SPIN_ENV);
}

/* The affinity mask's count, never more than the CPUs online. */
static void test_cpus_follow_affinity(void **state)
{
    (void)state;
    cpu_set_t set;
    assert_int_equal(sched_getaffinity(0, sizeof set, &set), 0);
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    uint32_t want = (uint32_t)CPU_COUNT(&set);
    if (online > 0 && (uint32_t)online < want) {
        want = (uint32_t)online;
    }
    assert_int_equal(pool_cpus(), want);
    /* Pinned to one CPU, the pool counts one. */
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE; c++) {
        if (CPU_ISSET(c, &set)) {
            CPU_SET(c, &one);
            break;
        }
    }
    assert_int_equal(sched_setaffinity(0, sizeof one, &one), 0);
    assert_int_equal(pool_cpus(), 1);
    assert_int_equal(sched_setaffinity(0, sizeof set, &set), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_item_once),
        cmocka_unit_test(test_cpus_follow_affinity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
