/*
 * base.c - the assert handler and out of memory inside a step (base.h).
 */
#include "swarmsim/base.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

static void print_assert(const char *condition, const char *file, int line)
{
    fprintf(stderr, "swarmsim: %s:%d: assertion failed: %s\n", file, line, condition);
}

/* The one piece of process-wide state: who reports a failed assertion.
 * Atomic, as runs on several threads may fail at once. */
static _Atomic(sim_assert_fn *) assert_handler = print_assert;

sim_assert_fn *sim_set_assert_handler(sim_assert_fn *fn)
{
    return atomic_exchange(&assert_handler, fn != NULL ? fn : print_assert);
}

void sim_assert_failed(const char *condition, const char *file, int line)
{
    atomic_load(&assert_handler)(condition, file, line);
    abort();
}

void sim_out_of_memory(const char *what)
{
    fprintf(stderr, "swarmsim: out of memory for %s\n", what);
    fflush(stderr);
    _Exit(1);
}
