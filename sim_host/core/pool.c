/*
 * pool.c - the worker threads of one run (pool.h).
 *
 * One mutex guards the queue of tasks with chunks left to take; a chunk is
 * taken under it and run outside it.  Chunks are a few hundred robots or
 * Box2D's own ranges, so the lock is taken a few times per phase, not per
 * item.  Task slots are a fixed array: Box2D has at most workerCount + 3
 * tasks in flight (solver workers, island split, tree rebuild, one
 * parallel-for), our phases one.
 */
#define _GNU_SOURCE 1   /* sched_getaffinity, CPU_COUNT (Linux): the CPUs this process may use */
#include "pool.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#define POOL_SLOTS (2u * POOL_MAX_THREADS + 8u)

typedef void box2d_fn(int start, int end, uint32_t worker, void *ctx);

typedef struct task {
    pool_fn *fn;            /**< ours, or */
    box2d_fn *b2;           /**< Box2D's */
    void *ctx;
    uint32_t n, chunk;      /**< items, items per chunk */
    uint32_t chunks, next, done;
    int used;
    struct task *queued;    /**< the next task with chunks left (FIFO) */
} task_t;

typedef struct worker_arg {
    pool_t *pool;
    uint32_t index;
} worker_arg_t;

struct pool {
    uint32_t threads;
    uint32_t forced_chunk;    /**< POOL_CHUNK_ENV, 0: none */
    pthread_t tid[POOL_MAX_THREADS];
    worker_arg_t arg[POOL_MAX_THREADS];
    pthread_mutex_t lock;
    pthread_cond_t work;      /**< a chunk was queued, or stop */
    pthread_cond_t finished;  /**< a task's last chunk completed */
    task_t slot[POOL_SLOTS];
    task_t *head, *tail;      /**< tasks with chunks left to take */
    int stop;
    int64_t spin_ns;          /**< how long an idle thread polls (POOL_SPIN_NS, POOL_SPIN_ENV; 0: never) */
    uint32_t cpus;            /**< pool_cpus() when it was made */
    atomic_uint queued_seq;   /**< + 1 at every task queued (a hint for spinning) */
    atomic_uint done_seq;     /**< + 1 at every task's last chunk done */
};

/* A thread that finds nothing to do polls this long before it sleeps on
 * its condition, ns.  A step hands out some fifteen tasks (our phases,
 * Box2D's stages), many of them tens of microseconds long below 10,000
 * robots, and waking a sleeping thread costs tens of microseconds on a
 * virtual machine: more than a short task.  Polling costs CPU time only
 * while a run's own threads wait for each other, and it must not take the
 * CPU a working thread needs: no more threads than the process has CPUs
 * poll at a time, counting every pool of the process (runs side by side),
 * and on one CPU none does.  (One fewer is too few: a 2-thread pool's two
 * threads poll at once for a moment whenever a task ends, the one waiting
 * for it and the one that ran its last chunk.) */
#define POOL_SPIN_NS 50000

/* The threads of every pool in the process polling now. */
static atomic_uint polling;

static inline void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("isb");   /* yield is close to a no-op on most cores */
#endif
}

static int64_t now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

/* Outside the lock: polls *seq until it is no longer `seen` (1) or
 * spin_ns (> 0) have passed (0; the clock read every 32 polls); 0 at once
 * when enough threads of the process already poll.
 * Only a hint: the caller looks again under the lock, and sleeps only
 * after a poll that timed out (a change may have been another thread's
 * chunk). */
static int spin_while(const pool_t *p, const atomic_uint *seq, unsigned seen)
{
    if (atomic_fetch_add_explicit(&polling, 1u, memory_order_relaxed) + 1u > p->cpus) {
        atomic_fetch_sub_explicit(&polling, 1u, memory_order_relaxed);
        return 0;
    }
    int changed = 1;
    int64_t until = now_ns() + p->spin_ns;
    for (uint32_t k = 1; atomic_load_explicit(seq, memory_order_relaxed) == seen; k++) {
        cpu_relax();
        if (k % 32 == 0 && now_ns() >= until) {
            changed = 0;
            break;
        }
    }
    atomic_fetch_sub_explicit(&polling, 1u, memory_order_relaxed);
    return changed;
}

uint32_t pool_cpus(void)
{
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    uint32_t n = online > 0 ? (uint32_t)online : 1u;
#ifdef CPU_COUNT
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0) {
        int allowed = CPU_COUNT(&set);
        n = (allowed > 0 && (uint32_t)allowed < n) ? (uint32_t)allowed : n;
    }
#endif
    return n;
}

/* Under the lock: the next chunk of the first queued task, or NULL. */
static task_t *take(pool_t *p, uint32_t *chunk)
{
    task_t *t = p->head;
    if (!t) {
        return NULL;
    }
    *chunk = t->next++;
    if (t->next == t->chunks) {
        p->head = t->queued;
        if (!p->head) {
            p->tail = NULL;
        }
    }
    return t;
}

/* Runs chunk c of t (outside the lock), then counts it (under it). */
static void run(pool_t *p, task_t *t, uint32_t c, uint32_t worker)
{
    pthread_mutex_unlock(&p->lock);
    uint32_t begin = c * t->chunk, end = begin + t->chunk < t->n ? begin + t->chunk : t->n;
    if (t->fn) {
        t->fn(begin, end, worker, t->ctx);
    } else {
        t->b2((int)begin, (int)end, worker, t->ctx);
    }
    pthread_mutex_lock(&p->lock);
    if (++t->done == t->chunks) {
        atomic_fetch_add_explicit(&p->done_seq, 1u, memory_order_relaxed);
        pthread_cond_broadcast(&p->finished);
    }
}

static void *worker_main(void *a)
{
    worker_arg_t *arg = a;
    pool_t *p = arg->pool;
    int spun = 0;
    pthread_mutex_lock(&p->lock);
    while (!p->stop) {
        uint32_t c;
        task_t *t = take(p, &c);
        if (t) {
            run(p, t, c, arg->index);
            spun = 0;
        } else if (!spun && p->spin_ns > 0) {   /* poll a while, then look again */
            unsigned seen = atomic_load_explicit(&p->queued_seq, memory_order_relaxed);
            pthread_mutex_unlock(&p->lock);
            spun = !spin_while(p, &p->queued_seq, seen);
            pthread_mutex_lock(&p->lock);
        } else {
            pthread_cond_wait(&p->work, &p->lock);
            spun = 0;
        }
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

pool_t *pool_create(uint32_t threads)
{
    if (threads < 1 || threads > POOL_MAX_THREADS) {
        return NULL;
    }
    pool_t *p = calloc(1, sizeof *p);
    if (!p) {
        return NULL;
    }
    p->threads = 1;
    p->cpus = pool_cpus();
    p->spin_ns = POOL_SPIN_NS;
    const char *spin = getenv(POOL_SPIN_ENV);
    if (spin) {
        char *end;
        unsigned long us = strtoul(spin, &end, 10);
        if (!*spin || *end || us > 1000000) {
            fprintf(stderr, "warning: %s=%s is not 0..1000000 microseconds: polling %d us\n", POOL_SPIN_ENV, spin,
                    POOL_SPIN_NS / 1000);
        } else {
            p->spin_ns = (int64_t)us * 1000;
        }
    }
    if (p->cpus < 2) {
        p->spin_ns = 0;   /* a polling thread would hold the only CPU */
    }
    const char *forced = getenv(POOL_CHUNK_ENV);
    if (forced) {
        char *end;
        unsigned long v = strtoul(forced, &end, 10);
        p->forced_chunk = (*forced && !*end && v >= 1 && v <= UINT32_MAX) ? (uint32_t)v : 0;
    }
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->work, NULL);
    pthread_cond_init(&p->finished, NULL);
    for (uint32_t k = 1; k < threads; k++) {
        p->arg[k] = (worker_arg_t){ p, k };
        if (pthread_create(&p->tid[k], NULL, worker_main, &p->arg[k]) != 0) {
            pool_destroy(p);
            return NULL;
        }
        p->threads = k + 1;
    }
    return p;
}

void pool_destroy(pool_t *p)
{
    if (!p) {
        return;
    }
    pthread_mutex_lock(&p->lock);
    p->stop = 1;
    atomic_fetch_add_explicit(&p->queued_seq, 1u, memory_order_relaxed);   /* a polling worker leaves now */
    pthread_cond_broadcast(&p->work);
    pthread_mutex_unlock(&p->lock);
    for (uint32_t k = 1; k < p->threads; k++) {
        pthread_join(p->tid[k], NULL);
    }
    pthread_mutex_destroy(&p->lock);
    pthread_cond_destroy(&p->work);
    pthread_cond_destroy(&p->finished);
    free(p);
}

uint32_t pool_threads(const pool_t *p) { return p->threads; }

/* Under the lock: a free slot holding the task, queued.  Slots cannot run
 * out (see the file comment); if they did, NULL. */
static task_t *submit(pool_t *p, pool_fn *fn, box2d_fn *b2, void *ctx, uint32_t n, uint32_t chunk)
{
    for (uint32_t s = 0; s < POOL_SLOTS; s++) {
        task_t *t = &p->slot[s];
        if (!t->used) {
            *t = (task_t){ .fn = fn, .b2 = b2, .ctx = ctx, .n = n, .chunk = chunk,
                           .chunks = (n + chunk - 1) / chunk, .used = 1 };
            if (p->tail) {
                p->tail->queued = t;
            } else {
                p->head = t;
            }
            p->tail = t;
            atomic_fetch_add_explicit(&p->queued_seq, 1u, memory_order_relaxed);
            pthread_cond_broadcast(&p->work);
            return t;
        }
    }
    return NULL;
}

/* Under the lock: helps with any queued chunk until t is done, then frees
 * its slot. */
static void help_until(pool_t *p, task_t *t)
{
    int spun = 0;
    while (t->done < t->chunks) {
        uint32_t c;
        task_t *any = take(p, &c);
        if (any) {
            run(p, any, c, 0);
            spun = 0;
        } else if (!spun && p->spin_ns > 0) {
            /* The last chunks are running elsewhere: poll a while.  Only
             * this thread queues tasks (Box2D enqueues from the thread
             * that steps the world), so nothing new can come meanwhile. */
            unsigned seen = atomic_load_explicit(&p->done_seq, memory_order_relaxed);
            pthread_mutex_unlock(&p->lock);
            spun = !spin_while(p, &p->done_seq, seen);
            pthread_mutex_lock(&p->lock);
        } else {
            pthread_cond_wait(&p->finished, &p->lock);
            spun = 0;
        }
    }
    t->used = 0;
}

/* Items per chunk: about four chunks per worker, so that a slow chunk
 * does not leave the others idle, and never fewer than min_chunk items. */
static uint32_t chunk_size(const pool_t *p, uint32_t n, uint32_t min_chunk)
{
    uint32_t parts = 4u * p->threads;
    uint32_t c = (n + parts - 1) / parts;
    return c < min_chunk ? (min_chunk ? min_chunk : 1) : c;
}

void pool_for(pool_t *p, uint32_t n, uint32_t min_chunk, pool_fn *fn, void *ctx)
{
    if (n == 0) {
        return;
    }
    if (p->forced_chunk) {
        min_chunk = p->forced_chunk;
    }
    if (p->threads == 1 || n <= min_chunk) {
        fn(0, n, 0, ctx);
        return;
    }
    pthread_mutex_lock(&p->lock);
    task_t *t = submit(p, fn, NULL, ctx, n, chunk_size(p, n, min_chunk));
    if (t) {
        help_until(p, t);
    }
    pthread_mutex_unlock(&p->lock);
    if (!t) {
        fn(0, n, 0, ctx);
    }
}

void *pool_box2d_enqueue(box2d_fn *task, int count, int min_range, void *task_ctx, void *user)
{
    pool_t *p = user;
    if (count <= 0) {
        return NULL;
    }
    uint32_t n = (uint32_t)count, min_chunk = min_range > 0 ? (uint32_t)min_range : 1u;
    pthread_mutex_lock(&p->lock);
    task_t *t = submit(p, NULL, task, task_ctx, n, chunk_size(p, n, min_chunk));
    pthread_mutex_unlock(&p->lock);
    if (!t) {
        task(0, count, 0, task_ctx);   /* cannot happen (slots); Box2D accepts NULL: done here */
    }
    return t;
}

void pool_box2d_finish(void *task, void *user)
{
    pool_t *p = user;
    pthread_mutex_lock(&p->lock);
    help_until(p, task);
    pthread_mutex_unlock(&p->lock);
}
