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
 * Static storage: the robot's struct hal and the controller (see
 * forager_main.c).
 */
#include <stdint.h>

#include "hal_epuck.h"
#include "nest_beacon.h"

#ifndef APP_N_ROBOTS
#define APP_N_ROBOTS 20u
#endif
#ifndef APP_ARENA_L_MM
#define APP_ARENA_L_MM 4000u
#endif

static struct hal app_hal;
static nest_beacon_t app_beacon;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

int main(void)
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

    for (;;) {
        if (hal_epuck_step_due(&app_hal) != 0u) {
            hal_epuck_begin_step(&app_hal);
            nest_beacon_step(&app_beacon, &app_hal);
            hal_epuck_end_step(&app_hal);
        } else {
            hal_epuck_poll(&app_hal);
        }
    }
}
