/*
 * telemetry_scene.c - the picture of a run as telemetry (telemetry_scene.h).
 *
 * The tasks draw into a drawing_t exactly as for a PNG frame (sim_render.c);
 * this turns it, the tasks' items, the scenario's arena, obstacles and
 * lamps and the run's legend (legend.h) into scene_t and task_drawing_t.  Whether the drawing changed is
 * decided on its encoded bytes (with utime 0), so a change is any change of
 * any bit, NaN included, and no field can be forgotten in a comparison.
 */
#include "telemetry_scene.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "legend.h"
#include "render.h"
#include "sim_internal.h"
#include "units.h"

struct telemetry_scene {
    swarmlcm_scene_obstacle_t *obstacles;
    swarmlcm_scene_light_t lights[SCENARIO_MAX_LIGHTS];
    /* the run's legend (legend.h), as scene_t carries it */
    int8_t key_kind[LEGEND_KEYS_MAX];
    int32_t key_rgb[LEGEND_KEYS_MAX];
    char *key_label[LEGEND_KEYS_MAX];

    drawing_t drawing;               /* what the tasks draw this step */
    swarmlcm_scene_shape_t *shapes;  /* TELEMETRY_SCENE_SHAPES_MAX */
    char (*texts)[DRAW_TEXT_MAX + 1];/* the labels, NUL-terminated */
    swarmlcm_scene_item_t *items;
    uint32_t items_cap;
    int32_t *fill_robot, *fill_rgb;  /* one per robot at most */

    uint8_t *now, *last;             /* encoded drawings (utime 0): this step's, the last sent */
    int now_cap, last_cap, last_len; /* last_len -1: none sent yet */
};

/* lcm-gen's C code computes a type's fingerprint lazily into a static:
 * compute them before two runs' threads can race on it (as telemetry.c
 * does for its types).  The nested types' come with them. */
static pthread_once_t hashes_once = PTHREAD_ONCE_INIT;
static void compute_hashes(void)
{
    (void)__swarmlcm_scene_t_get_hash();
    (void)__swarmlcm_task_drawing_t_get_hash();
}

telemetry_scene_t *telemetry_scene_create(const sim_t *simp)
{
    const struct sim *sim = simp;
    uint32_t n = sim->n ? sim->n : 1;
    pthread_once(&hashes_once, compute_hashes);
    telemetry_scene_t *s = calloc(1, sizeof *s);
    if (!s) {
        return NULL;
    }
    s->obstacles = calloc(sim->n_obstacles ? sim->n_obstacles : 1, sizeof *s->obstacles);
    s->drawing.shapes = calloc(TELEMETRY_SCENE_SHAPES_MAX, sizeof *s->drawing.shapes);
    s->drawing.cap = TELEMETRY_SCENE_SHAPES_MAX;
    s->drawing.robot_rgb = calloc(n, sizeof *s->drawing.robot_rgb);
    s->drawing.robot_count = sim->n;
    s->shapes = calloc(TELEMETRY_SCENE_SHAPES_MAX, sizeof *s->shapes);
    s->texts = calloc(TELEMETRY_SCENE_SHAPES_MAX, sizeof *s->texts);
    s->fill_robot = calloc(n, sizeof *s->fill_robot);
    s->fill_rgb = calloc(n, sizeof *s->fill_rgb);
    s->last_len = -1;
    if (!s->obstacles || !s->drawing.shapes || !s->drawing.robot_rgb || !s->shapes || !s->texts
        || !s->fill_robot || !s->fill_rgb) {
        telemetry_scene_destroy(s);
        return NULL;
    }
    return s;
}

void telemetry_scene_destroy(telemetry_scene_t *s)
{
    if (!s) {
        return;
    }
    free(s->obstacles);
    free(s->drawing.shapes);
    free(s->drawing.robot_rgb);
    free(s->shapes);
    free(s->texts);
    free(s->items);
    free(s->fill_robot);
    free(s->fill_rgb);
    free(s->now);
    free(s->last);
    free(s);
}

static int64_t utime_of(const struct sim *sim)
{
    return (int64_t)sim->step * sim->sc->control_period_ms * 1000;
}

void telemetry_scene_fill(telemetry_scene_t *s, const sim_t *simp, swarmlcm_scene_t *m)
{
    const struct sim *sim = simp;
    const scenario_t *sc = sim->sc;
    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        const object_def_t *o = &sim->objects[k];   /* the scenario's and the random cylinders */
        swarmlcm_scene_obstacle_t *out = &s->obstacles[k];
        out->shape = (int8_t)o->shape;
        out->x = o->x;
        out->y = o->y;
        out->radius = o->radius;
        out->width = o->width;
        out->depth = o->depth;
        out->angle = o->angle;
        out->height = o->height;
        out->rgb = (int32_t)render_colour_rgb(o->colour);
    }
    for (uint32_t l = 0; l < sc->light_count; l++) {
        swarmlcm_scene_light_t light = { sc->lights[l].x, sc->lights[l].y, sc->lights[l].height,
                                         sc->lights[l].intensity };
        s->lights[l] = light;
    }
    m->version = SWARMLCM_SCENE_T_VERSION;
    m->utime = utime_of(sim);
    m->run = (int64_t)sim->seed;
    m->arena_width = sc->arena.width;
    m->arena_height = sc->arena.height;
    m->wall_thickness = sc->arena.wall_thickness;
    m->robot_radius = EPUCK_BODY_RADIUS_M;
    m->n_obstacles = (int32_t)sim->n_obstacles;
    m->obstacles = s->obstacles;
    m->n_lights = (int16_t)sc->light_count;
    m->lights = s->lights;
    draw_key_t keys[LEGEND_KEYS_MAX];
    uint32_t n_keys = legend_collect(simp, keys);
    for (uint32_t k = 0; k < n_keys; k++) {
        s->key_kind[k] = (int8_t)keys[k].kind;
        s->key_rgb[k] = (int32_t)render_key_rgb(&keys[k]);
        s->key_label[k] = (char *)keys[k].label;   /* the task's constant; LCM only reads it */
    }
    m->robot_rgb = (int32_t)RENDER_RGB_ROBOT;
    m->n_keys = (int16_t)n_keys;
    m->key_kind = s->key_kind;
    m->key_rgb = s->key_rgb;
    m->key_label = s->key_label;
}

/* The tasks' items as the PNG frames draw them: those in the world and of a
 * colour.  Returns how many, or -1 when out of memory. */
static int32_t collect_items(telemetry_scene_t *s, const struct sim *sim)
{
    uint32_t n = 0;
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        const sim_item_t *items;
        uint32_t count = run->def->items ? run->def->items(run->self, &items) : 0;
        if (n + count > s->items_cap) {
            uint32_t cap = 2 * (n + count);
            swarmlcm_scene_item_t *b = realloc(s->items, cap * sizeof *b);
            if (!b) {
                return -1;
            }
            s->items = b;
            s->items_cap = cap;
        }
        for (uint32_t k = 0; k < count; k++) {
            if (isfinite(items[k].x) && items[k].colour != HAL_COLOUR_NONE) {
                swarmlcm_scene_item_t it = { items[k].x, items[k].y, items[k].radius, (int32_t)render_colour_rgb(items[k].colour) };
                s->items[n++] = it;
            }
        }
    }
    return (int32_t)n;
}

/* Grows *buf to at least `size` bytes. */
static int room(uint8_t **buf, int *cap, int size)
{
    if (size <= *cap) {
        return 0;
    }
    uint8_t *b = realloc(*buf, (size_t)size);
    if (!b) {
        return -1;
    }
    *buf = b;
    *cap = size;
    return 0;
}

int telemetry_scene_drawing(telemetry_scene_t *s, const sim_t *simp, int force, swarmlcm_task_drawing_t *m)
{
    const struct sim *sim = simp;
    drawing_t *d = &s->drawing;
    d->count = 0;
    memset(d->robot_rgb, 0, (size_t)sim->n * sizeof *d->robot_rgb);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        if (run->def->draw) {
            run->def->draw(run->self, simp, d);
        }
    }
    for (uint32_t k = 0; k < d->count; k++) {
        const draw_shape_t *in = &d->shapes[k];
        swarmlcm_scene_shape_t *out = &s->shapes[k];
        out->kind = (int8_t)in->kind;
        out->layer = (int8_t)in->layer;
        out->rgb = (int32_t)in->rgb;
        out->x = in->x;
        out->y = in->y;
        out->radius = in->radius;
        out->w = in->w;
        out->h = in->h;
        out->x2 = in->x2;
        out->y2 = in->y2;
        out->line = in->line;
        /* A task's label need not end in a NUL within DRAW_TEXT_MAX. */
        memcpy(s->texts[k], in->kind == DRAW_LABEL ? in->text : "", in->kind == DRAW_LABEL ? DRAW_TEXT_MAX : 1);
        s->texts[k][DRAW_TEXT_MAX] = '\0';
        out->text = s->texts[k];
    }
    int32_t n_fills = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (d->robot_rgb[i]) {
            s->fill_robot[n_fills] = (int32_t)i;
            s->fill_rgb[n_fills++] = (int32_t)d->robot_rgb[i];
        }
    }
    int32_t n_items = collect_items(s, sim);
    if (n_items < 0) {
        return -1;
    }
    m->version = SWARMLCM_TASK_DRAWING_T_VERSION;
    m->utime = 0;   /* the time is no change: compared without it */
    m->run = (int64_t)sim->seed;
    m->n_shapes = (int32_t)d->count;
    m->shapes = s->shapes;
    m->n_items = n_items;
    m->items = s->items;
    m->n_fills = n_fills;
    m->fill_robot = s->fill_robot;
    m->fill_rgb = s->fill_rgb;

    int len = swarmlcm_task_drawing_t_encoded_size(m);
    if (room(&s->now, &s->now_cap, len) != 0 || swarmlcm_task_drawing_t_encode(s->now, 0, len, m) != len) {
        return -1;
    }
    m->utime = utime_of(sim);
    if (!force && len == s->last_len && memcmp(s->now, s->last, (size_t)len) == 0) {
        return 0;
    }
    uint8_t *swap = s->last;   /* this step's bytes become the last sent */
    int swap_cap = s->last_cap;
    s->last = s->now;
    s->last_cap = s->now_cap;
    s->last_len = len;
    s->now = swap;
    s->now_cap = swap_cap;
    return 1;
}
