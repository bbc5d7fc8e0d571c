/*
 * camera_render.c - one robot's camera view with OSMesa (camera_render.h).
 *
 * The camera (hal/epuck's configuration): the lens at the front of the
 * body, EPUCK_CAMERA_HEIGHT_M above the floor, looking level (tilt 0: the
 * image's 320-row window is centred on the sensor's middle row, the
 * optical axis); `camera.fov` wide over camera.width_px columns, square
 * pixels, so camera.height_px rows span fov x height / width (28 deg for
 * the 40 x 20 frame).
 *
 * Why the frame is drawn at the subsampled size (40 x 20) and not at the
 * sensor's 640 x 320: the e-puck's driver subsamples 16 x 16 by keeping
 * pixels, not by averaging them (the sensor's QQVGA mode does part of it,
 * the dsPIC's pixel clock the rest: GCtronic's e-puck library, e_po3030k.h
 * and the PO6030K driver's timing notes).  A pixel of the frame is then one
 * point sample of the scene, which is what GL gives when it samples each
 * pixel's centre without anti-aliasing.  So an item about 2 columns wide
 * covers 2 or 3 columns depending on where it falls, on the robot and here
 * alike; rendering 256 times the pixels and keeping one in 256 would give
 * the same frame up to where in its 16 x 16 block the kept sample lies (at
 * most half a column, 0.7 deg: we sample the block's centre, which keeps
 * the image symmetric about the axis).
 *
 * Shading: GL's fixed-function lighting, each lamp a point light above the
 * floor (GL has 8: the 8 brightest lamps), over an ambient term.  The
 * camera runs automatic exposure and white balance (the driver's defaults),
 * so a lamp's absolute intensity does not reach the image: lamps set which
 * sides are lit, not how bright the frame is.  Without lamps the scene is
 * evenly lit.  LEDs are drawn unlit, in their own colour.
 */
#define _DEFAULT_SOURCE   /* setenv */
#include "camera_render.h"

#include <GL/osmesa.h>
#include <GL/gl.h>

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "core/render.h"
#include "core/sim_internal.h"
#include "units.h"

/* Objects farther than this from the lens are not drawn: an e-puck there
 * (70 mm) spans under one column of the 40-column frame, and a small item far
 * less; walls are always drawn. */
#define FAR_M 5.0f
/* The nearest thing drawn: an item a robot carries is 2 cm ahead. */
#define NEAR_M 0.002f
/* The arena's walls, m (the scenario gives their thickness, not their
 * height: 10 cm, a common e-puck arena). */
#define WALL_HEIGHT_M 0.10f
/* The e-puck's body: its height, and where its LEDs are (ring LEDs near
 * the top rim; the green body LED lights a band of the body; the red front
 * LED beside the camera), m. */
#define BODY_HEIGHT_M 0.050f
#define RING_LED_Z0 0.043f
#define RING_LED_Z1 0.047f
#define RING_LED_HALF_RAD 0.06f   /* half its width on the rim, rad (2 mm) */
#define BODY_LED_Z0 0.020f
#define BODY_LED_Z1 0.030f
#define FRONT_LED_Z0 0.018f
#define FRONT_LED_Z1 0.022f
#define FRONT_LED_HALF_RAD 0.06f
/* Sides of a drawn cylinder. */
#define SIDES 24
/* Lighting: the ambient share with lamps (the rest is each lamp's diffuse
 * light, scaled by its intensity relative to the brightest). */
#define AMBIENT_WITH_LAMPS 0.45f
#define DIFFUSE_SHARE 0.55f
#define GL_LIGHTS_MAX 8

struct camera_render {
    OSMesaContext gl;
    uint16_t w, h;
    uint8_t *rgba;        /**< w*h*4, OSMesa's buffer, bottom row first */
};

static pthread_once_t threads_once = PTHREAD_ONCE_INIT;

static void set_threads_once(void)
{
    setenv("LP_NUM_THREADS", "0", 0);   /* never overrides the user's */
}

void camera_render_set_threads(void)
{
    pthread_once(&threads_once, set_threads_once);
}

camera_render_t *camera_render_create(uint16_t width, uint16_t height, char err[SIM_ERR_MAX])
{
    camera_render_set_threads();
    if (width < 1 || height < 1 || width > CAMERA_RENDERED_MAX_PX || height > CAMERA_RENDERED_MAX_PX) {
        snprintf(err, SIM_ERR_MAX, "camera: frame %ux%u px is out of range (1..%u each)", width, height,
                 CAMERA_RENDERED_MAX_PX);
        return NULL;
    }
    camera_render_t *cr = calloc(1, sizeof *cr);
    if (!cr || !(cr->rgba = calloc((size_t)width * height, 4))) {
        free(cr);
        snprintf(err, SIM_ERR_MAX, "camera: out of memory");
        return NULL;
    }
    cr->w = width;
    cr->h = height;
    /* A depth buffer: unlike the top-down pictures, what is nearer hides
     * what is behind it. */
    cr->gl = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
    if (!cr->gl || !OSMesaMakeCurrent(cr->gl, cr->rgba, GL_UNSIGNED_BYTE, width, height)) {
        snprintf(err, SIM_ERR_MAX, "camera: cannot create an OSMesa context of %ux%u px", width, height);
        camera_render_destroy(cr);
        return NULL;
    }
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    return cr;
}

void camera_render_destroy(camera_render_t *cr)
{
    if (!cr) {
        return;
    }
    if (cr->gl) {
        OSMesaDestroyContext(cr->gl);
    }
    free(cr->rgba);
    free(cr);
}

/* ------------------------------------------------------------- shapes */

static void colour(uint32_t rgb)
{
    glColor3ub((GLubyte)(rgb >> 16), (GLubyte)(rgb >> 8), (GLubyte)rgb);
}

static uint32_t class_rgb(int c)
{
    switch (c) {
    case HAL_COLOUR_RED: return RENDER_RGB_OBJ_RED;
    case HAL_COLOUR_GREEN: return RENDER_RGB_OBJ_GREEN;
    case HAL_COLOUR_BLUE: return RENDER_RGB_OBJ_BLUE;
    default: return RENDER_RGB_OBJ_NONE;
    }
}

/* A vertical cylinder standing on the floor, with its top. */
static void cylinder(float cx, float cy, float r, float height)
{
    glBegin(GL_QUAD_STRIP);
    for (int k = 0; k <= SIDES; k++) {
        float a = 2.0f * (float)UNITS_PI * (float)k / SIDES, c = cosf(a), s = sinf(a);
        glNormal3f(c, s, 0.0f);
        glVertex3f(cx + r * c, cy + r * s, height);
        glVertex3f(cx + r * c, cy + r * s, 0.0f);
    }
    glEnd();
    glNormal3f(0.0f, 0.0f, 1.0f);
    glBegin(GL_TRIANGLE_FAN);
    glVertex3f(cx, cy, height);
    for (int k = 0; k <= SIDES; k++) {
        float a = 2.0f * (float)UNITS_PI * (float)k / SIDES;
        glVertex3f(cx + r * cosf(a), cy + r * sinf(a), height);
    }
    glEnd();
}

/* A vertical wall from a to b (its face's normal n), z0 to z1. */
static void wall_quad(vec2_t a, vec2_t b, vec2_t n, float z0, float z1)
{
    glNormal3f(n.x, n.y, 0.0f);
    glBegin(GL_QUADS);
    glVertex3f(a.x, a.y, z0);
    glVertex3f(b.x, b.y, z0);
    glVertex3f(b.x, b.y, z1);
    glVertex3f(a.x, a.y, z1);
    glEnd();
}

static void box(const obstacle_t *o)
{
    for (int e = 0; e < 4; e++) {
        vec2_t a = o->corner[e], b = o->corner[(e + 1) & 3];
        vec2_t d = v2_sub(b, a);
        float len = v2_len(d);
        vec2_t n = len > 0.0f ? v2(d.y / len, -d.x / len) : v2(0.0f, 0.0f);   /* outward: corners CCW */
        wall_quad(a, b, n, 0.0f, o->height);
    }
    glNormal3f(0.0f, 0.0f, 1.0f);
    glBegin(GL_QUADS);
    for (int e = 0; e < 4; e++) {
        glVertex3f(o->corner[e].x, o->corner[e].y, o->height);
    }
    glEnd();
}

/* A band of the body's rim from angle a0 to a1 (world frame), z0 to z1, a
 * hair outside the body so that it is not hidden by it. */
static void rim_band(float cx, float cy, float a0, float a1, float z0, float z1)
{
    float r = EPUCK_BODY_RADIUS_M * 1.02f;
    int n = (int)ceilf((a1 - a0) / (2.0f * (float)UNITS_PI) * SIDES);
    n = n < 1 ? 1 : n;
    glBegin(GL_QUAD_STRIP);
    for (int k = 0; k <= n; k++) {
        float a = a0 + (a1 - a0) * (float)k / (float)n;
        glVertex3f(cx + r * cosf(a), cy + r * sinf(a), z1);
        glVertex3f(cx + r * cosf(a), cy + r * sinf(a), z0);
    }
    glEnd();
}

/* Another robot: its body lit, then its lit LEDs unlit (they glow). */
static void robot(const sim_robot_t *q)
{
    glEnable(GL_LIGHTING);
    colour(RENDER_RGB_ROBOT);
    cylinder(q->x, q->y, EPUCK_BODY_RADIUS_M, BODY_HEIGHT_M);
    if ((q->leds & 0x3ffu) == 0u) {
        return;
    }
    glDisable(GL_LIGHTING);
    colour(RENDER_RGB_LED_RED);
    for (unsigned k = 0; k < HAL_LED_COUNT; k++) {
        if (q->leds & (1u << k)) {
            /* LED k at -45 k degrees from the heading (render.h). */
            float a = q->theta - (float)k * (float)UNITS_PI / 4.0f;
            rim_band(q->x, q->y, a - RING_LED_HALF_RAD, a + RING_LED_HALF_RAD, RING_LED_Z0, RING_LED_Z1);
        }
    }
    if (q->leds & (1u << HAL_LED_WORD_FRONT_BIT)) {
        rim_band(q->x, q->y, q->theta - FRONT_LED_HALF_RAD, q->theta + FRONT_LED_HALF_RAD, FRONT_LED_Z0,
                 FRONT_LED_Z1);
    }
    if (q->leds & (1u << HAL_LED_WORD_BODY_BIT)) {
        colour(RENDER_RGB_LED_GREEN);
        rim_band(q->x, q->y, 0.0f, 2.0f * (float)UNITS_PI, BODY_LED_Z0, BODY_LED_Z1);
    }
}

/* ------------------------------------------------------------- scene */

/* The view from the lens: GL's camera looks down -z with +y up; ours
 * looks along the heading with the world's +z up (column-major). */
static void load_view(vec2_t eye, float heading)
{
    float c = cosf(heading), s = sinf(heading), z = EPUCK_CAMERA_HEIGHT_M;
    /* right = (s, -c, 0), up = (0, 0, 1), forward = (c, s, 0) */
    GLfloat m[16] = {
        s, 0.0f, -c, 0.0f,
        -c, 0.0f, -s, 0.0f,
        0.0f, 1.0f, 0.0f, 0.0f,
        -(s * eye.x - c * eye.y), -z, c * eye.x + s * eye.y, 1.0f,
    };
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(m);
}

static void set_lights(const scenario_t *sc)
{
    /* The brightest lamps first (stable order for equal ones). */
    uint32_t order[SCENARIO_MAX_LIGHTS], n = sc->light_count;
    for (uint32_t k = 0; k < n; k++) order[k] = k;
    for (uint32_t a = 1; a < n; a++) {
        for (uint32_t b = a; b > 0 && sc->lights[order[b]].intensity > sc->lights[order[b - 1]].intensity; b--) {
            uint32_t t = order[b]; order[b] = order[b - 1]; order[b - 1] = t;
        }
    }
    uint32_t used = n < GL_LIGHTS_MAX ? n : GL_LIGHTS_MAX;
    float top = used > 0 ? sc->lights[order[0]].intensity : 0.0f;
    float amb = (used > 0 && top > 0.0f) ? AMBIENT_WITH_LAMPS : 1.0f;
    GLfloat ambient[4] = { amb, amb, amb, 1.0f };
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
    for (uint32_t k = 0; k < GL_LIGHTS_MAX; k++) {
        GLenum id = GL_LIGHT0 + k;
        if (k >= used || top <= 0.0f) {
            glDisable(id);
            continue;
        }
        const light_def_t *L = &sc->lights[order[k]];
        float d = DIFFUSE_SHARE * L->intensity / top;
        GLfloat pos[4] = { L->x, L->y, L->height, 1.0f }, diff[4] = { d, d, d, 1.0f }, zero[4] = { 0, 0, 0, 1 };
        glLightfv(id, GL_POSITION, pos);   /* through the view matrix: world coordinates */
        glLightfv(id, GL_DIFFUSE, diff);
        glLightfv(id, GL_AMBIENT, zero);
        glLightfv(id, GL_SPECULAR, zero);
        glEnable(id);
    }
}

#define NEAR_MAX 1024u

static void draw_scene(struct sim *sim, uint32_t i, vec2_t eye, vec2_t dir)
{
    const scenario_t *sc = sim->sc;
    float hw = sim->hw, hh = sim->hh, wt = sc->arena.wall_thickness;
    glEnable(GL_LIGHTING);
    colour(RENDER_RGB_FLOOR);
    glNormal3f(0.0f, 0.0f, 1.0f);
    glBegin(GL_QUADS);
    glVertex3f(-hw - wt, -hh - wt, 0.0f);
    glVertex3f(hw + wt, -hh - wt, 0.0f);
    glVertex3f(hw + wt, hh + wt, 0.0f);
    glVertex3f(-hw - wt, hh + wt, 0.0f);
    glEnd();
    /* The walls' inner faces (the lens is always inside). */
    colour(RENDER_RGB_WALL);
    wall_quad(v2(-hw, -hh), v2(hw, -hh), v2(0.0f, 1.0f), 0.0f, WALL_HEIGHT_M);
    wall_quad(v2(hw, -hh), v2(hw, hh), v2(-1.0f, 0.0f), 0.0f, WALL_HEIGHT_M);
    wall_quad(v2(hw, hh), v2(-hw, hh), v2(0.0f, -1.0f), 0.0f, WALL_HEIGHT_M);
    wall_quad(v2(-hw, hh), v2(-hw, -hh), v2(1.0f, 0.0f), 0.0f, WALL_HEIGHT_M);

    /* What may be in view: near enough and not wholly behind the lens. */
    uint32_t idx[NEAR_MAX];
    uint32_t no = sim_gather_obstacles(sim, &sim->scratch[0], eye.x - FAR_M, eye.y - FAR_M, eye.x + FAR_M,
                                       eye.y + FAR_M, idx, NEAR_MAX);
    for (uint32_t k = 0; k < no; k++) {
        const obstacle_t *o = &sim->obstacles[idx[k]];
        colour(class_rgb(o->colour));
        if (o->shape == SHAPE_CYLINDER) {
            cylinder(o->c.x, o->c.y, o->r, o->height);
        } else {
            box(o);
        }
    }
    uint32_t nr = sim_gather_robots(sim, eye.x - FAR_M, eye.y - FAR_M, eye.x + FAR_M, eye.y + FAR_M, idx, NEAR_MAX);
    for (uint32_t k = 0; k < nr; k++) {
        const sim_robot_t *q = &sim->robots[idx[k]];
        vec2_t v = v2_sub(v2(q->x, q->y), eye);
        if (idx[k] != i && v2_dot(v, dir) > -EPUCK_BODY_RADIUS_M * 1.1f) {
            robot(q);
        }
    }
    glEnable(GL_LIGHTING);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        const sim_item_t *items = NULL;
        uint32_t n_items = run->def->items ? run->def->items(run->self, &items) : 0;
        for (uint32_t k = 0; k < n_items; k++) {
            const sim_item_t *it = &items[k];
            if (!isfinite(it->x) || it->colour == HAL_COLOUR_NONE) {
                continue;   /* taken out of the world; or not seen (task.h) */
            }
            vec2_t v = v2_sub(v2(it->x, it->y), eye);
            if (fabsf(v.x) < FAR_M && fabsf(v.y) < FAR_M && v2_dot(v, dir) > -it->radius) {
                colour(class_rgb(it->colour));
                cylinder(it->x, it->y, it->radius, it->height);
            }
        }
    }
}

int camera_render_view(camera_render_t *cr, struct sim *sim, uint32_t i, uint8_t *rgb, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    const sim_robot_t *r = &sim->robots[i];
    vec2_t dir = v2(cosf(r->theta), sinf(r->theta));
    vec2_t eye = v2(r->x + EPUCK_BODY_RADIUS_M * dir.x, r->y + EPUCK_BODY_RADIUS_M * dir.y);
    if (!OSMesaMakeCurrent(cr->gl, cr->rgba, GL_UNSIGNED_BYTE, cr->w, cr->h)) {
        snprintf(err, SIM_ERR_MAX, "camera: OSMesaMakeCurrent failed");
        return -1;
    }
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; k++) {
        /* drop errors left from an earlier call */
    }
    glViewport(0, 0, cr->w, cr->h);
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glShadeModel(GL_SMOOTH);
    glEnable(GL_COLOR_MATERIAL);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);   /* nothing there: over the walls */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    float half = ((const camera_config_t *)sim_model_config(sim, SIM_MODEL_camera))->fov * (float)UNITS_PI / 360.0f;
    float xr = NEAR_M * tanf(half), yt = xr * (float)cr->h / (float)cr->w;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-xr, xr, -yt, yt, NEAR_M, 2.0f * FAR_M + sc->arena.width + sc->arena.height);
    load_view(eye, r->theta);
    set_lights(sc);
    draw_scene(sim, i, eye, dir);
    glFinish();
    GLenum gl_err = glGetError();
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    if (gl_err != GL_NO_ERROR) {
        snprintf(err, SIM_ERR_MAX, "camera: OpenGL error 0x%04x", (unsigned)gl_err);
        return -1;
    }
    for (uint16_t y = 0; y < cr->h; y++) {   /* GL's bottom row first; ours top first */
        const uint8_t *src = cr->rgba + (size_t)(cr->h - 1u - y) * cr->w * 4u;
        uint8_t *dst = rgb + (size_t)y * cr->w * 3u;
        for (uint16_t x = 0; x < cr->w; x++) {
            dst[3 * x] = src[4 * x];
            dst[3 * x + 1] = src[4 * x + 1];
            dst[3 * x + 2] = src[4 * x + 2];
        }
    }
    return 0;
}
