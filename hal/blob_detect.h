/*
 * blob_detect.h - platform-neutral colour blob detector over RGB565 frames.
 *
 * Runs on the robot (e-puck1: dsPIC30F6014A, 16-bit int, no FPU, 8 KB RAM)
 * and in the simulator, so it is plain C99 with integer arithmetic only, no
 * allocation, no static mutable storage and no blocking.  All working memory
 * is a caller-provided `blob_detect_work_t`.
 *
 * Frame
 * -----
 * `rgb565` holds `width * height` pixels, row-major (row 0 first, column 0
 * first within a row), 2 bytes per pixel, no padding between rows.  A pixel
 * is RRRRRGGG GGGBBBBB.  The e-puck poxxxx camera driver (e_poxxxx_* in
 * GCtronic's library, RGB_565_MODE) stores the HIGH byte first (big-endian),
 * which is the default; `byte_order` selects little-endian for other sources.
 * Column 0 is the LEFT edge of the image as seen by the robot looking
 * forward.  Frames of 1..BLOB_MAX_WIDTH columns and 1..BLOB_MAX_HEIGHT rows
 * are supported, e.g. 40x40, or a 120x1 line.
 *
 * Colour classes
 * --------------
 * Each pixel's 5/6/5-bit channels are expanded to 0..255 by bit replication
 * (r8 = r5 << 3 | r5 >> 2, g8 = g6 << 2 | g6 >> 4, b8 likewise).  Let `m`
 * be the largest channel and `s` the second largest.  The pixel is
 * HAL_COLOUR_RED / GREEN / BLUE (the channel holding `m`) when all hold:
 *   - m >= min_value                        (bright enough: rejects black),
 *   - m - s >= min_margin                   (absolute dominance),
 *   - (m - s) * 256 >= min_saturation_q8 * m (relative dominance: rejects
 *                                             grey, white and pastel tints);
 * otherwise HAL_COLOUR_NONE.  Two equal top channels (yellow, cyan, magenta,
 * any grey) are never classified.
 *
 * Blobs
 * -----
 * Column-wise run accumulation, per colour: for each column the pixels of
 * each colour are counted; a column is "on" for a colour when its count is
 * >= min_column_pixels; a blob is a maximal run of adjacent "on" columns.
 * A blob reports
 *   - colour:       hal_colour_t;
 *   - pixels:       sum of its columns' counts of that colour (pixels);
 *   - bearing_mrad: bearing of its pixel-weighted centre column
 *                   cbar = sum(count_c * c) / pixels, where the bearing of
 *                   a (fractional) column c in a frame W columns wide is
 *                       bearing(c) = (W - 1 - 2c) * fov_mrad / (2W)
 *                   milliradians: 0 at the image centre, CCW positive, so
 *                   LEFT of the centre (small c) is positive, as in hal.h;
 *                   rounded to nearest (halves away from zero), so
 *                   mirror-image blobs get exactly opposite bearings;
 *   - width_mrad:   number of columns in the run * fov_mrad / W, rounded
 *                   to nearest (a full-width blob is fov_mrad wide).
 * Blobs with fewer than min_pixels pixels are dropped.  The remaining blobs
 * are ordered largest first (pixels descending), ties by bearing_mrad
 * ascending (right first), then by colour ascending; the first
 * min(max, BLOB_DETECT_MAX_BLOBS) are returned.  When a frame holds more
 * blobs than that, the ones kept are still exactly the first ones of that
 * order.  Note two blobs of different colours may overlap (same columns).
 *
 * RAM and time
 * ------------
 * The frame is read column by column and never copied, so the working
 * memory does not depend on the frame size: sizeof(blob_detect_work_t) is
 * 81 bytes with avr-gcc (16-bit int, byte alignment), 90 on the dsPIC
 * (16-bit alignment), 92 on 32/64-bit hosts (the .c file checks it stays
 * <= 128).  Stack: about 110 bytes deep with avr-gcc -Os (blob_detect 65 +
 * close_run 37 + libgcc's 16-bit division).  Time: with the default
 * thresholds (min_value, min_margin, min_saturation_q8 as
 * blob_detect_default_params() sets them, as on the robot) a pixel is
 * classified by two byte lookups in constant tables (blob_detect_lut.h,
 * 4,608 bytes of flash), with other thresholds by blob_classify_rgb565()
 * (about 3 times slower); the results are the same either way.  Per blob,
 * 16-bit divisions and 16 x 16 -> 32-bit products only, and none for a
 * blob too small to enter a full list.  The CPU report (make
 * firmware-cpu) estimates a 40 x 20 frame at about 3.4 ms on the dsPIC.
 */
#ifndef BLOB_DETECT_H
#define BLOB_DETECT_H

#include <stdint.h>

#include "hal.h"

/** Widest frame accepted, in pixels (wider frames yield 0 blobs). */
#define BLOB_MAX_WIDTH 160u
/** Tallest frame accepted, in pixels (taller frames yield 0 blobs).  With
 *  BLOB_MAX_WIDTH this keeps every pixel count below 65536. */
#define BLOB_MAX_HEIGHT 160u
/** Widest field of view accepted, mrad (2 pi). */
#define BLOB_MAX_FOV_MRAD 6283u
/** Default horizontal field of view of the e-puck1 camera: 56 deg, mrad. */
#define BLOB_DEFAULT_FOV_MRAD 977u
/** Most blobs blob_detect() returns (the HAL's limit). */
#define BLOB_DETECT_MAX_BLOBS HAL_MAX_BLOBS

/** Byte order of the 16-bit pixels in a frame. */
typedef enum blob_byte_order {
    BLOB_BYTE_ORDER_BIG = 0,    /**< high byte first: e-puck poxxxx driver */
    BLOB_BYTE_ORDER_LITTLE = 1  /**< low byte first */
} blob_byte_order_t;

/** Detector parameters.  Start from blob_detect_default_params(). */
typedef struct blob_detect_params {
    uint16_t fov_mrad;          /**< horizontal field of view of the frame,
                                     mrad, 1..BLOB_MAX_FOV_MRAD (977) */
    uint8_t byte_order;         /**< blob_byte_order_t (BIG) */
    uint8_t min_value;          /**< dominant channel at least this, 0..255
                                     (64) */
    uint8_t min_margin;         /**< dominant channel exceeds the second by
                                     at least this, 0..255 (40) */
    uint8_t min_saturation_q8;  /**< (m - s) / m at least this / 256 (64,
                                     i.e. 25 %) */
    uint16_t min_column_pixels; /**< pixels of a colour for a column to be
                                     part of a blob of that colour; 0 acts
                                     as 1 (1, as a line frame needs) */
    uint16_t min_pixels;        /**< smaller blobs are dropped, pixels (3) */
} blob_detect_params_t;

/** An open run of columns of one colour (part of the working memory). */
typedef struct blob_detect_run {
    uint32_t weighted;  /**< sum of count_c * c over the run's columns */
    uint16_t start;     /**< first column of the run */
    uint16_t pixels;    /**< sum of count_c; 0 when no run is open */
} blob_detect_run_t;

/** Working memory of one blob_detect() call; contents are scratch and
 *  unspecified afterwards.  Size: see "RAM and time" above. */
typedef struct blob_detect_work {
    hal_blob_t blobs[BLOB_DETECT_MAX_BLOBS];  /**< best blobs, in order */
    blob_detect_run_t runs[HAL_COLOUR_COUNT - 1u]; /**< red, green, blue */
    uint8_t count;                            /**< entries used in blobs */
} blob_detect_work_t;

/** The defaults documented field by field above. */
blob_detect_params_t blob_detect_default_params(void);

/** RGB565 value (host order) of an 8-bit-per-channel colour, truncating
 *  each channel to 5/6/5 bits. */
uint16_t blob_rgb565(uint8_t r, uint8_t g, uint8_t b);

/** Colour class (hal_colour_t) of one RGB565 pixel value (already
 *  assembled from its two bytes).  HAL_COLOUR_NONE if `p` is NULL. */
uint8_t blob_classify_rgb565(const blob_detect_params_t *p, uint16_t pixel);

/** Bearing in mrad (CCW positive, left of centre positive) of the centre
 *  of column `column` in a frame `width` columns wide spanning `fov_mrad`:
 *  (width - 1 - 2 column) * fov_mrad / (2 width), rounded to nearest.
 *  0 if width is 0 or > BLOB_MAX_WIDTH, column >= width, or fov_mrad >
 *  BLOB_MAX_FOV_MRAD. */
int16_t blob_column_bearing_mrad(uint16_t fov_mrad, uint16_t width, uint16_t column);

/** Detects colour blobs in a `width` x `height` RGB565 frame (see the file
 *  comment) and writes up to min(max, BLOB_DETECT_MAX_BLOBS) of them to
 *  `out`, largest first; returns how many.  Returns 0 without touching
 *  `out` when a pointer is NULL, width or height is 0 or above its
 *  maximum, or a parameter is out of range (fov_mrad, byte_order). */
uint8_t blob_detect(const blob_detect_params_t *p, const uint8_t *rgb565,
                    uint16_t width, uint16_t height,
                    blob_detect_work_t *work, hal_blob_t *out, uint8_t max);

/** Statistics of a frame's pixels (hal_camera_colour_stats): with `colour`
 *  HAL_COLOUR_NONE every pixel, else those blob_classify_rgb565() gives
 *  `colour`; each channel's mean and standard deviation as the classifier
 *  expands it to 8 bits.  0, or -1 (and *out zeroed) for a NULL pointer, a
 *  colour above HAL_COLOUR_BLUE or a frame size out of range. */
int8_t blob_colour_stats(const blob_detect_params_t *p, const uint8_t *rgb565,
                         uint16_t width, uint16_t height, uint8_t colour, hal_colour_stats_t *out);

#endif /* BLOB_DETECT_H */
