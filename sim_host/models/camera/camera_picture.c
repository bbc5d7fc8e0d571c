/*
 * camera_picture.c - a camera frame with its blobs, as a picture
 * (camera_picture.h).
 */
#include "camera_picture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/render.h"
#include "units.h"

static void put(uint8_t *img, int W, int H, int x, int y, uint32_t rgb)
{
    if (x >= 0 && x < W && y >= 0 && y < H) {
        uint8_t *p = img + ((size_t)y * (size_t)W + (size_t)x) * 3u;
        p[0] = (uint8_t)(rgb >> 16);
        p[1] = (uint8_t)(rgb >> 8);
        p[2] = (uint8_t)rgb;
    }
}

static uint32_t class_rgb(uint8_t c)
{
    return c == HAL_COLOUR_RED ? 0xFF0000u : c == HAL_COLOUR_GREEN ? 0x00FF00u : c == HAL_COLOUR_BLUE ? 0x0000FFu
                                                                                                      : 0xFFFFFFu;
}

int camera_picture_png(const char *path, const uint8_t *rgb, uint16_t w, uint16_t h, float fov_deg,
                       const hal_blob_t *blobs, uint8_t n, char err[SIM_ERR_MAX])
{
    const int S = CAMERA_PICTURE_SCALE, W = w * S, H = h * S;
    uint8_t *img = malloc((size_t)W * (size_t)H * 3u);
    if (!img) {
        snprintf(err, SIM_ERR_MAX, "%s: out of memory", path);
        return -1;
    }
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            memcpy(img + ((size_t)y * (size_t)W + (size_t)x) * 3u, rgb + ((size_t)(y / S) * w + (size_t)(x / S)) * 3u, 3);
        }
    }
    /* Columns back from blob_detect.h's bearing and width:
     * bearing(c) = (w - 1 - 2c) fov / 2w, width = columns x fov / w. */
    double fov_mrad = fov_deg * UNITS_PI / 180.0 * 1000.0;
    for (uint8_t b = 0; b < n; b++) {
        double c = ((w - 1.0) - blobs[b].bearing_mrad * 2.0 * w / fov_mrad) / 2.0;
        double cols = blobs[b].width_mrad * (double)w / fov_mrad;
        int x0 = (int)lround((c - cols / 2.0 + 0.5) * S), x1 = (int)lround((c + cols / 2.0 + 0.5) * S) - 1;
        for (int t = 0; t < 2; t++) {        /* a box two pixels thick */
            for (int x = x0; x <= x1; x++) {
                put(img, W, H, x, t, 0xFFE600u);
                put(img, W, H, x, H - 1 - t, 0xFFE600u);
            }
            for (int y = 0; y < H; y++) {
                put(img, W, H, x0 + t, y, 0xFFE600u);
                put(img, W, H, x1 - t, y, 0xFFE600u);
            }
        }
        int xc = (int)lround((c + 0.5) * S);
        for (int y = 2; y < S + 2; y++) {    /* the bearing, in the blob's colour */
            for (int dx = -1; dx <= 1; dx++) put(img, W, H, xc + dx, y, class_rgb(blobs[b].colour));
        }
    }
    int rc = render_write_rgb_png(img, W, H, path, err);
    free(img);
    return rc;
}
