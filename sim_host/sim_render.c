#include "sim_render.h"

#include <stdio.h>
#include <stdlib.h>

int sim_render_png(const sim_t *sim, render_ctx_t *ctx, const char *png_path, char *err)
{
    const scenario_t *sc = sim_scenario(sim);
    uint32_t n = sim_robot_count(sim);
    render_robot_t *robots = calloc(n ? n : 1, sizeof *robots);
    render_object_t *objects = calloc(sc->object_count ? sc->object_count : 1, sizeof *objects);
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
    }
    for (uint32_t k = 0; k < sc->object_count; k++) {
        const object_def_t *d = &sc->objects[k];
        render_object_t o = { d->shape, d->x, d->y, d->radius, d->width, d->depth, d->angle, d->colour };
        objects[k] = o;
    }
    for (uint32_t l = 0; l < sc->light_count; l++) {
        lights[l].x = sc->lights[l].x;
        lights[l].y = sc->lights[l].y;
    }
    render_scene_t scene = {
        .arena_w = sc->arena.width, .arena_h = sc->arena.height, .wall = sc->arena.wall_thickness,
        .nest_enabled = sc->nest.enabled, .nest_x = sc->nest.x, .nest_y = sc->nest.y,
        .nest_d = sc->nest.diameter, .robots = robots, .robot_count = n, .robot_radius = SIM_ROBOT_RADIUS,
        .objects = objects, .object_count = sc->object_count, .lights = lights,
        .light_count = sc->light_count,
        .time_s = (double)sim_step_count(sim) * sc->control_period_ms / 1000.0,
    };
    int rc = render_scene_png(ctx, &scene, png_path, err);
    free(robots);
    free(objects);
    return rc;
}
