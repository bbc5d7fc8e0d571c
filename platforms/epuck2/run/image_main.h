/*
 * image_main.h - the run loop of every e-puck2 image, written once: ChibiOS
 * and the library's bus (epuck2_os_init), the HAL, the controller and its
 * parameters, the telemetry sender, then the main loop, which runs one
 * controller step per control period and the background work (camera, IR
 * reception, the host link) between steps, sleeping a tick between polls
 * so that the library's threads run.
 *
 * The images are the e-puck1's declarations (platforms/epuck1/images.list,
 * named by platform.py's IMAGES); tools/make/images.py generates each
 * one's main over this file, as for the e-puck1
 * (docs/how-to/add-a-platform.md: the controller's functions by token
 * pasting IMAGE_CONTROLLER, so the stack gate follows every chain).  The
 * keys, and this platform's default when one is not given:
 *   IMAGE_CAMERA               1: capture and detect blobs (0: no frame)
 *   IMAGE_PERIOD_MS            control period, ms (the HAL's, 100)
 *   IMAGE_SOUND                1: band levels and the speaker (0)
 *   IMAGE_IRCOM_TX_PER_PERIOD  IR messages a period may send (the HAL's, 1)
 *   IMAGE_HOST_LINK            1: poses and messages from the host (0)
 *   IMAGE_IR_RANDB, IMAGE_IR_LIBIRCOM   the IR backend (the turret over
 *                              I2C, or the library's libIrcom port), bound
 *                              at link time
 * and those of every platform (images.py).
 *
 * Static storage, as on the e-puck1 (hygiene.sh allows no other writable
 * statics in an image): the robot's struct hal (app_hal), its averaged
 * camera frame (camera_frames: one frame, the library's DCMI buffer holds
 * the capture), the host link's storage (app_host), the controller's state
 * (app_ctrl) and storage (app_storage), the telemetry sender (app_telemetry).
 *
 * app_setup and app_loop_once are apart so that a test can run an image
 * against the library's stubs.
 */
#ifndef EPUCK2_IMAGE_MAIN_H
#define EPUCK2_IMAGE_MAIN_H

#include <stdint.h>

#include "epuck2_os.h"
#include "hal_epuck2.h"

#ifndef IMAGE_CONTROLLER
#error "image_main.h: include it from an image's generated main (tools/make/images.py)"
#endif
#ifndef IMAGE_CAMERA
#define IMAGE_CAMERA 0
#endif
#ifndef IMAGE_SOUND
#define IMAGE_SOUND 0
#endif
#ifndef IMAGE_HOST_LINK
#define IMAGE_HOST_LINK 0
#endif
#if defined(IMAGE_IRCOM_TX_PER_PERIOD) && (IMAGE_IRCOM_TX_PER_PERIOD < 1 || IMAGE_IRCOM_TX_PER_PERIOD > HAL_EPUCK2_TX_MAX)
#error "ircom_tx_per_period: 1..HAL_EPUCK2_TX_MAX messages a period"
#endif
#if IMAGE_TELEMETRY
#include "image_telemetry.h"
#endif

#define IMAGE_CAT_(a, b) a##b
#define IMAGE_CAT(a, b) IMAGE_CAT_(a, b)
/** The controller's NAME##suffix. */
#define IMAGE_FN(suffix) IMAGE_CAT(IMAGE_CONTROLLER, suffix)

static struct hal app_hal;
#if IMAGE_CAMERA
static uint8_t camera_frames[HAL_EPUCK2_FRAME_BYTES];
#endif
#if IMAGE_HOST_LINK
static hal_epuck2_host_t app_host;
#endif
static IMAGE_FN(_t) app_ctrl;
#ifdef IMAGE_STORAGE_TYPE
static IMAGE_STORAGE_TYPE app_storage[IMAGE_STORAGE_COUNT];
#endif
#if IMAGE_TELEMETRY
static robot_telemetry_t app_telemetry;
#endif

#if IMAGE_TELEMETRY
static void app_send_telemetry(void)
{
    const robot_telemetry_source_t src = {
        .controller = IMAGE_CONTROLLER_NAME, .observables = IMAGE_FN(_observables),
        .state = &app_ctrl, .state_name = IMAGE_FN(_state_name)(&app_ctrl),
    };
    image_telemetry_step(&app_telemetry, &app_hal, &src, IMAGE_READS_SENSORS);
}
#endif

static void app_setup(void)
{
    hal_epuck2_config_t cfg;
    IMAGE_FN(_params_t) params;

    epuck2_os_init();
    hal_epuck2_default_config(&cfg);
#ifdef IMAGE_PERIOD_MS
    cfg.period_ms = IMAGE_PERIOD_MS;
#endif
#if IMAGE_SOUND
    cfg.sound = 1u;
#endif
#ifdef IMAGE_IRCOM_TX_PER_PERIOD
    cfg.ircom_tx_per_period = IMAGE_IRCOM_TX_PER_PERIOD;
#endif
#if IMAGE_CAMERA
    (void)hal_epuck2_init(&app_hal, &cfg, camera_frames, (uint16_t)sizeof camera_frames);
#else
    cfg.camera = 0u;
    (void)hal_epuck2_init(&app_hal, &cfg, (uint8_t *)0, 0u);
#endif
#if IMAGE_HOST_LINK
    hal_epuck2_host_attach(&app_hal, &app_host);
#endif
    hal_epuck2_start(&app_hal);

    IMAGE_FN(_default_params)(&params);
#if defined(IMAGE_SELECTOR)
    IMAGE_FN(_set_policy)(&params, app_policy(hal_epuck2_selector(&app_hal)));
#elif defined(IMAGE_POLICY)
    IMAGE_FN(_set_policy)(&params, IMAGE_POLICY);
#endif
    app_params(&params);
#ifdef IMAGE_STORAGE_TYPE
    IMAGE_STORAGE_ATTACH(&app_ctrl, app_storage);
#endif
#if defined(IMAGE_SEED_RANDOM)
    hal_epuck2_begin_step(&app_hal);   /* light readings for the seed */
    IMAGE_FN(_init)(&app_ctrl, &params, hal_epuck2_seed(&app_hal));
#elif defined(IMAGE_SEED_ID)
    IMAGE_FN(_init)(&app_ctrl, &params, (uint32_t)hal_robot_id(&app_hal));
#elif defined(IMAGE_SEED_ZERO)
    IMAGE_FN(_init)(&app_ctrl, &params, 0u);
#else
#error "image_main.h: no IMAGE_SEED_*"
#endif
#if IMAGE_TELEMETRY
    robot_telemetry_init(&app_telemetry);
#endif
}

/* The controller's step and the telemetry of this step. */
static void app_step(void)
{
    IMAGE_FN(_step)(&app_ctrl, &app_hal);
#if IMAGE_TELEMETRY
    app_send_telemetry();
#endif
}

/* When a control period is due: sample the sensors once, step, apply the
 * actuators and send the step's IR messages; otherwise the background
 * work and a tick's sleep. */
static void app_loop_once(void)
{
    if (hal_epuck2_step_due(&app_hal) != 0u) {
        hal_epuck2_begin_step(&app_hal);
        app_step();
        hal_epuck2_end_step(&app_hal);
    } else {
        hal_epuck2_poll(&app_hal);
        epuck2_os_idle();
    }
}

int main(void)
{
    app_setup();
    for (;;) {
        app_loop_once();
    }
}

#endif
