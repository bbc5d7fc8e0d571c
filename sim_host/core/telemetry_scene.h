/*
 * telemetry_scene.h - the picture of a run as telemetry, for views that draw
 * it (swarmtools.live): the same data the PNG frames are drawn from
 * (sim_render.c), as two LCM messages that telemetry.c publishes:
 *
 *   SCENE         scene_t          the arena, its walls, obstacles and lamps:
 *                                  at the start and with every RUN_INFO
 *   TASK_DRAWING  task_drawing_t   every task's drawing (drawing.h), the items
 *                                  its cameras see and the robots it marks:
 *                                  at the start, with every RUN_INFO, and at
 *                                  the swarm-state rate when it changed
 *
 * Only reads the simulation (the tasks' draw and items hooks are const), so
 * a run's results do not depend on it.
 */
#ifndef SIM_TELEMETRY_SCENE_H
#define SIM_TELEMETRY_SCENE_H

#include "swarmsim/sim.h"
#include "swarmlcm_scene_t.h"
#include "swarmlcm_task_drawing_t.h"

#define TELEMETRY_CHANNEL_SCENE "SCENE"
#define TELEMETRY_CHANNEL_TASK_DRAWING "TASK_DRAWING"

/** Shapes of one step's drawing kept, as many as a PNG frame draws; more
 *  are dropped (drawing_add). */
#define TELEMETRY_SCENE_SHAPES_MAX 4096

typedef struct telemetry_scene telemetry_scene_t;

/** Memory for the pictures of the run of `sim`; NULL when out of memory. */
telemetry_scene_t *telemetry_scene_create(const sim_t *sim);
void telemetry_scene_destroy(telemetry_scene_t *s);

/** Fills *m with the run's scene_t; it points into `s` until the next call. */
void telemetry_scene_fill(telemetry_scene_t *s, const sim_t *sim, swarmlcm_scene_t *m);

/** Fills *m with the tasks' drawing of the current step (pointing into `s`)
 *  and returns 1 when it is to be sent: with `force`, or when it differs from
 *  the last one this returned 1 for.  Returns 0 otherwise, and -1 when out of
 *  memory (nothing to send). */
int telemetry_scene_drawing(telemetry_scene_t *s, const sim_t *sim, int force, swarmlcm_task_drawing_t *m);

#endif
