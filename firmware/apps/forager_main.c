/*
 * forager_main.c - the forager image (seed 000): firmware/forager.c on a
 * real e-puck1 with the range-and-bearing turret (16-bit nest messages).
 *
 * Task allocation policy: the selector switch picks it at power-on,
 *   1 = DRTM, 2 = ARTM, 3 = FRTM, any other position = the build's default,
 * which is APP_FORAGER_POLICY (make firmware FORAGER_POLICY=drtm|artm|frtm;
 * DRTM when not given).  The experiment's constants come from the build
 * too: APP_N_ROBOTS (N_r, 20), APP_ARENA_L_MM (L, 4000 mm; a rectangle's
 * side of equal area), APP_F_D_TOKENS (F_d, 20), APP_NEST_RADIUS_MM (750)
 * and APP_DRTM_THETA (TA_THETA_OFFSET; the real-robot experiment's theta = 0
 * at the start is TA_THETA_RAW); everything else is forager_default_params
 * (seed 000's values).  README, seed 000, gives the make line of each
 * experiment.
 *
 * Telemetry: firmware/telemetry/robot_telemetry.c, pumped every step: the
 * controller's observables (forager_def.c) as a swarmlcm.robot_state_t once
 * a second and its schema a few entries at a time, framed through the
 * Bluetooth UART; swarmtools.telemetry.bridge republishes them on LCM.  A real
 * robot has no pose (pose_known false).
 *
 * Static storage: an image is the one place where the firmware's state
 * lives in static variables (no heap on the robot, and main never
 * returns): the robot's struct hal, its two camera frames, the controller,
 * and the telemetry sender with its buffers (app_telemetry).
 * tests/firmware/hygiene.sh checks that an app has no other writable
 * statics.
 *
 * The loop body is app_loop_once and the set-up app_setup, so that
 * platforms/epuck1/tests/test_app_telemetry.c can run the image against the stubs.
 */
#include <stdint.h>

#include "foraging/forager.h"
#include "app_telemetry.h"
#include "hal_epuck.h"
#include "foraging/task_alloc.h"

#ifndef APP_FORAGER_POLICY
#define APP_FORAGER_POLICY TA_DRTM
#endif
#ifndef APP_N_ROBOTS
#define APP_N_ROBOTS 20u
#endif
#ifndef APP_F_D_TOKENS
#define APP_F_D_TOKENS 20
#endif
#ifndef APP_NEST_RADIUS_MM
#define APP_NEST_RADIUS_MM 750u
#endif
#ifndef APP_DRTM_THETA
#define APP_DRTM_THETA TA_THETA_OFFSET
#endif
#ifndef APP_ARENA_L_MM
#define APP_ARENA_L_MM 4000u
#endif

static struct hal app_hal;
static uint8_t camera_frames[2u * HAL_EPUCK_FRAME_BYTES];
static forager_t app_forager;
static robot_telemetry_t app_telemetry;

/* Timer-2 agenda, interrupt context: only counts the period. */
static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static ta_policy_t choose_policy(uint8_t selector)
{
    switch (selector) {
    case 1u: return TA_DRTM;
    case 2u: return TA_ARTM;
    case 3u: return TA_FRTM;
    default: return APP_FORAGER_POLICY;
    }
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = FORAGER_NAME, .observables = forager_observables,
        .state = &app_forager, .state_name = forager_state_name(&app_forager),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, 1u);
}

static void app_setup(void)
{
    hal_epuck_config_t cfg;
    forager_params_t params;

    hal_epuck_default_config(&cfg);
    (void)hal_epuck_init(&app_hal, &cfg, camera_frames, (uint16_t)sizeof camera_frames);
    hal_epuck_start(&app_hal, app_tick);

    forager_default_params(&params);
    params.policy = choose_policy(hal_epuck_selector(&app_hal));
    params.n_robots = (uint16_t)APP_N_ROBOTS;
    params.arena_l_mm = (uint16_t)APP_ARENA_L_MM;
    params.f_d_tokens = (float)APP_F_D_TOKENS;
    params.nest_radius_mm = (uint16_t)APP_NEST_RADIUS_MM;
    params.drtm_theta = (uint8_t)APP_DRTM_THETA;
    hal_epuck_begin_step(&app_hal);   /* light readings for the seed */
    forager_init(&app_forager, &params, hal_epuck_seed(&app_hal));
    robot_telemetry_init(&app_telemetry);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    forager_step(&app_forager, &app_hal);
    app_send_telemetry();
}

static void app_loop_once(void)
{
    HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
}

int main(void)
{
    app_setup();
    for (;;) {
        app_loop_once();
    }
}
