/*
 * waypoint_main.c - the route-follower image (issue 16, seed 002's ALNS
 * baseline): firmware/waypoint/waypoint.c on a bare e-puck1 (libIrcom
 * backend: no turret, no IR messages; the IR sensors for obstacle
 * avoidance), no camera, no sound.  Its pose and its route come from the
 * host PC over the Bluetooth serial link (platforms/epuck1/hal/host_link.h: the
 * overhead tracker's POSE frames, the planner's route as a host message,
 * firmware/waypoint/route_msg.h); its telemetry goes out on the same link
 * (the controller's observables, waypoint_observables.c), as the other
 * images'.
 *
 * 25 ms control period: seed 002's step, the period the simulator's
 * ALNS and RepAtt worlds run at, so that pick_time_ms is the same whole
 * number of periods on both.
 *
 * Static storage: the robot's struct hal, its host link storage, the
 * controller and the telemetry sender (see forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "hal_epuck.h"
#include "waypoint/waypoint.h"

#define APP_PERIOD_MS 25u

static struct hal app_hal;
static hal_epuck_host_t app_host;
static waypoint_t app_waypoint;
static robot_telemetry_t app_telemetry;

/* Timer-2 agenda, interrupt context: only counts the period. */
static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = WAYPOINT_NAME, .observables = waypoint_observables,
        .state = &app_waypoint, .state_name = waypoint_state_name(&app_waypoint),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, 1u);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    waypoint_step(&app_waypoint, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    hal_epuck_config_t cfg;
    waypoint_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.period_ms = APP_PERIOD_MS;
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_host_attach(&app_hal, &app_host);
    hal_epuck_start(&app_hal, app_tick);

    waypoint_default_params(&params);
    hal_epuck_begin_step(&app_hal);   /* light readings for the seed */
    waypoint_init(&app_waypoint, &params, hal_epuck_seed(&app_hal));
    robot_telemetry_init(&app_telemetry);

    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
