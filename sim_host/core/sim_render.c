/*
 * sim_render.c - a picture of a running simulation: the arena, obstacles,
 * lights and robots from the core, the tasks' items as the camera sees
 * them, each task's drawing (drawing.h) as data, and the overlay: the
 * simulated time, the run's legend (legend.h) and the robots' ids.  Only reads the
 * simulation (a task's draw gets its state as const).
 */
#include "sim_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "legend.h"
#include "sim_internal.h"
#include "units.h"

/* Room for the shapes of every task's drawing of one step. */
#define SHAPES_MAX 4096

/* A scene and the memory behind it. */
typedef struct sim_scene {
    render_scene_t scene;
    render_robot_t *robots;
    render_object_t *objects;
    drawing_t drawing;
    render_light_t lights[SCENARIO_MAX_LIGHTS];
    draw_key_t keys[LEGEND_KEYS_MAX];
} sim_scene_t;

static void scene_free(sim_scene_t *ss)
{
    free(ss->robots);
    free(ss->objects);
    free(ss->drawing.shapes);
    free(ss->drawing.robot_rgb);
}

/* Fills ss from the current state of sim.  0, or -1 out of memory. */
static int scene_build(const sim_t *simp, sim_scene_t *ss)
{
    const struct sim *sim = simp;
    const scenario_t *sc = sim->sc;
    uint32_t n = sim->n, n_items = 0;
    const sim_item_t *items[SCENARIO_MAX_TASKS];
    uint32_t item_count[SCENARIO_MAX_TASKS];
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        item_count[t] = run->def->items ? run->def->items(run->self, &items[t]) : 0;
        n_items += item_count[t];
    }
    ss->robots = calloc(n ? n : 1, sizeof *ss->robots);
    ss->objects = calloc(sim->n_obstacles + n_items + 1, sizeof *ss->objects);
    ss->drawing = (drawing_t){ calloc(SHAPES_MAX, sizeof(draw_shape_t)), 0, SHAPES_MAX,
                               calloc(n ? n : 1, sizeof(uint32_t)), n };
    if (!ss->robots || !ss->objects || !ss->drawing.shapes || !ss->drawing.robot_rgb) {
        scene_free(ss);
        return -1;
    }
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        if (run->def->draw) {
            run->def->draw(run->self, simp, &ss->drawing);
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        const sim_robot_t *r = &sim->robots[i];
        render_robot_t *rb = &ss->robots[i];
        rb->x = r->x;
        rb->y = r->y;
        rb->theta = r->theta;
        rb->leds = (uint8_t)(r->leds & 0xffu);
        rb->body_led = (uint8_t)((r->leds >> HAL_LED_WORD_BODY_BIT) & 1u);
        rb->front_led = (uint8_t)((r->leds >> HAL_LED_WORD_FRONT_BIT) & 1u);
        rb->fill_rgb = ss->drawing.robot_rgb[i];
    }
    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        const object_def_t *d = &sim->objects[k];   /* the scenario's and the random cylinders */
        render_object_t o = { d->shape, d->x, d->y, d->radius, d->width, d->depth, d->angle, d->colour };
        ss->objects[k] = o;
    }
    uint32_t n_objects = sim->n_obstacles;
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        for (uint32_t k = 0; k < item_count[t]; k++) {
            const sim_item_t *it = &items[t][k];
            if (isfinite(it->x) && it->colour != HAL_COLOUR_NONE) {
                render_object_t o = { SHAPE_CYLINDER, it->x, it->y, it->radius, 0, 0, 0, it->colour };
                ss->objects[n_objects++] = o;
            }
        }
    }
    for (uint32_t l = 0; l < sc->light_count; l++) {
        ss->lights[l].x = sc->lights[l].x;
        ss->lights[l].y = sc->lights[l].y;
    }
    ss->scene = (render_scene_t){
        .arena_w = sc->arena.width, .arena_h = sc->arena.height, .wall = sc->arena.wall_thickness,
        .shapes = ss->drawing.shapes, .shape_count = ss->drawing.count,
        .robots = ss->robots, .robot_count = n, .robot_radius = EPUCK_BODY_RADIUS_M,
        .objects = ss->objects, .object_count = n_objects, .lights = ss->lights,
        .light_count = sc->light_count, .time_s = sim_time_s(simp),
        .overlay = 1, .legend = ss->keys, .legend_count = legend_collect(simp, ss->keys),
    };
    return 0;
}

int sim_render_png(const sim_t *sim, render_ctx_t *ctx, const char *png_path, char *err)
{
    sim_scene_t ss;
    if (scene_build(sim, &ss) != 0) {
        snprintf(err, SIM_ERR_MAX, "%s: out of memory", png_path);
        return -1;
    }
    int rc = render_scene_png(ctx, &ss.scene, png_path, err);
    scene_free(&ss);
    return rc;
}

int sim_render_rgb(const sim_t *sim, render_ctx_t *ctx, uint8_t *rgb, char *err)
{
    sim_scene_t ss;
    if (scene_build(sim, &ss) != 0) {
        snprintf(err, SIM_ERR_MAX, "frame: out of memory");
        return -1;
    }
    int rc = render_scene_rgb(ctx, &ss.scene, rgb, err);
    scene_free(&ss);
    return rc;
}

int sim_render_world_to_pixel(const sim_t *sim, const render_ctx_t *ctx, float x, float y, float *col,
                              float *row)
{
    sim_scene_t ss;
    if (scene_build(sim, &ss) != 0)
        return -1;
    int rc = render_world_to_pixel(ctx, &ss.scene, x, y, col, row);
    scene_free(&ss);
    return rc;
}
