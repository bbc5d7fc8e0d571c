/*
 * items.h - an index of the tasks' items (the things on the floor a camera
 * sees, task.h) for the camera's range queries.  Without it every camera
 * frame looked at every item of every task: at constant density, work
 * growing with robots x items.
 *
 * Items move only in the tasks' hooks, never while the controllers step,
 * so sim_step bins them once when the control phase begins and drops the
 * index when it ends.  Outside that phase (tests, tools reading sensors
 * between steps) queries answer "every item", as before: an index built
 * then could be stale.
 */
#ifndef SIM_ITEMS_H
#define SIM_ITEMS_H

#include <stdint.h>

#include "swarmsim/grid.h"
#include "swarmsim/scenario.h"

struct sim;
struct sim_scratch;

typedef struct sim_item_index {
    int valid;                         /**< 1 during the control phase */
    grid_t grid[SCENARIO_MAX_TASKS];   /**< per task; nx == 0 until first used */
    float *x, *y;                      /**< binning's copy of the centres */
    uint32_t cap;                      /**< of x, y and every worker's sim_scratch_t.items */
} sim_item_index_t;

/** Bins every task's items (the control phase begins).  Its buffers grow
 *  with the items (out of memory: sim_out_of_memory). */
void items_index_build(struct sim *sim);

/** The control phase ends: items may move again. */
void items_index_drop(struct sim *sim);

void items_index_free(struct sim *sim);

/** Task t's items (n_items of them) that may lie in the box: their indices
 *  in ascending order in *ids (in the worker's scratch `ws`), and how many;
 *  or *ids = NULL and n_items, meaning every item in index order (no index
 *  now). */
uint32_t items_near(const struct sim *sim, struct sim_scratch *ws, uint32_t t, uint32_t n_items, float minx,
                    float miny, float maxx, float maxy, const uint32_t **ids);

#endif
