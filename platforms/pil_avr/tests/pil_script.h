/*
 * pil_script.h - a scripted world for one PIL robot: what its requests
 * read, as pure functions of (seed, robot, step, channel), and a log of
 * every request and every actuator frame, so that two builds of one image
 * (the AVR's and this PC's) served by two scripts of the same seed can be
 * compared step by step (pil_compare.c).
 *
 * It is no simulation: the readings are noise shaped like the sensors'
 * ranges (mostly empty IR, the occasional obstacle, blobs, poses, IR
 * messages, routes for the waypoint follower, sound levels), which drives
 * a controller through its states and arithmetic without a world.  The
 * wheel counters integrate the commanded speeds, as the robot's would.
 */
#ifndef PIL_SCRIPT_H
#define PIL_SCRIPT_H

#include <stdint.h>
#include <stdio.h>

#include "pil/pil_host.h"

#define PIL_SCRIPT_QUEUE 20u
#define PIL_SCRIPT_LOG 4096u

typedef struct pil_script {
    uint64_t seed;
    uint32_t robot;
    uint32_t step;
    uint16_t period_ms;
    int frames;                      /**< answer the camera with RGB565 frames */
    uint16_t cam_w, cam_h;
    int32_t steps_left, steps_right; /**< steps, wrapping to int16 when read */
    uint8_t speaker_played;
    hal_ircom_msg_t queue[PIL_SCRIPT_QUEUE];
    uint8_t q_head, q_count;
    uint32_t host_sent;              /**< host messages given so far */
    /* This step's log: every request and the ACT, as text. */
    char log[PIL_SCRIPT_LOG];
    size_t log_len;
    uint64_t telemetry_bytes;
    FILE *telemetry_out;             /**< where the telemetry bytes go, or NULL */
} pil_script_t;

void pil_script_init(pil_script_t *s, uint64_t seed, uint32_t robot, uint16_t period_ms, int frames);

/** The CONFIG the script's simulator sends for a HELLO. */
pil_config_t pil_script_config(const pil_script_t *s, const pil_hello_t *hello);

/** This step's STEP (the step counter, time, wheel counters, microphones),
 *  new IR messages in the inbox; the log emptied. */
pil_step_t pil_script_begin(pil_script_t *s);

/** The robot's ACT: logged, its wheels integrated, its telemetry taken. */
void pil_script_end(pil_script_t *s, const pil_act_t *act);

/** The requests' callbacks over this script. */
pil_host_ops_t pil_script_ops(pil_script_t *s);

#endif
