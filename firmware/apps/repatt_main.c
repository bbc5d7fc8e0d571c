/*
 * repatt_main.c - the RepAtt image (seed 002): firmware/repatt/repatt.c on
 * an e-puck1 with the turret image's A/D module (the randb backend: the
 * only one whose A/D module fills the microphone buffers; RepAtt itself
 * sends no IR messages), with its
 * camera for the targets (red blobs) and its microphones and speaker for
 * the repulsion and attraction bands.  25 ms control period, the paper's
 * step, for which P_b and the queue are given.
 *
 * Policy: the selector switch at power-on, 1 = repatt (A4m100d-R1m10d),
 * 2 = random_walk (all gains 1), any other position = APP_REPATT_POLICY
 * (repatt).  Listening is slotted: an e-puck's own tone drowns its
 * microphones.  Queue: APP_QUEUE_MAX readings per average (40, the paper's
 * Q40), 2 x 40 readings per band: 640 bytes, within the 2 KB RAM gate.
 * Both are build constants (-DAPP_QUEUE_MAX=..., -DAPP_REPATT_POLICY=...).
 * Sound is on (cfg.sound): platforms/epuck1/hal measures the bands with the tone
 * detector (hal/tone_detect.c) and plays the bands' tables.
 *
 * Telemetry: the controller's observables (repatt_def.c) through the
 * Bluetooth UART, as the other images.
 *
 * Static storage: the robot's struct hal, its camera frames, the
 * controller, its queue storage and the telemetry sender (see
 * forager_main.c).
 */
#include <stdint.h>

#include "app_telemetry.h"
#include "hal_epuck.h"
#include "repatt/repatt.h"

#ifndef APP_QUEUE_MAX
#define APP_QUEUE_MAX 40u
#endif
#ifndef APP_REPATT_POLICY
#define APP_REPATT_POLICY REPATT_POLICY_REPATT
#endif
#define APP_PERIOD_MS 25u

static struct hal app_hal;
static uint8_t camera_frames[2u * HAL_EPUCK_FRAME_BYTES];
static repatt_t app_repatt;
static uint32_t app_queue[REPATT_QUEUE_WORDS(APP_QUEUE_MAX)];
static robot_telemetry_t app_telemetry;

/* Timer-2 agenda, interrupt context: only counts the period. */
static void app_tick(void)
{
    hal_epuck_tick(&app_hal);
}

static uint8_t choose_policy(uint8_t selector)
{
    switch (selector) {
    case 1u: return (uint8_t)REPATT_POLICY_REPATT;
    case 2u: return (uint8_t)REPATT_POLICY_RANDOM_WALK;
    default: return (uint8_t)APP_REPATT_POLICY;
    }
}

static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = REPATT_NAME, .observables = repatt_observables,
        .state = &app_repatt, .state_name = repatt_state_name(&app_repatt),
    };
    app_telemetry_step(&app_telemetry, &app_hal, &src, 1u);
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    repatt_step(&app_repatt, &app_hal);
    app_send_telemetry();
}

int main(void)
{
    hal_epuck_config_t cfg;
    repatt_params_t params;

    hal_epuck_default_config(&cfg);
    cfg.period_ms = APP_PERIOD_MS;
    cfg.sound = 1u;
    (void)hal_epuck_init(&app_hal, &cfg, camera_frames, (uint16_t)sizeof camera_frames);
    hal_epuck_start(&app_hal, app_tick);

    repatt_default_params(&params);
    repatt_apply_policy(&params, choose_policy(hal_epuck_selector(&app_hal)));
    params.listening = (uint8_t)REPATT_SLOTTED;
    params.queue_size = (uint16_t)APP_QUEUE_MAX;
    repatt_attach_queue(&app_repatt, app_queue, (uint16_t)APP_QUEUE_MAX);
    hal_epuck_begin_step(&app_hal);   /* light readings for the seed */
    repatt_init(&app_repatt, &params, hal_epuck_seed(&app_hal));
    robot_telemetry_init(&app_telemetry);

    for (;;) {
        HAL_EPUCK_LOOP_ONCE(&app_hal, app_step());
    }
}
