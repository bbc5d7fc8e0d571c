/*
 * random_walk_main.c - the random-walk image: firmware/random_walk.c
 * (run-and-tumble with IR obstacle avoidance, counting obstacle-avoidance
 * events) on a bare e-puck1 with libIrcom, no turret needed.  A first
 * image to try the robot, the flasher and the telemetry link with; it also
 * keeps the libIrcom backend of platforms/epuck1/hal built and gated.  No camera.
 *
 * Static storage: the robot's struct hal and the controller (see
 * forager_main.c).
 */
#include <stdint.h>

#include "hal_epuck.h"
#include "common/random_walk.h"

static struct hal app_hal;
static random_walk_t app_walk;

static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

/* The controller's step. */
static void app_step(void)
{
    random_walk_step(&app_walk, &app_hal);
}

int main(void)
{
    hal_epuck_config_t cfg;
    random_walk_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    (void)hal_epuck_init(&app_hal, &cfg, (uint8_t *)0, 0u);
    hal_epuck_start(&app_hal, app_tick);

    random_walk_default_params(&params);
    hal_epuck_begin_step(&app_hal);   /* light readings for the seed */
    random_walk_init(&app_walk, &params, hal_epuck_seed(&app_hal));

    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
