/*
 * eaipp_main.c - seed 003's EAIPP image: the swarm robot (Robot_Lost / Robot_Explorer / Robot_Node), running
 * firmware/eaipp/eaipp.c with role robot over the range-and-bearing turret
 * (16-bit messages); with APP_EAIPP_ROLE (eaipp_nest_main.c,
 * eaipp_food_main.c), Robot_Nest or Robot_Food, the fixed gradient sources.  No camera (its frames would cost 3.2 KB of RAM for
 * nothing).  The parameters are eaipp_default_params (the square arena of
 * Table 2: R = 0.6 m, 5 cm/s).
 *
 * Static storage: the robot's struct hal, the controller and the telemetry
 * sender with its buffers (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "eaipp/eaipp.h"
#include "hal_epuck.h"

/* The image's role: the swarm robot here; eaipp_nest_main.c and
 * eaipp_food_main.c are this source with APP_EAIPP_ROLE set to
 * EAIPP_ROLE_NEST and EAIPP_ROLE_FOOD (the fixed sources, which read no
 * sensors). */
#ifndef APP_EAIPP_ROLE
#define APP_EAIPP_ROLE EAIPP_ROLE_ROBOT
#endif
#define APP_READS_SENSORS ((uint8_t)(APP_EAIPP_ROLE == EAIPP_ROLE_ROBOT))

static struct hal app_hal;
static eaipp_t app_eaipp;
static robot_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = EAIPP_NAME, .observables = eaipp_observables,
        .state = &app_eaipp, .state_name = eaipp_state_name(&app_eaipp),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, APP_READS_SENSORS);
}

static void app_setup(void)
{
    hal_epuck_config_t cfg;
    eaipp_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    cfg.ircom_tx_per_period = 3u;   /* STATE, GRADIENT, ROOT in one period: ~12 ms of sends */
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    eaipp_default_params(&params);
    params.role = (uint8_t)APP_EAIPP_ROLE;
    eaipp_init(&app_eaipp, &params, (uint32_t)hal_robot_id(&app_hal));
    robot_telemetry_init(&app_telemetry);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    eaipp_step(&app_eaipp, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    app_setup();
    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
