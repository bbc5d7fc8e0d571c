/*
 * pool.h - the worker threads of one run: a blocking parallel-for for the
 * simulator's own phases (pool_for) and the task interface Box2D v3 asks
 * its user for (pool_box2d_enqueue / pool_box2d_finish, b2WorldDef).
 *
 * A pool of `threads` is the thread that calls it (worker 0) and threads - 1
 * threads of its own (workers 1 .. threads - 1).  Work is split into chunks
 * that any worker may take; a callback learns which worker runs it, so that
 * it can use that worker's scratch memory, and nothing else about the
 * schedule.  Results that must not depend on the thread count therefore
 * come from callbacks whose items are independent of each other.
 *
 * The caller of pool_for and pool_box2d_finish helps: while it waits it runs
 * pending chunks of any task.  Box2D's solver needs that: its workerCount
 * tasks wait for each other, so all of them must be able to run at once.
 * A thread left with nothing to do polls for about 50 us before it sleeps
 * (no more threads at a time than the process has CPUs, every pool
 * counted; none on one CPU): a step's tasks come tens of microseconds
 * apart, and a sleeping thread takes as long to wake.  POOL_SPIN_ENV sets the time (0: sleep at once),
 * for machines whose CPUs are shared in ways the process cannot see
 * (quotas, other jobs).
 */
#ifndef SIM_POOL_H
#define SIM_POOL_H

#include <stdint.h>

/** The most workers of a pool (Box2D's B2_MAX_WORKERS). */
#define POOL_MAX_THREADS 64u

/** Test hook: when this environment variable holds N >= 1 as a pool is
 *  created, its pool_for takes N as every caller's minimum chunk (about four
 *  chunks per worker, at least N items each), so that a small scenario's
 *  robots, too, are stepped on several threads at once
 *  (tests/cli/golden.sh, determinism.sh). */
#define POOL_CHUNK_ENV "SWARMSIM_POOL_CHUNK"

/** How long an idle thread polls before it sleeps, microseconds (0 to
 *  1,000,000; read as a pool is created; default 50). */
#define POOL_SPIN_ENV "SWARMSIM_POOL_SPIN_US"

typedef struct pool pool_t;

/** Items [begin, end) of a parallel-for, run by `worker` (< pool_threads). */
typedef void pool_fn(uint32_t begin, uint32_t end, uint32_t worker, void *ctx);

/** A pool of `threads` workers (1 .. POOL_MAX_THREADS; 1: everything runs
 *  on the caller, no thread is started).  NULL when threads cannot start. */
pool_t *pool_create(uint32_t threads);

/** Stops and joins the threads.  NULL is a no-op. */
void pool_destroy(pool_t *p);

uint32_t pool_threads(const pool_t *p);

/** The CPUs this process may use: those online, fewer when its affinity
 *  mask allows fewer (taskset, a batch system's binding). */
uint32_t pool_cpus(void);

/** Runs fn over [0, n) in chunks of at least `min_chunk` items, on every
 *  worker, and returns when all are done.  Called by the pool's owner
 *  thread only, never from inside a callback. */
void pool_for(pool_t *p, uint32_t n, uint32_t min_chunk, pool_fn *fn, void *ctx);

/** b2EnqueueTaskCallback: `user` is the pool.  Returns the task to finish,
 *  or NULL when it ran here already. */
void *pool_box2d_enqueue(void (*task)(int start, int end, uint32_t worker, void *ctx), int count, int min_range,
                         void *task_ctx, void *user);

/** b2FinishTaskCallback. */
void pool_box2d_finish(void *task, void *user);

#endif
