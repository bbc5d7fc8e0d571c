/*
 * render.h - headless top-down pictures of the arena (OSMesa + libpng).
 *
 * Self-contained: the renderer knows nothing about the simulator.  The caller
 * fills a plain render_scene_t (world units: metres, radians for robots,
 * degrees for boxes, origin at the arena centre, +x right, +y up in the
 * picture) and asks for a PNG.
 *
 * Threads: a render_ctx_t owns one OSMesa context and its pixel buffer.  Each
 * render call makes that context current on the calling thread and releases
 * it before returning, so a context may be used from any thread, but by one
 * thread at a time.  Give every worker thread its own context; different
 * contexts may render concurrently.
 *
 * Note: Mesa's llvmpipe starts its own rasteriser threads for every context
 * (LP_NUM_THREADS, default: the number of CPUs).  With many worker threads
 * each owning a context, set LP_NUM_THREADS (e.g. to 1) in the environment
 * before the first render_create.
 *
 * Link with -lOSMesa -lpng16 -lm (the renderer does not use GLU).
 */
#ifndef SIM_RENDER_H
#define SIM_RENDER_H

#include <stdint.h>

#include "swarmsim/drawing.h"
#include "swarmsim/base.h"


/** Picture size limits, pixels (both sides). */
#define RENDER_MIN_PX 16
#define RENDER_MAX_PX 8192

/** Robot radius used when render_scene_t.robot_radius is 0: the e-puck's
 *  70 mm diameter, m. */
#define RENDER_DEFAULT_ROBOT_RADIUS 0.035f

/** A robot is drawn at least this big (radius, pixels), however large the
 *  arena. */
#define RENDER_MIN_ROBOT_RADIUS_PX 3.0f

/**
 * The palette, 0xRRGGBB.  Features are drawn in exactly these colours (no
 * anti-aliasing, no shading), so a caller or a test can recognise them in the
 * picture.
 */
#define RENDER_RGB_BACKGROUND   0xFFFFFFu /**< margin outside the walls */
#define RENDER_RGB_FLOOR        0xEEEBE0u /**< arena floor */
#define RENDER_RGB_WALL         0x3C3C46u /**< walls */
#define RENDER_RGB_OBJ_NONE     0x6E6E73u /**< obstacle without colour */
#define RENDER_RGB_OBJ_RED      0xD22828u
#define RENDER_RGB_OBJ_GREEN    0x28AA3Cu
#define RENDER_RGB_OBJ_BLUE     0x285ADCu
#define RENDER_RGB_OUTLINE      0x28282Du /**< rims of robots and obstacles */
#define RENDER_RGB_LIGHT        0xFFC814u /**< light marker (star) */
#define RENDER_RGB_LIGHT_RIM    0xB4641Eu /**< light marker outline */
#define RENDER_RGB_ROBOT        0xAFBED2u /**< robot body, no highlight */
#define RENDER_RGB_HEADING      0x1E1E28u /**< heading bar, centre to front */
#define RENDER_RGB_LED_RED      0xFF1010u /**< ring LED and front LED, on */
#define RENDER_RGB_LED_GREEN    0x10E610u /**< body LED, on */
#define RENDER_RGB_TEXT         0x10101Au /**< overlay: time stamp, legend, ids */

/** The palette's colour of an obstacle's or an item's colour (0 none, 1 red,
 *  2 green, 3 blue: hal_colour_t), as the pictures draw it. */
uint32_t render_colour_rgb(int colour);

/** The colour a legend key's swatch is drawn in (drawing.h): a robot key's
 *  fill (rgb 0: RENDER_RGB_ROBOT), an item key's render_colour_rgb, else its
 *  rgb.  The live page gets the same through telemetry_scene.c. */
uint32_t render_key_rgb(const draw_key_t *key);

/** One robot.  The ring LEDs sit on the rim: LED0 at the front, LED i at
 *  -45*i degrees from the heading (clockwise seen from above). */
typedef struct render_robot {
    float x, y;        /**< centre, m */
    float theta;       /**< heading, rad, CCW, 0 = +x */
    uint8_t leds;      /**< bit i set = ring LED i on (drawn red) */
    uint8_t body_led;  /**< non-zero: green body LED on (centre dot) */
    uint8_t front_led; /**< non-zero: red front LED on (dot on the heading) */
    uint32_t fill_rgb; /**< body fill 0xRRGGBB; 0: RENDER_RGB_ROBOT */
} render_robot_t;

/** One static obstacle. */
typedef struct render_object {
    int shape;         /**< 0 cylinder, 1 box (others are not drawn) */
    float x, y;        /**< centre, m */
    float radius;      /**< cylinder radius, m */
    float width, depth;/**< box size along its own x and y, m */
    float angle_deg;   /**< box rotation, degrees CCW */
    int colour;        /**< 0 none (grey), 1 red, 2 green, 3 blue */
} render_object_t;

/** One light, drawn as a star marker (it hangs above the floor). */
typedef struct render_light {
    float x, y;        /**< m */
} render_light_t;

/**
 * What to draw.  The arrays are borrowed for the duration of the call only.
 * Items with a non-finite position or size are skipped.
 */
typedef struct render_scene {
    float arena_w, arena_h;   /**< free floor inside the walls, m, centred on
                                   0,0; both > 0 */
    float wall;               /**< wall thickness, m, drawn outside the floor;
                                   0 draws a 2-pixel border */
    const draw_shape_t *shapes;     /**< shape_count entries (drawing.h): floor marks
                                         under the obstacles, the rest over
                                         everything (NULL if 0) */
    uint32_t shape_count;
    const render_robot_t *robots;   /**< robot_count entries (NULL if 0) */
    uint32_t robot_count;
    float robot_radius;       /**< m; 0 = RENDER_DEFAULT_ROBOT_RADIUS */
    const render_object_t *objects; /**< object_count entries (NULL if 0) */
    uint32_t object_count;
    const render_light_t *lights;   /**< light_count entries (NULL if 0) */
    uint32_t light_count;
    double time_s;            /**< simulated time, s (drawn with `overlay`) */
    /** Non-zero: a band above the arena with the time stamp ("T = 12.3 S")
     *  and the legend (each key's swatch drawn as what it stands for is, its
     *  label, and for a robot fill how many robots have it now), and each
     *  robot's id (its index in `robots`) beside
     *  it.  The arena shrinks to make room for the band
     *  (render_overlay_band_px); without it nothing of this is drawn. */
    int overlay;
    const draw_key_t *legend;       /**< legend_count keys (drawing.h,
                                         legend.h), NULL if 0 */
    uint32_t legend_count;
} render_scene_t;

/** Opaque: owns the OSMesa context and the pixel buffers. */
typedef struct render_ctx render_ctx_t;

/**
 * Creates a renderer for pictures of width_px x height_px pixels
 * (RENDER_MIN_PX..RENDER_MAX_PX each).  Returns a context the caller owns and
 * frees with render_destroy, or NULL with a message in `err` (which may be
 * NULL; else SIM_ERR_MAX bytes).
 */
render_ctx_t *render_create(int width_px, int height_px, char *err);

/**
 * Draws `scene` and writes it to `png_path` as an 8-bit RGB PNG, atomically:
 * the picture goes to "<png_path>.tmp" first and is renamed over png_path
 * only when complete; on any error the temporary file is removed and an
 * existing png_path is left untouched.  The arena keeps its aspect ratio and
 * is centred with a margin.  Returns 0, or -1 with a message in `err` (may be
 * NULL) naming the path and the reason.
 */
int render_scene_png(render_ctx_t *ctx, const render_scene_t *scene,
                     const char *png_path, char *err);

/**
 * Writes `rgb` (width x height x 3 bytes, 8-bit RGB, the top row first; 1 to
 * RENDER_MAX_PX pixels a side) to `png_path` as render_scene_png writes its
 * pictures: atomically, through "<png_path>.tmp".  Returns 0, or -1 with a
 * message in `err` (may be NULL).
 */
int render_write_rgb_png(const uint8_t *rgb, int width_px, int height_px,
                         const char *png_path, char *err);

/**
 * Draws `scene` as render_scene_png does into `rgb`: width x height x 3
 * bytes, 8-bit RGB, the top row first (a raw video frame).  Returns 0, or
 * -1 with a message in `err` (may be NULL).
 */
int render_scene_rgb(render_ctx_t *ctx, const render_scene_t *scene,
                     uint8_t *rgb, char *err);

/** Height in pixels of the overlay's band at the top of the picture for
 *  this scene (0 without `overlay`). */
float render_overlay_band_px(const render_ctx_t *ctx,
                             const render_scene_t *scene);

/**
 * Where the world point (x, y) m lands in the picture render_scene_png draws
 * for this scene: *col from the left edge and *row from the top edge, in
 * pixels (pixel (c, r) covers [c, c+1) x [r, r+1)).  Returns 0, or -1 if the
 * scene's arena size is invalid (then *col and *row are unchanged).
 */
int render_world_to_pixel(const render_ctx_t *ctx, const render_scene_t *scene,
                          float x, float y, float *col, float *row);

/** Pixels per metre of the picture for this scene, or 0 if the scene's arena
 *  size is invalid. */
float render_scale_px_per_m(const render_ctx_t *ctx,
                            const render_scene_t *scene);

/** Frees the context and its buffers.  NULL is a no-op.  Must not be called
 *  while another thread is rendering with `ctx`. */
void render_destroy(render_ctx_t *ctx);

#endif /* SIM_RENDER_H */
