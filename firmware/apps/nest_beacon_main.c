/*
 * nest_beacon_main.c - the nest beacon image (seed 000): the static e-puck
 * at the nest centre running firmware/nest_beacon.c with the
 * range-and-bearing turret.  No camera (its frames would cost 3.2 KB of
 * RAM for nothing).
 *
 * Build constants: APP_N_ROBOTS (N_r, 20) and APP_ARENA_L_MM (L, 4000 mm),
 * from which T2 = L / (2 v) with seed 000's v = 0.05 m/s, in 100 ms steps:
 * L / 10 steps (400 for 4 m).  The rest is nest_beacon_default_params.
 *
 * Telemetry as in forager_main.c: a swarmlcm.robot_state_t every
 * APP_TELEMETRY_STEPS steps on TELEMETRY_CH_ROBOT_STATE, with the beacon's
 * ledger as the simulator reports it (sim_host/telemetry.c): energy F(t)
 * in tokens, M_A, the OAEs and deposits reported to it.  The beacon does
 * not send swarm_state_t (its doubles are 32-bit under XC16).
 *
 * Static storage: the robot's struct hal, the controller and the
 * telemetry sender with its buffers (app_telemetry; see forager_main.c).
 */
#include <math.h>
#include <stdint.h>

#include "app_telemetry.h"
#include "hal_epuck.h"
#include "foraging/nest_beacon.h"

#ifndef APP_N_ROBOTS
#define APP_N_ROBOTS 20u
#endif
#ifndef APP_ARENA_L_MM
#define APP_ARENA_L_MM 4000u
#endif

static struct hal app_hal;
static nest_beacon_t app_beacon;
static app_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

/* The beacon's state as sim_host/telemetry.c fills it. */
static void app_send_state(void)
{
    swarmlcm_robot_state_t m;
    const nest_beacon_t *b = &app_beacon;
    uint16_t te = b->params.token_energy != 0u ? b->params.token_energy : 1u;

    m.controller = (char *)"nest_beacon";
    m.state = (char *)nest_beacon_state_name(b->state);
    m.task_state = (int8_t)'B';
    m.policy = (char *)"";
    m.threshold = m.probability = m.stimulus = m.k = NAN;
    m.mean_oae = b->params.n_robots != 0u ? (float)b->m_t2 / (float)b->params.n_robots : 0.0f;
    m.response_n = 0;
    m.energy = (float)b->ledger_units / (float)te;
    m.oae_count = (int32_t)b->oae_total;
    m.deposits = (int32_t)b->deposits_total;
    m.carrying = 0;
    m.carried_item = -1;
    m.ir_max = -1;         /* the beacon reads no sensor */
    m.ir_max_index = -1;
    m.ambient_min = -1;
    m.blobs = -1;
    app_telemetry_send(&app_telemetry, &app_hal, &m);
}

static void app_setup(void)
{
    hal_epuck_config_t cfg;
    nest_beacon_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    nest_beacon_default_params(&params);
    params.n_robots = (uint16_t)APP_N_ROBOTS;
    params.t2_steps = (uint16_t)(APP_ARENA_L_MM / 10u);
    nest_beacon_init(&app_beacon, &params, 0u);
    app_telemetry_init(&app_telemetry);
}

static void app_loop_once(void)
{
    if (hal_epuck_step_due(&app_hal) != 0u) {
        hal_epuck_begin_step(&app_hal);
        nest_beacon_step(&app_beacon, &app_hal);
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
