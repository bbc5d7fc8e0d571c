/*
 * camera_picture.h - a robot's camera frame as a PNG picture with its blobs
 * drawn on it (swarmsim --camera-frames), for debugging a controller's
 * vision.
 */
#ifndef SIM_CAMERA_PICTURE_H
#define SIM_CAMERA_PICTURE_H

#include <stdint.h>

#include "hal.h"
#include "swarmsim/base.h"

/** Each frame pixel becomes a square of this many picture pixels. */
#define CAMERA_PICTURE_SCALE 8

/** Writes the w x h frame `rgb` (8-bit RGB, top row first) enlarged
 *  CAMERA_PICTURE_SCALE times, with a yellow box over the columns of each
 *  blob (the whole height: a blob has no rows) and a tick in the blob's
 *  colour at its bearing, to `path` atomically (path.tmp, then rename).
 *  `fov_deg` is the frame's horizontal field of view.  0, or -1 with a
 *  message in err. */
int camera_picture_png(const char *path, const uint8_t *rgb, uint16_t w, uint16_t h, float fov_deg,
                       const hal_blob_t *blobs, uint8_t n, char err[SIM_ERR_MAX]);

#endif
