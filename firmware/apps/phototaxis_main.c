/*
 * phototaxis_main.c - the README's example image: firmware/examples/
 * phototaxis.c on a bare e-puck1 (libIrcom backend, no turret, no camera),
 * with the robot's own telemetry (firmware/telemetry/robot_telemetry.c):
 * its declared observables reach the bridge, the monitor and the plots
 * with no tool change.  Listed in firmware/apps/images.list.
 *
 * Static storage: the robot's struct hal, the controller and the telemetry
 * sender (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "examples/phototaxis.h"
#include "hal_epuck.h"

static struct hal app_hal;
static phototaxis_t app_phototaxis;
static robot_telemetry_t app_telemetry;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = PHOTOTAXIS_NAME, .observables = phototaxis_observables,
        .state = &app_phototaxis, .state_name = phototaxis_state_name(&app_phototaxis),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, 1u);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    phototaxis_step(&app_phototaxis, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    hal_epuck_config_t cfg;
    phototaxis_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    phototaxis_default_params(&params);
    phototaxis_init(&app_phototaxis, &params, hal_epuck_seed(&app_hal));
    robot_telemetry_init(&app_telemetry);

    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
