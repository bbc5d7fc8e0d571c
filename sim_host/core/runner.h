/*
 * runner.h - runs the repetitions of a scenario on a thread pool and writes
 * their outputs.  Repetition r uses seed (base seed + r) and its results
 * depend only on that seed, never on the thread count or scheduling.
 *
 * Outputs, under `out_dir` (prepared by outdir.h: never mixed with another
 * invocation's):
 *   .swarmsim-out               the marker: this invocation's identity
 *   scenario.yaml               the effective scenario (file + overrides)
 *   run_<seed>/summary.json     scenario, provenance, seed, metrics
 *   run_<seed>/scenario.yaml    the same effective scenario, with the run
 *   run_<seed>/timeseries.csv   one row every output.timeseries_every steps
 *   run_<seed>/frames/frame_N.png  with frames_every > 0 (and the last frame)
 *   run_<seed>/camera/robot_<id>/frame_N.png  with camera_frames
 *   run_<seed>/telemetry.lcmlog LCM telemetry (telemetry.h), unless it goes
 *                               to an LCM URL or is off
 *   summary.json                with reps > 1, or when stopped early: mean
 *                               and sd of every metric over the finished
 *                               runs, and how many of how many
 * A run is written in run_<seed>.partial/ and renamed run_<seed>/ when it
 * finished: a run stopped (SIGINT, SIGTERM) or failed half-way, or one a
 * failing sibling stopped, leaves nothing under a final name.
 * and at video.path (not under out_dir) the first repetition's video (sim_video.h).
 */
#ifndef SIM_RUNNER_H
#define SIM_RUNNER_H

#include <signal.h>
#include <stdint.h>

#include "outdir.h"
#include "swarmsim/scenario.h"
#include "summary.h"
#include "sim_video.h"
#include "telemetry.h"

typedef struct run_options {
    const scenario_t *scenario;
    uint64_t seed;          /**< seed of the first repetition */
    uint32_t reps;          /**< >= 1 */
    uint32_t threads;       /**< >= 1: runs side by side, the spare ones inside each run */
    uint32_t run_threads;   /**< threads inside each run (1 .. 64); 0: the spare ones, for
                                 swarms of RUNNER_SPLIT_MIN_ROBOTS or more */
    uint64_t steps;         /**< control steps per run */
    const char *out_dir;
    outdir_mode_t out_mode; /**< new, replace or resume */
    uint32_t frames_every;  /**< 0: no pictures */
    uint32_t frame_px;      /**< picture side, pixels */
    int quiet;              /**< no summary on stdout */
    int progress;           /**< progress bar on stderr (when it takes > 1 s) */
    telemetry_options_t telemetry;  /**< all zero: no telemetry */
    const char *control_url;        /**< non-NULL: the run takes commands on this LCM bus (control.h) */
    int control_paused;             /**< and waits for one before its first step */
    const char *scenario_text;      /**< the effective scenario (scenario.yaml) */
    provenance_t provenance;        /**< scenario_hash is filled by runner_run */
    /** Set (to the signal number) by a signal handler to stop early; NULL: never. */
    volatile sig_atomic_t *stop;
    video_options_t video;  /**< path NULL: no video; else the first repetition is filmed */
    int camera_frames;      /**< non-zero: camera_robot's frames to run_<seed>/camera/robot_<id>/ */
    uint32_t camera_robot;
} run_options_t;

/** Below this many robots a run keeps to one thread unless run_threads
 *  says otherwise: a step is then too short to share (tools/bench/scale.py). */
#define RUNNER_SPLIT_MIN_ROBOTS 500u

enum {
    RUNNER_OK = 0,
    RUNNER_FAILED = -1,       /**< a run failed (exit 1) */
    RUNNER_SETUP_ERROR = -2,  /**< nothing ran, no folder written (exit 2) */
    RUNNER_STOPPED = -3       /**< *stop was set: finished runs kept (exit 128 + signal) */
};

/** Runs everything.  Returns a RUNNER_* code, with a message in `err`
 *  unless RUNNER_OK. */
int runner_run(const run_options_t *opt, char err[SIM_ERR_MAX]);

#endif
