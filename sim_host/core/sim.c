/*
 * sim.c - one run: builds robots, obstacles and the world from a scenario,
 * and advances it one control period at a time.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"

#define PI 3.14159265358979

static void build_obstacles(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        const object_def_t *d = &sc->objects[k];
        obstacle_t *o = &sim->obstacles[k];
        o->shape = d->shape;
        o->c = v2(d->x, d->y);
        o->height = d->height;
        o->colour = d->colour;
        if (d->shape == SHAPE_CYLINDER) {
            o->r = d->radius;
            o->aabb[0] = d->x - d->radius;
            o->aabb[1] = d->y - d->radius;
            o->aabb[2] = d->x + d->radius;
            o->aabb[3] = d->y + d->radius;
        } else {
            float a = d->angle * (float)PI / 180.0f, c = cosf(a), s = sinf(a);
            float hx = d->width / 2, hy = d->depth / 2;
            const float ux[4] = { -hx, hx, hx, -hx }, uy[4] = { -hy, -hy, hy, hy };
            o->r = sqrtf(hx * hx + hy * hy);
            o->aabb[0] = o->aabb[1] = INFINITY;
            o->aabb[2] = o->aabb[3] = -INFINITY;
            for (int e = 0; e < 4; e++) {
                o->corner[e] = v2_add(o->c, v2_rot(v2(ux[e], uy[e]), c, s));
                o->aabb[0] = fminf(o->aabb[0], o->corner[e].x);
                o->aabb[1] = fminf(o->aabb[1], o->corner[e].y);
                o->aabb[2] = fmaxf(o->aabb[2], o->corner[e].x);
                o->aabb[3] = fmaxf(o->aabb[3], o->corner[e].y);
            }
        }
    }
}

/* Gap between a robot at p and obstacle o (negative when they overlap). */
static float obstacle_gap(const obstacle_t *o, vec2_t p)
{
    if (o->shape == SHAPE_CYLINDER) {
        return v2_len(v2_sub(p, o->c)) - o->r - SIM_ROBOT_RADIUS;
    }
    /* Inside the box? (corners are counter-clockwise) */
    int inside = 1;
    float best = INFINITY;
    for (int e = 0; e < 4; e++) {
        vec2_t a = o->corner[e], b = o->corner[(e + 1) & 3];
        if (v2_cross(v2_sub(b, a), v2_sub(p, a)) < 0) inside = 0;
        best = fminf(best, v2_len(v2_sub(p, geom_closest_on_segment(p, a, b))));
    }
    return inside ? -best - SIM_ROBOT_RADIUS : best - SIM_ROBOT_RADIUS;
}

static int place_robots(struct sim *sim, char err[256])
{
    const scenario_t *sc = sim->sc;
    sim_rand_t rnd;
    sim_rand_seed(&rnd, sim->seed, 0, RAND_PLACEMENT);
    float margin = SIM_ROBOT_RADIUS + 0.005f;
    float spacing = fmaxf(sc->robots.min_spacing, 2 * SIM_ROBOT_RADIUS);
    uint32_t cols = (uint32_t)ceil(sqrt((double)sim->n_swarm * sim->hw / sim->hh));
    if (cols == 0) cols = 1;

    /* The nest beacon stands still at the nest centre; place it first so
     * the others keep clear of it. */
    if (sim->beacon >= 0) {
        sim_robot_t *b = &sim->robots[sim->beacon];
        b->x = sc->nest.x;
        b->y = sc->nest.y;
        b->theta = 0.0f;
    }
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        sim_robot_t *r = &sim->robots[i];
        int placed = 0;
        for (int attempt = 0; attempt < 20000 && !placed; attempt++) {
            float x, y;
            if (sc->robots.placement == PLACE_GRID) {
                uint32_t rows = (sim->n_swarm + cols - 1) / cols;
                x = -sim->hw + (2 * sim->hw) * ((float)(i % cols) + 0.5f) / (float)cols;
                y = -sim->hh + (2 * sim->hh) * ((float)(i / cols) + 0.5f) / (float)rows;
                attempt = 20000;   /* one position only */
            } else if (sc->robots.placement == PLACE_NEST && sc->nest.enabled) {
                double rad = sc->nest.diameter / 2 - SIM_ROBOT_RADIUS;
                double u = sqrt(sim_rand_uniform(&rnd)) * (rad > 0 ? rad : 0);
                double a = 2 * PI * sim_rand_uniform(&rnd);
                x = (float)(sc->nest.x + u * cos(a));
                y = (float)(sc->nest.y + u * sin(a));
            } else {
                x = (float)((2 * sim_rand_uniform(&rnd) - 1) * (sim->hw - margin));
                y = (float)((2 * sim_rand_uniform(&rnd) - 1) * (sim->hh - margin));
            }
            int ok = fabsf(x) <= sim->hw - margin && fabsf(y) <= sim->hh - margin;
            for (uint32_t j = 0; ok && j < i; j++) {
                float dx = sim->robots[j].x - x, dy = sim->robots[j].y - y;
                ok = dx * dx + dy * dy >= spacing * spacing;
            }
            if (ok && sim->beacon >= 0) {
                float dx = sim->robots[sim->beacon].x - x, dy = sim->robots[sim->beacon].y - y;
                ok = dx * dx + dy * dy >= spacing * spacing;
            }
            for (uint32_t k = 0; ok && k < sim->n_obstacles; k++) {
                ok = obstacle_gap(&sim->obstacles[k], v2(x, y)) >= 0.005f;
            }
            if (ok) {
                r->x = x;
                r->y = y;
                r->theta = (float)(2 * PI * sim_rand_uniform(&rnd) - PI);
                placed = 1;
            }
        }
        if (!placed) {
            snprintf(err, 256, "cannot place robot %u of %u (placement %s): no free spot; "
                     "enlarge the arena or nest, or use fewer robots",
                     i + 1, sim->n_swarm, sc->robots.placement == PLACE_GRID ? "grid"
                     : sc->robots.placement == PLACE_NEST ? "nest" : "random");
            return -1;
        }
    }
    return 0;
}

sim_t *sim_create(const scenario_t *sc, uint64_t seed, char err[256])
{
    struct sim *sim = calloc(1, sizeof *sim);
    if (!sim) {
        snprintf(err, 256, "out of memory");
        return NULL;
    }
    sim->sc = sc;
    sim->seed = seed;
    sim->dt = sc->control_period_ms / 1000.0f;
    sim->hw = sc->arena.width / 2;
    sim->hh = sc->arena.height / 2;
    sim->n_swarm = sc->robots.count;
    sim->beacon = -1;
    sim->n_obstacles = sc->object_count;
    sim->ctrl = controllers_find(sc->controller.name);
    sim->metrics.min_wall_clearance_m = INFINITY;
    sim->foraging_on = sc->foraging.enabled;
    if (sim->foraging_on && sc->foraging.information == INFO_BEACON) {
        sim->beacon_ctrl = controllers_find("nest_beacon");
        sim->beacon = (int32_t)sim->n_swarm;
    }
    sim->n = sim->n_swarm + (sim->beacon >= 0 ? 1u : 0u);
    if (!sim->ctrl || (sim->beacon >= 0 && !sim->beacon_ctrl)) {
        snprintf(err, 256, "unknown controller '%s'", sim->ctrl ? "nest_beacon" : sc->controller.name);
        free(sim);
        return NULL;
    }
    /* Each robot's params: the scenario's, then what the task tells it. */
    memcpy(sim->params.bytes, sc->controller.params.bytes, sizeof sim->params.bytes);
    if (sim->ctrl->configure) {
        sim->ctrl->configure(sim->params.bytes, sc);
    }
    if (sim->beacon_ctrl) {
        sim->beacon_ctrl->default_params(sim->beacon_params.bytes);
        if (sim->beacon_ctrl->configure) {
            sim->beacon_ctrl->configure(sim->beacon_params.bytes, sc);
        }
    }
    size_t n = sim->n ? sim->n : 1, no = sim->n_obstacles ? sim->n_obstacles : 1;
    sim->robots = calloc(n, sizeof *sim->robots);
    size_t state_size = sim->ctrl->state_size;
    if (sim->beacon_ctrl && sim->beacon_ctrl->state_size > state_size) {
        state_size = sim->beacon_ctrl->state_size;
    }
    state_size = (state_size + 15u) & ~(size_t)15u;   /* keep every state aligned */
    sim->ctrl_states = calloc(n, state_size ? state_size : 1);
    sim->px = calloc(n, sizeof *sim->px);
    sim->py = calloc(n, sizeof *sim->py);
    sim->obstacles = calloc(no, sizeof *sim->obstacles);
    sim->obstacle_mark = calloc(no, sizeof *sim->obstacle_mark);
    /* Cells a little larger than the IR reach: an IR query touches at
     * most 3 x 3 cells. */
    float cell = fmaxf(0.5f, 2 * SIM_ROBOT_RADIUS + sc->ir.range + 0.04f);
    if (!sim->robots || !sim->ctrl_states || !sim->px || !sim->py || !sim->obstacles || !sim->obstacle_mark
        || grid_init(&sim->robot_grid, -sim->hw, -sim->hh, 2 * sim->hw, 2 * sim->hh, cell) != 0
        || grid_init(&sim->obstacle_grid, -sim->hw, -sim->hh, 2 * sim->hw, 2 * sim->hh, cell) != 0) {
        snprintf(err, 256, "out of memory for %u robots", sim->n);
        sim_destroy(sim);
        return NULL;
    }
    build_obstacles(sim);
    float (*boxes)[4] = calloc(no, sizeof *boxes);
    int bad = !boxes;
    for (uint32_t k = 0; !bad && k < sim->n_obstacles; k++) {
        memcpy(boxes[k], sim->obstacles[k].aabb, sizeof boxes[k]);
    }
    bad = bad || grid_build_boxes(&sim->obstacle_grid, (const float (*)[4])boxes, sim->n_obstacles) != 0;
    free(boxes);
    if (bad) {
        snprintf(err, 256, "out of memory for %u obstacles", sim->n_obstacles);
        sim_destroy(sim);
        return NULL;
    }
    if (place_robots(sim, err) != 0) {
        sim_destroy(sim);
        return NULL;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *r = &sim->robots[i];
        r->hal.sim = sim;
        r->hal.index = i;
        r->ircom_tx = -1;
        sim->px[i] = r->x;
        sim->py[i] = r->y;
        sim_rand_seed(&r->noise, seed, i, RAND_SENSORS);
        sim_rand_seed(&r->ircom_rand, seed, i, RAND_IRCOM);
        sim_rand_seed(&r->wheel_rand, seed, i, RAND_WHEELS);
        int is_beacon = (int32_t)i == sim->beacon;
        r->ctrl_desc = is_beacon ? sim->beacon_ctrl : sim->ctrl;
        r->ctrl = r->ctrl_desc->state_size ? sim->ctrl_states + (size_t)i * state_size : NULL;
        if (r->ctrl) {
            r->ctrl_desc->init(r->ctrl, is_beacon ? sim->beacon_params.bytes : sim->params.bytes,
                               sim_rand_seed32(seed, i, RAND_CONTROLLER));
        }
    }
    if (world_create(sim, err) != 0 || grid_build_points(&sim->robot_grid, sim->px, sim->py, sim->n) != 0
        || (sim->foraging_on && foraging_init(sim, err) != 0)) {
        sim_destroy(sim);
        return NULL;
    }
    return sim;
}

void sim_destroy(sim_t *sim)
{
    if (!sim) {
        return;
    }
    world_destroy(sim);
    foraging_free(sim);
    grid_free(&sim->robot_grid);
    grid_free(&sim->obstacle_grid);
    free(sim->robots);
    free(sim->ctrl_states);
    free(sim->px);
    free(sim->py);
    free(sim->obstacles);
    free(sim->obstacle_mark);
    free(sim);
}

void sim_step(sim_t *sim)
{
    if (sim->foraging_on && sim->beacon < 0) {
        foraging_broadcast_truth(sim);
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *r = &sim->robots[i];
        if (r->ctrl) {
            r->ctrl_desc->step(r->ctrl, &r->hal);
        }
    }
    ircom_deliver(sim);
    if (sim->foraging_on) {
        foraging_release(sim);
    }
    world_drive(sim);
    world_advance(sim);
    world_read_poses(sim);
    grid_build_points(&sim->robot_grid, sim->px, sim->py, sim->n);
    if (sim->foraging_on) {
        foraging_update(sim);
    }
    sim->step++;
}

uint32_t sim_gather_obstacles(struct sim *sim, float minx, float miny, float maxx, float maxy,
                              uint32_t *out, uint32_t max)
{
    if (sim->n_obstacles == 0) {
        return 0;
    }
    const grid_t *g = &sim->obstacle_grid;
    int32_t cx0, cy0, cx1, cy1;
    uint32_t n = 0, stamp = ++sim->mark_stamp;
    if (stamp == 0) {   /* wrapped: clear the marks once every 2^32 queries */
        memset(sim->obstacle_mark, 0, sim->n_obstacles * sizeof *sim->obstacle_mark);
        stamp = sim->mark_stamp = 1;
    }
    grid_range(g, minx, miny, maxx, maxy, &cx0, &cy0, &cx1, &cy1);
    for (int32_t cy = cy0; cy <= cy1; cy++) {
        for (int32_t cx = cx0; cx <= cx1; cx++) {
            int32_t c = cy * g->nx + cx;
            for (uint32_t k = g->start[c]; k < g->start[c + 1]; k++) {
                uint32_t o = g->items[k];
                const float *b = sim->obstacles[o].aabb;
                if (sim->obstacle_mark[o] == stamp || b[0] > maxx || b[2] < minx || b[1] > maxy || b[3] < miny) {
                    continue;
                }
                sim->obstacle_mark[o] = stamp;
                if (n < max) {
                    out[n++] = o;
                }
            }
        }
    }
    return n;
}

uint32_t sim_gather_robots(const struct sim *sim, float minx, float miny, float maxx, float maxy,
                           uint32_t *out, uint32_t max)
{
    const grid_t *g = &sim->robot_grid;
    int32_t cx0, cy0, cx1, cy1;
    uint32_t n = 0;
    grid_range(g, minx, miny, maxx, maxy, &cx0, &cy0, &cx1, &cy1);
    for (int32_t cy = cy0; cy <= cy1; cy++) {
        for (int32_t cx = cx0; cx <= cx1; cx++) {
            int32_t c = cy * g->nx + cx;
            for (uint32_t k = g->start[c]; k < g->start[c + 1]; k++) {
                uint32_t j = g->items[k];
                if (sim->px[j] >= minx && sim->px[j] <= maxx && sim->py[j] >= miny && sim->py[j] <= maxy
                    && n < max) {
                    out[n++] = j;
                }
            }
        }
    }
    return n;
}

uint64_t sim_step_count(const sim_t *sim) { return sim->step; }
uint32_t sim_robot_count(const sim_t *sim) { return sim->n; }
uint32_t sim_swarm_count(const sim_t *sim) { return sim->n_swarm; }
int32_t sim_beacon_index(const sim_t *sim) { return sim->beacon; }
const scenario_t *sim_scenario(const sim_t *sim) { return sim->sc; }
hal_t *sim_robot_hal(sim_t *sim, uint32_t i) { return &sim->robots[i].hal; }
void *sim_robot_controller(sim_t *sim, uint32_t i) { return sim->robots[i].ctrl; }
const sim_metrics_t *sim_metrics(const sim_t *sim) { return &sim->metrics; }
const struct foraging *sim_foraging(const sim_t *sim) { return sim->foraging_on ? &sim->forage : NULL; }
uint16_t sim_robot_leds(const sim_t *sim, uint32_t i) { return sim->robots[i].leds; }

void sim_robot_pose(const sim_t *sim, uint32_t i, double *x, double *y, double *theta)
{
    const sim_robot_t *r = &sim->robots[i];
    *x = r->x;
    *y = r->y;
    *theta = r->theta;
}

void sim_set_robot_pose(sim_t *sim, uint32_t i, double x, double y, double theta)
{
    sim_robot_t *r = &sim->robots[i];
    r->x = (float)x;
    r->y = (float)y;
    r->theta = (float)theta;
    sim->px[i] = r->x;
    sim->py[i] = r->y;
    b2Body_SetTransform(r->body, (b2Vec2){ r->x, r->y }, b2MakeRot(r->theta));
    grid_build_points(&sim->robot_grid, sim->px, sim->py, sim->n);
    /* Sensors must see the new pose even within this step. */
    r->ir_stamp = r->ambient_stamp = r->camera_stamp = 0;
}

char sim_robot_task_state(const sim_t *sim, uint32_t i)
{
    const sim_robot_t *r = &sim->robots[i];
    if ((int32_t)i == sim->beacon) {
        return 'B';
    }
    return (r->ctrl && r->ctrl_desc->task_state) ? r->ctrl_desc->task_state(r->ctrl) : 0;
}

uint64_t sim_oae_total(const sim_t *sim)
{
    uint64_t total = 0;
    for (uint32_t i = 0; i < sim->n_swarm; i++) {
        if (sim->robots[i].ctrl && sim->ctrl->oae_count) {
            total += sim->ctrl->oae_count(sim->robots[i].ctrl);
        }
    }
    return total;
}

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t k = 0; k < n; k++) {
        h = (h ^ b[k]) * UINT64_C(0x100000001b3);
    }
    return h;
}

uint64_t sim_state_hash(const sim_t *sim)
{
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    h = fnv(h, &sim->step, sizeof sim->step);
    for (uint32_t i = 0; i < sim->n; i++) {
        const sim_robot_t *r = &sim->robots[i];
        h = fnv(h, &r->x, sizeof r->x);
        h = fnv(h, &r->y, sizeof r->y);
        h = fnv(h, &r->theta, sizeof r->theta);
        h = fnv(h, &r->steps_left, sizeof r->steps_left);
        h = fnv(h, &r->steps_right, sizeof r->steps_right);
    }
    return h;
}
