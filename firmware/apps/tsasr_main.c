/*
 * tsasr_main.c - seed 003's TSASR baseline image (Luo, Guo, Ye et al.
 * 2020, reconstructed: firmware/tsasr/tsasr.h, docs/notes/i15_tsasr.md):
 * the swarm robot (lost / explorer / chain member), running
 * firmware/tsasr/tsasr.c with role robot over the range-and-bearing turret
 * (16-bit messages); with APP_TSASR_ROLE (tsasr_nest_main.c,
 * tsasr_food_main.c), the nest or the food, a fixed robot that broadcasts
 * TSASR NEST or FOOD frames.  No camera (its
 * frames would cost 3.2 KB of RAM for nothing).  The parameters are
 * tsasr_default_params (the square arena of Table 2: R = 0.6 m, 5 cm/s).
 *
 * Static storage: the robot's struct hal, the controller and the telemetry
 * sender with its buffers (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "tsasr/tsasr.h"
#include "hal_epuck.h"

/* The image's role: the swarm robot here; tsasr_nest_main.c and
 * tsasr_food_main.c are this source with APP_TSASR_ROLE set to
 * TSASR_ROLE_NEST and TSASR_ROLE_FOOD (the fixed sources, which read no
 * sensors). */
#ifndef APP_TSASR_ROLE
#define APP_TSASR_ROLE TSASR_ROLE_ROBOT
#endif
#define APP_READS_SENSORS ((uint8_t)(APP_TSASR_ROLE == TSASR_ROLE_ROBOT))

static struct hal app_hal;
static tsasr_t app_tsasr;
static robot_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = TSASR_NAME, .observables = tsasr_observables,
        .state = &app_tsasr, .state_name = tsasr_state_name(&app_tsasr),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, APP_READS_SENSORS);
}

static void app_setup(void)
{
    hal_epuck_config_t cfg;
    tsasr_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    tsasr_default_params(&params);
    params.role = (uint8_t)APP_TSASR_ROLE;
    tsasr_init(&app_tsasr, &params, (uint32_t)hal_robot_id(&app_hal));
    robot_telemetry_init(&app_telemetry);
}

static void app_loop_once(void)
{
    if (hal_epuck_step_due(&app_hal) != 0u) {
        hal_epuck_begin_step(&app_hal);
        tsasr_step(&app_tsasr, &app_hal);
        app_send_telemetry();
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
