/*
 * sim_render.c - a picture of a running simulation: the arena, obstacles,
 * lights and robots from the core, the tasks' items as the camera sees
 * them, and each task's drawing (drawing.h) as data.
 */
#include "sim_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim_internal.h"
#include "units.h"

/* Room for the shapes of every task's drawing of one step. */
#define SHAPES_MAX 4096

int sim_render_png(const sim_t *simp, render_ctx_t *ctx, const char *png_path, char *err)
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
    render_robot_t *robots = calloc(n ? n : 1, sizeof *robots);
    render_object_t *objects = calloc(sc->object_count + n_items + 1, sizeof *objects);
    drawing_t drawing = { calloc(SHAPES_MAX, sizeof(draw_shape_t)), 0, SHAPES_MAX,
                          calloc(n ? n : 1, sizeof(uint32_t)), n };
    render_light_t lights[SCENARIO_MAX_LIGHTS];
    if (!robots || !objects || !drawing.shapes || !drawing.robot_rgb) {
        free(robots);
        free(objects);
        free(drawing.shapes);
        free(drawing.robot_rgb);
        snprintf(err, RENDER_ERR_MAX, "%s: out of memory", png_path);
        return -1;
    }
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        if (run->def->draw) {
            run->def->draw(run->self, simp, &drawing);
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        const sim_robot_t *r = &sim->robots[i];
        robots[i].x = r->x;
        robots[i].y = r->y;
        robots[i].theta = r->theta;
        robots[i].leds = (uint8_t)(r->leds & 0xffu);
        robots[i].body_led = (uint8_t)((r->leds >> HAL_LED_WORD_BODY_BIT) & 1u);
        robots[i].front_led = (uint8_t)((r->leds >> HAL_LED_WORD_FRONT_BIT) & 1u);
        robots[i].fill_rgb = drawing.robot_rgb[i];
    }
    for (uint32_t k = 0; k < sc->object_count; k++) {
        const object_def_t *d = &sc->objects[k];
        render_object_t o = { d->shape, d->x, d->y, d->radius, d->width, d->depth, d->angle, d->colour };
        objects[k] = o;
    }
    uint32_t n_objects = sc->object_count;
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        for (uint32_t k = 0; k < item_count[t]; k++) {
            const sim_item_t *it = &items[t][k];
            if (isfinite(it->x) && it->colour != HAL_COLOUR_NONE) {
                render_object_t o = { SHAPE_CYLINDER, it->x, it->y, it->radius, 0, 0, 0, it->colour };
                objects[n_objects++] = o;
            }
        }
    }
    for (uint32_t l = 0; l < sc->light_count; l++) {
        lights[l].x = sc->lights[l].x;
        lights[l].y = sc->lights[l].y;
    }
    render_scene_t scene = {
        .arena_w = sc->arena.width, .arena_h = sc->arena.height, .wall = sc->arena.wall_thickness,
        .shapes = drawing.shapes, .shape_count = drawing.count,
        .robots = robots, .robot_count = n, .robot_radius = EPUCK_BODY_RADIUS_M,
        .objects = objects, .object_count = n_objects, .lights = lights,
        .light_count = sc->light_count, .time_s = sim_time_s(simp),
    };
    int rc = render_scene_png(ctx, &scene, png_path, err);
    free(robots);
    free(objects);
    free(drawing.shapes);
    free(drawing.robot_rgb);
    return rc;
}
