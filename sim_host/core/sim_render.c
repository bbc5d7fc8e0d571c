#include "sim_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/foraging/foraging.h"

int sim_render_png(const sim_t *sim, render_ctx_t *ctx, const char *png_path, char *err)
{
    const scenario_t *sc = sim_scenario(sim);
    uint32_t n = sim_robot_count(sim);
    const foraging_t *food = sim_foraging(sim);
    uint32_t n_tokens = food ? food->n_tokens : 0;
    render_robot_t *robots = calloc(n ? n : 1, sizeof *robots);
    render_object_t *objects = calloc(sc->object_count + n_tokens + 1, sizeof *objects);
    render_light_t lights[SCENARIO_MAX_LIGHTS];
    if (!robots || !objects) {
        free(robots);
        free(objects);
        snprintf(err, RENDER_ERR_MAX, "%s: out of memory", png_path);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++) {
        double x, y, t;
        uint16_t leds = sim_robot_leds(sim, i);
        sim_robot_pose(sim, i, &x, &y, &t);
        robots[i].x = (float)x;
        robots[i].y = (float)y;
        robots[i].theta = (float)t;
        robots[i].leds = (uint8_t)(leds & 0xffu);
        robots[i].body_led = (uint8_t)((leds >> 8) & 1u);
        robots[i].front_led = (uint8_t)((leds >> 9) & 1u);
        /* Seed 000's task states: searching green, returning yellow, the
         * nest beacon blue, waiting plain. */
        switch (sim_robot_task_state(sim, i)) {
        case 'S': robots[i].highlight = 2; break;
        case 'R': robots[i].highlight = 4; break;
        case 'B': robots[i].highlight = 3; break;
        default: break;
        }
    }
    for (uint32_t k = 0; k < sc->object_count; k++) {
        const object_def_t *d = &sc->objects[k];
        render_object_t o = { d->shape, d->x, d->y, d->radius, d->width, d->depth, d->angle, d->colour };
        objects[k] = o;
    }
    uint32_t n_objects = sc->object_count;
    for (uint32_t k = 0; k < n_tokens; k++) {
        const food_token_t *t = &food->tokens[k];
        if (isfinite(t->x)) {
            render_object_t o = { 0, t->x, t->y, sc->foraging.token_radius, 0, 0, 0, 1 /* red */ };
            objects[n_objects++] = o;
        }
    }
    for (uint32_t l = 0; l < sc->light_count; l++) {
        lights[l].x = sc->lights[l].x;
        lights[l].y = sc->lights[l].y;
    }
    render_scene_t scene = {
        .arena_w = sc->arena.width, .arena_h = sc->arena.height, .wall = sc->arena.wall_thickness,
        .nest_enabled = sc->nest.enabled, .nest_x = sc->nest.x, .nest_y = sc->nest.y,
        .nest_d = sc->nest.diameter, .robots = robots, .robot_count = n, .robot_radius = SIM_ROBOT_RADIUS,
        .objects = objects, .object_count = n_objects, .lights = lights,
        .light_count = sc->light_count,
        .time_s = (double)sim_step_count(sim) * sc->control_period_ms / 1000.0,
    };
    int rc = render_scene_png(ctx, &scene, png_path, err);
    free(robots);
    free(objects);
    return rc;
}
