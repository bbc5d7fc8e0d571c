/*
 * grid.h - a uniform grid over the arena for neighbour queries.
 *
 * Robots are re-binned every control step (a counting sort, O(n)); static
 * obstacles are binned once by their bounding boxes.  Cell contents are
 * in index order, so queries visit items in a deterministic order.
 */
#ifndef SIM_GRID_H
#define SIM_GRID_H

#include <stdint.h>

typedef struct grid {
    float x0, y0;        /**< lower-left corner, m */
    float cell;          /**< cell side, m */
    int32_t nx, ny;
    uint32_t *start;     /**< nx*ny + 1 offsets into items */
    uint32_t *items;
    uint32_t item_cap;
    uint32_t *point_cell; /**< point_cap: each point's cell while binning (found once, used twice) */
    uint32_t point_cap;
} grid_t;

/** Covers [x0, x0+w] x [y0, y0+h] with cells of side about `cell`.
 *  Returns 0, or -1 when out of memory. */
int grid_init(grid_t *g, float x0, float y0, float w, float h, float cell);
void grid_free(grid_t *g);

/** Makes room for `n` items, so that binning up to `n` never allocates (a
 *  step cannot fail: reserve when the run is built).  Returns 0 or -1. */
int grid_reserve(grid_t *g, uint32_t n);

/** Bins `n` points (robot centres, items).  A point with a NaN coordinate
 *  is left out (an item out of play).  Returns 0 or -1 (out of memory). */
int grid_build_points(grid_t *g, const float *x, const float *y, uint32_t n);

/** Writes to `out` (at most `max`) what the cells meeting the box hold,
 *  cell by cell: a superset of the points in the box (the caller tests
 *  each), not in index order (grid_sort_ids).  Returns how many. */
uint32_t grid_gather(const grid_t *g, float minx, float miny, float maxx, float maxy, uint32_t *out,
                     uint32_t max);

/** Sorts distinct ids ascending: candidates from several cells visited in
 *  index order, as a scan of every item would visit them.  Ids must be
 *  distinct (a grid holds each point once) and below UINT32_MAX. */
void grid_sort_ids(uint32_t *ids, uint32_t n);

/** Bins `n` boxes given as min x, min y, max x, max y. */
int grid_build_boxes(grid_t *g, const float (*aabb)[4], uint32_t n);

/** Column or row of coordinate offset v (in cells), clamped to [0, n-1]
 *  in float before the conversion, so that a NaN or a far-away value
 *  (a task's item out of play) is never converted out of int32 range. */
static inline int32_t grid_clamp(float v, int32_t n)
{
    if (!(v >= 1.0f)) {
        return 0;           /* also NaN; (-1, 1) truncates to 0 as before */
    }
    if (v >= (float)(n - 1)) {
        return n - 1;
    }
    return (int32_t)v;
}

/** Cell index range covering a box, clamped to the grid. */
static inline void grid_range(const grid_t *g, float minx, float miny, float maxx, float maxy,
                              int32_t *cx0, int32_t *cy0, int32_t *cx1, int32_t *cy1)
{
    *cx0 = grid_clamp((minx - g->x0) / g->cell, g->nx);
    *cy0 = grid_clamp((miny - g->y0) / g->cell, g->ny);
    *cx1 = grid_clamp((maxx - g->x0) / g->cell, g->nx);
    *cy1 = grid_clamp((maxy - g->y0) / g->cell, g->ny);
}

#endif
