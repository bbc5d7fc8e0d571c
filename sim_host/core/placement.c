/*
 * placement.c - the start pose of every robot, group by group.
 *
 * Groups with explicit poses are placed first, then the others in scenario
 * order, so that robots drawn at random keep clear of the fixed ones.  One
 * random stream (the run seed's placement stream) serves every random
 * group in turn.  A spot is taken when the body lies inside the arena,
 * clears every obstacle by 5 mm, and is at least the group's min_spacing
 * (and never less than a body) from every robot placed before; a random
 * group tries up to 20,000 spots per robot.  Regions (the body must lie
 * inside them):
 *   rectangle  centre x, y, size width x height (0: the arena's), with a
 *              5 mm margin inside its edges;
 *   circle     centre x, y, radius;
 *   ring       centre x, y, between inner and outer radius (uniform by area);
 *   grid       rows and columns over the rectangle, one spot per robot
 *              (as many columns as the rectangle's aspect asks);
 *   poses      one pose per robot, in order.
 * The heading is the group's (degrees), or drawn uniformly when `random`;
 * a pose's own heading, when given, wins.  Robot k of a group takes the
 * k-th spot drawn, or with `order: space` the k-th along a Morton curve
 * once every group is placed (renumber_by_space).
 *
 * Random cylinders (scenario random_cylinders, placement_cylinders) come
 * before any robot: cylinder k draws its radius uniformly in [radius_min,
 * radius_max], then its centre uniformly over the arena, until it clears by
 * `gap` the walls, every obstacle before it (the scenario's objects, then
 * cylinders 0..k-1) and the body of every robot of a `poses` group (their
 * spots are known before the run); up to 20,000 draws per cylinder.  Their
 * own stream (layout_seed, or the run seed when it is 0; RAND_OBSTACLES)
 * keeps the robots' placement stream, and every scenario without random
 * cylinders, as it was.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sim_internal.h"
#include "units.h"

#define PLACE_TRIES 20000
/* Bodies keep this far inside a rectangle's edges and from obstacles, m. */
#define PLACE_MARGIN 0.005f

static const char *const shape_names[] = { "rectangle", "circle", "ring", "grid", "poses" };

/* Gap between a robot at p and obstacle o (negative when they overlap). */
static float obstacle_gap(const obstacle_t *o, vec2_t p)
{
    if (o->shape == SHAPE_CYLINDER) {
        return v2_len(v2_sub(p, o->c)) - o->r - EPUCK_BODY_RADIUS_M;
    }
    /* Inside the box? (corners are counter-clockwise) */
    int inside = 1;
    float best = INFINITY;
    for (int e = 0; e < 4; e++) {
        vec2_t a = o->corner[e], b = o->corner[(e + 1) & 3];
        if (v2_cross(v2_sub(b, a), v2_sub(p, a)) < 0) inside = 0;
        best = fminf(best, v2_len(v2_sub(p, geom_closest_on_segment(p, a, b))));
    }
    return inside ? -best - EPUCK_BODY_RADIUS_M : best - EPUCK_BODY_RADIUS_M;
}

/* The robots placed so far, hashed by cell (a cell as wide as the widest
 * spacing of any group), so that a candidate spot is checked against its
 * neighbours only: placing n robots costs O(n), not O(n^2) (100,000 robots
 * took 24 s of all-pairs checks).  Verdicts and messages are the all-pairs
 * scan's: the lowest-numbered robot too close is the one named. */
typedef struct placed {
    float cell;             /* m */
    uint32_t mask;          /* buckets - 1 (a power of two) */
    uint32_t *head;         /* bucket -> last robot in it, or PLACED_NONE */
    uint32_t *next;         /* robot -> the one before it in its bucket */
} placed_t;

#define PLACED_NONE UINT32_MAX

static uint32_t cell_bucket(const placed_t *pl, int32_t cx, int32_t cy)
{
    uint32_t h = (uint32_t)cx * 73856093u ^ (uint32_t)cy * 19349663u;
    return h & pl->mask;
}

static int32_t cell_of(const placed_t *pl, float v)
{
    return (int32_t)floorf(v / pl->cell);
}

static int placed_init(placed_t *pl, const struct sim *sim)
{
    uint32_t buckets = 1u;
    pl->cell = 2 * EPUCK_BODY_RADIUS_M;
    for (uint32_t g = 0; g < sim->sc->group_count; g++) {
        pl->cell = fmaxf(pl->cell, sim->sc->groups[g].min_spacing);
    }
    while (buckets < 2u * sim->n && buckets < (1u << 30)) {
        buckets <<= 1;
    }
    pl->mask = buckets - 1u;
    pl->head = malloc(buckets * sizeof *pl->head);
    pl->next = malloc((sim->n ? sim->n : 1) * sizeof *pl->next);
    if (!pl->head || !pl->next) {
        return -1;
    }
    for (uint32_t b = 0; b < buckets; b++) {
        pl->head[b] = PLACED_NONE;
    }
    return 0;
}

static void placed_free(placed_t *pl)
{
    free(pl->head);
    free(pl->next);
}

static void placed_add(placed_t *pl, const struct sim *sim, uint32_t j)
{
    uint32_t b = cell_bucket(pl, cell_of(pl, sim->robots[j].x), cell_of(pl, sim->robots[j].y));
    pl->next[j] = pl->head[b];
    pl->head[b] = j;
}

/* The lowest-numbered placed robot closer than `spacing` (<= the cell) to
 * (x, y), or PLACED_NONE. */
static uint32_t placed_too_close(const placed_t *pl, const struct sim *sim, float spacing, float x, float y)
{
    int32_t cx = cell_of(pl, x), cy = cell_of(pl, y);
    uint32_t worst = PLACED_NONE;
    for (int32_t ox = -1; ox <= 1; ox++) {
        for (int32_t oy = -1; oy <= 1; oy++) {
            for (uint32_t j = pl->head[cell_bucket(pl, cx + ox, cy + oy)]; j != PLACED_NONE; j = pl->next[j]) {
                float dx = sim->robots[j].x - x, dy = sim->robots[j].y - y;
                if (dx * dx + dy * dy < spacing * spacing && j < worst) {
                    worst = j;
                }
            }
        }
    }
    return worst;
}

/* Why a robot may not stand at (x, y), given the robots placed: NULL when
 * it may, else a phrase for messages (written into why[]). */
static const char *spot_problem(const struct sim *sim, const placed_t *placed, float spacing, float x, float y,
                                char why[96])
{
    float margin = EPUCK_BODY_RADIUS_M + PLACE_MARGIN;
    if (!(fabsf(x) <= sim->hw - margin && fabsf(y) <= sim->hh - margin)) {
        return "is not inside the arena";
    }
    uint32_t j = placed_too_close(placed, sim, spacing, x, y);
    if (j != PLACED_NONE) {
        snprintf(why, 96, "is closer than %g m to robot %u", (double)spacing, j);
        return why;
    }
    for (uint32_t k = 0; k < sim->n_obstacles; k++) {
        if (obstacle_gap(&sim->obstacles[k], v2(x, y)) < PLACE_MARGIN) {
            snprintf(why, 96, "is on objects[%u]", k);
            return why;
        }
    }
    return NULL;
}

/* Whether a robot may stand at (x, y), given the robots placed. */
static int free_spot(const struct sim *sim, const placed_t *placed, float spacing, float x, float y)
{
    char why[96];
    return spot_problem(sim, placed, spacing, x, y, why) == NULL;
}

static float heading_rad(float deg) { return deg * (float)UNITS_PI / 180.0f; }

/* A candidate spot for robot k of group `grp` (k-th of its group). */
static void draw_spot(const struct sim *sim, const robot_group_t *grp, uint32_t k, sim_rand_t *rnd,
                      float *x, float *y)
{
    const placement_def_t *p = &grp->placement;
    float hw = p->width > 0 ? p->width / 2 : sim->hw, hh = p->height > 0 ? p->height / 2 : sim->hh;
    switch (p->shape) {
    case PLACE_GRID: {
        uint32_t cols = (uint32_t)ceil(sqrt((double)grp->count * hw / hh));
        if (cols == 0) cols = 1;
        uint32_t rows = (grp->count + cols - 1) / cols;
        *x = p->x - hw + (2 * hw) * ((float)(k % cols) + 0.5f) / (float)cols;
        *y = p->y - hh + (2 * hh) * ((float)(k / cols) + 0.5f) / (float)rows;
        break;
    }
    case PLACE_CIRCLE: {
        double rad = p->radius - EPUCK_BODY_RADIUS_M;
        double u = sqrt(sim_rand_uniform(rnd)) * (rad > 0 ? rad : 0);
        double a = 2 * UNITS_PI * sim_rand_uniform(rnd);
        *x = (float)(p->x + u * cos(a));
        *y = (float)(p->y + u * sin(a));
        break;
    }
    case PLACE_RING: {
        double r0 = p->inner + EPUCK_BODY_RADIUS_M, r1 = p->outer - EPUCK_BODY_RADIUS_M;
        if (r1 < r0) r1 = r0;
        double u = sqrt(r0 * r0 + sim_rand_uniform(rnd) * (r1 * r1 - r0 * r0));
        double a = 2 * UNITS_PI * sim_rand_uniform(rnd);
        *x = (float)(p->x + u * cos(a));
        *y = (float)(p->y + u * sin(a));
        break;
    }
    default: {   /* rectangle */
        float margin = EPUCK_BODY_RADIUS_M + PLACE_MARGIN;
        *x = (float)(p->x + (2 * sim_rand_uniform(rnd) - 1) * (hw - margin));
        *y = (float)(p->y + (2 * sim_rand_uniform(rnd) - 1) * (hh - margin));
        break;
    }
    }
}

static int place_group(struct sim *sim, const robot_group_t *grp, uint32_t gi, uint32_t first,
                       placed_t *placed, sim_rand_t *rnd, char err[SIM_ERR_MAX])
{
    float spacing = fmaxf(grp->min_spacing, 2 * EPUCK_BODY_RADIUS_M);
    const placement_def_t *p = &grp->placement;
    for (uint32_t k = 0; k < grp->count; k++) {
        sim_robot_t *r = &sim->robots[first + k];
        int ok = 0;
        if (p->shape == PLACE_POSES) {
            const pose_def_t *q = &p->poses[k];
            r->x = q->x;
            r->y = q->y;
            float deg = isnan(q->heading) ? grp->heading : q->heading;
            r->theta = isnan(deg) ? (float)(2 * UNITS_PI * sim_rand_uniform(rnd) - UNITS_PI) : heading_rad(deg);
            ok = free_spot(sim, placed, spacing, r->x, r->y);
            if (!ok) {
                snprintf(err, SIM_ERR_MAX, "robots[%u] (%s): pose %u at (%g, %g) m is not free: "
                         "outside the arena, on an obstacle or too close to another robot",
                         gi, grp->name, k, (double)q->x, (double)q->y);
                return -1;
            }
        }
        int tries = p->shape == PLACE_GRID ? 1 : PLACE_TRIES;
        for (int attempt = 0; attempt < tries && !ok && p->shape != PLACE_POSES; attempt++) {
            float x, y;
            draw_spot(sim, grp, k, rnd, &x, &y);
            if (free_spot(sim, placed, spacing, x, y)) {
                r->x = x;
                r->y = y;
                r->theta = isnan(grp->heading) ? (float)(2 * UNITS_PI * sim_rand_uniform(rnd) - UNITS_PI)
                                               : heading_rad(grp->heading);
                ok = 1;
            }
        }
        if (!ok && p->shape == PLACE_GRID) {
            /* A grid spot is fixed: say what is in its way, and what helps. */
            char why[96];
            float x, y;
            draw_spot(sim, grp, k, rnd, &x, &y);
            const char *problem = spot_problem(sim, placed, spacing, x, y, why);
            snprintf(err, SIM_ERR_MAX, "robots[%u] (%s): grid spot %u of %u at (%.3f, %.3f) m %s; grid spots "
                     "do not move, so shift or resize the grid (placement x, y, width, height) or "
                     "use shape: rectangle, whose random spots avoid obstacles",
                     gi, grp->name, k + 1, grp->count, (double)x, (double)y, problem ? problem : "is taken");
            return -1;
        }
        if (!ok) {
            snprintf(err, SIM_ERR_MAX, "cannot place robot %u of %u of robots[%u] (%s, placement %s): no free "
                     "spot; enlarge the region or the arena, or use fewer robots",
                     k + 1, grp->count, gi, grp->name, shape_names[p->shape]);
            return -1;
        }
        placed_add(placed, sim, first + k);
    }
    return 0;
}

/* Gap between a cylinder of radius r at p and obstacle o. */
static float cylinder_gap(const obstacle_t *o, vec2_t p, float r)
{
    return obstacle_gap(o, p) + EPUCK_BODY_RADIUS_M - r;
}

int placement_cylinders(struct sim *sim, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    uint32_t count = sc->random_cylinders.count, first = sc->object_count;
    float gap = sc->random_cylinders.gap, rmin = sc->random_cylinders.radius_min;
    float rmax = sc->random_cylinders.radius_max;
    uint64_t seed = sc->random_cylinders.layout_seed ? sc->random_cylinders.layout_seed : sim->seed;
    obstacle_t *before;
    sim_rand_t rnd;
    if (count == 0) {
        return 0;
    }
    /* The obstacles before cylinder k, as the gap test needs them (the
     * scenario's boxes with their corners). */
    before = calloc(first + count, sizeof *before);
    if (!before) {
        snprintf(err, SIM_ERR_MAX, "out of memory for %u random cylinders", count);
        return -1;
    }
    for (uint32_t k = 0; k < first; k++) {
        const object_def_t *d = &sim->objects[k];
        obstacle_t *o = &before[k];
        o->shape = d->shape;
        o->c = v2(d->x, d->y);
        o->r = d->radius;
        if (d->shape == SHAPE_BOX) {
            float a = d->angle * (float)UNITS_PI / 180.0f, c = cosf(a), s = sinf(a);
            float hx = d->width / 2, hy = d->depth / 2;
            const float ux[4] = { -hx, hx, hx, -hx }, uy[4] = { -hy, -hy, hy, hy };
            for (int e = 0; e < 4; e++) {
                o->corner[e] = v2_add(o->c, v2_rot(v2(ux[e], uy[e]), c, s));
            }
        }
    }
    sim_rand_seed(&rnd, seed, 0, RAND_OBSTACLES);
    for (uint32_t k = 0; k < count; k++) {
        int ok = 0;
        float x = 0.0f, y = 0.0f, r = rmin;
        for (int attempt = 0; attempt < PLACE_TRIES && !ok; attempt++) {
            r = (float)(rmin + (rmax - rmin) * sim_rand_uniform(&rnd));
            float mx = sim->hw - r - gap, my = sim->hh - r - gap;
            if (mx < 0 || my < 0) {
                break;
            }
            x = (float)((2 * sim_rand_uniform(&rnd) - 1) * mx);
            y = (float)((2 * sim_rand_uniform(&rnd) - 1) * my);
            ok = 1;
            for (uint32_t j = 0; ok && j < first + k; j++) {
                ok = cylinder_gap(&before[j], v2(x, y), r) >= gap;
            }
            for (uint32_t g = 0; ok && g < sc->group_count; g++) {
                const robot_group_t *grp = &sc->groups[g];
                for (uint32_t q = 0; ok && grp->placement.shape == PLACE_POSES && q < grp->count; q++) {
                    float dx = grp->placement.poses[q].x - x, dy = grp->placement.poses[q].y - y;
                    ok = sqrtf(dx * dx + dy * dy) - r - EPUCK_BODY_RADIUS_M >= gap;
                }
            }
        }
        if (!ok) {
            snprintf(err, SIM_ERR_MAX, "random_cylinders: cannot place cylinder %u of %u (radius %.3g m) %.3g m clear of "
                     "the walls, the obstacles and the fixed robots; use fewer or smaller cylinders, or a "
                     "smaller gap", k + 1, count, (double)r, (double)gap);
            free(before);
            return -1;
        }
        before[first + k] = (obstacle_t){ .shape = SHAPE_CYLINDER, .c = v2(x, y), .r = r };
        sim->objects[first + k] = (object_def_t){ .shape = SHAPE_CYLINDER, .x = x, .y = y, .radius = r,
                                                  .height = sc->random_cylinders.height,
                                                  .colour = 0 /* HAL_COLOUR_NONE */ };
    }
    free(before);
    return 0;
}

/* placement.order: space.  Cells of this side (m) along a Morton (Z)
 * curve: the robot grid's cell at the default IR range, so that robots of
 * one cell, and of neighbouring cells mostly, are neighbours in id too. */
#define ORDER_CELL_M SIM_ROBOT_CELL_MIN_M

typedef struct spot {
    uint64_t key;               /* Morton code of its cell */
    uint32_t drawn;             /* which robot drew it (ties: the order drawn) */
    float x, y, theta;
} spot_t;

/* The low 32 bits of v spread to the even bits of the result. */
static uint64_t spread_bits(uint32_t v)
{
    uint64_t x = v;
    x = (x | (x << 16)) & UINT64_C(0x0000FFFF0000FFFF);
    x = (x | (x << 8)) & UINT64_C(0x00FF00FF00FF00FF);
    x = (x | (x << 4)) & UINT64_C(0x0F0F0F0F0F0F0F0F);
    x = (x | (x << 2)) & UINT64_C(0x3333333333333333);
    x = (x | (x << 1)) & UINT64_C(0x5555555555555555);
    return x;
}

static uint32_t order_cell(float v, float half)
{
    float c = (v + half) / ORDER_CELL_M;
    return c >= 1.0f ? (uint32_t)fminf(c, 4.0e9f) : 0u;
}

static int by_key(const void *a, const void *b)
{
    const spot_t *p = a, *q = b;
    if (p->key != q->key) {
        return p->key < q->key ? -1 : 1;
    }
    return (p->drawn > q->drawn) - (p->drawn < q->drawn);
}

/* A group's spots, once all are drawn, given to its robots in Morton order:
 * the same poses and headings, robot k now the k-th along the curve.  After
 * every group is placed, so that the placement's checks (which name robots
 * by index) are those of the order drawn. */
static int renumber_by_space(struct sim *sim, uint32_t first, uint32_t count, char err[SIM_ERR_MAX])
{
    spot_t *spot = malloc((count ? count : 1) * sizeof *spot);
    if (!spot) {
        snprintf(err, SIM_ERR_MAX, "out of memory ordering %u robots by space", count);
        return -1;
    }
    for (uint32_t k = 0; k < count; k++) {
        const sim_robot_t *r = &sim->robots[first + k];
        uint64_t key = spread_bits(order_cell(r->x, sim->hw)) | (spread_bits(order_cell(r->y, sim->hh)) << 1);
        spot[k] = (spot_t){ key, k, r->x, r->y, r->theta };
    }
    qsort(spot, count, sizeof *spot, by_key);
    for (uint32_t k = 0; k < count; k++) {
        sim_robot_t *r = &sim->robots[first + k];
        r->x = spot[k].x;
        r->y = spot[k].y;
        r->theta = spot[k].theta;
    }
    free(spot);
    return 0;
}

int placement_run(struct sim *sim, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    placed_t placed = { 0 };
    uint32_t first[SCENARIO_MAX_GROUPS];
    sim_rand_t rnd;
    int rc = 0;
    if (placed_init(&placed, sim) != 0) {
        placed_free(&placed);
        snprintf(err, SIM_ERR_MAX, "out of memory placing %u robots", sim->n);
        return -1;
    }
    sim_rand_seed(&rnd, sim->seed, 0, RAND_PLACEMENT);
    for (uint32_t g = 0, i = 0; g < sc->group_count; i += sc->groups[g].count, g++) {
        first[g] = i;
    }
    /* Fixed poses first, then the rest, each pass in scenario order. */
    for (int pass = 0; pass < 2 && rc == 0; pass++) {
        for (uint32_t g = 0; g < sc->group_count && rc == 0; g++) {
            const robot_group_t *grp = &sc->groups[g];
            if ((grp->placement.shape == PLACE_POSES) == (pass == 0)) {
                rc = place_group(sim, grp, g, first[g], &placed, &rnd, err);
            }
        }
    }
    placed_free(&placed);
    for (uint32_t g = 0; g < sc->group_count && rc == 0; g++) {
        /* Poses are the user's, robot by robot: the loader refuses space
         * for them, and a scenario built in code is held to it here. */
        if (sc->groups[g].placement.order == PLACE_ORDER_SPACE && sc->groups[g].placement.shape != PLACE_POSES) {
            rc = renumber_by_space(sim, first[g], sc->groups[g].count, err);
        }
    }
    return rc;
}
