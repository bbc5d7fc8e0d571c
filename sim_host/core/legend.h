/*
 * legend.h - a run's legend: what the colours of its pictures mean, from
 * its tasks' legends (task_def_t.legend).  The PNG frames and the videos
 * draw it (sim_render.c, render_overlay.c) and the scene telemetry carries
 * it to the live page (telemetry_scene.c), so every view has the same keys
 * in the same colours.
 */
#ifndef SIM_LEGEND_H
#define SIM_LEGEND_H

#include <stdint.h>

#include "swarmsim/drawing.h"
#include "swarmsim/sim.h"

/** Room for the keys of every task, and the default body's. */
#define LEGEND_KEYS_MAX 32

/** Fills keys (LEGEND_KEYS_MAX of room) and returns how many: every task's
 *  robot fills in registry order, then the default body's key if no task
 *  says what it means ("other" beside a task's keys, else "robot"), then
 *  the tasks' floor areas, outlines and items.  Keys past the room are
 *  dropped. */
uint32_t legend_collect(const sim_t *sim, draw_key_t keys[LEGEND_KEYS_MAX]);

#endif
