/*
 * render_overlay.c - what a picture says besides the arena (render.h,
 * render_scene_t.overlay): a band at the top with the simulated time and
 * the legend (robot fills with their counts, the tasks' floor areas,
 * outlines and items), and each robot's id beside it.
 *
 * The band's height depends only on the picture's width, the legend's
 * labels and the robot count, never on the time or the counts shown, so
 * the arena stays put from one video frame to the next.
 */
#include "render_gl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Every slot's room is reserved for the widest text it can hold: the time
 * up to this many seconds, a count as many digits as the robot count. */
#define TIME_WIDEST "T = 99999.9 S"
#define ITEM_TEXT_MAX 64

/* Font pixel of the band's text: 2 screen pixels on a picture of 800 (as
 * the tasks' labels), more on larger ones, 1 only on tiny pictures where
 * 2 would not leave room for the arena. */
static float band_cell(int w)
{
    return w >= 240 ? fmaxf(2.0f, floorf((float)w / 400.0f)) : 1.0f;
}

/* The margin the arena keeps from the picture's edges (render.c's). */
static float edge_margin(int w, int h)
{
    return fmaxf(4.0f, 0.03f * (float)(w < h ? w : h));
}

static int digits(uint32_t n)
{
    int d = 1;
    while (n >= 10) {
        n /= 10;
        d++;
    }
    return d;
}

/* Robots whose fill is the key's (rgb 0: the default body). */
static uint32_t key_count(const render_scene_t *sc, uint32_t rgb)
{
    uint32_t n = 0;
    for (uint32_t i = 0; sc->robots && i < sc->robot_count; i++)
        n += sc->robots[i].fill_rgb == rgb;
    return n;
}

/* A key's swatch in the square of side `side` centred on (cx, cy), drawn as
 * what it stands for is drawn in the arena. */
static void swatch(const draw_key_t *key, float cx, float cy, float side, float c)
{
    float rim = fmaxf(1.0f, 0.5f * c);
    uint32_t rgb = render_key_rgb(key);
    switch (key->kind) {
    case DRAW_KEY_AREA:
        rgl_colour(rgb);
        rgl_rect(cx - 0.5f * side, cy - 0.5f * side, cx + 0.5f * side, cy + 0.5f * side);
        break;
    case DRAW_KEY_RING:
        rgl_colour(rgb);
        rgl_disc(cx, cy, 0.5f * side);
        rgl_colour(RENDER_RGB_BACKGROUND);
        rgl_disc(cx, cy, 0.5f * side - rim);
        break;
    case DRAW_KEY_LINE:
        rgl_colour(rgb);
        rgl_rect(cx - 0.5f * side, cy - rim, cx + 0.5f * side, cy + rim);
        break;
    case DRAW_KEY_ITEM:   /* an item as the arena's: rim and colour, smaller than a robot */
        rgl_colour(RENDER_RGB_OUTLINE);
        rgl_disc(cx, cy, 0.35f * side);
        rgl_colour(rgb);
        rgl_disc(cx, cy, 0.35f * side - rim);
        break;
    default:              /* a robot's body: rim, then fill */
        rgl_colour(RENDER_RGB_OUTLINE);
        rgl_disc(cx, cy, 0.5f * side);
        rgl_colour(rgb);
        rgl_disc(cx, cy, 0.5f * side - rim);
        break;
    }
}

/* Lays the band's items out left to right from its top left, wrapping at
 * the right margin, and draws them when `draw`.  Slot 0 is the time stamp,
 * slot k > 0 legend key k - 1.  Returns the number of lines. */
static int flow(const render_scene_t *sc, int w, int h, float top, int draw)
{
    float c = band_cell(w), m = edge_margin(w, h);
    float line = 5.0f * c, gap = 3.0f * c, side = 6.0f * c, sep = 12.0f * c;
    float x = m, y = top - m - line;   /* GL: the first line's bottom */
    int lines = 1;
    char text[ITEM_TEXT_MAX], widest[ITEM_TEXT_MAX];
    for (uint32_t k = 0; k <= sc->legend_count; k++) {
        const draw_key_t *key = k ? &sc->legend[k - 1] : NULL;
        const char *label = key && key->label ? key->label : "";
        float lead = key ? side + 2.0f * c : 0.0f;
        if (key && key->kind != DRAW_KEY_ROBOT) {
            snprintf(text, sizeof text, "%s", label);
            snprintf(widest, sizeof widest, "%s", label);
        } else if (key) {
            /* Laying out needs no count: `widest` has room for any. */
            snprintf(text, sizeof text, "%s %u", label, draw ? key_count(sc, key->rgb) : 0u);
            snprintf(widest, sizeof widest, "%s %0*u", label, digits(sc->robot_count), 0u);
        } else {
            snprintf(text, sizeof text, "T = %.1f S", sc->time_s);
            snprintf(widest, sizeof widest, "%s", TIME_WIDEST);
        }
        float room = lead + fmaxf(rgl_text_width(text, c), rgl_text_width(widest, c));
        if (k > 0 && x + room > (float)w - m) {
            x = m;
            y -= line + gap;
            lines++;
        }
        if (draw) {
            if (key)
                swatch(key, x + 0.5f * side, y + 0.5f * line, side, c);
            rgl_colour(RENDER_RGB_TEXT);
            rgl_text(x + lead, y, text, c);
        }
        x += room + sep;
    }
    return lines;
}

float overlay_band_px(const render_scene_t *sc, int w, int h)
{
    if (!sc || !sc->overlay || (sc->legend_count && !sc->legend))
        return 0.0f;
    float c = band_cell(w);
    int lines = flow(sc, w, h, (float)h, 0);
    return edge_margin(w, h) + (float)lines * 5.0f * c + (float)(lines - 1) * 3.0f * c;
}

void overlay_draw_band(const frame_t *f, const render_scene_t *sc, float band)
{
    if (band <= 0.0f)
        return;
    flow(sc, f->w_px, f->h_px, (float)f->h_px, 1);
}

void overlay_draw_ids(const frame_t *f, const render_scene_t *sc, float r)
{
    /* A font pixel a third of the body's radius: about the body's height
     * for the digits, readable and no bigger than the robot. */
    float c = fmaxf(1.0f, floorf(r / 3.0f));
    char id[12];
    rgl_colour(RENDER_RGB_TEXT);
    for (uint32_t i = 0; i < sc->robot_count; i++) {
        const render_robot_t *rb = &sc->robots[i];
        if (!isfinite(rb->x) || !isfinite(rb->y))
            continue;
        snprintf(id, sizeof id, "%u", i);
        /* Up and right of the body, clear of its heading bar. */
        rgl_text(f->cx + rb->x * f->s + 0.8f * r, f->cy + rb->y * f->s + 0.5f * r, id, c);
    }
}
