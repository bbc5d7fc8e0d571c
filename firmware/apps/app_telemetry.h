/*
 * app_telemetry.h - what the e-puck images that publish telemetry share: the
 * part of robot_telemetry's input only the e-puck's struct hal knows (this
 * step's wheel and LED commands, IR and ambient summaries).  The messages
 * themselves are firmware/telemetry/robot_telemetry.c's, the same code the
 * simulator runs for every robot when a scenario asks.
 */
#ifndef APP_TELEMETRY_H
#define APP_TELEMETRY_H

#include "hal_epuck.h"
#include "telemetry/robot_telemetry.h"

/** This step's platform values of the robot `hal`: the commands it was
 *  given and the summaries of its IR and ambient readings (sampled once
 *  per step on the e-puck, so reading them here costs nothing). */
void app_telemetry_platform(struct hal *hal, robot_telemetry_platform_t *out);

#endif
