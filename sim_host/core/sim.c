/*
 * sim.c - one run: builds the groups' robots, obstacles, the world and the
 * tasks from a scenario, and advances it one control period at a time in
 * the phases task.h describes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool.h"
#include "sim_internal.h"
#include "units.h"

static void build_obstacles(struct sim *sim)
{
    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        const object_def_t *d = &sim->objects[k];
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
            float a = d->angle * (float)UNITS_PI / 180.0f, c = cosf(a), s = sinf(a);
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

/* Every group's robots and their controllers, initialised with the
 * group's params (the scenario's, then its policy, then what the tasks
 * tell it). */
static int build_robots(struct sim *sim, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    uint32_t i = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        const controller_def_t *def = grp->def;
        scenario_params_t params = grp->params;
        if (def->set_policy) {
            def->set_policy(params.bytes, grp->policy_index);
        }
        for (uint32_t t = 0; t < sc->task_count; t++) {
            const task_def_t *task = sc->tasks[t].def;
            if (task->configure) {
                task->configure(sc->tasks[t].config.bytes, sc, grp, params.bytes);
            }
        }
        /* Each state on its own 16-byte boundary. */
        size_t stride = (def->state_size + 15u) & ~(size_t)15u;
        if (stride && grp->count) {
            sim->ctrl_blocks[g] = calloc(grp->count, stride);
            if (!sim->ctrl_blocks[g]) {
                snprintf(err, SIM_ERR_MAX, "out of memory for the controllers of group %u", g);
                return -1;
            }
        }
        for (uint32_t k = 0; k < grp->count; k++, i++) {
            sim_robot_t *r = &sim->robots[i];
            r->hal.sim = sim;
            r->hal.index = i;
            r->id = (uint16_t)(grp->first_id == SCENARIO_IDS_BY_INDEX ? i : grp->first_id + k);
            r->group = g;
            r->def = def;
            r->step = def->step;
            r->moves = grp->moves;
            r->ctrl = stride ? (uint8_t *)sim->ctrl_blocks[g] + (size_t)k * stride : NULL;
            if (r->ctrl) {
                def->init(r->ctrl, params.bytes, sim_rand_seed32(sim->seed, i, RAND_CONTROLLER));
            }
        }
    }
    return 0;
}

/* Every distinct counter name the groups' controllers declare, in order
 * (one total per name, over every controller that counts it), and each
 * group's counters with the total they add to. */
static void find_counters(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const controller_def_t *def = sc->groups[g].def;
        for (const observable_t *o = def->observables; o && o->name; o++) {
            if (o->kind != OBS_COUNTER) {
                continue;
            }
            uint32_t k = 0;
            while (k < sim->n_counters && strcmp(sim->counters[k].name, o->name) != 0) {
                k++;
            }
            if (k == SIM_MAX_COUNTERS) {
                continue;
            }
            if (sim->n_group_counters[g] < SIM_MAX_COUNTERS) {
                sim->group_counters[g][sim->n_group_counters[g]++] =
                    (sim_group_counter_t){ .obs = o, .slot = (uint8_t)k };
            }
            if (k < sim->n_counters) {
                continue;
            }
            sim_counter_t *c = &sim->counters[sim->n_counters++];
            c->name = o->name;
            c->unit = o->unit ? o->unit : "";
            snprintf(c->total_doc, sizeof c->total_doc, "summed over the robots that count it: %.120s",
                     o->doc ? o->doc : o->name);
            snprintf(c->total_key, sizeof c->total_key, "%.40s_total", o->name);
            snprintf(c->per_robot_key, sizeof c->per_robot_key, "%.40s_per_robot", o->name);
        }
    }
}

void sim_robot_platform(const struct sim *sim, uint32_t i, uint64_t since, robot_telemetry_platform_t *p)
{
    const sim_robot_t *r = &sim->robots[i];
    p->wheel_left = p->wheel_right = 0;
    p->leds = (int16_t)r->leds;
    p->ir_max = -1;            /* the models fill what they read at `since` or later */
    p->ir_max_index = -1;
    p->ambient_min = -1;
    p->blobs = -1;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim->models[id].def->platform) {
            sim->models[id].def->platform(sim, sim->models[id].self, i, since, p);
        }
    }
}

void sim_robot_inspect(const struct sim *sim, uint32_t i, model_inspect_t *out)
{
    memset(out, 0, sizeof *out);
    out->n_blobs = -1;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim->models[id].def->inspect) {
            sim->models[id].def->inspect(sim, sim->models[id].self, i, out);
        }
    }
}

/* Robots take a few microseconds each: chunks of 64 keep the pool's
 * locking small beside the work. */
#define CONTROL_CHUNK 64u

/* pool_fn: robots step_order[begin .. end) run their controllers on
 * `worker`, their sensors in its scratch. */
static void step_robots(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    struct sim *sim = ctx;
    for (uint32_t k = begin; k < end; k++) {
        uint32_t i = sim->step_order[k];
        sim_robot_t *r = &sim->robots[i];
        if (r->ctrl && !sim_robot_halted(sim, i)) {
            r->hal.worker = worker;
            r->step(r->ctrl, &r->hal);
            for (uint32_t h = 0; h < sim->n_after_robot; h++) {
                const sim_model_run_t *m = &sim->models[sim->after_robot[h]];
                m->def->after_robot(sim, m->self, i);
            }
            r->hal.worker = 0;
        }
    }
}

/* ---------------------------------------------------------------- models */

/* 64-byte aligned, zero-filled: a robot's element never shares a cache
 * line with another model's. */
static void *alloc_zeroed(size_t bytes)
{
    size_t size = (bytes + 63u) & ~(size_t)63u;
    void *p = aligned_alloc(64, size ? size : 64);
    if (p) {
        memset(p, 0, size ? size : 64);
    }
    return p;
}

/* Every model's arrays and scratch, then its create, in list order. */
static int create_models(struct sim *sim, char err[SIM_ERR_MAX])
{
    uint32_t workers = pool_threads(sim->pool);
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        sim_model_run_t *m = &sim->models[id];
        m->def = sim_models[id];
        m->config = scenario_model_config(sim->sc, (sim_model_id_t)id);
        if (m->def->layout) {
            m->def->layout(m->config, sim->sc, &m->layout);
        }
        SIM_ASSERT(m->layout.arrays <= MODEL_MAX_ARRAYS);
        for (uint32_t k = 0; k < m->layout.arrays; k++) {
            if (!(m->array[k] = alloc_zeroed((size_t)sim->n * m->layout.elem_size[k]))) {
                snprintf(err, SIM_ERR_MAX, "out of memory for the %s model's state of %u robots", m->def->name, sim->n);
                return -1;
            }
        }
        if (m->layout.scratch_size) {
            m->scratch_stride = (m->layout.scratch_size + 63u) & ~(size_t)63u;
            if (!(m->scratch = alloc_zeroed(workers * m->scratch_stride))) {
                snprintf(err, SIM_ERR_MAX, "out of memory for the %s model's working memory", m->def->name);
                return -1;
            }
        }
    }
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        sim_model_run_t *m = &sim->models[id];
        m->created = 1;
        if (m->def->create && m->def->create(sim, m->config, &m->self, err) != 0) {
            return -1;
        }
    }
    return 0;
}

static void destroy_models(struct sim *sim)
{
    for (uint32_t id = SIM_MODEL_COUNT; id-- > 0;) {
        sim_model_run_t *m = &sim->models[id];
        if (m->created && m->def->destroy) {
            m->def->destroy(m->self);
        }
        for (uint32_t k = 0; k < MODEL_MAX_ARRAYS; k++) {
            free(m->array[k]);
        }
        free(m->scratch);
    }
}

int sim_robot_halted(const struct sim *sim, uint32_t i)
{
    for (uint32_t k = 0; k < sim->n_halts; k++) {
        const sim_model_run_t *m = &sim->models[sim->halts[k]];
        if (m->def->halts(sim, m->self, i)) {
            return 1;
        }
    }
    return 0;
}

typedef enum phase { PHASE_BEGIN, PHASE_BEFORE_CONTROL, PHASE_AFTER_CONTROL, PHASE_DRIVE, PHASE_END } phase_t;
_Static_assert(PHASE_END + 1 == SIM_PHASES, "SIM_PHASES counts phase_t");

static void (*phase_hook(const model_def_t *d, phase_t p))(sim_t *, void *)
{
    switch (p) {
    case PHASE_BEGIN: return d->begin_step;
    case PHASE_BEFORE_CONTROL: return d->before_control;
    case PHASE_AFTER_CONTROL: return d->after_control;
    case PHASE_DRIVE: return d->drive;
    default: return d->end_step;
    }
}

/* Which models take part in each phase and per-robot hook, in list order. */
static void find_hooks(struct sim *sim)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const model_def_t *d = sim->models[id].def;
        for (phase_t p = PHASE_BEGIN; p <= PHASE_END; p++) {
            if (phase_hook(d, p)) {
                sim->phase_model[p][sim->n_phase[p]++] = (uint8_t)id;
            }
        }
        if (d->after_robot) {
            sim->after_robot[sim->n_after_robot++] = (uint8_t)id;
        }
        if (d->halts) {
            sim->halts[sim->n_halts++] = (uint8_t)id;
        }
    }
}

/* One phase's hook of every model that takes part, in list order. */
static void run_phase(struct sim *sim, phase_t p)
{
    for (uint32_t k = 0; k < sim->n_phase[p]; k++) {
        const sim_model_run_t *m = &sim->models[sim->phase_model[p][k]];
        phase_hook(m->def, p)(sim, m->self);
    }
}

static int models_serial(const struct sim *sim)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const sim_model_run_t *m = &sim->models[id];
        if (m->def->serial && m->def->serial(sim, m->self)) {
            return 1;
        }
    }
    return 0;
}

static int create_tasks(struct sim *sim, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    for (uint32_t t = 0; t < sc->task_count; t++) {
        const task_def_t *def = sc->tasks[t].def;
        sim_task_run_t *run = &sim->tasks[sim->n_tasks];
        run->def = def;
        run->self = def->create ? def->create(sim, sc->tasks[t].config.bytes, err) : NULL;
        if (def->create && !run->self) {
            return -1;
        }
        sim->n_tasks++;
    }
    return 0;
}

/* The pool and one scratch per worker (sim_internal.h). */
static int create_workers(struct sim *sim, uint32_t threads)
{
    size_t n = sim->n ? sim->n : 1, no = sim->n_obstacles ? sim->n_obstacles : 1;
    sim->pool = pool_create(threads);
    if (!sim->pool) {
        return -1;
    }
    uint32_t workers = pool_threads(sim->pool);
    sim->scratch = calloc(workers, sizeof *sim->scratch);
    if (!sim->scratch) {
        return -1;
    }
    for (uint32_t w = 0; w < workers; w++) {
        sim->scratch[w].obstacle_mark = calloc(no, sizeof *sim->scratch[w].obstacle_mark);
        sim->scratch[w].robots = malloc(n * sizeof *sim->scratch[w].robots);
        if (!sim->scratch[w].obstacle_mark || !sim->scratch[w].robots) {
            return -1;
        }
    }
    return 0;
}

/* Box2D v3's memory per body, bytes: a dynamic body with one circle
 * shape (b2Body, its sim and state, the shape, its broad-phase proxy and
 * tree node, its share of the contacts and islands at the benchmark
 * worlds' density), and per static shape.  Measured on random walks at 20
 * robots/m^2: swarmsim's peak resident memory grew by 2,823 B a robot from
 * 10,000 to 100,000 robots (outputs and the runner included), a run's own
 * growth in test_sim is 2,330 B a robot at 20,000; with this constant the
 * estimate says 2,567 B a robot, between the two (test_sim keeps it
 * within 25 % of the run's growth). */
#define BOX2D_BYTES_PER_BODY 1800u
#define BOX2D_BYTES_PER_SHAPE 400u
/* The sim itself, the pool, the scenario's copy of the objects... */
#define RUN_FIXED_BYTES (256u * 1024u)

void sim_memory_estimate(const scenario_t *sc, uint32_t threads, sim_memory_t *out)
{
    uint64_t n = scenario_robot_count(sc), no = (uint64_t)sc->object_count + sc->random_cylinders.count;
    uint64_t w = threads ? threads : 1;
    uint64_t robots = n * (sizeof(sim_robot_t) + 2 * sizeof(float) + sizeof(uint32_t) + sizeof(world_velocity_t)
                           + sizeof(uint32_t) + w * sizeof(uint32_t) + BOX2D_BYTES_PER_BODY
                           + sizeof(uint32_t) /* the robot grid's point_cell */);
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const controller_def_t *def = sc->groups[g].def;
        robots += (uint64_t)sc->groups[g].count * (def ? (def->state_size + 15u) & ~(size_t)15u : 0u);
    }
    uint64_t models = 0;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        model_layout_t lay = { 0 };
        if (sim_models[id]->layout) {
            sim_models[id]->layout(scenario_model_config(sc, (sim_model_id_t)id), sc, &lay);
        }
        for (uint32_t k = 0; k < lay.arrays && k < MODEL_MAX_ARRAYS; k++) {
            robots += n * lay.elem_size[k];
        }
        models += w * lay.scratch_size + lay.run_bytes;
    }
    uint64_t tasks = 0;
    for (uint32_t t = 0; t < sc->task_count; t++) {
        const task_def_t *def = sc->tasks[t].def;
        tasks += def->memory ? def->memory(sc->tasks[t].config.bytes, sc) : 0u;
    }
    /* Two grids over the arena (robots, obstacles), cells of 0.5 m at least. */
    uint64_t cells = (uint64_t)(sc->arena.width / 0.5f + 2.0f) * (uint64_t)(sc->arena.height / 0.5f + 2.0f);
    uint64_t world = no * (sizeof(obstacle_t) + sizeof(object_def_t) + w * sizeof(uint32_t) + sizeof(uint32_t)
                           + BOX2D_BYTES_PER_SHAPE) + 2 * cells * sizeof(uint32_t);
    out->robots = (uint32_t)n;
    out->per_robot = n ? robots / n : 0;
    out->total = RUN_FIXED_BYTES + robots + models + tasks + world;
}

sim_t *sim_create(const scenario_t *sc, uint64_t seed, char err[SIM_ERR_MAX])
{
    return sim_create_threads(sc, seed, 1, err);
}

sim_t *sim_create_threads(const scenario_t *sc, uint64_t seed, uint32_t threads, char err[SIM_ERR_MAX])
{
    if (threads < 1 || threads > POOL_MAX_THREADS) {
        snprintf(err, SIM_ERR_MAX, "threads in a run: %u is not in [1, %u]", threads, POOL_MAX_THREADS);
        return NULL;
    }
    struct sim *sim = calloc(1, sizeof *sim);
    if (!sim) {
        snprintf(err, SIM_ERR_MAX, "out of memory");
        return NULL;
    }
    sim->sc = sc;
    sim->seed = seed;
    sim->dt = sc->control_period_ms / 1000.0f;
    sim->hw = sc->arena.width / 2;
    sim->hh = sc->arena.height / 2;
    sim->n = scenario_robot_count(sc);
    sim->n_obstacles = sc->object_count + sc->random_cylinders.count;
    sim->metrics.min_wall_clearance_m = INFINITY;
    size_t n = sim->n ? sim->n : 1, no = sim->n_obstacles ? sim->n_obstacles : 1;
    size_t ng = sc->group_count ? sc->group_count : 1;
    sim->robots = calloc(n, sizeof *sim->robots);
    sim->ctrl_blocks = calloc(ng, sizeof *sim->ctrl_blocks);
    sim->step_order = calloc(n, sizeof *sim->step_order);
    sim->px = calloc(n, sizeof *sim->px);
    sim->py = calloc(n, sizeof *sim->py);
    sim->obstacles = calloc(no, sizeof *sim->obstacles);
    sim->objects = calloc(no, sizeof *sim->objects);
    /* Cells a little larger than the farthest per-step query around a
     * robot (the IR sensors' reach): such a query touches at most 3 x 3
     * cells. */
    float reach = 0.0f;
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        model_layout_t lay = { 0 };
        if (sim_models[id]->layout) {
            sim_models[id]->layout(scenario_model_config(sc, (sim_model_id_t)id), sc, &lay);
        }
        reach = fmaxf(reach, lay.neighbour_reach_m);
    }
    float cell = fmaxf(SIM_ROBOT_CELL_MIN_M, 2 * EPUCK_BODY_RADIUS_M + reach + 0.04f);
    if (!sim->robots || !sim->ctrl_blocks || !sim->step_order || !sim->px
        || !sim->py || !sim->obstacles || !sim->objects
        || grid_init(&sim->robot_grid, -sim->hw, -sim->hh, 2 * sim->hw, 2 * sim->hh, cell) != 0
        || grid_init(&sim->obstacle_grid, -sim->hw, -sim->hh, 2 * sim->hw, 2 * sim->hh, cell) != 0) {
        snprintf(err, SIM_ERR_MAX, "out of memory for %u robots", sim->n);
        sim_destroy(sim);
        return NULL;
    }
    if (create_workers(sim, threads) != 0) {
        snprintf(err, SIM_ERR_MAX, "cannot start %u threads for the run (or out of memory)", threads);
        sim_destroy(sim);
        return NULL;
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim->step_order[i] = i;
    }
    if (sc->object_count > 0) {
        memcpy(sim->objects, sc->objects, sc->object_count * sizeof *sim->objects);
    }
    if (placement_cylinders(sim, err) != 0) {
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
        snprintf(err, SIM_ERR_MAX, "out of memory for %u obstacles", sim->n_obstacles);
        sim_destroy(sim);
        return NULL;
    }
    if (build_robots(sim, err) != 0 || placement_run(sim, err) != 0 || create_models(sim, err) != 0) {
        sim_destroy(sim);
        return NULL;
    }
    find_hooks(sim);
    for (uint32_t i = 0; i < sim->n; i++) {
        sim->px[i] = sim->robots[i].x;
        sim->py[i] = sim->robots[i].y;
    }
    find_counters(sim);
    if (world_create(sim, err) != 0 || grid_build_points(&sim->robot_grid, sim->px, sim->py, sim->n) != 0
        || create_tasks(sim, err) != 0) {
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
    for (uint32_t t = sim->n_tasks; t-- > 0;) {
        if (sim->tasks[t].def->destroy) {
            sim->tasks[t].def->destroy(sim->tasks[t].self);
        }
    }
    destroy_models(sim);
    world_destroy(sim);
    for (uint32_t w = 0; sim->scratch && w < pool_threads(sim->pool); w++) {
        free(sim->scratch[w].obstacle_mark);
        free(sim->scratch[w].robots);
        free(sim->scratch[w].items);
    }
    free(sim->scratch);
    pool_destroy(sim->pool);
    items_index_free(sim);
    grid_free(&sim->robot_grid);
    grid_free(&sim->obstacle_grid);
    for (uint32_t g = 0; sim->ctrl_blocks && g < sim->sc->group_count; g++) {
        free(sim->ctrl_blocks[g]);
    }
    free(sim->ctrl_blocks);
    free(sim->robots);
    free(sim->step_order);
    free(sim->px);
    free(sim->py);
    free(sim->obstacles);
    free(sim->objects);
    free(sim->events);
    free(sim);
}

/* The robot grid from this step's poses.  Its room for every robot was
 * made when the run was built (the first binning), so this cannot fail
 * unless memory is already gone. */
static void rebin_robots(struct sim *sim)
{
    if (grid_build_points(&sim->robot_grid, sim->px, sim->py, sim->n) != 0) {
        sim_out_of_memory("the robot grid");
    }
}

void sim_step(sim_t *sim)
{
    sim->n_events = 0;
    run_phase(sim, PHASE_BEGIN);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        if (sim->tasks[t].def->before_control) {
            sim->tasks[t].def->before_control(sim->tasks[t].self, sim);
        }
    }
    run_phase(sim, PHASE_BEFORE_CONTROL);
    /* Items stay put while the controllers step (items.h). */
    items_index_build(sim);
    /* Side by side when every sensor can be (not the rendered camera: one
     * GL context); each robot reads the start of the step, so the order
     * and the threads do not matter (test_sim: step order, thread count). */
    if (!models_serial(sim)) {
        pool_for(sim->pool, sim->n, CONTROL_CHUNK, step_robots, sim);
    } else {
        step_robots(0, sim->n, 0, sim);
    }
    items_index_drop(sim);
    run_phase(sim, PHASE_AFTER_CONTROL);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        if (sim->tasks[t].def->after_control) {
            sim->tasks[t].def->after_control(sim->tasks[t].self, sim);
        }
    }
    run_phase(sim, PHASE_DRIVE);
    world_drive(sim);
    world_advance(sim);
    world_read_poses(sim);
    rebin_robots(sim);
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        if (sim->tasks[t].def->after_physics) {
            sim->tasks[t].def->after_physics(sim->tasks[t].self, sim);
        }
    }
    run_phase(sim, PHASE_END);
    sim->step++;
    for (uint32_t t = 0; t < sim->n_tasks && !sim->done; t++) {
        if (sim->tasks[t].def->done) {
            sim->done = sim->tasks[t].def->done(sim->tasks[t].self, sim) != 0;
        }
    }
}

int sim_done(const sim_t *sim) { return sim->done; }

const char *sim_error(const sim_t *sim)
{
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const sim_model_run_t *m = &sim->models[id];
        const char *e = m->def->error ? m->def->error(sim, m->self) : NULL;
        if (e) {
            return e;
        }
    }
    return NULL;
}

uint32_t sim_gather_obstacles(const struct sim *sim, sim_scratch_t *ws, float minx, float miny, float maxx,
                              float maxy, uint32_t *out, uint32_t max)
{
    if (sim->n_obstacles == 0) {
        return 0;
    }
    const grid_t *g = &sim->obstacle_grid;
    int32_t cx0, cy0, cx1, cy1;
    uint32_t n = 0, stamp = ++ws->mark_stamp;
    if (stamp == 0) {   /* wrapped: clear the marks once every 2^32 queries */
        memset(ws->obstacle_mark, 0, sim->n_obstacles * sizeof *ws->obstacle_mark);
        stamp = ws->mark_stamp = 1;
    }
    grid_range(g, minx, miny, maxx, maxy, &cx0, &cy0, &cx1, &cy1);
    for (int32_t cy = cy0; cy <= cy1; cy++) {
        for (int32_t cx = cx0; cx <= cx1; cx++) {
            int32_t c = cy * g->nx + cx;
            for (uint32_t k = g->start[c]; k < g->start[c + 1]; k++) {
                uint32_t o = g->items[k];
                const float *b = sim->obstacles[o].aabb;
                if (ws->obstacle_mark[o] == stamp || b[0] > maxx || b[2] < minx || b[1] > maxy || b[3] < miny) {
                    continue;
                }
                ws->obstacle_mark[o] = stamp;
                if (n < max) {
                    out[n++] = o;
                }
            }
        }
    }
    return n;
}

sim_scratch_t *sim_robot_scratch(const struct sim *sim, uint32_t i)
{
    return &sim->scratch[sim->robots[i].hal.worker];
}

uint32_t sim_gather_robots(const struct sim *sim, float minx, float miny, float maxx, float maxy,
                           uint32_t *out, uint32_t max)
{
    const grid_t *g = &sim->robot_grid;
    int32_t cx0, cy0, cx1, cy1;
    uint32_t n = 0;
    grid_range(g, minx, miny, maxx, maxy, &cx0, &cy0, &cx1, &cy1);
    const uint32_t *items = g->items, *start = g->start;
    const float *px = sim->px, *py = sim->py;
    /* A row's cells are consecutive in items: one run of candidates a row
     * (the same ones in the same order as cell by cell).  Each candidate is
     * written and kept when inside: no branch to mispredict on the test. */
    for (int32_t cy = cy0; cy <= cy1 && n < max; cy++) {
        int32_t c = cy * g->nx;
        for (uint32_t k = start[c + cx0], end = start[c + cx1 + 1]; k < end && n < max; k++) {
            uint32_t j = items[k];
            float x = px[j], y = py[j];
            out[n] = j;
            n += (uint32_t)((x >= minx) & (x <= maxx) & (y >= miny) & (y <= maxy));
        }
    }
    return n;
}

/* ---------------------------------------------------------------- fields */

#define CORE_FIELD(name, unit, doc, type, member) \
    { name, unit, doc, type, 0, offsetof(sim_robot_t, member), 1 }
/* What every robot has (array 0: sim->robots). */
static const model_field_t core_fields[] = {
    CORE_FIELD("pose.x", "m", "x of the centre at the start of the step", SIM_FIELD_F32, x),
    CORE_FIELD("pose.y", "m", "y of the centre at the start of the step", SIM_FIELD_F32, y),
    CORE_FIELD("pose.theta", "rad", "heading, CCW from +x", SIM_FIELD_F32, theta),
    CORE_FIELD("leds", "", "LED word: bit k ring LED k, bit 8 body, bit 9 front", SIM_FIELD_U16, leds),
    CORE_FIELD("group", "", "index into the scenario's groups", SIM_FIELD_U32, group),
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

static void view_of(const model_field_t *f, const void *array, size_t stride, sim_field_t *out)
{
    out->name = f->name;
    out->unit = f->unit;
    out->doc = f->doc;
    out->type = f->type;
    out->base = array ? (const char *)array + f->offset : NULL;
    out->stride = stride;
    out->count = f->count;
}

int sim_field_at(const sim_t *sim, uint32_t k, sim_field_t *out)
{
    for (const model_field_t *f = core_fields; f->name; f++) {
        if (k-- == 0) {
            view_of(f, sim->n ? sim->robots : NULL, sizeof(sim_robot_t), out);
            return 0;
        }
    }
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        const sim_model_run_t *m = &sim->models[id];
        for (const model_field_t *f = m->def->fields; f && f->name; f++) {
            /* Only what this run allocated: a model off holds nothing. */
            if (f->array >= m->layout.arrays || m->layout.elem_size[f->array] == 0) {
                continue;
            }
            if (k-- == 0) {
                view_of(f, sim->n ? m->array[f->array] : NULL, m->layout.elem_size[f->array], out);
                return 0;
            }
        }
    }
    return -1;
}

int sim_field(const sim_t *sim, const char *name, sim_field_t *out)
{
    for (uint32_t k = 0; sim_field_at(sim, k, out) == 0; k++) {
        if (strcmp(out->name, name) == 0) {
            return 0;
        }
    }
    return -1;
}

/* ---------------------------------------------------------------- accessors */

uint64_t sim_step_count(const sim_t *sim) { return sim->step; }
double sim_time_s(const sim_t *sim) { return (double)sim->step * sim->sc->control_period_ms / 1000.0; }
uint64_t sim_seed(const sim_t *sim) { return sim->seed; }
const scenario_t *sim_scenario(const sim_t *sim) { return sim->sc; }
const sim_metrics_t *sim_metrics(const sim_t *sim) { return &sim->metrics; }
uint32_t sim_robot_count(const sim_t *sim) { return sim->n; }
uint32_t sim_robot_group(const sim_t *sim, uint32_t i) { SIM_ASSERT(i < sim->n); return sim->robots[i].group; }
const controller_def_t *sim_robot_def(const sim_t *sim, uint32_t i) { SIM_ASSERT(i < sim->n); return sim->robots[i].def; }
void *sim_robot_controller(sim_t *sim, uint32_t i) { SIM_ASSERT(i < sim->n); return sim->robots[i].ctrl; }
const void *sim_robot_controller_const(const sim_t *sim, uint32_t i)
{
    SIM_ASSERT(i < sim->n);
    return sim->robots[i].ctrl;
}
hal_t *sim_robot_hal(sim_t *sim, uint32_t i) { SIM_ASSERT(i < sim->n); return &sim->robots[i].hal; }
uint16_t sim_robot_leds(const sim_t *sim, uint32_t i) { SIM_ASSERT(i < sim->n); return sim->robots[i].leds; }
uint32_t sim_obstacle_count(const sim_t *sim) { return sim->n_obstacles; }

const char *sim_robot_state_name(const sim_t *sim, uint32_t i)
{
    SIM_ASSERT(i < sim->n);
    const sim_robot_t *r = &sim->robots[i];
    return r->def->state_name(r->ctrl);   /* ctrl is NULL for a stateless controller */
}

int sim_robot_observable(const sim_t *sim, uint32_t i, const char *name, float *value)
{
    SIM_ASSERT(i < sim->n);
    const sim_robot_t *r = &sim->robots[i];
    for (const observable_t *o = r->def->observables; r->ctrl && o && o->name; o++) {
        if (strcmp(o->name, name) == 0) {
            *value = observable_read(o, r->ctrl);
            return 0;
        }
    }
    return -1;
}

void sim_robot_pose(const sim_t *sim, uint32_t i, double *x, double *y, double *theta)
{
    SIM_ASSERT(i < sim->n);
    const sim_robot_t *r = &sim->robots[i];
    *x = r->x;
    *y = r->y;
    *theta = r->theta;
}

void sim_set_robot_pose(sim_t *sim, uint32_t i, double x, double y, double theta)
{
    SIM_ASSERT(i < sim->n);
    sim_robot_t *r = &sim->robots[i];
    r->x = (float)x;
    r->y = (float)y;
    r->theta = (float)theta;
    sim->px[i] = r->x;
    sim->py[i] = r->y;
    b2Body_SetTransform(r->body, (b2Vec2){ r->x, r->y }, b2MakeRot(r->theta));
    rebin_robots(sim);
    /* Sensors must see the new pose even within this step (the sound
     * field too, when it is read before the step's controllers run). */
    for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
        if (sim->models[id].def->moved) {
            sim->models[id].def->moved(sim, sim->models[id].self, i);
        }
    }
}

void sim_arena_half(const sim_t *sim, float *hw, float *hh)
{
    *hw = sim->hw;
    *hh = sim->hh;
}

const object_def_t *sim_object(const sim_t *sim, uint32_t k)
{
    return k < sim->n_obstacles ? &sim->objects[k] : NULL;
}

int sim_obstacles_cut(const struct sim *sim, sim_scratch_t *ws, vec2_t p, vec2_t q)
{
    uint32_t near[256];
    uint32_t n = sim_gather_obstacles(sim, ws, fminf(p.x, q.x), fminf(p.y, q.y), fmaxf(p.x, q.x), fmaxf(p.y, q.y),
                                      near, 256);
    for (uint32_t k = 0; k < n; k++) {
        const obstacle_t *o = &sim->obstacles[near[k]];
        if (o->shape == SHAPE_CYLINDER) {
            if (geom_segment_hits_circle(p, q, o->c, o->r)) return 1;
        } else {
            for (int e = 0; e < 4; e++) {
                if (geom_segments_intersect(p, q, o->corner[e], o->corner[(e + 1) & 3])) return 1;
            }
        }
    }
    return 0;
}

int sim_segment_blocked(sim_t *sim, double x0, double y0, double x1, double y1)
{
    return sim_obstacles_cut(sim, &sim->scratch[0], v2((float)x0, (float)y0), v2((float)x1, (float)y1));
}

void sim_obstacle_bounds(const sim_t *sim, uint32_t k, float out[4])
{
    memcpy(out, sim->obstacles[k].aabb, 4 * sizeof out[0]);
}

void *sim_task(const sim_t *sim, const struct task_def *def)
{
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        if (sim->tasks[t].def == def) {
            return sim->tasks[t].self;
        }
    }
    return NULL;
}

void sim_task_rand_seed(const sim_t *sim, const struct task_def *def, uint64_t index,
                        struct sim_rand *out)
{
    uint64_t slot = 0;
    for (uint32_t t = 0; t < sim->sc->task_count; t++) {
        if (sim->sc->tasks[t].def == def) {
            slot = t;
        }
    }
    sim_rand_seed(out, sim->seed, (slot << 32) | index, RAND_TASK);
}

void sim_event(sim_t *sim, uint32_t robot, const char *kind, const char *detail, int32_t value)
{
    if (sim->n_events == sim->events_cap) {
        uint32_t cap = sim->events_cap ? 2 * sim->events_cap : 64;
        sim_event_rec_t *e = realloc(sim->events, cap * sizeof *e);
        if (!e) {
            sim_out_of_memory("a step's events");
        }
        sim->events = e;
        sim->events_cap = cap;
    }
    sim_event_rec_t *e = &sim->events[sim->n_events++];
    e->robot = robot;
    e->kind = kind;
    e->detail = detail;
    e->value = value;
}


uint32_t sim_events(const sim_t *sim, const sim_event_rec_t **events)
{
    *events = sim->events;
    return sim->n_events;
}

void sim_set_step_order(sim_t *sim, int order, uint64_t key)
{
    for (uint32_t i = 0; i < sim->n; i++) {
        sim->step_order[i] = order == 1 ? sim->n - 1 - i : i;
    }
    if (order == 2) {   /* Fisher-Yates */
        sim_rand_t r;
        sim_rand_seed(&r, key, 0, RAND_PLACEMENT);
        for (uint32_t i = sim->n; i > 1; i--) {
            uint32_t j = (uint32_t)(sim_rand_u64(&r) % i), t = sim->step_order[i - 1];
            sim->step_order[i - 1] = sim->step_order[j];
            sim->step_order[j] = t;
        }
    }
}

uint64_t sim_hash_bytes(uint64_t h, const void *p, size_t n)
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
    h = sim_hash_bytes(h, &sim->step, sizeof sim->step);
    for (uint32_t i = 0; i < sim->n; i++) {
        const sim_robot_t *r = &sim->robots[i];
        h = sim_hash_bytes(h, &r->x, sizeof r->x);
        h = sim_hash_bytes(h, &r->y, sizeof r->y);
        h = sim_hash_bytes(h, &r->theta, sizeof r->theta);
        for (uint32_t id = 0; id < SIM_MODEL_COUNT; id++) {
            if (sim->models[id].def->hash) {
                h = sim->models[id].def->hash(sim, sim->models[id].self, i, h);
            }
        }
    }
    return h;
}
