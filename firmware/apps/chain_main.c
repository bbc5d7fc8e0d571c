/*
 * chain_main.c - the one source of seed 003's chain-baseline images: PFIAS
 * (Nouyan, Campo, Dorigo 2008: firmware/pfias/pfias.h,
 * docs/notes/i15_baselines.md) and TSASR (Luo, Guo, Ye et al. 2020,
 * reconstructed: firmware/tsasr/tsasr.h, docs/notes/i15_tsasr.md), which is
 * PFIAS's chain model with its elimination on.  Each image's own file
 * (pfias_main.c, pfias_nest_main.c, ..., tsasr_food_main.c) sets
 * APP_CHAIN_TSASR (0: PFIAS, 1: TSASR) and APP_CHAIN_ROLE (robot: lost /
 * explorer / chain member; nest or food: a fixed robot broadcasting NEST or
 * FOOD frames) and includes this file.  The turret carries the 16-bit
 * frames.  No camera (its frames would cost 3.2 KB of RAM for nothing).
 * The parameters are the controller's defaults (the square arena of
 * Table 2: R = 0.6 m, 5 cm/s).
 *
 * Static storage: the robot's struct hal, the controller and the telemetry
 * sender with its buffers (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "tsasr/tsasr.h"
#include "hal_epuck.h"

/* Which controller and which role (see above); the fixed sources read no
 * sensors.  Compiled alone (the firmware hygiene test compiles every file
 * here) it is the PFIAS robot. */
#ifndef APP_CHAIN_TSASR
#define APP_CHAIN_TSASR 0
#endif
#ifndef APP_CHAIN_ROLE
#define APP_CHAIN_ROLE PFIAS_ROLE_ROBOT
#endif
#if APP_CHAIN_TSASR
#define APP_CHAIN_NAME TSASR_NAME
#define APP_CHAIN_OBSERVABLES tsasr_observables
#define APP_CHAIN_DEFAULTS tsasr_default_params
#else
#define APP_CHAIN_NAME PFIAS_NAME
#define APP_CHAIN_OBSERVABLES pfias_observables
#define APP_CHAIN_DEFAULTS pfias_default_params
#endif
#define APP_READS_SENSORS ((uint8_t)(APP_CHAIN_ROLE == PFIAS_ROLE_ROBOT))

static struct hal app_hal;
static pfias_t app_chain;
static robot_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = APP_CHAIN_NAME, .observables = APP_CHAIN_OBSERVABLES,
        .state = &app_chain, .state_name = pfias_state_name(&app_chain),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, APP_READS_SENSORS);
}

static void app_setup(void)
{
    hal_epuck_config_t cfg;
    pfias_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    APP_CHAIN_DEFAULTS(&params);
    params.role = (uint8_t)APP_CHAIN_ROLE;
    pfias_init(&app_chain, &params, (uint32_t)hal_robot_id(&app_hal));
    robot_telemetry_init(&app_telemetry);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    pfias_step(&app_chain, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    app_setup();
    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
