/*
 * nest_beacon_main.c - the nest beacon image (seed 000): the static e-puck
 * at the nest centre running firmware/nest_beacon.c with the
 * range-and-bearing turret.  No camera (its frames would cost 3.2 KB of
 * RAM for nothing).
 *
 * Build constants: APP_N_ROBOTS (N_r, 20) and APP_ARENA_L_MM (L, 4000 mm),
 * from which T2 = L / (2 v) with seed 000's v = 0.05 m/s, in 100 ms steps:
 * L / 10 steps (400 for 4 m); the ledger's APP_F0_TOKENS (F(0), 5),
 * APP_C_RATE_MILLI (consumption, 1/1000 token per minute, 2000),
 * APP_MOVE_COST (1) and APP_E_A (10).  The rest is nest_beacon_default_params.
 *
 * Telemetry as in forager_main.c: the beacon's observables
 * (nest_beacon_def.c: its ledger's F(t), N_W, M_T2, the reports) through
 * firmware/telemetry/robot_telemetry.c.
 *
 * Static storage: the robot's struct hal, the controller and the
 * telemetry sender with its buffers (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "foraging/nest_beacon.h"
#include "hal_epuck.h"

#ifndef APP_N_ROBOTS
#define APP_N_ROBOTS 20u
#endif
#ifndef APP_ARENA_L_MM
#define APP_ARENA_L_MM 4000u
#endif
#ifndef APP_F0_TOKENS
#define APP_F0_TOKENS 5
#endif
#ifndef APP_C_RATE_MILLI
#define APP_C_RATE_MILLI 2000u
#endif
#ifndef APP_MOVE_COST
#define APP_MOVE_COST 1u
#endif
#ifndef APP_E_A
#define APP_E_A 10u
#endif

static struct hal app_hal;
static nest_beacon_t app_beacon;
static robot_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = NEST_BEACON_NAME, .observables = nest_beacon_observables,
        .state = &app_beacon, .state_name = nest_beacon_state_name(&app_beacon),
    };
    /* the beacon reads no sensor */
    app_telemetry_step(&app_telemetry, &app_hal, &src, 0u);
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
    params.f0_tokens = (int16_t)APP_F0_TOKENS;
    params.c_rate_milli_tokens_per_min = (uint16_t)APP_C_RATE_MILLI;
    params.move_cost = (uint16_t)APP_MOVE_COST;
    params.e_a = (uint16_t)APP_E_A;
    nest_beacon_init(&app_beacon, &params, 0u);
    robot_telemetry_init(&app_telemetry);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    nest_beacon_step(&app_beacon, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    app_setup();
    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
