/*
 * image_telemetry.h - the e-puck2 run loop's telemetry (image_main.h, for
 * the images with `telemetry yes`): the part of robot_telemetry's input
 * only the e-puck2's struct hal knows (this step's wheel and LED commands,
 * IR and ambient summaries).  The messages are firmware/telemetry/
 * robot_telemetry.c's, as on the e-puck1 and in the simulator, so the
 * bridge, monitor and plots take an e-puck2's stream as an e-puck1's.
 */
#ifndef EPUCK2_IMAGE_TELEMETRY_H
#define EPUCK2_IMAGE_TELEMETRY_H

#include "hal_epuck2.h"
#include "telemetry/robot_telemetry.h"

/** The image's telemetry for this step (robot_telemetry_step), after its
 *  controller's step; on the steps that send a robot_state_t, the commands
 *  of this step and, when `reads_sensors` is non-zero, the IR and ambient
 *  summaries (-1: a controller that reads none). */
void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src,
                          uint8_t reads_sensors);

#endif
