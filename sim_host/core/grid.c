/*
 * grid.c - the uniform grid of grid.h: counting-sort binning of points and
 * boxes.
 */
#include "swarmsim/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int grid_init(grid_t *g, float x0, float y0, float w, float h, float cell)
{
    memset(g, 0, sizeof *g);
    g->x0 = x0;
    g->y0 = y0;
    g->nx = (int32_t)(w / cell) + 1;
    g->ny = (int32_t)(h / cell) + 1;
    /* Keep the grid bounded for huge arenas with tiny cells. */
    while ((int64_t)g->nx * g->ny > 4000000) {
        cell *= 2.0f;
        g->nx = (int32_t)(w / cell) + 1;
        g->ny = (int32_t)(h / cell) + 1;
    }
    g->cell = cell;
    g->start = calloc((size_t)g->nx * (size_t)g->ny + 1, sizeof *g->start);
    return g->start ? 0 : -1;
}

void grid_free(grid_t *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

int grid_reserve(grid_t *g, uint32_t n)
{
    if (n <= g->item_cap) {
        return 0;
    }
    uint32_t *p = realloc(g->items, (size_t)n * sizeof *p);
    if (!p) {
        return -1;
    }
    g->items = p;
    g->item_cap = n;
    return 0;
}

static int32_t cell_of(const grid_t *g, float x, float y)
{
    int32_t cx, cy, cx1, cy1;
    grid_range(g, x, y, x, y, &cx, &cy, &cx1, &cy1);
    return cy * g->nx + cx;
}

int grid_build_points(grid_t *g, const float *x, const float *y, uint32_t n)
{
    size_t cells = (size_t)g->nx * (size_t)g->ny;
    uint32_t kept = 0;
    if (grid_reserve(g, n) != 0) {
        return -1;
    }
    memset(g->start, 0, (cells + 1) * sizeof *g->start);
    for (uint32_t i = 0; i < n; i++) {
        if (!isnan(x[i]) && !isnan(y[i])) {
            g->start[cell_of(g, x[i], y[i]) + 1]++;
            kept++;
        }
    }
    for (size_t c = 0; c < cells; c++) {
        g->start[c + 1] += g->start[c];
    }
    /* Fill back to front so each cell ends up in ascending index order
     * without a cursor array: start[c] walks down to its final value. */
    for (uint32_t k = n; k-- > 0;) {
        if (!isnan(x[k]) && !isnan(y[k])) {
            int32_t c = cell_of(g, x[k], y[k]);
            g->items[--g->start[c + 1]] = k;
        }
    }
    /* start[c+1] now holds the beginning of cell c: shift back by one. */
    memmove(g->start, g->start + 1, cells * sizeof *g->start);
    g->start[cells] = kept;
    return 0;
}

int grid_build_boxes(grid_t *g, const float (*aabb)[4], uint32_t n)
{
    size_t cells = (size_t)g->nx * (size_t)g->ny;
    uint32_t total = 0;
    int32_t cx0, cy0, cx1, cy1;
    memset(g->start, 0, (cells + 1) * sizeof *g->start);
    for (uint32_t i = 0; i < n; i++) {
        grid_range(g, aabb[i][0], aabb[i][1], aabb[i][2], aabb[i][3], &cx0, &cy0, &cx1, &cy1);
        for (int32_t cy = cy0; cy <= cy1; cy++) {
            for (int32_t cx = cx0; cx <= cx1; cx++) {
                g->start[cy * g->nx + cx + 1]++;
                total++;
            }
        }
    }
    if (grid_reserve(g, total) != 0) {
        return -1;
    }
    for (size_t c = 0; c < cells; c++) {
        g->start[c + 1] += g->start[c];
    }
    for (uint32_t k = n; k-- > 0;) {
        grid_range(g, aabb[k][0], aabb[k][1], aabb[k][2], aabb[k][3], &cx0, &cy0, &cx1, &cy1);
        for (int32_t cy = cy0; cy <= cy1; cy++) {
            for (int32_t cx = cx0; cx <= cx1; cx++) {
                g->items[--g->start[cy * g->nx + cx + 1]] = k;
            }
        }
    }
    memmove(g->start, g->start + 1, cells * sizeof *g->start);
    g->start[cells] = total;
    return 0;
}

uint32_t grid_gather(const grid_t *g, float minx, float miny, float maxx, float maxy, uint32_t *out,
                     uint32_t max)
{
    int32_t cx0, cy0, cx1, cy1;
    uint32_t n = 0;
    grid_range(g, minx, miny, maxx, maxy, &cx0, &cy0, &cx1, &cy1);
    for (int32_t cy = cy0; cy <= cy1; cy++) {
        for (int32_t cx = cx0; cx <= cx1; cx++) {
            int32_t c = cy * g->nx + cx;
            for (uint32_t k = g->start[c]; k < g->start[c + 1] && n < max; k++) {
                out[n++] = g->items[k];
            }
        }
    }
    return n;
}

static int id_order(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

void grid_sort_ids(uint32_t *ids, uint32_t n)
{
    if (n > 32) {
        qsort(ids, n, sizeof *ids, id_order);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {   /* a few candidates: insertion sort */
        uint32_t v = ids[i], j = i;
        for (; j > 0 && ids[j - 1] > v; j--) {
            ids[j] = ids[j - 1];
        }
        ids[j] = v;
    }
}
