/*
 * calib.h - the calibration image: a controller that does nothing of its
 * own and, as the host asks (calib_msg.h: one host message per command),
 * streams raw sensor readings through the ordinary telemetry, for the
 * calibration kit (tools/swarmtools/calibrate, docs/how-to/calibrate.md)
 * to fit the simulator's models to this robot.
 *
 * Readings are taken every control period and summed over windows of
 * window_steps periods (default ROBOT_TELEMETRY_STEPS: one window per
 * robot_state_t message, so each message carries one window).  After a
 * command the first settle_windows windows are dropped (the robot was just
 * placed, a sensor's filter settles) and the state says "settle" until
 * the first window after them is latched (at least one whole window: one
 * robot_state_t says "settle" at least once); then
 * every window's mean and variance per channel is latched into the
 * observables mean0..7 and var0..7 until the next command:
 *
 *   state      channels (mean<k>, var<k>)
 *   prox       k = IR sensor 0..7, counts, counts^2
 *   ambient    k = IR sensor 0..7, counts, counts^2
 *   mic        k = microphone 0..2 of the band asked, level counts
 *   camera     k = 0 bearing, 1 width of the widest blob of the colour
 *              asked (mrad; 0 when none), 2 blobs of it in view
 *   frame      k = 0 pixels counted, 1..3 their R, G, B mean, 4..6 their
 *              R, G, B sd (0..255; every pixel for colour 0, else those
 *              the detector gives the colour asked: hal_camera_colour_stats)
 *   drive      mean0, mean1: left and right steps counted since the
 *   driven     command; mean2: periods driven ("driven": stopped, and
 *              the counts read after the last period driven: final); no
 *              settling
 *   idle       nothing (after power-on and 'S')
 *   tone       mean0: the band its speaker plays ('T', 0: silent): the
 *              emitter of another robot's microphone procedure
 *   no_sound   a mic command on an image or platform without sound
 *   no_frame   a frame command on a platform that passes no frames on
 *
 * Variances are of the readings within a window, from sums of differences
 * to the window's first reading (no cancellation in float).  The controller
 * draws nothing; its wheels turn only during a drive command.
 */
#ifndef FW_CALIB_H
#define FW_CALIB_H

#include <stdint.h>

#include "common/controller.h"
#include "hal.h"
#include "calib_msg.h"

/** Channels per window. */
#define CALIB_CHANNELS 8u

typedef struct calib_params {
    uint8_t window_steps;      /**< control periods per window (10) */
    uint8_t settle_windows;    /**< windows dropped after a command (1) */
} calib_params_t;

typedef enum calib_mode {
    CALIB_IDLE = 0,
    CALIB_PROX = 1,
    CALIB_AMBIENT = 2,
    CALIB_MIC = 3,
    CALIB_CAMERA = 4,
    CALIB_DRIVE = 5,
    CALIB_TONE = 6,
    CALIB_FRAME = 7
} calib_mode_t;

typedef struct calib {
    calib_params_t params;
    uint32_t seed;             /**< kept by the contract; it draws nothing */
    uint8_t mode;              /**< calib_mode_t */
    uint8_t arg;               /**< the band (mic) or colour (camera, frame) asked */
    uint8_t dropped;           /**< windows dropped since the command (to settle_windows) */
    uint8_t latched;           /**< 1: a window was latched since the command */
    uint8_t samples;           /**< readings in the current window */
    uint8_t unavailable;       /**< the sensor asked for is not on this robot */
    uint16_t bad_msgs;         /**< malformed commands ignored */
    uint16_t drive_left;       /**< periods still to drive */
    uint16_t driven;           /**< periods driven since the command */
    int16_t cmd_left, cmd_right;   /**< the drive's speeds, steps/s */
    int16_t last_left, last_right; /**< step counters at the previous period */
    int32_t steps_left, steps_right; /**< steps counted since the command */
    float first[CALIB_CHANNELS];   /**< the window's first reading per channel */
    float sum[CALIB_CHANNELS];     /**< sum of (reading - first) */
    float sum2[CALIB_CHANNELS];    /**< sum of (reading - first)^2 */
    float mean[CALIB_CHANNELS];    /**< the last window's (observables) */
    float var[CALIB_CHANNELS];
} calib_t;

/* The controller contract (controller.h). */
CONTROLLER_API(calib);

#define CALIB_NAME "calib"
extern const observable_t calib_observables[];
extern const controller_def_t calib_def;

#endif
