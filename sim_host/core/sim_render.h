/* sim_render.h - pictures of a running simulation (fills a render_scene_t). */
#ifndef SIM_SIM_RENDER_H
#define SIM_SIM_RENDER_H

#include "render.h"
#include "sim.h"

/** Draws the current state of `sim` to `png_path`.  Returns 0 or -1 with a
 *  message in `err` (RENDER_ERR_MAX bytes). */
int sim_render_png(const sim_t *sim, render_ctx_t *ctx, const char *png_path, char *err);

#endif
