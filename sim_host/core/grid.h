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
} grid_t;

/** Covers [x0, x0+w] x [y0, y0+h] with cells of side about `cell`.
 *  Returns 0, or -1 when out of memory. */
int grid_init(grid_t *g, float x0, float y0, float w, float h, float cell);
void grid_free(grid_t *g);

/** Bins `n` points (robot centres).  Returns 0 or -1 (out of memory). */
int grid_build_points(grid_t *g, const float *x, const float *y, uint32_t n);

/** Bins `n` boxes given as min x, min y, max x, max y. */
int grid_build_boxes(grid_t *g, const float (*aabb)[4], uint32_t n);

/** Cell index range covering a box, clamped to the grid. */
static inline void grid_range(const grid_t *g, float minx, float miny, float maxx, float maxy,
                              int32_t *cx0, int32_t *cy0, int32_t *cx1, int32_t *cy1)
{
    int32_t a = (int32_t)((minx - g->x0) / g->cell), b = (int32_t)((miny - g->y0) / g->cell);
    int32_t c = (int32_t)((maxx - g->x0) / g->cell), d = (int32_t)((maxy - g->y0) / g->cell);
    *cx0 = a < 0 ? 0 : (a >= g->nx ? g->nx - 1 : a);
    *cy0 = b < 0 ? 0 : (b >= g->ny ? g->ny - 1 : b);
    *cx1 = c < 0 ? 0 : (c >= g->nx ? g->nx - 1 : c);
    *cy1 = d < 0 ? 0 : (d >= g->ny ? g->ny - 1 : d);
}

#endif
