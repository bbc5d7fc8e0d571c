/*
 * render.c - headless top-down pictures of the arena (see render.h).
 *
 * Drawing is legacy OpenGL 1.x immediate mode into an OSMesa colour buffer,
 * in pixel coordinates (origin at the bottom-left, as GL has it); the PNG
 * writer flips the rows.  Every shape is a flat-coloured polygon drawn in
 * painter's order, with no depth buffer, blending, dithering or smoothing, so
 * the picture holds exactly the palette colours of render.h.
 */
#include "render.h"
#include "render_gl.h"

#include "units.h"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <png.h>

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_F ((float)UNITS_PI)

struct render_ctx {
    OSMesaContext gl;  /**< owned */
    int w, h;          /**< picture size, px */
    uint8_t *rgba;     /**< w*h*4 bytes, the OSMesa colour buffer, bottom row
                            first; owned */
    uint8_t *row;      /**< w*3 bytes, one PNG row; owned */
};

/* ------------------------------------------------------------------ */
/* Errors                                                              */
/* ------------------------------------------------------------------ */

static void set_err(char *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

static void set_err(char *err, const char *fmt, ...)
{
    if (!err)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, SIM_ERR_MAX, fmt, ap);
    va_end(ap);
}

/** strerror, thread-safe (strerror_r: XSI, or GNU under _GNU_SOURCE). */
static const char *errstr(int e, char *buf, size_t len)
{
#if defined(_GNU_SOURCE)
    return strerror_r(e, buf, len);
#else
    if (strerror_r(e, buf, len) != 0)
        snprintf(buf, len, "error %d", e);
    return buf;
#endif
}

/* ------------------------------------------------------------------ */
/* Create / destroy                                                    */
/* ------------------------------------------------------------------ */

render_ctx_t *render_create(int width_px, int height_px, char *err)
{
    if (width_px < RENDER_MIN_PX || width_px > RENDER_MAX_PX ||
        height_px < RENDER_MIN_PX || height_px > RENDER_MAX_PX) {
        set_err(err, "render: picture size %dx%d px is out of range "
                "(%d..%d each)", width_px, height_px, RENDER_MIN_PX,
                RENDER_MAX_PX);
        return NULL;
    }
    render_ctx_t *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        set_err(err, "render: out of memory");
        return NULL;
    }
    ctx->w = width_px;
    ctx->h = height_px;
    ctx->rgba = calloc((size_t)width_px * (size_t)height_px, 4);
    ctx->row = malloc((size_t)width_px * 3);
    if (!ctx->rgba || !ctx->row) {
        set_err(err, "render: out of memory for a %dx%d picture",
                width_px, height_px);
        render_destroy(ctx);
        return NULL;
    }
    /* Colour only: shapes are drawn in painter's order. */
    ctx->gl = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, NULL);
    if (!ctx->gl) {
        set_err(err, "render: OSMesaCreateContextExt failed");
        render_destroy(ctx);
        return NULL;
    }
    /* Check now that the context can be bound and is big enough. */
    if (!OSMesaMakeCurrent(ctx->gl, ctx->rgba, GL_UNSIGNED_BYTE,
                           width_px, height_px)) {
        set_err(err, "render: OSMesaMakeCurrent failed for %dx%d px",
                width_px, height_px);
        render_destroy(ctx);
        return NULL;
    }
    GLint dims[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    if (dims[0] < width_px || dims[1] < height_px) {
        set_err(err, "render: %dx%d px exceeds the GL limit %dx%d",
                width_px, height_px, (int)dims[0], (int)dims[1]);
        render_destroy(ctx);
        return NULL;
    }
    return ctx;
}

void render_destroy(render_ctx_t *ctx)
{
    if (!ctx)
        return;
    if (ctx->gl)
        OSMesaDestroyContext(ctx->gl);
    free(ctx->rgba);
    free(ctx->row);
    free(ctx);
}

/* ------------------------------------------------------------------ */
/* World to picture                                                    */
/* ------------------------------------------------------------------ */

/** Pixels per metre for this scene, or 0 if the arena size is invalid.
 *  The arena is centred in the picture below the overlay's band. */
static float view_scale(const render_ctx_t *ctx, const render_scene_t *sc)
{
    if (!ctx || !sc || !isfinite(sc->arena_w) || !isfinite(sc->arena_h) ||
        sc->arena_w <= 0.0f || sc->arena_h <= 0.0f)
        return 0.0f;
    float wall = (isfinite(sc->wall) && sc->wall > 0.0f) ? sc->wall : 0.0f;
    float ext_w = sc->arena_w + 2.0f * wall;
    float ext_h = sc->arena_h + 2.0f * wall;
    int small = ctx->w < ctx->h ? ctx->w : ctx->h;
    float margin = fmaxf(4.0f, 0.03f * (float)small);
    float band = overlay_band_px(sc, ctx->w, ctx->h);
    float s = fminf(((float)ctx->w - 2.0f * margin) / ext_w,
                    ((float)ctx->h - band - 2.0f * margin) / ext_h);
    return (isfinite(s) && s > 0.0f) ? s : 0.0f;
}

float render_overlay_band_px(const render_ctx_t *ctx,
                             const render_scene_t *scene)
{
    return ctx && scene ? overlay_band_px(scene, ctx->w, ctx->h) : 0.0f;
}

float render_scale_px_per_m(const render_ctx_t *ctx,
                            const render_scene_t *scene)
{
    return view_scale(ctx, scene);
}

int render_world_to_pixel(const render_ctx_t *ctx, const render_scene_t *scene,
                          float x, float y, float *col, float *row)
{
    float s = view_scale(ctx, scene);
    if (s <= 0.0f || !col || !row)
        return -1;
    *col = 0.5f * (float)ctx->w + x * s;
    *row = 0.5f * ((float)ctx->h + overlay_band_px(scene, ctx->w, ctx->h)) - y * s;
    return 0;
}

/* ------------------------------------------------------------------ */
/* Drawing primitives, pixel coordinates (GL: y up)                    */
/* ------------------------------------------------------------------ */

void rgl_colour(uint32_t rgb)
{
    glColor3ub((GLubyte)(rgb >> 16), (GLubyte)(rgb >> 8), (GLubyte)rgb);
}

static int segments(float r_px)
{
    int n = (int)ceilf(2.0f * PI_F * r_px / 2.5f);
    return n < 12 ? 12 : n > 256 ? 256 : n;
}

void rgl_disc(float cx, float cy, float r)
{
    if (!(r > 0.0f))
        return;
    int n = segments(r);
    glBegin(GL_TRIANGLE_FAN);
    glVertex2f(cx, cy);
    for (int i = 0; i <= n; i++) {
        float a = 2.0f * PI_F * (float)(i % n) / (float)n;
        glVertex2f(cx + r * cosf(a), cy + r * sinf(a));
    }
    glEnd();
}

/** Rectangle centred on (cx, cy), half sizes hx, hy along its own axes,
 *  rotated by `a` rad CCW. */
static void box(float cx, float cy, float hx, float hy, float a)
{
    if (!(hx > 0.0f) || !(hy > 0.0f))
        return;
    float c = cosf(a), s = sinf(a);
    static const float k[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    glBegin(GL_TRIANGLE_FAN);
    for (int i = 0; i < 4; i++) {
        float u = k[i][0] * hx, v = k[i][1] * hy;
        glVertex2f(cx + u * c - v * s, cy + u * s + v * c);
    }
    glEnd();
}

/** Axis-aligned rectangle [x0, x1] x [y0, y1]. */
void rgl_rect(float x0, float y0, float x1, float y1)
{
    glBegin(GL_TRIANGLE_FAN);
    glVertex2f(x0, y0);
    glVertex2f(x1, y0);
    glVertex2f(x1, y1);
    glVertex2f(x0, y1);
    glEnd();
}

/** Five-pointed star, outer radius r, one point up. */
static void star(float cx, float cy, float r)
{
    glBegin(GL_TRIANGLE_FAN);
    glVertex2f(cx, cy);
    for (int i = 0; i <= 10; i++) {
        float a = 0.5f * PI_F + (float)(i % 10) * PI_F / 5.0f;
        float rr = (i % 2) ? 0.45f * r : r;
        glVertex2f(cx + rr * cosf(a), cy + rr * sinf(a));
    }
    glEnd();
}

static int finite2(float a, float b)
{
    return isfinite(a) && isfinite(b);
}

/* ------------------------------------------------------------------ */
/* Scene                                                               */
/* ------------------------------------------------------------------ */

uint32_t render_colour_rgb(int c)
{
    switch (c) {
    case 1: return RENDER_RGB_OBJ_RED;
    case 2: return RENDER_RGB_OBJ_GREEN;
    case 3: return RENDER_RGB_OBJ_BLUE;
    default: return RENDER_RGB_OBJ_NONE;
    }
}

uint32_t render_key_rgb(const draw_key_t *key)
{
    switch (key->kind) {
    case DRAW_KEY_ROBOT: return key->rgb ? key->rgb : RENDER_RGB_ROBOT;
    case DRAW_KEY_ITEM: return render_colour_rgb(key->colour);
    default: return key->rgb;
    }
}


static void draw_arena(const frame_t *f, const render_scene_t *sc)
{
    float hw = 0.5f * sc->arena_w * f->s, hh = 0.5f * sc->arena_h * f->s;
    float wall = (isfinite(sc->wall) && sc->wall > 0.0f) ? sc->wall * f->s
                                                           : 0.0f;
    if (wall < 2.0f)
        wall = 2.0f;
    rgl_colour(RENDER_RGB_WALL);
    rgl_rect(f->cx - hw - wall, f->cy - hh - wall, f->cx + hw + wall,
         f->cy + hh + wall);
    rgl_colour(RENDER_RGB_FLOOR);
    rgl_rect(f->cx - hw, f->cy - hh, f->cx + hw, f->cy + hh);
}

/* Labels: a 3 x 5 pixel font (digits, capitals, a little punctuation;
 * lower case is drawn in capitals, anything else as '?').  Each glyph is
 * 15 bits, rows top to bottom, three bits a row, the left pixel first. */
typedef struct glyph { char ch; uint16_t bits; } glyph_t;
static const glyph_t font[] = {
    { ' ', 0x0000u },
    { '%', 0x52A5u },
    { '(', 0x2922u },
    { ')', 0x224Au },
    { '+', 0x05D0u },
    { ',', 0x0014u },
    { '-', 0x01C0u },
    { '.', 0x0002u },
    { '/', 0x12A4u },
    { '0', 0x7B6Fu },
    { '1', 0x2C97u },
    { '2', 0x73E7u },
    { '3', 0x73CFu },
    { '4', 0x5BC9u },
    { '5', 0x79CFu },
    { '6', 0x79EFu },
    { '7', 0x7249u },
    { '8', 0x7BEFu },
    { '9', 0x7BCFu },
    { ':', 0x0410u },
    { '=', 0x0E38u },
    { '?', 0x7282u },
    { 'A', 0x2BEDu },
    { 'B', 0x6BAEu },
    { 'C', 0x3923u },
    { 'D', 0x6B6Eu },
    { 'E', 0x79A7u },
    { 'F', 0x79A4u },
    { 'G', 0x396Bu },
    { 'H', 0x5BEDu },
    { 'I', 0x7497u },
    { 'J', 0x126Au },
    { 'K', 0x5BADu },
    { 'L', 0x4927u },
    { 'M', 0x5FEDu },
    { 'N', 0x6B6Du },
    { 'O', 0x2B6Au },
    { 'P', 0x6BA4u },
    { 'Q', 0x2B73u },
    { 'R', 0x6BADu },
    { 'S', 0x388Eu },
    { 'T', 0x7492u },
    { 'U', 0x5B6Fu },
    { 'V', 0x5B6Au },
    { 'W', 0x5BFDu },
    { 'X', 0x5AADu },
    { 'Y', 0x5A92u },
    { 'Z', 0x72A7u },
    { '_', 0x0007u },
};

static uint16_t glyph_bits(char c)
{
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    for (size_t k = 0; k < sizeof font / sizeof font[0]; k++)
        if (font[k].ch == c)
            return font[k].bits;
    return glyph_bits('?');
}

/* Text with its lower left corner at (x, y) pixels, `cell` pixels a font
 * pixel, a blank column between letters. */
void rgl_text(float x, float y, const char *s, float cell)
{
    for (; *s != '\0'; s++, x += 4.0f * cell) {
        uint16_t bits = glyph_bits(*s);
        for (int row = 0; row < 5; row++)
            for (int col = 0; col < 3; col++)
                if (bits & (1u << (14 - 3 * row - col)))
                    rgl_rect(x + (float)col * cell, y + (float)(4 - row) * cell,
                         x + (float)(col + 1) * cell, y + (float)(5 - row) * cell);
    }
}

float rgl_text_width(const char *s, float cell)
{
    size_t n = strlen(s);
    return n ? (4.0f * (float)n - 1.0f) * cell : 0.0f;
}

/* A segment of width w pixels (at least one) from (x0, y0) to (x1, y1). */
static void thick_line(float x0, float y0, float x1, float y1, float w)
{
    float dx = x1 - x0, dy = y1 - y0, len = sqrtf(dx * dx + dy * dy);
    if (len <= 0.0f)
        return;
    box(0.5f * (x0 + x1), 0.5f * (y0 + y1), 0.5f * len, 0.5f * fmaxf(w, 1.0f),
        atan2f(dy, dx));
}

/* One shape of a task's drawing (drawing.h). */
static void draw_shape(const frame_t *f, const draw_shape_t *d)
{
    float x = f->cx + d->x * f->s, y = f->cy + d->y * f->s;
    if (!finite2(d->x, d->y))
        return;
    rgl_colour(d->rgb);
    switch (d->kind) {
    case DRAW_DISC:
        if (isfinite(d->radius) && d->radius > 0.0f)
            rgl_disc(x, y, fmaxf(d->radius * f->s, 1.0f));
        break;
    case DRAW_RING: {
        if (!isfinite(d->radius) || d->radius <= 0.0f)
            break;
        float r = d->radius * f->s, w = fmaxf(isfinite(d->line) ? d->line * f->s : 0.0f, 1.0f);
        for (int k = 0; k < 48; k++) {
            float a0 = 2.0f * PI_F * (float)k / 48.0f, a1 = 2.0f * PI_F * (float)(k + 1) / 48.0f;
            thick_line(x + r * cosf(a0), y + r * sinf(a0), x + r * cosf(a1), y + r * sinf(a1), w);
        }
        break;
    }
    case DRAW_RECT:
        if (finite2(d->w, d->h) && d->w > 0.0f && d->h > 0.0f)
            rgl_rect(x - 0.5f * d->w * f->s, y - 0.5f * d->h * f->s, x + 0.5f * d->w * f->s,
                 y + 0.5f * d->h * f->s);
        break;
    case DRAW_LINE:
        if (finite2(d->x2, d->y2))
            thick_line(x, y, f->cx + d->x2 * f->s, f->cy + d->y2 * f->s,
                       isfinite(d->line) ? d->line * f->s : 0.0f);
        break;
    case DRAW_LABEL: {
        char buf[DRAW_TEXT_MAX + 1];
        memcpy(buf, d->text, DRAW_TEXT_MAX);
        buf[DRAW_TEXT_MAX] = '\0';
        /* 2 pixels a font pixel on an 800-pixel picture, never under 1. */
        rgl_text(x, y, buf, fmaxf(1.0f, floorf((float)f->w_px / 400.0f)));
        break;
    }
    default:
        break;
    }
}

static void draw_shapes(const frame_t *f, const render_scene_t *sc, int layer)
{
    for (uint32_t i = 0; sc->shapes && i < sc->shape_count; i++)
        if ((sc->shapes[i].layer == DRAW_FLOOR) == (layer == DRAW_FLOOR))
            draw_shape(f, &sc->shapes[i]);
}

static void draw_object(const frame_t *f, const render_object_t *o)
{
    if (!finite2(o->x, o->y))
        return;
    float x = f->cx + o->x * f->s, y = f->cy + o->y * f->s;
    uint32_t fill = render_colour_rgb(o->colour);
    if (o->shape == 0) {
        if (!isfinite(o->radius) || o->radius <= 0.0f)
            return;
        float r = fmaxf(o->radius * f->s, 1.0f);
        rgl_colour(RENDER_RGB_OUTLINE);
        rgl_disc(x, y, r);
        rgl_colour(fill);
        rgl_disc(x, y, r > 3.0f ? r - 1.0f : r);
    } else if (o->shape == 1) {
        if (!finite2(o->width, o->depth) || !isfinite(o->angle_deg) ||
            o->width <= 0.0f || o->depth <= 0.0f)
            return;
        float hx = fmaxf(0.5f * o->width * f->s, 0.5f);
        float hy = fmaxf(0.5f * o->depth * f->s, 0.5f);
        float a = o->angle_deg * PI_F / 180.0f;
        rgl_colour(RENDER_RGB_OUTLINE);
        box(x, y, hx, hy, a);
        rgl_colour(fill);
        if (hx > 3.0f && hy > 3.0f)
            box(x, y, hx - 1.0f, hy - 1.0f, a);
        else
            box(x, y, hx, hy, a);
    }
}

static void draw_light(const frame_t *f, const render_light_t *l)
{
    if (!finite2(l->x, l->y))
        return;
    float x = f->cx + l->x * f->s, y = f->cy + l->y * f->s;
    float r = fmaxf(0.05f * f->s, 7.0f);
    rgl_colour(RENDER_RGB_LIGHT_RIM);
    star(x, y, r + 2.0f);
    rgl_colour(RENDER_RGB_LIGHT);
    star(x, y, r);
}

static void draw_robot(const frame_t *f, const render_robot_t *rb, float r)
{
    if (!finite2(rb->x, rb->y) || !isfinite(rb->theta))
        return;
    float x = f->cx + rb->x * f->s, y = f->cy + rb->y * f->s;
    float c = cosf(rb->theta), s = sinf(rb->theta);
    float rim = fmaxf(1.0f, 0.08f * r);

    rgl_colour(RENDER_RGB_OUTLINE);
    rgl_disc(x, y, r);
    rgl_colour(rb->fill_rgb ? rb->fill_rgb : RENDER_RGB_ROBOT);
    rgl_disc(x, y, r - rim);
    if (rb->body_led) {
        rgl_colour(RENDER_RGB_LED_GREEN);
        rgl_disc(x, y, fmaxf(0.3f * r, 1.0f));
    }
    /* Heading bar: centre to the rim. */
    float len = r - 0.5f * rim, hw = fmaxf(0.6f, 0.09f * r);
    rgl_colour(RENDER_RGB_HEADING);
    box(x + 0.5f * len * c, y + 0.5f * len * s, 0.5f * len, hw, rb->theta);
    if (rb->front_led) {
        rgl_colour(RENDER_RGB_LED_RED);
        rgl_disc(x + 0.55f * r * c, y + 0.55f * r * s, fmaxf(0.7f, 0.13f * r));
    }
    /* Ring LEDs: LED i at -45*i degrees from the heading, on the rim. */
    float lr = fmaxf(0.7f, 0.16f * r), ld = r - rim - 0.5f * lr;
    rgl_colour(RENDER_RGB_LED_RED);
    for (int i = 0; i < 8; i++) {
        if (!(rb->leds & (1u << i)))
            continue;
        float a = rb->theta - (float)i * (PI_F / 4.0f);
        rgl_disc(x + ld * cosf(a), y + ld * sinf(a), lr);
    }
}

static void draw_scene(const render_ctx_t *ctx, const render_scene_t *sc,
                       float s)
{
    float band = overlay_band_px(sc, ctx->w, ctx->h);
    frame_t f = {s, 0.5f * (float)ctx->w, 0.5f * ((float)ctx->h - band), ctx->w, ctx->h};

    glViewport(0, 0, ctx->w, ctx->h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_DITHER);
    glDisable(GL_CULL_FACE);
    glDisable(GL_LIGHTING);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_POLYGON_SMOOTH);
    glDisable(GL_SCISSOR_TEST);
    glShadeModel(GL_FLAT);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0.0, (double)ctx->w, 0.0, (double)ctx->h, -1.0, 1.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    glClearColor(((RENDER_RGB_BACKGROUND >> 16) & 255u) / 255.0f,
                 ((RENDER_RGB_BACKGROUND >> 8) & 255u) / 255.0f,
                 (RENDER_RGB_BACKGROUND & 255u) / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    draw_arena(&f, sc);
    draw_shapes(&f, sc, DRAW_FLOOR);
    for (uint32_t i = 0; i < sc->object_count; i++)
        draw_object(&f, &sc->objects[i]);
    /* Lights beneath the robots, so a robot under a lamp stays visible. */
    for (uint32_t i = 0; i < sc->light_count; i++)
        draw_light(&f, &sc->lights[i]);

    float rr = sc->robot_radius > 0.0f && isfinite(sc->robot_radius)
                   ? sc->robot_radius : RENDER_DEFAULT_ROBOT_RADIUS;
    float r = fmaxf(rr * s, RENDER_MIN_ROBOT_RADIUS_PX);
    for (uint32_t i = 0; i < sc->robot_count; i++)
        draw_robot(&f, &sc->robots[i], r);
    if (sc->overlay)
        overlay_draw_ids(&f, sc, r);
    draw_shapes(&f, sc, DRAW_OVER);
    if (sc->overlay)
        overlay_draw_band(&f, sc, band);
}

/* ------------------------------------------------------------------ */
/* PNG                                                                 */
/* ------------------------------------------------------------------ */

typedef struct png_job {
    FILE *fp;
    const char *path;  /**< the final path, for messages */
    char *err;
    int io_errno;      /**< errno of a failed write, else 0 */
    const render_ctx_t *ctx;  /**< the picture: a context's buffer, or */
    const uint8_t *rgb;       /**< an RGB image, top row first (ctx NULL) */
    int w, h;
} png_job_t;

static void png_error_cb(png_structp png, png_const_charp msg)
{
    png_job_t *job = png_get_error_ptr(png);
    char buf[128];
    if (job->io_errno)
        set_err(job->err, "render: cannot write '%s': %s", job->path,
                errstr(job->io_errno, buf, sizeof buf));
    else
        set_err(job->err, "render: cannot write '%s': libpng: %s",
                job->path, msg);
    png_longjmp(png, 1);
}

static void png_warning_cb(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

static void png_write_cb(png_structp png, png_bytep data, size_t len)
{
    png_job_t *job = png_get_io_ptr(png);
    if (fwrite(data, 1, len, job->fp) != len) {
        job->io_errno = errno ? errno : EIO;
        png_error(png, "write failed");
    }
}

static void png_flush_cb(png_structp png)
{
    png_job_t *job = png_get_io_ptr(png);
    if (fflush(job->fp) != 0) {
        job->io_errno = errno ? errno : EIO;
        png_error(png, "flush failed");
    }
}

/** Fills one PNG row (top row first) from the bottom-up RGBA buffer. */
static void png_row(const render_ctx_t *ctx, int y)
{
    const uint8_t *src = ctx->rgba + (size_t)(ctx->h - 1 - y) *
                                         (size_t)ctx->w * 4;
    uint8_t *dst = ctx->row;
    for (int x = 0; x < ctx->w; x++, src += 4, dst += 3) {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
    }
}

/** Encodes the picture to job->fp.  0 or -1 with job->err set. */
static int png_encode(png_job_t *job)
{
    const render_ctx_t *ctx = job->ctx;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, job,
                                              png_error_cb, png_warning_cb);
    if (!png) {
        set_err(job->err, "render: cannot write '%s': libpng init failed",
                job->path);
        return -1;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        set_err(job->err, "render: cannot write '%s': libpng init failed",
                job->path);
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_set_write_fn(png, job, png_write_cb, png_flush_cb);
    png_set_IHDR(png, info, (png_uint_32)job->w, (png_uint_32)job->h, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* Flat colours compress well even at a fast level. */
    png_set_compression_level(png, 3);
    png_write_info(png, info);
    for (int y = 0; y < job->h; y++) {
        if (ctx) {
            png_row(ctx, y);
            png_write_row(png, ctx->row);
        } else {
            png_write_row(png, (png_bytep)(job->rgb + (size_t)y * (size_t)job->w * 3));
        }
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return 0;
}

/** Writes the picture (ctx's, or rgb when ctx is NULL) to path atomically
 *  (path.tmp, then rename). */
static int write_png_atomic(const render_ctx_t *ctx, const uint8_t *rgb,
                            int w, int h, const char *path, char *err)
{
    char ebuf[128];
    size_t n = strlen(path);
    char *tmp = malloc(n + 5);
    if (!tmp) {
        set_err(err, "render: cannot write '%s': out of memory", path);
        return -1;
    }
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmp", 5);

    FILE *fp = fopen(tmp, "wb");
    if (!fp) {
        int e = errno;
        set_err(err, "render: cannot write '%s' (temporary '%s'): %s", path,
                tmp, errstr(e, ebuf, sizeof ebuf));
        free(tmp);
        return -1;
    }
    png_job_t job = {fp, path, err, 0, ctx, rgb, w, h};
    int rc = png_encode(&job);
    if (rc == 0 && (fflush(fp) != 0 || ferror(fp))) {
        int e = errno ? errno : EIO;
        set_err(err, "render: cannot write '%s': %s", path,
                errstr(e, ebuf, sizeof ebuf));
        rc = -1;
    }
    if (fclose(fp) != 0 && rc == 0) {
        int e = errno;
        set_err(err, "render: cannot write '%s': %s", path,
                errstr(e, ebuf, sizeof ebuf));
        rc = -1;
    }
    if (rc == 0 && rename(tmp, path) != 0) {
        int e = errno;
        set_err(err, "render: cannot rename '%s' to '%s': %s", tmp, path,
                errstr(e, ebuf, sizeof ebuf));
        rc = -1;
    }
    if (rc != 0)
        remove(tmp);
    free(tmp);
    return rc;
}

/* ------------------------------------------------------------------ */
/* Render                                                              */
/* ------------------------------------------------------------------ */

/** Draws `scene` into ctx->rgba; `what` names the picture in messages. */
static int render_draw(render_ctx_t *ctx, const render_scene_t *scene,
                       const char *what, char *err)
{
    float s = view_scale(ctx, scene);
    if (s <= 0.0f) {
        set_err(err, "render: '%s': invalid arena size %gx%g m", what,
                (double)scene->arena_w, (double)scene->arena_h);
        return -1;
    }
    if ((scene->robot_count && !scene->robots) ||
        (scene->object_count && !scene->objects) ||
        (scene->light_count && !scene->lights) ||
        (scene->legend_count && !scene->legend)) {
        set_err(err, "render: '%s': a scene count is non-zero but its array "
                "is NULL", what);
        return -1;
    }

    /* OSMesa contexts are current per thread: bind ours on this thread for
     * this call only, and release it before returning. */
    if (!OSMesaMakeCurrent(ctx->gl, ctx->rgba, GL_UNSIGNED_BYTE, ctx->w,
                           ctx->h)) {
        set_err(err, "render: '%s': OSMesaMakeCurrent failed", what);
        return -1;
    }
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++) {
        /* drop errors left from an earlier call */
    }
    draw_scene(ctx, scene, s);
    glFinish();
    GLenum gl_err = glGetError();
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    if (gl_err != GL_NO_ERROR) {
        set_err(err, "render: '%s': OpenGL error 0x%04x", what,
                (unsigned)gl_err);
        return -1;
    }
    return 0;
}

int render_scene_png(render_ctx_t *ctx, const render_scene_t *scene,
                     const char *png_path, char *err)
{
    if (!ctx || !scene || !png_path || !*png_path) {
        set_err(err, "render: %s", !ctx ? "no render context"
                                   : !scene ? "no scene"
                                            : "empty PNG path");
        return -1;
    }
    if (render_draw(ctx, scene, png_path, err) != 0)
        return -1;
    return write_png_atomic(ctx, NULL, ctx->w, ctx->h, png_path, err);
}

int render_write_rgb_png(const uint8_t *rgb, int width_px, int height_px,
                         const char *png_path, char *err)
{
    if (!rgb || !png_path || !*png_path || width_px < 1 || height_px < 1 ||
        width_px > RENDER_MAX_PX || height_px > RENDER_MAX_PX) {
        set_err(err, "render: %s", !rgb ? "no image" : !png_path || !*png_path
                                   ? "empty PNG path" : "image size out of range");
        return -1;
    }
    return write_png_atomic(NULL, rgb, width_px, height_px, png_path, err);
}

int render_scene_rgb(render_ctx_t *ctx, const render_scene_t *scene,
                     uint8_t *rgb, char *err)
{
    if (!ctx || !scene || !rgb) {
        set_err(err, "render: %s", !ctx ? "no render context"
                                   : !scene ? "no scene"
                                            : "no frame buffer");
        return -1;
    }
    if (render_draw(ctx, scene, "frame", err) != 0)
        return -1;
    for (int y = 0; y < ctx->h; y++) {
        png_row(ctx, y);
        memcpy(rgb + (size_t)y * (size_t)ctx->w * 3, ctx->row, (size_t)ctx->w * 3);
    }
    return 0;
}
