/*
 * platform_facts.h - what differs between the robot models the toolkit
 * runs on (the e-puck1 and the e-puck2), written once: the firmware's
 * platform folders read the facts of their robot (platforms/epuck2/hal
 * through epuck2_lib.h), and the simulator's models take them as their
 * defaults for a group of that model (the scenario's `robots[].robot`,
 * sim_host/models/platform/; a model's own scenario key still overrides).
 * What the two share (geometry, the IR ring, hal.h's limits) is in
 * units.h and hal.h.
 *
 * Each fact says where it comes from:
 *   (documented)  GCtronic's documentation or its library's own notes:
 *                 a number measured by GCtronic, not by us;
 *   (library)     read in the robot library's public headers or sources
 *                 (the e-puck library, e-puck2_main-processor): what the
 *                 firmware configures, so true by construction;
 *   (ours)        how our HAL uses the hardware (the same on every robot
 *                 of the model);
 *   (assumed) [?] not confirmed anywhere: check it on a robot.
 * No fact here was measured on a robot by us (docs/hardware/epuck2.md,
 * "What the tests cover").
 *
 * Integer constants only (the dsPIC has no FPU): a frame rate is in
 * tenths of a frame per second.
 */
#ifndef HAL_PLATFORM_FACTS_H
#define HAL_PLATFORM_FACTS_H

#include <stdint.h>

#include "sound_bands.h"
#include "units.h"

/** The robot models, in the order of their ids (0: the default). */
#define PLATFORM_MODELS(X) X(EPUCK1) X(EPUCK2)

/** Bits of <P>_IRCOM_BACKENDS: the IR communication a model can carry. */
#define PLATFORM_IRCOM_LIBIRCOM 1u   /**< libIrcom, 8 bits over the proximity sensors' emitters */
#define PLATFORM_IRCOM_RANDB 2u      /**< the range-and-bearing turret (an extension board), 16 bits */

/* ------------------------------------------------------------ e-puck1 */

#define EPUCK1_NAME "e-puck1"
/** Camera sensor, pixels (documented: PO3030K or PO6030K, 640 x 480). */
#define EPUCK1_CAMERA_SENSOR_WIDTH_PX 640u
#define EPUCK1_CAMERA_SENSOR_HEIGHT_PX 480u
/** The frame the blob detector gets (ours: the 640 x 320 window
 *  subsampled 16 x 16 by the camera, platforms/epuck1/hal). */
#define EPUCK1_CAMERA_FRAME_WIDTH_PX EPUCK_CAMERA_WIDTH_PX
#define EPUCK1_CAMERA_FRAME_HEIGHT_PX EPUCK_CAMERA_HEIGHT_PX
/** Horizontal field of view, deg (assumed [?]: "about 56 deg" in
 *  third-party e-puck libraries' notes; Webots models a narrower one). */
#define EPUCK1_CAMERA_FOV_DEG 56u
/** Frames per second x 10 (documented: 4.3 fps, GCtronic's e-puck library
 *  for 16 x 16 subsampling in RGB565, camera/fast_2_timer/e_po3030k.h). */
#define EPUCK1_CAMERA_FPS_X10 43u
/** Microphones on the robot (documented) and their sampling rate as the
 *  tone detector gets it (library: sound_bands.h's SOUND_MIC_RATE_HZ, the
 *  A/D scan in ALL_ADC mode); the detector takes TONE_DETECT_N samples. */
#define EPUCK1_MIC_COUNT 3u
#define EPUCK1_MIC_RATE_HZ SOUND_MIC_RATE_HZ
/** Bearings of hal.h's microphones 0, 1, 2, deg counter-clockwise from
 *  ahead (assumed [?]: right, left, back, as the library names them). */
#define EPUCK1_MIC_BEARINGS_DEG { -90, 90, 180 }
/** The motors' top speed, steps/s (documented: 1000 steps/s, 12.9 cm/s). */
#define EPUCK1_MOTOR_SPEED_LIMIT 1000
/** IR communication (library: libIrcom on the robot; documented: the
 *  range-and-bearing turret as an extension board). */
#define EPUCK1_IRCOM_BACKENDS (PLATFORM_IRCOM_LIBIRCOM | PLATFORM_IRCOM_RANDB)
/** LEDs (documented): 8 red in the ring, no RGB LED. */
#define EPUCK1_RED_LEDS 8u
#define EPUCK1_RGB_LEDS 0u
/** Time-of-flight distance sensor, accelerometer, gyroscope: 1 when
 *  fitted (documented: a 3-axis accelerometer only).  hal.h has no
 *  channel for them. */
#define EPUCK1_TOF 0u
#define EPUCK1_ACCELEROMETER 1u
#define EPUCK1_GYROSCOPE 0u

/* ------------------------------------------------------------ e-puck2 */

#define EPUCK2_NAME "e-puck2"
/** Camera sensor, pixels (library: PO8030, PO8030_MAX_WIDTH/HEIGHT). */
#define EPUCK2_CAMERA_SENSOR_WIDTH_PX 640u
#define EPUCK2_CAMERA_SENSOR_HEIGHT_PX 480u
/** The frame the blob detector gets (ours: the same 640 x 320 window,
 *  subsampled 4 x 4 by the camera and averaged 4 x 4 by the HAL into the
 *  e-puck1's frame, platforms/epuck2/hal). */
#define EPUCK2_CAMERA_FRAME_WIDTH_PX EPUCK_CAMERA_WIDTH_PX
#define EPUCK2_CAMERA_FRAME_HEIGHT_PX EPUCK_CAMERA_HEIGHT_PX
/** Horizontal field of view, deg (assumed [?]: taken as the e-puck1's;
 *  the PO8030's lens is not documented where we looked). */
#define EPUCK2_CAMERA_FOV_DEG 56u
/** Frames per second x 10 (assumed [?]: 15 fps, a VGA sensor's usual rate,
 *  one frame a sensor frame in the HAL's one-shot cycle; not confirmed:
 *  count the HAL's cam_frames over a minute on a robot). */
#define EPUCK2_CAMERA_FPS_X10 150u
/** Microphones on the robot (library: 4, right, left, back, front; hal.h
 *  uses the first three) and their PCM rate (library: PDM decimated to
 *  16 kHz, 10 ms buffers); the detector takes TONE_DETECT_N samples. */
#define EPUCK2_MIC_COUNT 4u
#define EPUCK2_MIC_RATE_HZ 16000u
/** Bearings of hal.h's microphones 0, 1, 2 (assumed [?]: the library's
 *  MIC_RIGHT, MIC_LEFT, MIC_BACK, at right, left and back). */
#define EPUCK2_MIC_BEARINGS_DEG { -90, 90, 180 }
/** The motors' top speed, steps/s (library: motors.h MOTOR_SPEED_LIMIT). */
#define EPUCK2_MOTOR_SPEED_LIMIT 1100
/** IR communication (library: the port of libIrcom in src/ircom/, the
 *  turret on the I2C bus). */
#define EPUCK2_IRCOM_BACKENDS (PLATFORM_IRCOM_LIBIRCOM | PLATFORM_IRCOM_RANDB)
/** LEDs (library: 4 red on the STM32, 4 RGB driven by the ESP32). */
#define EPUCK2_RED_LEDS 4u
#define EPUCK2_RGB_LEDS 4u
/** (documented: a ToF distance sensor and a 9-axis IMU.)  hal.h has no
 *  channel for them. */
#define EPUCK2_TOF 1u
#define EPUCK2_ACCELEROMETER 1u
#define EPUCK2_GYROSCOPE 1u

/* ------------------------------------------------------------ as a table */

/** One model's facts, for code that picks a model at run time (the
 *  simulator); firmware uses the constants of its own model above. */
typedef struct platform_facts {
    const char *name;
    uint16_t camera_sensor_width_px, camera_sensor_height_px;
    uint16_t camera_frame_width_px, camera_frame_height_px;
    uint16_t camera_fov_deg;
    uint16_t camera_fps_x10;
    uint8_t mic_count;
    uint16_t mic_rate_hz;
    int16_t mic_bearing_deg[3];
    int16_t motor_speed_limit;   /**< steps/s */
    uint8_t ircom_backends;      /**< PLATFORM_IRCOM_* bits */
    uint8_t red_leds, rgb_leds;
    uint8_t tof, accelerometer, gyroscope;
} platform_facts_t;

/** The initialiser of model P's platform_facts_t (P: EPUCK1, EPUCK2). */
#define PLATFORM_FACTS_INIT(P)                                                              \
    { P##_NAME, P##_CAMERA_SENSOR_WIDTH_PX, P##_CAMERA_SENSOR_HEIGHT_PX,                    \
      P##_CAMERA_FRAME_WIDTH_PX, P##_CAMERA_FRAME_HEIGHT_PX, P##_CAMERA_FOV_DEG,             \
      P##_CAMERA_FPS_X10, P##_MIC_COUNT, P##_MIC_RATE_HZ, P##_MIC_BEARINGS_DEG,              \
      P##_MOTOR_SPEED_LIMIT, P##_IRCOM_BACKENDS, P##_RED_LEDS, P##_RGB_LEDS, P##_TOF,        \
      P##_ACCELEROMETER, P##_GYROSCOPE },

#endif
