/*
 * camera.h - the e-puck's front camera and the blobs its image's detector
 * reports (section `camera`): either a fast geometric model (blobs from
 * the objects' angles, camera_geometric.c) or an OSMesa-rendered RGB565
 * frame through the robot's own detector (hal/blob_detect.c,
 * camera_render.c), at the robot image's frame rate (camera.c says when a
 * robot gets new blobs).  A `camera_fail` fault hides them.
 */
#ifndef SIM_MODELS_CAMERA_H
#define SIM_MODELS_CAMERA_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"
#include "platform_facts.h"

/** The widest pinhole camera, deg: a wider `camera.fov` (up to 360) is the
 *  all-round stand-in, a panoramic (cylindrical) image centred ahead with
 *  its lens on the robot's axis (camera_geometric.c). */
#define CAMERA_PINHOLE_MAX_DEG 179.0f
/** The rendered camera's largest frame side, pixels (hal/blob_detect.h's
 *  BLOB_MAX_WIDTH and BLOB_MAX_HEIGHT). */
#define CAMERA_RENDERED_MAX_PX 160u
/** Frames per second of the e-puck1 image's camera (40 x 20 RGB565: the
 *  sensor's 640 x 320 window subsampled 16 x 16): 4.3 fps, the rate GCtronic's
 *  e-puck library gives for 16 x 16 subsampling in RGB565 (camera/fast_2_timer/
 *  e_po3030k.h, "Performances"; the PO6030K driver quotes the same), from
 *  the table of robot facts (hal/platform_facts.h).  An e-puck2's is its
 *  own (camera.fps unset: each robot's model's). */
#define CAMERA_EPUCK_FPS ((float)EPUCK1_CAMERA_FPS_X10 / 10.0f)
/** How far the e-puck image's detector sees a red cylinder 3.5 cm wide and
 *  4.2 cm high (seed 000's food), m: the rendered model sees it straight
 *  ahead to 0.88 m, lit or shaded (test_camera_render), where it covers
 *  about 3 pixels, the detector's min_pixels.  The geometric model's
 *  default camera.range. */
#define CAMERA_EPUCK_REACH_M 0.9f

/** How the camera's blobs are made (camera.model). */
typedef enum camera_kind {
    CAMERA_GEOMETRIC = 0,        /**< from the objects' angles: fast, the default */
    CAMERA_RENDERED = 1          /**< an OSMesa frame through hal/blob_detect.c */
} camera_kind_t;

/** The names of camera_kind_t (NULL-terminated). */
extern const char *const camera_kind_names[];

/** One robot's camera as fitted (`camera.robots`, models/per_robot.h:
 *  the calibration kit's); NaN: the section's. */
typedef struct camera_robot_cal {
    uint16_t id;               /**< hal_robot_id */
    float fov;                 /**< deg */
    float range;               /**< m */
    float gain[3];             /**< colour response: R, G, B gain on its frames */
} camera_robot_cal_t;

typedef struct camera_config {
    float fov;                 /**< horizontal field of view, deg; above
                                    CAMERA_PINHOLE_MAX_DEG an all-round
                                    (panoramic) stand-in, up to 360 */
    float range;               /**< objects farther away are not seen, m */
    uint16_t width_px, height_px; /**< the robot's frame, pixels (blob sizes refer to it) */
    int model;                 /**< camera_kind_t */
    float fps;                 /**< frames per second; NaN (unset): each robot model's
                                    (platform.h: CAMERA_EPUCK_FPS on an e-puck1); 0: fresh
                                    every control step */
    float noise;               /**< rendered: Gaussian sd per 8-bit channel, counts */
    float gain[3];             /**< colour response: R, G, B gain on the drawn frame (rendered, frame statistics) */
    uint8_t min_value, min_margin, min_saturation_q8; /**< the detector's thresholds (hal/blob_detect.h) */
    uint32_t robot_count;      /**< `robots` (the geometric model's only) */
    camera_robot_cal_t *robots; /**< on the heap (free_config) */
} camera_config_t;

MODEL_CONFIG_ACCESSORS(camera, camera_config_t)

/** The geometric model's blobs of robot i now, whatever camera.model says
 *  (tools/bench/camera_bench.c compares the two). */
/** Robot `id`'s field of view (deg) and range (m): its `robots` entry's,
 *  else the section's. */
void camera_lens(const camera_config_t *cfg, uint16_t id, float *fov_deg, float *range_m);

/** Robot `id`'s colour response: R, G, B gains (its `robots` entry's, else the section's). */
void camera_colour_gain(const camera_config_t *cfg, uint16_t id, float gain[3]);

uint8_t camera_geometric_blobs(sim_t *sim, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS]);

#endif
