/*
 * world.c - the Box2D side of a run: walls, static obstacles and the robot
 * bodies, driven by their wheel speeds.
 *
 * A robot is a dynamic disc.  At each control step its velocity is set from
 * the commanded wheel speeds (differential drive); Box2D then resolves the
 * contacts over `physics_substeps` sub-steps, so robots push each other and
 * never pass through walls.  A pushed robot keeps the velocity the solver
 * gave it until the next control step resets it (at most one period).
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "pool.h"
#include "sim_internal.h"
#include "units.h"

/* 150 g on a 70 mm disc. */
#define ROBOT_DENSITY (0.150f / ((float)UNITS_PI * EPUCK_BODY_RADIUS_M * EPUCK_BODY_RADIUS_M))
/* Plastic on plastic and painted walls: low friction so robots slide
 * along walls instead of sticking to them. */
#define ROBOT_FRICTION 0.1f

static void add_box(b2BodyId body, float hx, float hy, b2Vec2 centre, float angle)
{
    b2ShapeDef sd = b2DefaultShapeDef();
    b2Polygon box = b2MakeOffsetBox(hx, hy, centre, b2MakeRot(angle));
    b2CreatePolygonShape(body, &sd, &box);
}

static void create_static(struct sim *sim)
{
    const scenario_t *sc = sim->sc;
    b2BodyDef bd = b2DefaultBodyDef();
    b2BodyId ground = b2CreateBody(sim->world, &bd);
    float t = sc->arena.wall_thickness, hw = sim->hw, hh = sim->hh;

    /* Four walls whose inner faces bound [-hw, hw] x [-hh, hh]. */
    add_box(ground, hw + t, t / 2, (b2Vec2){ 0, hh + t / 2 }, 0);
    add_box(ground, hw + t, t / 2, (b2Vec2){ 0, -hh - t / 2 }, 0);
    add_box(ground, t / 2, hh + t, (b2Vec2){ hw + t / 2, 0 }, 0);
    add_box(ground, t / 2, hh + t, (b2Vec2){ -hw - t / 2, 0 }, 0);

    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        const obstacle_t *o = &sim->obstacles[k];
        const object_def_t *d = &sim->objects[k];
        if (o->shape == SHAPE_CYLINDER) {
            b2ShapeDef sd = b2DefaultShapeDef();
            b2Circle c = { { o->c.x, o->c.y }, o->r };
            b2CreateCircleShape(ground, &sd, &c);
        } else {
            add_box(ground, d->width / 2, d->depth / 2, (b2Vec2){ o->c.x, o->c.y },
                    d->angle * (float)UNITS_PI / 180.0f);
        }
    }
}

/* Box2D keeps its worlds in one process-wide table that b2CreateWorld and
 * b2DestroyWorld change without locking: runs on the thread pool take
 * turns for those two calls.  Everything else in a world is its own. */
static pthread_mutex_t world_table_lock = PTHREAD_MUTEX_INITIALIZER;

int world_create(struct sim *sim, char err[SIM_ERR_MAX])
{
    b2WorldDef wd = b2DefaultWorldDef();
    wd.gravity = (b2Vec2){ 0.0f, 0.0f };
    /* Robots are always driven; sleeping would only cost checks. */
    wd.enableSleep = false;
    /* The run's threads for the solver (Box2D's results do not depend on
     * the worker count: its determinism test, and ours in test_sim). */
    if (pool_threads(sim->pool) > 1) {
        wd.workerCount = (int)pool_threads(sim->pool);
        wd.enqueueTask = pool_box2d_enqueue;
        wd.finishTask = pool_box2d_finish;
        wd.userTaskContext = sim->pool;
    }
    pthread_mutex_lock(&world_table_lock);
    sim->world = b2CreateWorld(&wd);
    pthread_mutex_unlock(&world_table_lock);
    sim->drive = calloc(sim->n ? sim->n : 1, sizeof *sim->drive);
    if (!b2World_IsValid(sim->world) || !sim->drive) {
        snprintf(err, SIM_ERR_MAX, "cannot create the Box2D world (or out of memory)");
        return -1;
    }
    create_static(sim);

    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *r = &sim->robots[i];
        b2BodyDef bd = b2DefaultBodyDef();
        /* A group that does not move (a fixed station, a landmark) is a static
         * body: robots bump into it but cannot push it. */
        bd.type = r->moves ? b2_dynamicBody : b2_staticBody;
        bd.position = (b2Vec2){ r->x, r->y };
        bd.rotation = b2MakeRot(r->theta);
        bd.userData = (void *)(uintptr_t)(i + 1);
        r->body = b2CreateBody(sim->world, &bd);
        b2ShapeDef sd = b2DefaultShapeDef();
        sd.density = ROBOT_DENSITY;
        sd.material.friction = ROBOT_FRICTION;
        sd.enableContactEvents = true;
        sd.userData = (void *)(uintptr_t)(i + 1);
        b2Circle c = { { 0.0f, 0.0f }, EPUCK_BODY_RADIUS_M };
        b2CreateCircleShape(r->body, &sd, &c);
    }
    return 0;
}

void world_destroy(struct sim *sim)
{
    free(sim->drive);
    sim->drive = NULL;
    pthread_mutex_lock(&world_table_lock);
    if (b2World_IsValid(sim->world)) {
        b2DestroyWorld(sim->world);
    }
    pthread_mutex_unlock(&world_table_lock);
}

/* Poses are read side by side. */
#define DRIVE_CHUNK 256u

/* The velocities the models' drive phase asked for (the wheels'), set in
 * one loop on the stepping thread: Box2D's API is not promised to be safe
 * from several threads at once. */
void world_drive(struct sim *sim)
{
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *r = &sim->robots[i];
        if (r->moves) {
            b2Body_SetLinearVelocity(r->body, sim->drive[i].v);
            b2Body_SetAngularVelocity(r->body, sim->drive[i].w);
        }
    }
}

static int is_robot(b2ShapeId s) { return b2Shape_GetUserData(s) != NULL; }

void world_advance(struct sim *sim)
{
    b2World_Step(sim->world, sim->dt, sim->sc->physics_substeps);
    b2ContactEvents ev = b2World_GetContactEvents(sim->world);
    for (int k = 0; k < ev.beginCount; k++) {
        int a = is_robot(ev.beginEvents[k].shapeIdA), b = is_robot(ev.beginEvents[k].shapeIdB);
        if (a && b) {
            sim->metrics.robot_contacts++;
        } else if (a || b) {
            sim->metrics.static_contacts++;
        }
    }
}

/* pool_fn: robots [begin, end) take their poses from Box2D (reads only)
 * and how far they moved (sim->drive[i].moved, summed in id order after). */
static void read_range(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    struct sim *sim = ctx;
    (void)worker;
    for (uint32_t i = begin; i < end; i++) {
        sim_robot_t *r = &sim->robots[i];
        /* Position and rotation in one look-up of the body (the same values
         * as b2Body_GetPosition and b2Body_GetRotation, each its own). */
        b2Transform t = b2Body_GetTransform(r->body);
        b2Vec2 p = t.p;
        float dx = p.x - r->x, dy = p.y - r->y;
        sim->drive[i].moved = sqrt((double)dx * dx + (double)dy * dy);
        r->x = p.x;
        r->y = p.y;
        r->theta = b2Rot_GetAngle(t.q);
        sim->px[i] = p.x;
        sim->py[i] = p.y;
    }
}

void world_read_poses(struct sim *sim)
{
    pool_for(sim->pool, sim->n, DRIVE_CHUNK, read_range, sim);
    double moved = 0.0, clearance = sim->metrics.min_wall_clearance_m;
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_robot_t *r = &sim->robots[i];
        moved += sim->drive[i].moved;
        double gap = fmin(sim->hw - fabs(r->x), sim->hh - fabs(r->y)) - EPUCK_BODY_RADIUS_M;
        if (gap < clearance) {
            clearance = gap;
        }
        if (!r->escaped && (fabsf(r->x) > sim->hw || fabsf(r->y) > sim->hh)) {
            r->escaped = 1;
            sim->metrics.escaped++;
        }
    }
    sim->metrics.distance_m += moved;
    sim->metrics.min_wall_clearance_m = clearance;
}
