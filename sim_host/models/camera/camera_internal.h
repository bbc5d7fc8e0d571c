/*
 * camera_internal.h - what the camera model's files share: each robot's
 * frames, the run's renderer and recorder, and a worker's scratch.
 */
#ifndef SIM_MODELS_CAMERA_INTERNAL_H
#define SIM_MODELS_CAMERA_INTERNAL_H

#include <pthread.h>
#include <stdint.h>

#include "camera.h"
#include "camera_render.h"
#include "core/sim_internal.h"

#define CAMERA_DIR_MAX 1024

/* One robot's camera.  With camera.fps > 0: `blobs` come from the last
 * complete frame, `next` from the one being captured (camera.c). */
typedef struct camera_robot {
    uint64_t stamp;                /* blobs are this step's when == the step's stamp */
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint8_t blob_count;
    uint8_t ready;                 /* phase_s and rand are drawn */
    uint8_t next_count;
    int64_t capture;               /* index of the frame `next` holds */
    double phase_s;                /* when its frame 0 began, s */
    hal_blob_t next[HAL_MAX_BLOBS];
    sim_rand_t rand;               /* phase and pixel noise (RAND_CAMERA) */
    float fps;                     /* camera.fps, or its robot model's (platform.h) */
} camera_robot_t;

/* The run's renderer (made at the first rendered frame) and recorder. */
typedef struct camera {
    const camera_config_t *cfg;
    camera_robot_t *robot;
    camera_render_t *render;       /* NULL until the first frame is drawn */
    uint8_t *rgb;                  /* one frame, 8-bit RGB */
    uint8_t *rgb565;               /* the same, RGB565 big-endian as the e-puck's driver */
    int64_t record_robot;          /* -1: no pictures */
    char record_dir[CAMERA_DIR_MAX];
    char err[SIM_ERR_MAX];         /* the first error; empty: none */
    pthread_mutex_t frame_lock;    /* frame statistics: robots' steps may run side by side */
} camera_t;

/* An angular interval seen from the camera, rad, and its nearest distance, m. */
typedef struct camera_interval { float lo, hi, near; } camera_interval_t;

/* An interval the all-round camera may turn into a blob, and the most
 * pixels it could show. */
typedef struct camera_candidate { float bound; uint32_t index; } camera_candidate_t;

/* Most robots or obstacles the camera considers within its range. */
#define CAMERA_MAX_NEAR 1024u

/* One pool worker's working memory for the geometric model. */
typedef struct camera_scratch {
    uint32_t obstacles[CAMERA_MAX_NEAR];
    uint32_t robots[CAMERA_MAX_NEAR];
    uint32_t occluder_object[2 * CAMERA_MAX_NEAR];
    camera_interval_t intervals[2 * CAMERA_MAX_NEAR];
    camera_candidate_t candidates[2 * CAMERA_MAX_NEAR];   /* the all-round camera's */
} camera_scratch_t;

#endif
