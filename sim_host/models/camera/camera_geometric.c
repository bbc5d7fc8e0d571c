/*
 * camera_geometric.c - the camera's geometric model (camera.model
 * geometric): blobs from the angles the other robots, the obstacles and the
 * tasks' items cover as seen from the lens, each cut by whatever is nearer
 * in front of it, sized in the robot image's pixels.  Fast, and the
 * default; the rendered model (camera_render.c) is its check.
 */
#include <math.h>
#include <stdlib.h>

#include "camera_internal.h"
#include "units.h"

/* Where the camera is: hal/units.h. */
#define CAMERA_HEIGHT EPUCK_CAMERA_HEIGHT_M

typedef camera_interval_t interval_t;

/* What the camera sees from: the lens, its heading (angle and unit vector)
 * and its range; all_round: the panoramic stand-in (fov > 179 deg), which
 * sees behind the robot too. */
typedef struct view {
    vec2_t cam;
    float heading;
    vec2_t dir;
    float range;
    int all_round;
    vec2_t left, right;   /**< a pinhole camera's field-of-view edges (dir turned by +-half) */
} view_t;

/* A disc this far (m) outside a field-of-view edge is outside the view:
 * far above float rounding (about 1e-3 rad at the camera's range). */
#define FOV_MARGIN 1e-3f

/* Angular interval (robot frame, rad) and nearest distance of a disc, or 0
 * when it cannot matter: the lens inside it, wholly behind the lens (a
 * pinhole camera's field of view is narrower than 180 deg), or farther than
 * the range (then it can neither be seen nor hide anything that can).  The
 * interval's ends may pass +-pi for the all-round camera (lo < hi always,
 * its width below pi).  2 when a pinhole camera's disc lies wholly outside
 * its field of view (beyond the margin from an edge's line): it would get
 * an interval too, but one that shows nothing and hides nothing within
 * the view, so its trigonometry is saved and *out left as it was. */
static int disc_interval(const view_t *vw, vec2_t c, float rad, interval_t *out)
{
    vec2_t v = v2_sub(c, vw->cam);
    float d = v2_len(v);
    if (d <= rad || (!vw->all_round && v2_dot(v, vw->dir) < -rad) || d - rad > vw->range) {
        return 0;
    }
    if (!vw->all_round
        && (v2_cross(vw->left, v) > rad + FOV_MARGIN || v2_cross(v, vw->right) > rad + FOV_MARGIN)) {
        return 2;
    }
    float heading = vw->heading;
    float mid = geom_wrap(atan2f(v.y, v.x) - heading), w = asinf(rad / d);
    out->lo = mid - w;
    out->hi = mid + w;
    out->near = d - rad;
    return 1;
}

static int box_interval(vec2_t cam, float heading, const obstacle_t *o, interval_t *out)
{
    vec2_t v = v2_sub(o->c, cam);
    float mid = atan2f(v.y, v.x);
    float lo = 0.0f, hi = 0.0f, near = INFINITY;
    for (int e = 0; e < 4; e++) {
        vec2_t q = v2_sub(o->corner[e], cam);
        float rel = geom_wrap(atan2f(q.y, q.x) - mid);
        lo = fminf(lo, rel);
        hi = fmaxf(hi, rel);
        vec2_t n = v2_sub(geom_closest_on_segment(cam, o->corner[e], o->corner[(e + 1) & 3]), cam);
        near = fminf(near, v2_len(n));
    }
    if (near <= 0.0f || hi - lo >= (float)UNITS_PI) {
        return 0;   /* camera inside or against the box */
    }
    float m = geom_wrap(mid - heading);
    out->lo = m + lo;
    out->hi = m + hi;
    out->near = near;
    return 1;
}

#define CAM_MAX_PIECES 16
/* occluder_object of a task's item: the flag, the task in bits 24-30, the
 * item's index below. */
#define CAM_ITEM 0x80000000u
#define CAM_ITEM_TASK_SHIFT 24
#define CAM_ITEM_INDEX 0x00FFFFFFu
#define CAM_MAX_BLOBS 64

/* Removes [lo, hi] from a set of disjoint pieces. */
static int subtract(interval_t *pieces, int n, float lo, float hi)
{
    interval_t out[CAM_MAX_PIECES];
    int m = 0;
    for (int k = 0; k < n; k++) {
        if (hi <= pieces[k].lo || lo >= pieces[k].hi) {
            out[m++] = pieces[k];
            continue;
        }
        if (lo > pieces[k].lo && m < CAM_MAX_PIECES) {
            out[m] = pieces[k];
            out[m++].hi = lo;
        }
        if (hi < pieces[k].hi && m < CAM_MAX_PIECES) {
            out[m] = pieces[k];
            out[m++].lo = hi;
        }
    }
    for (int k = 0; k < m; k++) pieces[k] = out[k];
    return m;
}

static int blob_order(const void *a, const void *b)
{
    const hal_blob_t *x = a, *y = b;
    if (x->pixels != y->pixels) return (x->pixels < y->pixels) ? 1 : -1;
    return (x->bearing_mrad > y->bearing_mrad) - (x->bearing_mrad < y->bearing_mrad);
}

/* Keeps the CAM_MAX_BLOBS largest blobs: a new one replaces the smallest
 * kept when it ranks before it (in a crowd of a task's items more than
 * CAM_MAX_BLOBS can be in view, and the nearest must not be lost to index
 * order).  Below CAM_MAX_BLOBS blobs it only appends. */
static void keep_blob(hal_blob_t *blobs, uint32_t *nb, const hal_blob_t *b)
{
    if (*nb < CAM_MAX_BLOBS) {
        blobs[(*nb)++] = *b;
        return;
    }
    uint32_t worst = 0;
    for (uint32_t k = 1; k < *nb; k++) {
        if (blob_order(&blobs[k], &blobs[worst]) > 0) worst = k;
    }
    if (blob_order(b, &blobs[worst]) < 0) blobs[worst] = *b;
}

/* The all-round camera: what is left of the disc interval `it` (centred
 * on bearing `mid`, half-width `w`) after the blind sector and every nearer
 * occluder, in a frame centred on `mid` so that nothing wraps: each
 * occluder's interval is moved to the same frame and subtracted at its
 * bearing and +-2 pi (an interval narrower than pi that crosses the back of
 * the robot).  Returns the pieces' count. */
static int all_round_pieces(const interval_t *occ, uint32_t nocc, uint32_t t, float half,
                            interval_t pieces[CAM_MAX_PIECES])
{
    const float two_pi = 2.0f * (float)UNITS_PI;
    interval_t it = occ[t];
    float mid = 0.5f * (it.lo + it.hi), w = 0.5f * (it.hi - it.lo);
    pieces[0] = (interval_t){ -w, w, it.near };
    int np = 1;
    if (half < (float)UNITS_PI) {   /* the blind sector behind, centred on pi */
        float b = geom_wrap((float)UNITS_PI - mid), bw = (float)UNITS_PI - half;
        for (int s = -1; s <= 1 && np > 0; s++) {
            np = subtract(pieces, np, b + s * two_pi - bw, b + s * two_pi + bw);
        }
    }
    for (uint32_t q = 0; q < nocc && np > 0; q++) {
        if (q == t || occ[q].near >= it.near) {
            continue;
        }
        float qw = 0.5f * (occ[q].hi - occ[q].lo);
        float d = geom_wrap(0.5f * (occ[q].lo + occ[q].hi) - mid);
        for (int s = -1; s <= 1 && np > 0; s++) {
            float c = d + s * two_pi;
            if (c + qw > -w && c - qw < w) {
                np = subtract(pieces, np, c - qw, c + qw);
            }
        }
    }
    for (int k = 0; k < np; k++) {   /* back to the robot frame */
        pieces[k].lo += mid;
        pieces[k].hi += mid;
    }
    return np;
}

/* What one camera needs to turn an interval into a blob. */
typedef struct camera_frame {
    const camera_config_t *cfg;
    const sim_item_t *const *items;   /**< per task */
    const interval_t *occ;
    const uint32_t *occ_obj;
    uint32_t nocc;
    float half, col, vfov, range;
    int all_round;
} camera_frame_t;

static void what_of(const struct sim *sim, const camera_frame_t *fr, uint32_t t, int *colour, float *height)
{
    uint32_t what = fr->occ_obj[t];
    const sim_item_t *item = (what & CAM_ITEM)
        ? &fr->items[(what & ~CAM_ITEM) >> CAM_ITEM_TASK_SHIFT][what & CAM_ITEM_INDEX] : NULL;
    const obstacle_t *o = item ? NULL : &sim->obstacles[what];
    *colour = item ? item->colour : o->colour;
    *height = item ? item->height : o->height;
}

/* Rows: the object spans the floor to its top, seen from the lens. */
static float rows_of(const camera_frame_t *fr, float near, float height)
{
    float dist = near > 0.001f ? near : 0.001f;
    float vang = atanf(fmaxf(height - CAMERA_HEIGHT, 0.0f) / dist) + atanf(CAMERA_HEIGHT / dist);
    return fminf(vang, fr->vfov) / (fr->vfov / fr->cfg->height_px);
}

/* The blob of interval t (an obstacle or an item), or 0 when it shows
 * none: colourless, out of range, hidden, or narrower than a column. */
static int blob_of(const struct sim *sim, const camera_frame_t *fr, uint32_t t, hal_blob_t *b)
{
    int colour;
    float height, half = fr->half;
    interval_t it = fr->occ[t];
    what_of(sim, fr, t, &colour, &height);
    if (colour == HAL_COLOUR_NONE || it.near > fr->range) {
        return 0;
    }
    interval_t pieces[CAM_MAX_PIECES] = { { fmaxf(it.lo, -half), fminf(it.hi, half), it.near } };
    int np = (pieces[0].hi > pieces[0].lo) ? 1 : 0;
    if (fr->all_round) {
        np = all_round_pieces(fr->occ, fr->nocc, t, half, pieces);
    }
    for (uint32_t q = 0; !fr->all_round && q < fr->nocc && np > 0; q++) {
        if (q != t && fr->occ[q].near < it.near) {
            np = subtract(pieces, np, fr->occ[q].lo, fr->occ[q].hi);
        }
    }
    int best = -1;
    for (int k = 0; k < np; k++) {
        if (best < 0 || pieces[k].hi - pieces[k].lo > pieces[best].hi - pieces[best].lo) best = k;
    }
    if (best < 0) {
        return 0;
    }
    float width = pieces[best].hi - pieces[best].lo;
    float cols = width / fr->col;
    if (cols < 1.0f) {
        return 0;   /* narrower than a pixel column */
    }
    float rows = rows_of(fr, it.near, height);
    float bearing = 0.5f * (pieces[best].lo + pieces[best].hi);
    b->colour = (uint8_t)colour;
    /* All round: in (-pi, pi], +-pi straight behind. */
    b->bearing_mrad = (int16_t)lroundf(1000.0f * (fr->all_round ? geom_wrap(bearing) : bearing));
    b->width_mrad = (uint16_t)lroundf(1000.0f * width);
    float px = floorf(cols) * fmaxf(1.0f, floorf(rows));
    b->pixels = (uint16_t)fminf(px, 65535.0f);
    return 1;
}

/* The most pixels interval t could show (all of it in view, nothing in
 * front), a little generous for rounding; 0 when it can show none. */
static float pixel_bound(const struct sim *sim, const camera_frame_t *fr, uint32_t t)
{
    int colour;
    float height;
    interval_t it = fr->occ[t];
    what_of(sim, fr, t, &colour, &height);
    if (colour == HAL_COLOUR_NONE || it.near > fr->range) {
        return 0.0f;
    }
    float cols = floorf((it.hi - it.lo) / fr->col * 1.001f + 0.001f);
    return cols < 1.0f ? 0.0f : fminf(cols * fmaxf(1.0f, floorf(rows_of(fr, it.near, height))), 65535.0f);
}

/* Candidates by their bound, most first, then by index. */
static int by_bound(const void *a, const void *b)
{
    const camera_candidate_t *x = a, *y = b;
    if (x->bound != y->bound) return x->bound < y->bound ? 1 : -1;
    return (x->index > y->index) - (x->index < y->index);
}

uint8_t camera_geometric_blobs(sim_t *sim, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS])
{
    const camera_config_t *cfg = sim_model_config(sim, SIM_MODEL_camera);
    const sim_robot_t *r = &sim->robots[i];
    float fov, range;
    camera_lens(cfg, r->id, &fov, &range);
    float heading = r->theta;
    float half = fov * (float)UNITS_PI / 360.0f;
    float col = 2.0f * half / cfg->width_px;        /* rad per column */
    float vfov = 2.0f * half * cfg->height_px / cfg->width_px;
    vec2_t dir = v2(cosf(heading), sinf(heading));
    vec2_t cam = v2(r->x + EPUCK_BODY_RADIUS_M * dir.x, r->y + EPUCK_BODY_RADIUS_M * dir.y);
    /* The all-round stand-in (fov > 179 deg): a panoramic (cylindrical)
     * image of `fov` degrees centred ahead, its lens on the robot's axis
     * (as the e-puck's omnidirectional turret sits on top of the body),
     * pixels square in angle: col rad per column and per row. */
    int all_round = fov > CAMERA_PINHOLE_MAX_DEG;
    if (all_round) {
        cam = v2(r->x, r->y);
        vfov = col * cfg->height_px;
    }
    view_t vw = { cam, heading, dir, range, all_round, v2_rot(dir, cosf(half), sinf(half)),
                  v2_rot(dir, cosf(half), -sinf(half)) };

    sim_scratch_t *ws = sim_robot_scratch(sim, i);
    camera_scratch_t *cw = sim_model_scratch(sim, SIM_MODEL_camera, sim->robots[i].hal.worker);
    uint32_t *obst = cw->obstacles, *rob = cw->robots;
    uint32_t *occ_obj = cw->occluder_object;
    interval_t *occ = cw->intervals;
    uint32_t no = sim_gather_obstacles(sim, ws, cam.x - range, cam.y - range, cam.x + range, cam.y + range,
                                       obst, CAMERA_MAX_NEAR);
    uint32_t nr = sim_gather_robots(sim, cam.x - range - EPUCK_BODY_RADIUS_M, cam.y - range - EPUCK_BODY_RADIUS_M,
                                    cam.x + range + EPUCK_BODY_RADIUS_M, cam.y + range + EPUCK_BODY_RADIUS_M,
                                    rob, CAMERA_MAX_NEAR);
    /* Everything that can hide something: other robots and all obstacles.
     * `counted`: what nocc would be with the discs outside the view kept
     * too (the items' cap below counts them, as it always did). */
    uint32_t nocc = 0, counted = 0;
    for (uint32_t j = 0; j < nr; j++) {
        if (rob[j] != i) {
            int got = disc_interval(&vw, sim_robot_at(sim, rob[j]), EPUCK_BODY_RADIUS_M, &occ[nocc]);
            nocc += got == 1;
            counted += got != 0;
        }
    }
    uint32_t first_obstacle = nocc;
    for (uint32_t j = 0; j < no; j++) {
        const obstacle_t *o = &sim->obstacles[obst[j]];
        int got = (o->shape == SHAPE_CYLINDER) ? disc_interval(&vw, o->c, o->r, &occ[nocc])
                                               : box_interval(cam, heading, o, &occ[nocc]);
        if (got == 1) {
            occ_obj[nocc++] = obst[j];
        }
        counted += got != 0;
    }
    /* The tasks' items (things on the floor): seen and hiding like any object.
     * An item a robot carries sits just ahead of its lens and fills the view. */
    const sim_item_t *items[SCENARIO_MAX_TASKS] = { NULL };
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        uint32_t n_items = run->def->items ? run->def->items(run->self, &items[t]) : 0;
        /* The index's candidates (a box a little larger than the test
         * below, which they then pass or not) in index order, or every item. */
        float m = sqrtf(range * range + 0.01f) + 0.01f;
        const uint32_t *ids;
        uint32_t n_cand = items_near(sim, ws, t, n_items, cam.x - m, cam.y - m, cam.x + m, cam.y + m, &ids);
        for (uint32_t c = 0; c < n_cand && counted < 2 * CAMERA_MAX_NEAR; c++) {
            uint32_t k = ids ? ids[c] : c;
            if (k > CAM_ITEM_INDEX) {
                break;
            }
            const sim_item_t *it = &items[t][k];
            float dx = it->x - cam.x, dy = it->y - cam.y;
            if (dx * dx + dy * dy <= range * range + 0.01f) {
                int got = disc_interval(&vw, v2(it->x, it->y), it->radius, &occ[nocc]);
                if (got == 1) {
                    occ_obj[nocc++] = CAM_ITEM | (t << CAM_ITEM_TASK_SHIFT) | k;
                }
                counted += got != 0;
            }
        }
    }

    camera_frame_t fr = { cfg, items, occ, occ_obj, nocc, half, col, vfov, range, all_round };
    hal_blob_t blobs[CAM_MAX_BLOBS];
    uint32_t nb = 0;
    if (!all_round) {
        for (uint32_t t = first_obstacle; t < nocc; t++) {
            hal_blob_t b;
            if (blob_of(sim, &fr, t, &b)) {
                keep_blob(blobs, &nb, &b);
            }
        }
    } else {
        /* In a crowd of a task's items a hundred can be in view, and each
         * is cut by every nearer one: candidates in order of the most pixels
         * they could show (their whole interval), stopping once HAL_MAX_BLOBS
         * blobs are larger than anything left can be (the robot gets only
         * those).  The result is the one the full scan gives. */
        camera_candidate_t *cand = cw->candidates;
        uint32_t m = 0;
        for (uint32_t t = first_obstacle; t < nocc; t++) {
            float bd = pixel_bound(sim, &fr, t);
            if (bd > 0.0f) {
                cand[m++] = (camera_candidate_t){ bd, t };
            }
        }
        qsort(cand, m, sizeof cand[0], by_bound);
        for (uint32_t k = 0; k < m; k++) {
            uint32_t above = 0;
            for (uint32_t j = 0; j < nb; j++) {
                above += (float)blobs[j].pixels > cand[k].bound;
            }
            if (above >= HAL_MAX_BLOBS) {
                break;
            }
            hal_blob_t b;
            if (blob_of(sim, &fr, cand[k].index, &b)) {
                keep_blob(blobs, &nb, &b);
            }
        }
    }
    qsort(blobs, nb, sizeof blobs[0], blob_order);
    uint8_t count = (uint8_t)(nb < HAL_MAX_BLOBS ? nb : HAL_MAX_BLOBS);
    for (uint8_t k = 0; k < count; k++) out[k] = blobs[k];
    return count;
}
