/*
 * render_gl.h - inside the renderer only: the flat GL primitives and the
 * bitmap font of render.c, and the overlay of render_overlay.c (time stamp,
 * legend, robot ids).  Pixel coordinates with GL's origin at the bottom
 * left; callers of the renderer use render.h.
 */
#ifndef SIM_RENDER_GL_H
#define SIM_RENDER_GL_H

#include <stdint.h>

#include "render.h"

/** The drawing frame: world (x, y) m -> GL pixel (cx + x*s, cy + y*s). */
typedef struct frame {
    float s, cx, cy;
    int w_px, h_px;    /**< picture size, pixels */
} frame_t;

void rgl_colour(uint32_t rgb);
/** Axis-aligned rectangle [x0, x1] x [y0, y1]. */
void rgl_rect(float x0, float y0, float x1, float y1);
void rgl_disc(float cx, float cy, float r);
/** Text with its lower left corner at (x, y), `cell` pixels a font pixel. */
void rgl_text(float x, float y, const char *s, float cell);
/** Width of rgl_text's `s` in pixels. */
float rgl_text_width(const char *s, float cell);

/** Height of the overlay's band at the top of a w x h picture (0 without
 *  scene->overlay). */
float overlay_band_px(const render_scene_t *scene, int w, int h);

/** Draws the band (time stamp and legend) over the top `band` pixels. */
void overlay_draw_band(const frame_t *f, const render_scene_t *scene, float band);

/** Draws each robot's id beside it; r is the robots' radius in pixels. */
void overlay_draw_ids(const frame_t *f, const render_scene_t *scene, float r);

#endif
