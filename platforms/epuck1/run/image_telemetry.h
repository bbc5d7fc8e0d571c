/*
 * image_telemetry.h - the e-puck1 run loop's telemetry (image_main.h, for the
 * images with `telemetry yes`): the part of robot_telemetry's input only the
 * e-puck's struct hal knows (this step's wheel and LED commands, IR and
 * ambient summaries).  The messages themselves are
 * firmware/telemetry/robot_telemetry.c's, the same code the simulator runs
 * for every robot when a scenario asks.
 */
#ifndef EPUCK1_IMAGE_TELEMETRY_H
#define EPUCK1_IMAGE_TELEMETRY_H

#include "hal_epuck.h"
#include "telemetry/robot_telemetry.h"

/** The image's telemetry for this step (robot_telemetry_step), after its
 *  controller's step.  On the steps that send a robot_state_t it adds what
 *  the e-puck's struct hal knows: the commands of this step and, when
 *  `reads_sensors` is non-zero, the summaries of the IR and ambient
 *  readings (-1: a controller that reads none, such as the beacon). */
void image_telemetry_step(robot_telemetry_t *t, struct hal *hal, const robot_telemetry_source_t *src,
                          uint8_t reads_sensors);

#endif
