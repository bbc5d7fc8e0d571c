/*
 * items.c - the index of the tasks' items (items.h).
 */
#include "items.h"

#include <stdlib.h>

#include "pool.h"
#include "sim_internal.h"

/* Cells of 0.5 m, as the robot grid's: a camera's range (0.6 m by
 * default) meets about 4 x 4 of them. */
#define ITEM_CELL_M 0.5f

/* Room for n items: the binning's copy, and every worker's query buffer
 * (sim_scratch_t.items). */
static int reserve(struct sim *sim, uint32_t n)
{
    sim_item_index_t *ix = &sim->item_index;
    if (n <= ix->cap) {
        return 0;
    }
    float *x = realloc(ix->x, (size_t)n * sizeof *x);
    if (x) ix->x = x;
    float *y = realloc(ix->y, (size_t)n * sizeof *y);
    if (y) ix->y = y;
    int bad = !x || !y;
    for (uint32_t w = 0; w < pool_threads(sim->pool); w++) {
        uint32_t *near = realloc(sim->scratch[w].items, (size_t)n * sizeof *near);
        if (near) sim->scratch[w].items = near;
        bad |= !near;
    }
    if (bad) {
        return -1;
    }
    ix->cap = n;
    return 0;
}

void items_index_build(struct sim *sim)
{
    sim_item_index_t *ix = &sim->item_index;
    ix->valid = 0;
    for (uint32_t t = 0; t < sim->n_tasks; t++) {
        const sim_task_run_t *run = &sim->tasks[t];
        const sim_item_t *items = NULL;
        uint32_t n = run->def->items ? run->def->items(run->self, &items) : 0;
        grid_t *g = &ix->grid[t];
        if (n == 0) {
            continue;
        }
        if (reserve(sim, n) != 0
            || (g->nx == 0 && grid_init(g, -sim->hw, -sim->hh, 2 * sim->hw, 2 * sim->hh, ITEM_CELL_M) != 0)) {
            sim_out_of_memory("the index of the tasks' items");
        }
        for (uint32_t k = 0; k < n; k++) {
            ix->x[k] = items[k].x;
            ix->y[k] = items[k].y;
        }
        if (grid_build_points(g, ix->x, ix->y, n) != 0) {
            sim_out_of_memory("the index of the tasks' items");
        }
    }
    ix->valid = 1;
}

void items_index_drop(struct sim *sim) { sim->item_index.valid = 0; }

void items_index_free(struct sim *sim)
{
    sim_item_index_t *ix = &sim->item_index;
    for (uint32_t t = 0; t < SCENARIO_MAX_TASKS; t++) {
        grid_free(&ix->grid[t]);
    }
    free(ix->x);
    free(ix->y);
}

uint32_t items_near(const struct sim *sim, struct sim_scratch *ws, uint32_t t, uint32_t n_items, float minx,
                    float miny, float maxx, float maxy, const uint32_t **ids)
{
    const sim_item_index_t *ix = &sim->item_index;
    if (!ix->valid || n_items == 0 || ix->grid[t].nx == 0) {
        *ids = NULL;
        return n_items;
    }
    uint32_t n = grid_gather(&ix->grid[t], minx, miny, maxx, maxy, ws->items, ix->cap);
    grid_sort_ids(ws->items, n);
    *ids = ws->items;
    return n;
}
