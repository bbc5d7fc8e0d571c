/*
 * sim_video.h - a run on video (swarmsim --video): the command-line options
 * and the recorder that renders the simulation (sim_render.h, with its
 * time stamp, legend and ids) at a cadence of control steps and hands the
 * frames to ffmpeg (video.h).  Rendering only reads the simulation.
 *
 * Frames: one at step 0 and every `every` steps before the run's end, then
 * the state at the end: ceil(steps / every) + 1 frames, shown at `fps`.
 */
#ifndef SIM_SIM_VIDEO_H
#define SIM_SIM_VIDEO_H

#include <stdint.h>
#include <stdio.h>

#include "swarmsim/sim.h"

/* Defaults: a 1200 s run at 100 ms steps is 1,201 frames, one minute. */
#define VIDEO_DEFAULT_EVERY 10
#define VIDEO_DEFAULT_FPS 20.0

typedef struct video_options {
    const char *path;     /**< the .mp4 to write; NULL: no video */
    uint32_t every;       /**< control steps between frames, >= 1 */
    double fps;           /**< frames per second of the video */
    int every_set, fps_set;   /**< given on the command line */
} video_options_t;

#define VIDEO_OPTIONS_DEFAULT { NULL, VIDEO_DEFAULT_EVERY, VIDEO_DEFAULT_FPS, 0, 0 }

/** Takes --video, --video-every or --video-fps with its value.  Returns 1
 *  if `opt` is one of them (then *bad is 1 for a bad value, reported on
 *  stderr), 0 if it is not. */
int video_parse_option(const char *opt, const char *value, video_options_t *o, int *bad);

/** After all options, before anything runs: --video-every or --video-fps
 *  without --video, a file that is not .mp4 or whose folder does not
 *  exist, ffmpeg missing.  Returns 0, or -1 with the reason on stderr. */
int video_check_options(const video_options_t *o);

typedef struct sim_video sim_video_t;

/** Starts a video of `sim` at frame_px wide (rounded down to even, the
 *  height from the arena's aspect).  `quiet`: no line on stderr at the
 *  end.  NULL with a message in `err` (SIM_ERR_MAX bytes). */
sim_video_t *sim_video_open(const video_options_t *o, const sim_t *sim, uint32_t frame_px,
                            int quiet, char *err);

/** Call before each control step: adds a frame when the step count is on
 *  the cadence.  0, or -1 with a message. */
int sim_video_step(sim_video_t *v, const sim_t *sim, char *err);

/** With `keep` (the run completed): adds the final state's frame and gives
 *  the file its name; else removes what was written.  Frees `v` (NULL is a
 *  no-op).  0, or -1 with a message. */
int sim_video_close(sim_video_t *v, const sim_t *sim, int keep, char *err);

#endif
