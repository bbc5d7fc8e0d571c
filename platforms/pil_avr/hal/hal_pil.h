/*
 * hal_pil.h - hal.h on an emulated microcontroller in the simulator's loop
 * (processor-in-the-loop): the robot's sensors and actuators are the
 * simulator's, reached through the PIL protocol (wire/pil/pil_robot.h),
 * one sensor and one actuator exchange per control period, in lockstep.
 *
 * An image (its main generated from the e-puck1's declarations over this
 * platform's run loop, run/image_main.h) defines the one `struct hal` and
 * its mailbox as static storage, and runs:
 *
 *     hal_pil_init(&robot, &cfg, mailbox, sizeof mailbox);
 *     hal_pil_hello(&robot, &hello);          HELLO, CONFIG
 *     ...controller_init(&ctl, &params, hal_pil_seed(&robot));
 *     hal_pil_ready(&robot);                  READY, the first STEP
 *     for (;;) {
 *         ...the controller's step and the image's telemetry
 *         hal_pil_end_step(&robot);           ACT, the next STEP
 *     }
 *
 * No timer, no interrupt: the simulator's STEP is the period's tick, and
 * the core is stopped between a frame handed over and the simulator's
 * answer, so a step's cycles are the controller's, its HAL's and its
 * telemetry's, nothing else.  The sources of this folder have no mutable
 * static storage (hygiene.sh checks it): all state is in this struct.
 */
#ifndef HAL_PIL_H
#define HAL_PIL_H

#include <stdint.h>

#include "hal.h"
#include "pil/pil_robot.h"

/** The image's declaration, as the run loop gives it. */
typedef struct hal_pil_config {
    uint16_t period_ms;        /**< the control period (100) */
    uint8_t ircom_bits;        /**< 16: the turret's (ir randb), 8: libIrcom's */
    uint8_t tx_per_period;     /**< IR messages a period may send (1) */
    uint8_t flags;             /**< PIL_HAS_* */
} hal_pil_config_t;

struct hal {
    pil_robot_t link;
    uint16_t period_ms;
};

/** The image's defaults: 100 ms, the turret's 16 bits, one message a
 *  period, no camera, sound, host link or telemetry. */
void hal_pil_default_config(hal_pil_config_t *cfg);

/** The struct only: the mailbox (`cap` bytes, PIL_MAILBOX_BYTES) is the
 *  image's. */
void hal_pil_init(hal_t *hal, const hal_pil_config_t *cfg, uint8_t *mailbox, uint16_t cap);

/** HELLO (the image and its controller's names, where its state is) and
 *  CONFIG: 0, or -1 (the simulator is told, and stops the run). */
int8_t hal_pil_hello(hal_t *hal, pil_hello_t *hello);

/** The controller's seed the simulator gives a `seed random` image. */
uint32_t hal_pil_seed(hal_t *hal);

/** The selector switch's position, 0..15 (the simulator's). */
uint8_t hal_pil_selector(hal_t *hal);

/** READY and the first STEP; then, after each step, ACT and the next. */
void hal_pil_ready(hal_t *hal);
void hal_pil_end_step(hal_t *hal);

#endif
