/* sim_render.h - pictures of a running simulation (fills a render_scene_t,
 * with the overlay: time stamp, legend, robot ids). */
#ifndef SIM_SIM_RENDER_H
#define SIM_SIM_RENDER_H

#include "render.h"
#include "swarmsim/sim.h"

/** Draws the current state of `sim` to `png_path`.  Returns 0 or -1 with a
 *  message in `err` (SIM_ERR_MAX bytes). */
int sim_render_png(const sim_t *sim, render_ctx_t *ctx, const char *png_path, char *err);

/** Draws the current state of `sim` into `rgb` (the context's width x
 *  height x 3 bytes, top row first).  Returns 0 or -1 with a message in
 *  `err` (SIM_ERR_MAX bytes). */
int sim_render_rgb(const sim_t *sim, render_ctx_t *ctx, uint8_t *rgb, char *err);

/** Where the world point (x, y) m lands in the picture sim_render_rgb would
 *  draw now (render_world_to_pixel).  Returns 0, or -1 out of memory or
 *  with an invalid arena. */
int sim_render_world_to_pixel(const sim_t *sim, const render_ctx_t *ctx, float x, float y, float *col,
                              float *row);

#endif
