/*
 * forager_main.c - the forager image (seed 000): firmware/forager.c on a
 * real e-puck1 with the range-and-bearing turret (16-bit nest messages).
 *
 * Task allocation policy: the selector switch picks it at power-on,
 *   1 = DRTM, 2 = ARTM, 3 = FRTM, any other position = the build's default,
 * which is APP_FORAGER_POLICY (make firmware FORAGER_POLICY=drtm|artm|frtm;
 * DRTM when not given).  Swarm constants of eq 4 and T2 come from the build
 * too: APP_N_ROBOTS (N_r, 20) and APP_ARENA_L_MM (L, 4000 mm); everything
 * else is forager_default_params (seed 000's values).
 *
 * Telemetry: once per simulated second (every APP_TELEMETRY_STEPS control
 * steps) the controller's state goes out as an LCM swarmlcm.robot_state_t
 * (lcm_types/robot_state_t.lcm, encoded by the lcm-gen C code in
 * build/lcm_c/) in a telemetry frame on TELEMETRY_CH_ROBOT_STATE
 * (telemetry_frame.h) through the Bluetooth UART (app_telemetry.c, shared
 * with the nest beacon's image); the sender is pumped every step so a frame
 * trickles out as the UART takes it.
 * tools/telemetry/bridge.py republishes it on the LCM bus.  Field meanings
 * follow the simulator's (sim_host/telemetry.c); a real robot has no pose
 * (pose_known false) and no ground truth of the token (carried_item -2).
 *
 * Static storage: an image is the one place where the firmware's state
 * lives in static variables (no heap on the robot, and main never
 * returns): the robot's struct hal, its two camera frames, the controller,
 * and the telemetry sender with its buffers (app_telemetry).
 * tests/firmware/hygiene.sh checks that an app has no other writable
 * statics.
 *
 * The loop body is app_loop_once and the set-up app_setup, so that
 * tests/firmware/test_app_telemetry.c can run the image against the stubs.
 */
#include <math.h>
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
#ifndef APP_ARENA_L_MM
#define APP_ARENA_L_MM 4000u
#endif

static struct hal app_hal;
static uint8_t camera_frames[2u * HAL_EPUCK_FRAME_BYTES];
static forager_t app_forager;
static app_telemetry_t app_telemetry;

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

/* The robot's state as sim_host/telemetry.c fills it for a forager. */
static void app_send_state(void)
{
    swarmlcm_robot_state_t m;
    const forager_t *f = &app_forager;
    uint16_t ir_best = 0u, amb_low = 0xFFFFu, v;
    uint8_t k, ir_at = 0u;

    m.controller = (char *)"forager";
    m.state = (char *)forager_state_name(f->state);
    m.task_state = (int8_t)forager_paper_state(f->state);
    m.policy = (char *)ta_policy_name(f->params.policy);
    m.threshold = f->theta;
    m.probability = f->P_s;
    m.stimulus = f->S;
    m.k = f->k;
    m.mean_oae = f->M_A;
    m.response_n = (int8_t)f->n;
    m.energy = (f->beacon_known & FORAGER_KNOWS_FOOD) != 0u ? (float)f->beacon_food_q4 / 16.0f : NAN;
    m.oae_count = (int32_t)f->walk.oae_count;
    m.deposits = (int32_t)f->deposits;
    m.carrying = f->carrying != 0u;
    m.carried_item = -2;   /* no ground truth on a robot */
    for (k = 0u; k < HAL_IR_COUNT; k++) {
        v = hal_ir_proximity(&app_hal, k);
        if (v > ir_best) {
            ir_best = v;
            ir_at = k;
        }
        v = hal_ir_ambient(&app_hal, k);
        amb_low = v < amb_low ? v : amb_low;
    }
    m.ir_max = (int16_t)ir_best;
    m.ir_max_index = (int8_t)ir_at;
    m.ambient_min = (int16_t)amb_low;
    m.blobs = -1;   /* not recomputed for telemetry */
    app_telemetry_send(&app_telemetry, &app_hal, &m);
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
    hal_epuck_begin_step(&app_hal);   /* light readings for the seed */
    forager_init(&app_forager, &params, hal_epuck_seed(&app_hal));
    app_telemetry_init(&app_telemetry);
}

static void app_loop_once(void)
{
    if (hal_epuck_step_due(&app_hal) != 0u) {
        hal_epuck_begin_step(&app_hal);
        forager_step(&app_forager, &app_hal);
        if (app_telemetry_due(&app_telemetry) != 0u) {
            app_send_state();
        }
        app_telemetry_pump(&app_telemetry, &app_hal);
        hal_epuck_end_step(&app_hal);
    } else {
        hal_epuck_poll(&app_hal);
    }
}

int main(void)
{
    app_setup();
    for (;;) {
        app_loop_once();
    }
}
