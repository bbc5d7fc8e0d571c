/*
 * video.h - an H.264 MP4 file from raw RGB frames, encoded by an ffmpeg
 * subprocess (Debian package ffmpeg) that reads them on its standard input.
 * Knows nothing of the simulator (sim_video.h films a run).
 *
 * The file is written under "<path>.tmp" and renamed to `path` only when
 * ffmpeg finished without error and the caller asked to keep it; otherwise
 * the temporary file is removed, so `path` is never half-written.
 */
#ifndef SIM_VIDEO_H
#define SIM_VIDEO_H

#include <stdint.h>

#include "swarmsim/base.h"


typedef struct video video_t;

/** 0 if an executable `ffmpeg` is on PATH, else -1 with a message that
 *  names the Debian package in `err`. */
int video_find_ffmpeg(char *err);

/**
 * Starts ffmpeg encoding frames of w x h pixels (both even, as yuv420p
 * needs) shown at `fps` frames per second into "<path>.tmp".  Returns the
 * encoder, or NULL with a message in `err`.
 */
video_t *video_open(const char *path, int w, int h, double fps, char *err);

/** Sends one frame, w x h x 3 bytes of 8-bit RGB, the top row first.
 *  Returns 0, or -1 with a message (ffmpeg's own last words if it died). */
int video_write(video_t *v, const uint8_t *rgb, char *err);

/** Frames sent so far. */
uint64_t video_frame_count(const video_t *v);

/**
 * Ends the stream, waits for ffmpeg and frees `v`.  With `keep` and a
 * successful ffmpeg the file is renamed to its path; else the temporary
 * file is removed.  Returns 0, or -1 with a message in `err` (a failure of
 * ffmpeg is an error even when not keeping).  NULL is a no-op.
 */
int video_close(video_t *v, int keep, char *err);

#endif
