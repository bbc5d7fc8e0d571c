/*
 * robot.h - which robot model each group is (`robots[].robot`:
 * e-puck1, the default, or e-puck2) and that model's facts
 * (hal/platform_facts.h, the one table the firmware reads too).
 *
 * The other models take a robot's facts as their defaults for it: a key
 * of theirs left unset in the scenario means "the robot model's", a key
 * set there overrides it for every robot.  What the facts set:
 *  - camera: the frame rate (camera.fps unset: 4.3 fps on an e-puck1,
 *    15 [?] on an e-puck2); the field of view and the frame the detector
 *    gets (40 x 20 on both: the e-puck2's HAL averages its capture into
 *    the e-puck1's frame) are the same, so camera.fov, width_px and
 *    height_px stay one per run (robot.c asserts that the facts agree);
 *  - wheels: the top speed, the motors' or hal.h's 1000 steps/s where
 *    lower (both HALs clamp to hal.h's: 1000 on both);
 *  - sound: nothing: the sound model gives levels per band, and the tone
 *    detector takes TONE_DETECT_N samples on both robots (5.9 ms at
 *    16384 Hz, 6.0 ms at 16 kHz, with coefficients for each rate), so a
 *    tone reads the same; the rate and count are reported (robot.*);
 *  - IR communication: both models carry libIrcom and the turret;
 *  - RGB LEDs, ToF, IMU: no hal.h channel.
 * docs/hardware/epuck2.md says which facts are measured and which assumed.
 */
#ifndef SIM_MODELS_ROBOT_H
#define SIM_MODELS_ROBOT_H

#include <stdint.h>

#include "models/model.h"
#include "platform_facts.h"

/** The robot models' ids, in PLATFORM_MODELS order (0: e-puck1). */
#define ROBOT_MODEL_ID(P) ROBOT_MODEL_##P,
typedef enum robot_model_id { PLATFORM_MODELS(ROBOT_MODEL_ID) ROBOT_MODEL_COUNT } robot_model_id_t;
#undef ROBOT_MODEL_ID

/** The names a group's `robot` key takes, NULL-terminated. */
extern const char *const robot_model_names[ROBOT_MODEL_COUNT + 1];

/** A group's key. */
typedef struct robot_group_config {
    int model;                 /**< robot_model_id_t (`robot`) */
} robot_group_config_t;

/** The facts of model `id`. */
const platform_facts_t *robot_model_facts(robot_model_id_t id);
/** The facts of group `g`'s robot model. */
const platform_facts_t *robot_group_facts(const robot_group_t *g);
/** The facts of robot `robot`'s model in a run. */
const platform_facts_t *robot_facts(const sim_t *sim, uint32_t robot);

/** The camera's frame rate of these facts, fps. */
static inline float robot_camera_fps(const platform_facts_t *f)
{
    return (float)f->camera_fps_x10 / 10.0f;
}

/** The fastest a wheel turns, steps/s: hal.h's limit, or the motors' when
 *  lower (every HAL clamps to hal.h's). */
static inline int16_t robot_wheel_speed_max(const platform_facts_t *f)
{
    return f->motor_speed_limit < HAL_WHEEL_SPEED_MAX ? f->motor_speed_limit : (int16_t)HAL_WHEEL_SPEED_MAX;
}

#endif
