/*
 * floor_bench.c - the simulator against its floor: CPU time per robot-step
 * of Box2D v3 alone stepping the same world, beside the random walk and
 * full sensing, in one process, interleaved.
 *
 * Worlds (at constant density, 1.25 robots per m^2; the arena's side
 * sqrt(n / 1.25) m):
 *   floor  the random walk's own Box2D world (built by the simulator's
 *          world.c: the same walls, bodies, density, friction and
 *          sub-steps, in the same library) stepped with nothing else: each
 *          control period the velocities the random walk's wheels asked for
 *          in that step are set on the bodies (b2Body_SetLinearVelocity,
 *          b2Body_SetAngularVelocity), then b2World_Step.  So it follows the
 *          random walk's trajectory exactly (checked at the end: every
 *          body's pose equal bit for bit), and its cost is what any
 *          simulator of these bodies pays for their physics;
 *   rw     tools/bench/bench_random_walk.yaml: random walk, IR proximity;
 *   fs     tools/bench/bench_full_sensing.yaml: every robot reads every
 *          sensor every step (forager_sense_all), 1.25 tokens per m^2.
 * Each (robot count, thread count) gets its own worlds; one round steps
 * every world `steps` control steps in turn (all thread counts of a count
 * side by side), the first round is a warm-up, then --reps timed rounds.
 * A chunk's CPU time is the process's (every thread's, user + system),
 * its wall time the monotonic clock's; the figures are medians over the
 * rounds, each world's multiple of the floor the median of the rounds'
 * ratios (a load change hits both worlds of a round alike).
 *
 *   floor_bench [--counts 20:2000,200:500,2000:50,10000:10,100000:2]
 *               [--threads 1,2] [--reps 7] [--worlds floor,rw,fs]
 *               [--rw FILE] [--fs FILE] [--set K=V ...]
 * --set overrides a key of both worlds' scenarios (as swarmsim's), after
 * the robot count and the arena: `--set ir.noise_draws=summed` measures an
 * option.  Prints one line per count, world and thread count, then the
 * multiples.
 */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/sim_internal.h"

#define MAX_COUNTS 8
#define MAX_THREADS 4
#define MAX_REPS 51
#define DENSITY 1.25
#define MAX_SETS 16

enum { W_FLOOR, W_RW, W_FS, WORLDS };
static const char *const world_name[WORLDS] = { "floor", "rw", "fs" };

typedef struct velocity {
    b2Vec2 v;
    float w;
} velocity_t;

typedef struct world {
    scenario_t *sc;
    sim_t *sim;
    double cpu[MAX_REPS], wall[MAX_REPS];   /* s per chunk */
} world_t;

/* The floor replays the random walk's velocities of the same steps:
 * recorded while the random walk steps (into `rec`, steps x n). */
typedef struct bench {
    world_t w[WORLDS];
    velocity_t *rec;
    uint32_t n, steps;
} bench_t;

static double clock_s(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(const double *v, int n)
{
    double s[MAX_REPS];
    memcpy(s, v, (size_t)n * sizeof *s);
    qsort(s, (size_t)n, sizeof *s, by_value);
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

/* --set's overrides, in the order given. */
typedef struct sets {
    scenario_override_t o[MAX_SETS];
    int n;
} sets_t;

static scenario_t *load(const char *path, uint32_t n, int tokens, const sets_t *sets)
{
    char count[64], width[64], height[64], food[64], err[SIM_ERR_MAX];
    double side = sqrt(n / DENSITY);
    snprintf(count, sizeof count, "robots.0.count=%u", n);
    snprintf(width, sizeof width, "arena.width=%.3f", side);
    snprintf(height, sizeof height, "arena.height=%.3f", side);
    snprintf(food, sizeof food, "foraging.food_count=%u", n);
    scenario_override_t o[4 + MAX_SETS] = { { count }, { width }, { height }, { food } };
    size_t k = tokens ? 4 : 3;
    for (int i = 0; i < sets->n; i++) {
        o[k++] = sets->o[i];
    }
    scenario_t *sc = calloc(1, sizeof *sc);
    if (!sc || scenario_load(path, o, k, sc, err) != 0) {
        fprintf(stderr, "floor_bench: %s\n", sc ? err : "out of memory");
        FILE *f = sc ? fopen(path, "r") : NULL;
        if (f) {
            fclose(f);   /* there, and bad: its error says why */
        } else if (sc && strncmp(path, "tools/bench/", 12) == 0) {
            fprintf(stderr, "floor_bench: its worlds are read from the current directory: run it from the "
                            "repository's root (as make bench-floor does), or give --rw FILE and --fs FILE\n");
        }
        exit(1);
    }
    return sc;
}

/* A multiple, or "-" when the world it is taken against was not run. */
static void print_multiple(int run, double m)
{
    if (run) {
        printf(" %10.2f", m);
    } else {
        printf(" %10s", "-");
    }
}

static sim_t *create(const scenario_t *sc, uint32_t threads)
{
    char err[SIM_ERR_MAX];
    sim_t *sim = sim_create_threads(sc, sc->seed, threads, err);
    if (!sim) {
        fprintf(stderr, "floor_bench: %s\n", err);
        exit(1);
    }
    return sim;
}

/* Each world's chunk in a function of its own (not inlined), so that a
 * profiler can count one world's instructions alone
 * (valgrind --tool=callgrind --toggle-collect=step_rw).  The random walk's
 * velocities are recorded for the floor (n stores a step: charged to the
 * random walk, not to the floor). */
static __attribute__((noinline)) void step_rw(bench_t *b)
{
    struct sim *sim = b->w[W_RW].sim;
    for (uint32_t s = 0; s < b->steps; s++) {
        sim_step(sim);
        velocity_t *row = b->rec + (size_t)s * b->n;
        for (uint32_t i = 0; b->rec && i < b->n; i++) {
            row[i].v = sim->drive[i].v;
            row[i].w = sim->drive[i].w;
        }
    }
}

/* The floor's chunk: Box2D alone (world_drive's calls, then the step). */
static __attribute__((noinline)) void step_floor(bench_t *b)
{
    struct sim *f = b->w[W_FLOOR].sim;
    for (uint32_t s = 0; s < b->steps; s++) {
        const velocity_t *row = b->rec + (size_t)s * b->n;
        for (uint32_t i = 0; i < b->n; i++) {
            if (f->robots[i].moves) {
                b2Body_SetLinearVelocity(f->robots[i].body, row[i].v);
                b2Body_SetAngularVelocity(f->robots[i].body, row[i].w);
            }
        }
        b2World_Step(f->world, f->dt, f->sc->physics_substeps);
    }
}

static __attribute__((noinline)) void step_fs(bench_t *b)
{
    for (uint32_t s = 0; s < b->steps; s++) {
        sim_step(b->w[W_FS].sim);
    }
}

static void step_world(bench_t *b, int w, int rep)
{
    double c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID), t0 = clock_s(CLOCK_MONOTONIC);
    if (w == W_FLOOR) {
        step_floor(b);
    } else if (w == W_RW) {
        step_rw(b);
    } else {
        step_fs(b);
    }
    if (rep >= 0) {
        b->w[w].cpu[rep] = clock_s(CLOCK_PROCESS_CPUTIME_ID) - c0;
        b->w[w].wall[rep] = clock_s(CLOCK_MONOTONIC) - t0;
    }
}

/* Bodies of the floor and of the random walk at the same poses, bit for bit. */
static uint32_t trajectory_mismatches(const bench_t *b)
{
    const struct sim *f = b->w[W_FLOOR].sim, *r = b->w[W_RW].sim;
    uint32_t bad = 0;
    for (uint32_t i = 0; i < b->n; i++) {
        b2Transform x = b2Body_GetTransform(f->robots[i].body), y = b2Body_GetTransform(r->robots[i].body);
        bad += memcmp(&x, &y, sizeof x) != 0;
    }
    return bad;
}

static int parse_list(const char *s, uint32_t *a, uint32_t *b, int max)
{
    int k = 0;
    while (*s && k < max) {
        char *end;
        a[k] = (uint32_t)strtoul(s, &end, 10);
        if (b) {
            if (*end != ':') return -1;
            b[k] = (uint32_t)strtoul(end + 1, &end, 10);
        }
        if ((*end && *end != ',') || a[k] == 0 || (b && b[k] == 0)) return -1;
        k++;
        s = *end ? end + 1 : end;
    }
    return *s ? -1 : k;
}

static void usage(void)
{
    fprintf(stderr, "usage: floor_bench [--counts N:STEPS,...] [--threads T,...] [--reps R] "
                    "[--worlds floor,rw,fs] [--rw FILE] [--fs FILE] [--set K=V ...]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    const char *counts_arg = "20:2000,200:500,2000:50,10000:10,100000:2", *threads_arg = "1,2";
    const char *worlds_arg = "floor,rw,fs";
    const char *path[WORLDS] = { NULL, "tools/bench/bench_random_walk.yaml", "tools/bench/bench_full_sensing.yaml" };
    int reps = 7;
    sets_t sets = { .n = 0 };
    for (int a = 1; a < argc; a++) {
        if (a + 1 >= argc) usage();
        if (!strcmp(argv[a], "--counts")) counts_arg = argv[++a];
        else if (!strcmp(argv[a], "--threads")) threads_arg = argv[++a];
        else if (!strcmp(argv[a], "--reps")) reps = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--worlds")) worlds_arg = argv[++a];
        else if (!strcmp(argv[a], "--rw")) path[W_RW] = argv[++a];
        else if (!strcmp(argv[a], "--fs")) path[W_FS] = argv[++a];
        else if (!strcmp(argv[a], "--set") && sets.n < MAX_SETS) sets.o[sets.n++].text = argv[++a];
        else usage();
    }
    uint32_t count[MAX_COUNTS], steps[MAX_COUNTS], threads[MAX_THREADS];
    int nc = parse_list(counts_arg, count, steps, MAX_COUNTS), nt = parse_list(threads_arg, threads, NULL, MAX_THREADS);
    int on[WORLDS] = { 0 };
    for (int w = 0; w < WORLDS; w++) {
        const char *p = strstr(worlds_arg, world_name[w]);
        on[w] = p && (p == worlds_arg || p[-1] == ',') && (p[strlen(world_name[w])] == ',' || !p[strlen(world_name[w])]);
    }
    if (nc <= 0 || nt <= 0 || reps < 1 || reps > MAX_REPS) usage();
    on[W_RW] |= on[W_FLOOR];   /* the floor replays the random walk */
    /* Every world's file is read before the table starts: a bad one fails
     * alone, not under a header. */
    for (int w = W_RW; w < WORLDS; w++) {
        if (on[w]) {
            scenario_t *sc = load(path[w], count[0], w == W_FS, &sets);
            scenario_free(sc);
            free(sc);
        }
    }

    printf("%7s %6s %5s %3s %4s %10s %10s %10s %10s %8s\n", "robots", "steps", "world", "thr", "reps", "cpu_us/rs",
           "wall_us/rs", "x_floor", "x_rw", "x_1thr");
    for (int c = 0; c < nc; c++) {
        uint32_t n = count[c];
        bench_t b[MAX_THREADS];
        memset(b, 0, sizeof b);
        for (int t = 0; t < nt; t++) {
            b[t].n = n;
            b[t].steps = steps[c];
            for (int w = 0; w < WORLDS; w++) {
                if (on[w]) {
                    b[t].w[w].sc = load(path[w == W_FLOOR ? W_RW : w], n, w == W_FS, &sets);
                    b[t].w[w].sim = create(b[t].w[w].sc, threads[t]);
                }
            }
            if (on[W_FLOOR] && !(b[t].rec = malloc((size_t)n * steps[c] * sizeof *b[t].rec))) {
                fprintf(stderr, "floor_bench: out of memory\n");
                return 1;
            }
        }
        /* Round -1 warms up (robots spread, caches and Box2D's pools filled). */
        for (int r = -1; r < reps; r++) {
            for (int t = 0; t < nt; t++) {
                for (int w = W_RW; w < WORLDS; w++) {   /* rw before the floor: it records */
                    if (on[w]) step_world(&b[t], w, r);
                }
                if (on[W_FLOOR]) step_world(&b[t], W_FLOOR, r);
            }
        }
        double rs = (double)n * steps[c];
        for (int t = 0; t < nt; t++) {
            for (int w = 0; w < WORLDS; w++) {
                if (!on[w]) continue;
                const world_t *x = &b[t].w[w];
                double ratio_f[MAX_REPS], ratio_rw[MAX_REPS], speed[MAX_REPS];
                for (int r = 0; r < reps; r++) {
                    ratio_f[r] = on[W_FLOOR] ? x->cpu[r] / b[t].w[W_FLOOR].cpu[r] : NAN;
                    ratio_rw[r] = x->cpu[r] / b[t].w[W_RW].cpu[r];
                    speed[r] = b[0].w[w].wall[r] / x->wall[r];
                }
                printf("%7u %6u %5s %3u %4d %10.3f %10.3f", n, steps[c], world_name[w], threads[t], reps,
                       1e6 * median(x->cpu, reps) / rs, 1e6 * median(x->wall, reps) / rs);
                print_multiple(on[W_FLOOR], median(ratio_f, reps));
                print_multiple(on[W_RW], median(ratio_rw, reps));
                printf(" %8.2f\n", median(speed, reps));
            }
            if (on[W_FLOOR]) {
                uint32_t bad = trajectory_mismatches(&b[t]);
                if (bad) {
                    printf("%7u floor and rw at %u threads: %u of %u bodies apart\n", n, threads[t], bad, n);
                }
            }
        }
        fflush(stdout);
        for (int t = 0; t < nt; t++) {
            for (int w = 0; w < WORLDS; w++) {
                if (b[t].w[w].sim) {
                    sim_destroy(b[t].w[w].sim);
                    scenario_free(b[t].w[w].sc);
                    free(b[t].w[w].sc);
                }
            }
            free(b[t].rec);
        }
    }
    double load[3];
    FILE *f = fopen("/proc/loadavg", "r");
    if (f && fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) == 3) {
        printf("load average at the end: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
    }
    if (f) fclose(f);
    return 0;
}
