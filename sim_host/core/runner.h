/*
 * runner.h - runs the repetitions of a scenario on a thread pool and writes
 * their outputs.  Repetition r uses seed (base seed + r) and its results
 * depend only on that seed, never on the thread count or scheduling.
 *
 * Outputs, under `out_dir`:
 *   run_<seed>/summary.json     scenario, seed, controller, metrics
 *   run_<seed>/timeseries.csv   one row every output.timeseries_every steps
 *   run_<seed>/frames/frame_N.png  with frames_every > 0 (and the last frame)
 *   run_<seed>/telemetry.lcmlog LCM telemetry (telemetry.h), unless it goes
 *                               to an LCM URL or is off
 *   summary.json                with reps > 1: mean and sd of every metric
 * and at video.path (not under out_dir) the first repetition's video (sim_video.h).
 * Every file is written to a temporary name and renamed when complete.
 */
#ifndef SIM_RUNNER_H
#define SIM_RUNNER_H

#include <stdint.h>

#include "scenario.h"
#include "sim_video.h"
#include "telemetry.h"

typedef struct run_options {
    const scenario_t *scenario;
    uint64_t seed;          /**< seed of the first repetition */
    uint32_t reps;          /**< >= 1 */
    uint32_t threads;       /**< >= 1 */
    uint64_t steps;         /**< control steps per run */
    const char *out_dir;
    uint32_t frames_every;  /**< 0: no pictures */
    uint32_t frame_px;      /**< picture side, pixels */
    int quiet;              /**< no summary on stdout */
    int progress;           /**< progress bar on stderr (when it takes > 1 s) */
    telemetry_options_t telemetry;  /**< all zero: no telemetry */
    video_options_t video;  /**< path NULL: no video; else the first repetition is filmed */
} run_options_t;

/** Runs everything.  Returns 0, or -1 with a message in `err`. */
int runner_run(const run_options_t *opt, char err[512]);

#endif
