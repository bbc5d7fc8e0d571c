/*
 * runner.c - repetitions on a thread pool, outputs, progress.
 *
 * Workers take repetition indices from a shared counter; each repetition is
 * a self-contained sim, so which worker runs it cannot change its result.
 * Results are stored by repetition index and aggregated in that order.
 */
#include "runner.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "metrics.h"
#include "sim.h"
#include "sim_render.h"
#include "task.h"

#define PATH_MAX_LEN 1024

typedef struct rep_result {
    metric_list_t metrics;
    uint64_t state_hash;
    uint64_t steps;                /**< done: fewer than asked when a task stopped the run */
    int failed;
} rep_result_t;

typedef struct job {
    const run_options_t *opt;
    rep_result_t *results;
    atomic_uint next_rep;
    atomic_ullong steps_done;
    atomic_int failed;
    pthread_mutex_t err_lock;
    double t_end;                  /**< when the last worker finished (under err_lock) */
    char err[512];
} job_t;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int mkdirs(const char *path)
{
    char buf[PATH_MAX_LEN];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; p++) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            *p = '/';
        }
    }
    return (mkdir(buf, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

static void fail(job_t *job, const char *fmt, const char *a, const char *b)
{
    pthread_mutex_lock(&job->err_lock);
    if (!atomic_load(&job->failed)) {
        snprintf(job->err, sizeof job->err, fmt, a, b);
        atomic_store(&job->failed, 1);
    }
    pthread_mutex_unlock(&job->err_lock);
}

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

/* Numbers print with up to 10 significant digits: enough for every
 * metric, and the same bits always print the same text. */
static void json_number(FILE *f, double v)
{
    if (!isfinite(v)) fputs("null", f);
    else fprintf(f, "%.10g", v);
}

/* "groups": [{name, controller, policy, count}, ...], "tasks": [...] */
static void write_groups_and_tasks(FILE *f, const scenario_t *sc)
{
    fputs("  \"groups\": [", f);
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        fputs(g ? ",\n    {\"name\": " : "\n    {\"name\": ", f);
        json_string(f, grp->name);
        fputs(", \"controller\": ", f);
        json_string(f, grp->controller);
        fputs(", \"policy\": ", f);
        json_string(f, grp->policy);
        fprintf(f, ", \"count\": %u}", grp->count);
    }
    fputs(sc->group_count ? "\n  ],\n  \"tasks\": [" : "],\n  \"tasks\": [", f);
    for (uint32_t t = 0; t < sc->task_count; t++) {
        if (t) fputs(", ", f);
        json_string(f, sc->tasks[t].def->name);
    }
    fputs("],\n", f);
}

static void write_run_summary(FILE *f, const run_options_t *opt, uint64_t seed, const rep_result_t *r)
{
    const scenario_t *sc = opt->scenario;
    fputs("{\n  \"scenario\": ", f);
    json_string(f, sc->name);
    fputs(",\n  \"scenario_file\": ", f);
    json_string(f, sc->path);
    fprintf(f, ",\n  \"seed\": %llu,\n", (unsigned long long)seed);
    write_groups_and_tasks(f, sc);
    fprintf(f, "  \"robots\": %u,\n  \"steps\": %llu,\n  \"control_period_ms\": %u,\n",
            scenario_robot_count(sc), (unsigned long long)r->steps, sc->control_period_ms);
    fprintf(f, "  \"state_hash\": \"%016llx\",\n  \"metrics\": {\n", (unsigned long long)r->state_hash);
    for (unsigned k = 0; k < r->metrics.count; k++) {
        fprintf(f, "    \"%s\": ", r->metrics.name[k]);
        json_number(f, r->metrics.value[k]);
        fputs(k + 1 < r->metrics.count ? ",\n" : "\n", f);
    }
    fputs("  }\n}\n", f);
}

/* Opens path.tmp for writing; commit() renames it over path. */
static FILE *open_tmp(const char *path, char *tmp, size_t tmp_size)
{
    if (snprintf(tmp, tmp_size, "%s.tmp", path) >= (int)tmp_size) {
        errno = ENAMETOOLONG;
        return NULL;
    }
    return fopen(tmp, "w");
}

static int commit(FILE *f, const char *tmp, const char *path)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad || rename(tmp, path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

static void write_row(FILE *f, const metric_list_t *m)
{
    for (unsigned k = 0; k < m->count; k++) {
        if (k) fputc(',', f);
        fprintf(f, "%.10g", m->value[k]);
    }
    fputc('\n', f);
}

static int render_frame(job_t *job, const sim_t *sim, render_ctx_t **ctx, const char *dir)
{
    char path[PATH_MAX_LEN], err[RENDER_ERR_MAX];
    if (!*ctx) {
        const scenario_t *sc = job->opt->scenario;
        int w = (int)job->opt->frame_px;
        int h = (int)fmax(RENDER_MIN_PX, floor(w * sc->arena.height / sc->arena.width));
        *ctx = render_create(w, h, err);
        if (!*ctx) {
            fail(job, "%s%s", "cannot render frames: ", err);
            return -1;
        }
    }
    snprintf(path, sizeof path, "%s/frames/frame_%06llu.png", dir, (unsigned long long)sim_step_count(sim));
    if (sim_render_png(sim, *ctx, path, err) != 0) {
        fail(job, "%s%s", "", err);
        return -1;
    }
    return 0;
}

static void run_rep(job_t *job, uint32_t rep, render_ctx_t **render)
{
    const run_options_t *opt = job->opt;
    const scenario_t *sc = opt->scenario;
    uint64_t seed = opt->seed + rep;
    char err[256], dir[PATH_MAX_LEN - 64], path[PATH_MAX_LEN], tmp[PATH_MAX_LEN + 8];
    rep_result_t *res = &job->results[rep];

    snprintf(dir, sizeof dir, "%s/run_%llu", opt->out_dir, (unsigned long long)seed);
    sim_t *sim = sim_create(sc, seed, err);
    if (!sim) {
        fail(job, "%s: %s", sc->path, err);
        return;
    }
    snprintf(path, sizeof path, "%s/frames", dir);
    if (mkdirs(opt->frames_every ? path : dir) != 0) {
        fail(job, "%s: cannot create: %s", dir, strerror(errno));
        sim_destroy(sim);
        return;
    }
    telemetry_t *tel = NULL;
    snprintf(path, sizeof path, "%s/" TELEMETRY_LOG_NAME, dir);
    if (telemetry_open(&opt->telemetry, sim, path, &tel, err) != 0) {
        fail(job, "%s%s", "", err);
        sim_destroy(sim);
        return;
    }
    snprintf(path, sizeof path, "%s/timeseries.csv", dir);
    FILE *ts = open_tmp(path, tmp, sizeof tmp);
    if (!ts) {
        fail(job, "%s: cannot write: %s", path, strerror(errno));
        telemetry_close(tel, 0, err);
        sim_destroy(sim);
        return;
    }
    telemetry_begin(tel, sim, opt->steps);
    metric_list_t row;
    metrics_sample(sim, &row);
    for (unsigned k = 0; k < row.count; k++) {
        fprintf(ts, k ? ",%s" : "%s", row.name[k]);
    }
    fputc('\n', ts);

    uint32_t every = sc->output.timeseries_every;
    int ok = 1;
    uint64_t s = 0;
    sim_video_t *video = NULL;   /* the first repetition only (sim_video.h) */
    if (rep == 0 && opt->video.path
        && !(video = sim_video_open(&opt->video, sim, opt->frame_px, opt->quiet, err))) {
        fail(job, "%s%s", "", err);
        ok = 0;
    }
    for (; s < opt->steps && ok && !sim_done(sim) && !atomic_load(&job->failed); s++) {
        if (s % every == 0) {
            metrics_sample(sim, &row);
            write_row(ts, &row);
        }
        if (opt->frames_every && s % opt->frames_every == 0) {
            ok = render_frame(job, sim, render, dir) == 0;
        }
        if (ok && video && sim_video_step(video, sim, err) != 0) {
            fail(job, "%s%s", "", err);
            ok = 0;
        }
        sim_step(sim);
        telemetry_step(tel, sim);
        atomic_fetch_add(&job->steps_done, 1);
    }
    /* A run a task stopped early counts its remaining steps as done. */
    atomic_fetch_add(&job->steps_done, opt->steps - s);
    res->steps = sim_step_count(sim);
    if (ok && !atomic_load(&job->failed)) {
        metrics_sample(sim, &row);
        write_row(ts, &row);
        if (opt->frames_every) {
            ok = render_frame(job, sim, render, dir) == 0;
        }
    }
    /* The video gets its name only if the run got this far intact. */
    if (video && sim_video_close(video, sim, ok && !atomic_load(&job->failed), err) != 0) {
        fail(job, "%s%s", "", err);
        ok = 0;
    }
    if (commit(ts, tmp, path) != 0 && ok) {
        fail(job, "%s: cannot write: %s", path, strerror(errno));
        ok = 0;
    }
    if (ok && !atomic_load(&job->failed)) {
        metrics_final(sim, &res->metrics);
        res->state_hash = sim_state_hash(sim);
        telemetry_end(tel, sim, &res->metrics, res->state_hash);
        snprintf(path, sizeof path, "%s/summary.json", dir);
        FILE *f = open_tmp(path, tmp, sizeof tmp);
        if (f) write_run_summary(f, opt, seed, res);
        if (!f || commit(f, tmp, path) != 0) {
            fail(job, "%s: cannot write: %s", path, strerror(errno));
        }
    }
    if (telemetry_close(tel, ok && !atomic_load(&job->failed), err) != 0) {
        fail(job, "%s%s", "", err);
    }
    sim_destroy(sim);
}

static void *worker(void *arg)
{
    job_t *job = arg;
    render_ctx_t *render = NULL;
    for (;;) {
        uint32_t rep = atomic_fetch_add(&job->next_rep, 1);
        if (rep >= job->opt->reps || atomic_load(&job->failed)) {
            break;
        }
        run_rep(job, rep, &render);
    }
    render_destroy(render);
    /* The wall time ends when the work does, not when the main thread's
     * progress poll (every 100 ms) next looks. */
    double t = now_s();
    pthread_mutex_lock(&job->err_lock);
    if (t > job->t_end) {
        job->t_end = t;
    }
    pthread_mutex_unlock(&job->err_lock);
    return NULL;
}

static void progress(const job_t *job, double elapsed, int final)
{
    uint64_t total = (uint64_t)job->opt->reps * job->opt->steps;
    uint64_t done = atomic_load(&job->steps_done);
    double frac = total ? (double)done / (double)total : 1.0;
    int width = 30, fill = (int)(frac * width);
    double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    fprintf(stderr, "\r[%.*s%*s] %5.1f%%  %llu/%llu steps  %.0f s elapsed, %.0f s left ",
            fill, "##############################", width - fill, "", 100.0 * frac,
            (unsigned long long)done, (unsigned long long)total, elapsed, final ? 0.0 : eta);
    if (final) fputc('\n', stderr);
    fflush(stderr);
}

static int write_aggregate(const run_options_t *opt, const rep_result_t *res, FILE *echo)
{
    char path[PATH_MAX_LEN], tmp[PATH_MAX_LEN + 8];
    snprintf(path, sizeof path, "%s/summary.json", opt->out_dir);
    FILE *f = open_tmp(path, tmp, sizeof tmp);
    if (!f) return -1;
    for (int pass = 0; pass < 2; pass++) {
        FILE *o = pass ? echo : f;
        if (!o) continue;
        fputs("{\n  \"scenario\": ", o);
        json_string(o, opt->scenario->name);
        fputs(",\n", o);
        write_groups_and_tasks(o, opt->scenario);
        fprintf(o, "  \"reps\": %u,\n  \"first_seed\": %llu,\n  \"steps\": %llu,\n  \"metrics\": {\n",
                opt->reps, (unsigned long long)opt->seed, (unsigned long long)opt->steps);
        const metric_list_t *m0 = &res[0].metrics;
        for (unsigned k = 0; k < m0->count; k++) {
            double sum = 0, sq = 0, lo = INFINITY, hi = -INFINITY;
            for (uint32_t r = 0; r < opt->reps; r++) {
                double v = res[r].metrics.value[k];
                sum += v;
                lo = fmin(lo, v);
                hi = fmax(hi, v);
            }
            double mean = sum / opt->reps;
            for (uint32_t r = 0; r < opt->reps; r++) {
                double d = res[r].metrics.value[k] - mean;
                sq += d * d;
            }
            double sd = opt->reps > 1 ? sqrt(sq / (opt->reps - 1)) : 0.0;
            fprintf(o, "    \"%s\": {\"mean\": ", m0->name[k]);
            json_number(o, mean);
            fputs(", \"sd\": ", o);
            json_number(o, sd);
            fputs(", \"min\": ", o);
            json_number(o, lo);
            fputs(", \"max\": ", o);
            json_number(o, hi);
            fputs(k + 1 < m0->count ? "},\n" : "}\n", o);
        }
        fputs("  }\n}\n", o);
    }
    return commit(f, tmp, path);
}

int runner_run(const run_options_t *opt, char err[512])
{
    job_t job;
    memset(&job, 0, sizeof job);
    job.opt = opt;
    job.results = calloc(opt->reps, sizeof *job.results);
    if (!job.results || mkdirs(opt->out_dir) != 0) {
        snprintf(err, 512, "%s: cannot create: %s", opt->out_dir, job.results ? strerror(errno) : "out of memory");
        free(job.results);
        return -1;
    }
    pthread_mutex_init(&job.err_lock, NULL);
    atomic_init(&job.next_rep, 0);
    atomic_init(&job.steps_done, 0);
    atomic_init(&job.failed, 0);

    uint32_t nthreads = opt->threads < opt->reps ? opt->threads : opt->reps;
    pthread_t *tid = calloc(nthreads, sizeof *tid);
    uint32_t started = 0;
    double t0 = now_s();
    for (; tid && started < nthreads; started++) {
        if (pthread_create(&tid[started], NULL, worker, &job) != 0) break;
    }
    if (started == 0) {
        worker(&job);   /* no threads available: run here */
    }
    int shown = 0, tty = opt->progress && isatty(STDERR_FILENO);
    /* Only a progress line needs the main thread awake; otherwise it joins at
     * once (polling would add up to 100 ms to every short run of a sweep). */
    while (tty && started > 0 && atomic_load(&job.steps_done) < (uint64_t)opt->reps * opt->steps
           && !atomic_load(&job.failed)) {
        struct timespec nap = { 0, 100 * 1000 * 1000 };
        nanosleep(&nap, NULL);
        double el = now_s() - t0;
        if (tty && el > 1.0) {
            progress(&job, el, 0);
            shown = 1;
        }
    }
    for (uint32_t k = 0; k < started; k++) {
        pthread_join(tid[k], NULL);
    }
    double wall = (job.t_end > t0 ? job.t_end : now_s()) - t0;
    free(tid);
    if (shown) progress(&job, wall, 1);

    int rc = 0;
    if (atomic_load(&job.failed)) {
        snprintf(err, 512, "%s", job.err);
        rc = -1;
    } else {
        char path[PATH_MAX_LEN];
        snprintf(path, sizeof path, "%s/run_%llu/summary.json", opt->out_dir, (unsigned long long)opt->seed);
        if (opt->reps > 1) {
            if (write_aggregate(opt, job.results, opt->quiet ? NULL : stdout) != 0) {
                snprintf(err, 512, "%s/summary.json: cannot write: %s", opt->out_dir, strerror(errno));
                rc = -1;
            }
        } else if (!opt->quiet) {
            FILE *f = fopen(path, "r");
            int c;
            while (f && (c = fgetc(f)) != EOF) putchar(c);
            if (f) fclose(f);
        }
        if (!opt->quiet && rc == 0) {
            /* The steps the runs really did: a task may have stopped them. */
            double steps = 0.0;
            for (uint32_t r = 0; r < opt->reps; r++) steps += (double)job.results[r].steps;
            double robot_steps = steps * scenario_robot_count(opt->scenario);
            double sim_time = steps * opt->scenario->control_period_ms / 1000.0;
            printf("outputs: %s/ (run_<seed>/summary.json, timeseries.csv%s%s)\n", opt->out_dir,
                   opt->frames_every ? ", frames/*.png" : "",
                   opt->telemetry.enabled && !opt->telemetry.url ? ", " TELEMETRY_LOG_NAME : "");
            fprintf(stderr, "swarmsim: %u run(s), %.0f steps x %u robots in %.3f s wall on %u thread(s): "
                    "%.0f robot-steps/s, %.0fx real time\n", opt->reps, steps,
                    scenario_robot_count(opt->scenario), wall, nthreads, robot_steps / wall, sim_time / wall);
        }
    }
    pthread_mutex_destroy(&job.err_lock);
    free(job.results);
    return rc;
}
