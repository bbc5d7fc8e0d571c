/*
 * image_main.h - the run loop of every image on the emulated ATmega2560
 * (processor-in-the-loop), written once: set-up (the HAL and its mailbox,
 * HELLO and CONFIG, the controller and its parameters, the telemetry
 * sender), then one controller step per STEP the simulator sends.
 *
 * The images are the e-puck1's (platforms/epuck1/images.list, named by
 * this platform's platform.py): the same declarations, generated into
 * mains by tools/make/images.py exactly as for the e-puck1, over this run
 * loop and this platform's HAL.  So the machine code the emulator runs is
 * the controller's and its declaration's, not an emulator-only program.
 *
 * The declaration's platform keys (the e-puck1's), and what they mean here:
 *   IMAGE_CAMERA               1: blobs, or frames into the mailbox (0: none)
 *   IMAGE_PERIOD_MS            control period, ms (100)
 *   IMAGE_SOUND                1: band levels and the speaker (0)
 *   IMAGE_IRCOM_TX_PER_PERIOD  IR messages a period may send (1)
 *   IMAGE_HOST_LINK            1: the pose and host messages (0)
 *   IMAGE_GROUND               1: the ground-sensor module (0; the e-puck1
 *                              declares none yet)
 *   IMAGE_IR_RANDB, IMAGE_IR_LIBIRCOM   16- or 8-bit IR messages
 * and those of every platform (images.py).  The simulator checks at HELLO
 * that its scenario gives the robot what the image was built for (period,
 * message bits, messages per period).
 *
 * Static storage, as on the e-puck1: the robot's struct hal (app_hal), its
 * mailbox (app_mailbox), the controller's state (app_ctrl) and storage
 * (app_storage), the telemetry sender (app_telemetry).
 */
#ifndef PIL_IMAGE_MAIN_H
#define PIL_IMAGE_MAIN_H

#include <stdint.h>

#include "hal_pil.h"
#include "units.h"

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
#ifndef IMAGE_GROUND
#define IMAGE_GROUND 0
#endif
#if defined(IMAGE_IRCOM_TX_PER_PERIOD) && (IMAGE_IRCOM_TX_PER_PERIOD < 1 || IMAGE_IRCOM_TX_PER_PERIOD > PIL_TX_MAX)
#error "ircom_tx_per_period: 1..PIL_TX_MAX messages a period"
#endif
#if IMAGE_TELEMETRY
#include "image_telemetry.h"
#endif

#define IMAGE_CAT_(a, b) a##b
#define IMAGE_CAT(a, b) IMAGE_CAT_(a, b)
/** The controller's NAME##suffix. */
#define IMAGE_FN(suffix) IMAGE_CAT(IMAGE_CONTROLLER, suffix)

/* One camera frame of the e-puck's size fits the mailbox, where the
 * detector reads it. */
#if IMAGE_CAMERA
#define APP_MAILBOX_BYTES PIL_MAILBOX_BYTES(2u * EPUCK_CAMERA_WIDTH_PX * EPUCK_CAMERA_HEIGHT_PX)
#else
#define APP_MAILBOX_BYTES PIL_MAILBOX_BYTES(0u)
#endif

static struct hal app_hal;
static uint8_t app_mailbox[APP_MAILBOX_BYTES];
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
    image_telemetry_step(&app_telemetry, &app_hal, &src);
}
#endif

static void app_setup(void)
{
    hal_pil_config_t cfg;
    pil_hello_t hello;
    IMAGE_FN(_params_t) params;
    const char *image = IMAGE_NAME, *ctrl = IMAGE_CONTROLLER_NAME;
    uint8_t k;

    hal_pil_default_config(&cfg);
#ifdef IMAGE_PERIOD_MS
    cfg.period_ms = IMAGE_PERIOD_MS;
#endif
#ifdef IMAGE_IR_LIBIRCOM
    cfg.ircom_bits = 8u;
#endif
#ifdef IMAGE_IRCOM_TX_PER_PERIOD
    cfg.tx_per_period = IMAGE_IRCOM_TX_PER_PERIOD;
#endif
    cfg.flags = (uint8_t)((IMAGE_CAMERA ? PIL_HAS_CAMERA : 0u) | (IMAGE_SOUND ? PIL_HAS_SOUND : 0u)
                          | (IMAGE_HOST_LINK ? PIL_HAS_HOST_LINK : 0u) | (IMAGE_TELEMETRY ? PIL_HAS_TELEMETRY : 0u)
                          | (IMAGE_GROUND ? PIL_HAS_GROUND : 0u));
    hal_pil_init(&app_hal, &cfg, app_mailbox, (uint16_t)sizeof app_mailbox);

    for (k = 0u; k < PIL_NAME_MAX && image[k] != '\0'; k++) {
        hello.name[k] = image[k];
    }
    hello.name[k] = '\0';
    for (k = 0u; k < PIL_NAME_MAX && ctrl[k] != '\0'; k++) {
        hello.controller[k] = ctrl[k];
    }
    hello.controller[k] = '\0';
    hello.state_addr = (uint32_t)(uintptr_t)&app_ctrl;
    hello.state_size = (uint16_t)sizeof app_ctrl;
#ifdef IMAGE_STORAGE_TYPE
    hello.storage_addr = (uint32_t)(uintptr_t)app_storage;
    hello.storage_size = (uint16_t)sizeof app_storage;
#else
    hello.storage_addr = 0u;
    hello.storage_size = 0u;
#endif
    (void)hal_pil_hello(&app_hal, &hello);

    IMAGE_FN(_default_params)(&params);
#if defined(IMAGE_SELECTOR)
    IMAGE_FN(_set_policy)(&params, app_policy(hal_pil_selector(&app_hal)));
#elif defined(IMAGE_POLICY)
    IMAGE_FN(_set_policy)(&params, IMAGE_POLICY);
#endif
    app_params(&params);
#ifdef IMAGE_STORAGE_TYPE
    IMAGE_STORAGE_ATTACH(&app_ctrl, app_storage);
#endif
#if defined(IMAGE_SEED_RANDOM)
    IMAGE_FN(_init)(&app_ctrl, &params, hal_pil_seed(&app_hal));
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
    hal_pil_ready(&app_hal);
}

/* One control step: the controller's (between two marks: the emulator
 * times it), its telemetry, then ACT (which returns with the next step's
 * STEP). */
static void app_loop_once(void)
{
    pil_port_mark();
    IMAGE_FN(_step)(&app_ctrl, &app_hal);
    pil_port_mark();
#if IMAGE_TELEMETRY
    app_send_telemetry();
#endif
    hal_pil_end_step(&app_hal);
}

int main(void)
{
    app_setup();
    for (;;) {
        app_loop_once();
    }
}

#endif
