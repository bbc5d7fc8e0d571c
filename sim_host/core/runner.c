/*
 * runner.c - repetitions on a thread pool, outputs, progress.
 *
 * Workers take repetition indices from a shared counter; each repetition is
 * a self-contained sim, so which worker runs it cannot change its result.
 * Results are stored by repetition index and aggregated in that order.
 * A run's files get their final names only when the whole run finished
 * (runner.h): a stop or a failure anywhere discards unfinished runs.
 */
#include "runner.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "swarmsim/metrics.h"
#include "pool.h"
#include "swarmsim/sim.h"
#include "control.h"
#include "sim_render.h"
#include "swarmsim/task.h"

#define PATH_MAX_LEN 1024

typedef struct rep_result {
    metric_list_t metrics;
    uint64_t state_hash;
    uint64_t steps;                /**< done: fewer than asked when a task stopped the run */
    int done;                      /**< finished, outputs under their final names */
} rep_result_t;

typedef struct job {
    const run_options_t *opt;
    uint32_t run_threads;          /**< threads inside each run */
    const metric_list_t *names;    /**< the probe's metrics, their strings kept (check_setup) */
    rep_result_t *results;
    atomic_uint next_rep;
    atomic_ullong steps_done;
    atomic_int failed;
    pthread_mutex_t err_lock;
    double t_end;                  /**< when the last worker finished (under err_lock) */
    char err[SIM_ERR_MAX];
} job_t;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* CPU time of the whole process (every thread), user + system, s: beside
 * the wall time, a rate that other load on the machine does not inflate. */
static double cpu_s(void)
{
    struct rusage u;
    if (getrusage(RUSAGE_SELF, &u) != 0) {
        return NAN;
    }
    return (double)u.ru_utime.tv_sec + (double)u.ru_stime.tv_sec
           + 1e-6 * ((double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_usec);
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
    char path[PATH_MAX_LEN], err[SIM_ERR_MAX];
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

static int stopping(const job_t *job)
{
    return atomic_load(&job->failed) || (job->opt->stop && *job->opt->stop);
}

/* Writes `text` to path (through path.tmp).  0 or -1 (errno). */
static int write_text(const char *path, const char *text)
{
    char tmp[PATH_MAX_LEN + 8];
    FILE *f = open_tmp(path, tmp, sizeof tmp);
    if (!f) return -1;
    fputs(text, f);
    return commit(f, tmp, path);
}

/* One repetition, written in run_<seed>.partial/ and renamed run_<seed>/
 * when it finished; removed when it did not. */
static void run_rep(job_t *job, uint32_t rep, render_ctx_t **render)
{
    const run_options_t *opt = job->opt;
    const scenario_t *sc = opt->scenario;
    uint64_t seed = opt->seed + rep;
    char err[SIM_ERR_MAX], final_dir[PATH_MAX_LEN - 80], dir[PATH_MAX_LEN - 64], path[PATH_MAX_LEN];
    char tmp[PATH_MAX_LEN + 8];
    rep_result_t *res = &job->results[rep];

    snprintf(final_dir, sizeof final_dir, "%s/run_%" PRIu64, opt->out_dir, seed);
    snprintf(dir, sizeof dir, "%s.partial", final_dir);
    outdir_remove_tree(dir);      /* a run stopped by an earlier invocation */
    sim_t *sim = sim_create_threads(sc, seed, job->run_threads, err);
    if (!sim) {
        fail(job, "%s: %s", sc->path, err);
        return;
    }
    snprintf(path, sizeof path, "%s/frames", dir);
    if (outdir_mkdirs(opt->frames_every ? path : dir) != 0) {
        fail(job, "%s: cannot create: %s", dir, strerror(errno));
        sim_destroy(sim);
        return;
    }
    if (opt->camera_frames) {
        snprintf(path, sizeof path, "%s/camera/robot_%u", dir, opt->camera_robot);
        if (outdir_mkdirs(path) != 0 || sim_camera_record(sim, opt->camera_robot, path) != 0) {
            fail(job, "%s: cannot create: %s", path, strerror(errno));
            sim_destroy(sim);
            outdir_remove_tree(dir);
            return;
        }
    }
    snprintf(path, sizeof path, "%s/" SUMMARY_SCENARIO_COPY, dir);
    if (write_text(path, opt->scenario_text) != 0) {
        fail(job, "%s: cannot write: %s", path, strerror(errno));
        sim_destroy(sim);
        outdir_remove_tree(dir);
        return;
    }
    telemetry_t *tel = NULL;
    snprintf(path, sizeof path, "%s/" TELEMETRY_LOG_NAME, dir);
    if (telemetry_open(&opt->telemetry, sim, path, &tel, err) != 0) {
        fail(job, "%s%s", "", err);
        sim_destroy(sim);
        outdir_remove_tree(dir);
        return;
    }
    snprintf(path, sizeof path, "%s/timeseries.csv", dir);
    FILE *ts = open_tmp(path, tmp, sizeof tmp);
    if (!ts) {
        fail(job, "%s: cannot write: %s", path, strerror(errno));
        telemetry_close(tel, 0, err);
        sim_destroy(sim);
        outdir_remove_tree(dir);
        return;
    }
    telemetry_begin(tel, sim, opt->steps);
    control_t *ctl = NULL;
    if (opt->control_url && control_open(opt->control_url, opt->control_paused, sim, opt->steps, tel, &ctl, err) != 0) {
        fail(job, "%s%s", "", err);
        fclose(ts);
        remove(tmp);
        telemetry_close(tel, 0, err);
        sim_destroy(sim);
        outdir_remove_tree(dir);
        return;
    }
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
    for (; s < opt->steps && ok && !sim_done(sim) && !stopping(job); s++) {
        if (control_before_step(ctl, opt->stop) != 0) {
            break;   /* stopped while paused */
        }
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
        if (sim_error(sim)) {   /* a renderer or a camera picture failed */
            fail(job, "%s: %s", sc->path, sim_error(sim));
            ok = 0;
        }
        telemetry_step(tel, sim);
        control_after_step(ctl);
        atomic_fetch_add(&job->steps_done, 1);
    }
    /* A run a task stopped early counts its remaining steps as done. */
    atomic_fetch_add(&job->steps_done, opt->steps - s);
    res->steps = sim_step_count(sim);
    ok = ok && !stopping(job);
    if (ok) {
        metrics_sample(sim, &row);
        write_row(ts, &row);
        if (opt->frames_every) {
            ok = render_frame(job, sim, render, dir) == 0;
        }
    }
    /* The video gets its name only if the run got this far intact. */
    if (video && sim_video_close(video, sim, ok, err) != 0) {
        fail(job, "%s%s", "", err);
        ok = 0;
    }
    if (!ok) {
        fclose(ts);                /* unfinished: no final name for any of it */
        remove(tmp);
    } else if (commit(ts, tmp, path) != 0) {
        fail(job, "%s: cannot write: %s", path, strerror(errno));
        ok = 0;
    }
    if (ok) {
        metrics_final(sim, &res->metrics);
        res->state_hash = sim_state_hash(sim);
        telemetry_end(tel, sim, &res->metrics, res->state_hash);
        snprintf(path, sizeof path, "%s/summary.json", dir);
        FILE *f = open_tmp(path, tmp, sizeof tmp);
        provenance_t pv = opt->provenance;
        char *control = control_json(ctl);
        pv.control = control;
        if (f) summary_write_run(f, sc, &pv, sim, seed, res->steps, res->state_hash, &res->metrics);
        free(control);
        if (!f || commit(f, tmp, path) != 0) {
            fail(job, "%s: cannot write: %s", path, strerror(errno));
            ok = 0;
        }
    }
    if (ok) {
        snprintf(path, sizeof path, "%s/" SUMMARY_EXACT_METRICS, dir);
        FILE *f = open_tmp(path, tmp, sizeof tmp);
        if (f) summary_write_exact(f, &res->metrics);
        if (!f || commit(f, tmp, path) != 0) {
            fail(job, "%s: cannot write: %s", path, strerror(errno));
            ok = 0;
        }
    }
    control_close(ctl);
    if (telemetry_close(tel, ok, err) != 0) {
        if (ok) fail(job, "%s%s", "", err);
        ok = 0;
    }
    /* The metrics' names, units and docs are partly the sim's own strings:
     * point them at the kept copies (the same metrics, in the same order)
     * before it goes, for the aggregate summary. */
    for (unsigned k = 0; ok && k < res->metrics.count; k++) {
        if (k >= job->names->count || strcmp(res->metrics.name[k], job->names->name[k]) != 0) {
            fail(job, "%s: %s: metrics differ from the first run's", sc->path, final_dir);
            ok = 0;
            break;
        }
        res->metrics.name[k] = job->names->name[k];
        res->metrics.unit[k] = job->names->unit[k];
        res->metrics.doc[k] = job->names->doc[k];
    }
    sim_destroy(sim);
    /* The run's last check: a sibling failing or a signal during its final
     * writes still leaves it unfinished, never half-named. */
    if (ok && !stopping(job)) {
        if (rename(dir, final_dir) != 0) {
            fail(job, "%s: cannot rename to its final name: %s", dir, strerror(errno));
        } else {
            res->done = 1;
            return;
        }
    }
    outdir_remove_tree(dir);
}

static void *worker(void *arg)
{
    job_t *job = arg;
    render_ctx_t *render = NULL;
    for (;;) {
        uint32_t rep = atomic_fetch_add(&job->next_rep, 1);
        if (rep >= job->opt->reps || stopping(job)) {
            break;
        }
        if (!job->results[rep].done) {     /* done: kept from an earlier invocation */
            run_rep(job, rep, &render);
        }
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

/* OUT/summary.json over the finished runs (and echoed when asked). */
static int write_aggregate(const run_options_t *opt, const rep_result_t *res, FILE *echo)
{
    char path[PATH_MAX_LEN], tmp[PATH_MAX_LEN + 8];
    const metric_list_t **done = calloc(opt->reps, sizeof *done);
    uint32_t n = 0;
    if (!done) return -1;
    for (uint32_t r = 0; r < opt->reps; r++) {
        if (res[r].done) done[n++] = &res[r].metrics;
    }
    snprintf(path, sizeof path, "%s/summary.json", opt->out_dir);
    FILE *f = open_tmp(path, tmp, sizeof tmp);
    int rc = -1;
    if (f) {
        summary_write_aggregate(f, opt->scenario, &opt->provenance, opt->seed, opt->reps, opt->steps, done, n);
        if (echo) {
            summary_write_aggregate(echo, opt->scenario, &opt->provenance, opt->seed, opt->reps, opt->steps,
                                    done, n);
        }
        rc = commit(f, tmp, path);
    }
    free(done);
    return rc;
}

/* One line that names the invocation: what --resume requires to be equal. */
static void identity(const run_options_t *opt, char *buf, size_t len)
{
    const telemetry_options_t *t = &opt->telemetry;
    snprintf(buf, len, "swarmsim-out/1 scenario=%016" PRIx64 " seeds=%" PRIu64 "+%u steps=%" PRIu64
             " frames=%ux%u telemetry=%s/%g/%g", opt->provenance.scenario_hash, opt->seed, opt->reps,
             opt->steps, opt->frames_every, opt->frame_px, !t->enabled ? "off" : t->url ? "url" : "log",
             t->robot_hz, t->swarm_hz);
    if (opt->camera_frames) {   /* only then: earlier folders keep their identity */
        size_t n = strlen(buf);
        snprintf(buf + n, len - n, " camera=%u", opt->camera_robot);
    }
}

/* --resume: the runs an earlier invocation finished, read back. */
static uint32_t load_finished(const run_options_t *opt, const metric_list_t *names, rep_result_t *res)
{
    uint32_t n = 0;
    for (uint32_t r = 0; r < opt->reps; r++) {
        char path[PATH_MAX_LEN];
        snprintf(path, sizeof path, "%s/run_%" PRIu64 "/summary.json", opt->out_dir, opt->seed + r);
        if (summary_read_run(path, opt->seed + r, names, &res[r].metrics, &res[r].steps,
                             &res[r].state_hash) == 0) {
            res[r].done = 1;
            n++;
        } else {
            /* Not finished (or not readable): it runs again from scratch. */
            snprintf(path, sizeof path, "%s/run_%" PRIu64, opt->out_dir, opt->seed + r);
            outdir_remove_tree(path);
        }
    }
    return n;
}

/* A metric's name, unit and doc, copied out of the probe. */
#define METRIC_TEXT_MAX 256
typedef char metric_text_t[3][METRIC_TEXT_MAX];

/* Before anything is written: can the runs start at all?  A scenario whose
 * robots cannot be placed, or an LCM URL no provider takes, is a setup
 * error (exit 2, no folder).  Fills `names` with the run's metrics, their
 * strings in `text` (some are the probe's own, its counters' keys, which
 * die with it; --resume reads finished runs by these names). */
static int check_setup(const run_options_t *opt, metric_list_t *names, metric_text_t *text, char err[SIM_ERR_MAX])
{
    char e[SIM_ERR_MAX];
    sim_t *probe = sim_create(opt->scenario, opt->seed, e);
    if (!probe) {
        snprintf(err, SIM_ERR_MAX, "%.200s: %.300s", opt->scenario->path, e);
        return -1;
    }
    metrics_final(probe, names);
    for (unsigned k = 0; k < names->count; k++) {
        snprintf(text[k][0], METRIC_TEXT_MAX, "%s", names->name[k]);
        snprintf(text[k][1], METRIC_TEXT_MAX, "%s", names->unit[k] ? names->unit[k] : "");
        snprintf(text[k][2], METRIC_TEXT_MAX, "%s", names->doc[k] ? names->doc[k] : "");
        names->name[k] = text[k][0];
        names->unit[k] = text[k][1];
        names->doc[k] = text[k][2];
    }
    sim_destroy(probe);
    if (opt->telemetry.enabled && opt->telemetry.url && telemetry_check_url("--lcm", opt->telemetry.url, e) != 0) {
        snprintf(err, SIM_ERR_MAX, "%s", e);
        return -1;
    }
    return 0;
}

static int run_with(const run_options_t *opt, metric_text_t *text, char err[SIM_ERR_MAX])
{
    job_t job;
    metric_list_t names;
    char ident[SIM_ERR_MAX], path[PATH_MAX_LEN];
    memset(&job, 0, sizeof job);
    job.opt = opt;
    if (check_setup(opt, &names, text, err) != 0) {
        return RUNNER_SETUP_ERROR;
    }
    job.names = &names;
    identity(opt, ident, sizeof ident);
    if (outdir_prepare(opt->out_dir, opt->out_mode, ident, err) != 0) {
        return RUNNER_SETUP_ERROR;
    }
    snprintf(path, sizeof path, "%s/" SUMMARY_SCENARIO_COPY, opt->out_dir);
    job.results = calloc(opt->reps, sizeof *job.results);
    if (!job.results || write_text(path, opt->scenario_text) != 0) {
        snprintf(err, SIM_ERR_MAX, "%.400s: cannot write: %s", path, job.results ? strerror(errno) : "out of memory");
        free(job.results);
        return RUNNER_FAILED;
    }
    uint32_t kept = opt->out_mode == OUTDIR_RESUME ? load_finished(opt, &names, job.results) : 0;
    pthread_mutex_init(&job.err_lock, NULL);
    atomic_init(&job.next_rep, 0);
    atomic_init(&job.steps_done, (unsigned long long)kept * opt->steps);
    atomic_init(&job.failed, 0);
    if (kept && !opt->quiet) {
        fprintf(stderr, "swarmsim: --resume: %u of %u runs already finished in %s\n", kept, opt->reps,
                opt->out_dir);
    }

    uint32_t todo = opt->reps - kept;
    uint32_t nthreads = opt->threads < todo ? opt->threads : (todo ? todo : 1);
    job.run_threads = opt->run_threads;
    if (job.run_threads == 0) {
        uint32_t spare = opt->threads / nthreads;
        job.run_threads = scenario_robot_count(opt->scenario) < RUNNER_SPLIT_MIN_ROBOTS ? 1
                          : spare > POOL_MAX_THREADS                                 ? POOL_MAX_THREADS
                                                                                     : spare;
    }
    pthread_t *tid = calloc(nthreads, sizeof *tid);
    uint32_t started = 0;
    double t0 = now_s(), c0 = cpu_s();
    for (; tid && todo && started < nthreads; started++) {
        if (pthread_create(&tid[started], NULL, worker, &job) != 0) break;
    }
    if (started == 0 && todo) {
        worker(&job);   /* no threads available: run here */
    }
    int shown = 0, tty = opt->progress && isatty(STDERR_FILENO);
    /* Only a progress line needs the main thread awake; otherwise it joins at
     * once (polling would add up to 100 ms to every short run of a sweep). */
    while (tty && started > 0 && atomic_load(&job.steps_done) < (uint64_t)opt->reps * opt->steps
           && !stopping(&job)) {
        struct timespec nap = { 0, 100 * 1000 * 1000 };
        nanosleep(&nap, NULL);
        double el = now_s() - t0;
        if (el > 1.0) {
            progress(&job, el, 0);
            shown = 1;
        }
    }
    for (uint32_t k = 0; k < started; k++) {
        pthread_join(tid[k], NULL);
    }
    double wall = (job.t_end > t0 ? job.t_end : now_s()) - t0;
    double cpu = cpu_s() - c0;
    free(tid);
    if (shown) {
        progress(&job, wall, 1);   /* ends the line, whatever happened */
    }

    uint32_t done = 0;
    for (uint32_t r = 0; r < opt->reps; r++) done += job.results[r].done != 0;
    int rc = RUNNER_OK;
    int stopped = opt->stop && *opt->stop;
    if (atomic_load(&job.failed)) {
        snprintf(err, SIM_ERR_MAX, "%s", job.err);
        rc = RUNNER_FAILED;
    } else if (stopped || done < opt->reps) {
        snprintf(err, SIM_ERR_MAX, "stopped: %u of %u runs finished in %s (each run_<seed>/ complete); "
                 "--resume continues", done, opt->reps, opt->out_dir);
        rc = RUNNER_STOPPED;
    }
    /* The aggregate covers the finished runs, also when stopped early. */
    if ((opt->reps > 1 || rc != RUNNER_OK) && done > 0) {
        if (write_aggregate(opt, job.results, opt->quiet || rc != RUNNER_OK ? NULL : stdout) != 0 &&
            rc == RUNNER_OK) {
            snprintf(err, SIM_ERR_MAX, "%s/summary.json: cannot write: %s", opt->out_dir, strerror(errno));
            rc = RUNNER_FAILED;
        }
    } else if (rc == RUNNER_OK && !opt->quiet) {
        snprintf(path, sizeof path, "%s/run_%" PRIu64 "/summary.json", opt->out_dir, opt->seed);
        FILE *f = fopen(path, "r");
        int c;
        while (f && (c = fgetc(f)) != EOF) putchar(c);
        if (f) fclose(f);
    }
    if (!opt->quiet && rc == RUNNER_OK) {
        /* The steps the runs really did: a task may have stopped them. */
        double steps = 0.0;
        for (uint32_t r = 0; r < opt->reps; r++) steps += (double)job.results[r].steps;
        double robot_steps = steps * scenario_robot_count(opt->scenario);
        double sim_time = steps * opt->scenario->control_period_ms / 1000.0;
        printf("outputs: %s/ (run_<seed>/summary.json, scenario.yaml, timeseries.csv%s%s%s)\n", opt->out_dir,
               opt->frames_every ? ", frames/*.png" : "", opt->camera_frames ? ", camera/robot_<id>/*.png" : "",
               opt->telemetry.enabled && !opt->telemetry.url ? ", " TELEMETRY_LOG_NAME : "");
        fprintf(stderr, "swarmsim: %u run(s), %.0f steps x %u robots in %.3f s wall on %u thread(s) x %u in a run: "
                "%.0f robot-steps/s, %.0fx real time; %.3f s CPU: %.0f robot-steps/s per CPU second\n",
                opt->reps, steps, scenario_robot_count(opt->scenario), wall, nthreads, job.run_threads,
                robot_steps / wall,
                sim_time / wall, cpu, robot_steps / cpu);
    }
    pthread_mutex_destroy(&job.err_lock);
    free(job.results);
    return rc;
}

int runner_run(const run_options_t *opt, char err[SIM_ERR_MAX])
{
    metric_text_t *text = calloc(METRICS_MAX, sizeof *text);
    if (!text) {
        snprintf(err, SIM_ERR_MAX, "out of memory");
        return RUNNER_SETUP_ERROR;
    }
    int rc = run_with(opt, text, err);
    free(text);
    return rc;
}
