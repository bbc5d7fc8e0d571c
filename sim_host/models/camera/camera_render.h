/*
 * camera_render.h - what one robot's front camera sees, drawn with OSMesa
 * (camera.model: rendered): the arena's floor and walls, the obstacles,
 * the other robots (bodies and lit LEDs) and the tasks' items in their
 * colours, lit by the scenario's lamps, at the robot image's frame size.
 *
 * Threads: a renderer owns one OSMesa context and binds it on the calling
 * thread only for the duration of a call.  One sim owns at most one (it
 * creates it at its first rendered frame), and a sim is stepped by one
 * thread at a time, so each worker thread renders with its own context.
 * llvmpipe's rasteriser threads: camera_render_set_threads.
 */
#ifndef SIM_CAMERA_RENDER_H
#define SIM_CAMERA_RENDER_H

#include <stdint.h>

#include "swarmsim/base.h"

struct sim;

typedef struct camera_render camera_render_t;

/** Sets LP_NUM_THREADS to 0 (llvmpipe rasterises on the calling thread)
 *  unless the environment already sets it.  A 40 x 20 viewport is a few
 *  tiles: helper threads would only add hand-offs, and each worker thread
 *  already renders its own runs.  Mesa reads it once, when the first OSMesa
 *  context of the process is created, so swarmsim calls this before any
 *  rendering when a scenario renders its cameras; camera_render_create
 *  calls it too. */
void camera_render_set_threads(void);

/** A renderer of width x height pixel frames (1..160 each).  NULL with a
 *  message in err when OSMesa cannot make one. */
camera_render_t *camera_render_create(uint16_t width, uint16_t height, char err[SIM_ERR_MAX]);
void camera_render_destroy(camera_render_t *cr);

/** Draws robot i's view of the current state of `sim` into rgb (width x
 *  height x 3 bytes, 8-bit RGB, the top row first, column 0 the left edge
 *  as the robot looks ahead).  Only reads the simulation.  0, or -1 with a
 *  message in err. */
int camera_render_view(camera_render_t *cr, struct sim *sim, uint32_t i, uint8_t *rgb, char err[SIM_ERR_MAX]);

#endif
