/*
 * pil.h - processor-in-the-loop: robots whose controller runs as machine
 * code on an emulated microcontroller, in lockstep with the simulator
 * (docs/reference/pil.md).  A model (model.h) of its own: the platform
 * binding of its robots.
 *
 * A group says what its robots run and on what (C a controller, I an
 * image of it):
 *
 *   robots:
 *     - {count: 3, controller: C, image: I, platform: pil_avr}
 *     - {count: 17, controller: C, image: I}        # host-built
 *     - {count: 20, controller: C, image: I, platform: pil_avr,
 *        platform_robots: 3}           # its first 3 on MCUs, 17 host-built
 *
 * `image` names a robot image (platforms/epuck1/images.list, pil_images.h):
 * its robots start with the parameters and the seed its declaration gives
 * (the run loop's), whichever platform runs them.  `platform: pil_avr`
 * puts each of its robots on an emulated ATmega2560 (platforms/pil_avr/:
 * the image's ELF, run by the emulator program, one per robot), `pil_m4`
 * on an emulated Cortex-M4F (platforms/pil_m4/: QEMU, one per robot); `host`
 * (the default) runs the controller built into the simulator.  So one
 * scenario with `platform` flipped gives the host-built run and the PIL
 * run, which must end in the same state hash.
 *
 * Each control step a PIL robot's step (in place of its controller's, on
 * the thread that steps it) sends the MCU its STEP, answers its requests
 * through this robot's hal.h (so every model computes what it serves, with
 * its noise drawn, exactly as for a host-built robot), applies its ACT
 * through hal.h, and mirrors its controller state from the MCU's RAM into
 * the robot's struct (pil_mirror.h).  Its telemetry bytes are the image's
 * own, down the robot's UART (robot_telemetry): the simulator does not run
 * the image's sender for it.  Anything wrong (a malformed or missing
 * answer, the cycle budget, a crash or reset of the MCU, an emulator that
 * died or hangs) is an error naming the robot and the step (sim_error):
 * the run stops, exit 1, nothing written.
 *
 * Section `pil`: the cycle budget of a step, the wall-time bound of an
 * answer, and where the emulator and the images are (pil.dir: by default
 * beside the swarmsim program, its build folder's firmware/pil_avr).  The
 * camera hands the MCU the simulator's blobs (the RGB565 frame, with
 * blob_detect on the MCU, is the comparison driver's: platforms/pil_avr/
 * tests/).
 */
#ifndef SIM_MODELS_PIL_H
#define SIM_MODELS_PIL_H

#include <stdint.h>

#include "models/model.h"

/** Which platform runs a group's robots. */
typedef enum pil_platform {
    PIL_PLATFORM_HOST = 0,    /**< built into the simulator */
    PIL_PLATFORM_AVR = 1,     /**< an emulated ATmega2560 (simavr) */
    PIL_PLATFORM_M4 = 2       /**< an emulated Cortex-M4F (QEMU's netduinoplus2) */
} pil_platform_t;

/** Section `pil`. */
typedef struct pil_model_config {
    uint32_t cycle_budget;    /**< cycles a step may take on the MCU (0: its control period at 16 MHz) */
    uint32_t boot_budget;     /**< cycles from reset to HELLO */
    float timeout_s;          /**< wall time an answer may take, s */
    float boot_timeout_s;     /**< wall time the first frame may take, s */
    char dir[192];            /**< the emulator and images ("": beside the program) */
} pil_model_config_t;

/** A group's keys. */
typedef struct pil_group_config {
    int platform;             /**< pil_platform_t */
    char image[32];           /**< an image's name, or "" */
    uint32_t platform_robots; /**< how many of its robots (its first) run on the platform; 0: all */
    uint8_t selector;         /**< the selector switch's position (images with a selector) */
} pil_group_config_t;

MODEL_CONFIG_ACCESSORS(pil, pil_model_config_t)

#endif
