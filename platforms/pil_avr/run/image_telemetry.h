/*
 * image_telemetry.h - the PIL run loop's telemetry (image_main.h, for the
 * images with `telemetry yes`): what only this platform's struct hal knows
 * of a step (its wheel and LED commands, the IR and ambient readings and
 * blobs it read).  The messages are firmware/telemetry/robot_telemetry.c's,
 * as on the robot and in the simulator.
 *
 * Unlike the e-puck1's run loop it reads no sensor for the summaries: a
 * read here would be a request the host-built robot never makes, and the
 * simulator's noise streams would part.  It reports what the controller
 * read this step, as the simulator does for its own robots
 * (sim_robot_platform), so the two send the same bytes.
 */
#ifndef PIL_IMAGE_TELEMETRY_H
#define PIL_IMAGE_TELEMETRY_H

#include "hal_pil.h"
#include "telemetry/robot_telemetry.h"

/** The image's telemetry for this step, after its controller's step. */
void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src);

#endif
