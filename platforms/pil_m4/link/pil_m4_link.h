/*
 * pil_m4_link.h - the simulator's end of the emulated Cortex-M4F: starts
 * QEMU (Debian's qemu-system-arm, a program of its own) on a robot's image
 * in its netduinoplus2 machine, with semihosting to the host (the robot's
 * doorbell: it reads and writes the frames on QEMU's standard input and
 * output, hal/pil_port_m4.c) and `-icount shift=0` (one instruction, one
 * emulated ns: the robot's SysTick then counts instructions).  The pipes, the wall-time
 * bound and the emulator's death with the simulator are pil_avr_link's
 * (platforms/pil_avr/link/): the frames are the same.  Host code.
 */
#ifndef PIL_M4_LINK_H
#define PIL_M4_LINK_H

#include <stdint.h>

#include "pil_avr_link.h"

/** The QEMU program. */
#define PIL_M4_QEMU "qemu-system-arm"

/** The robot's budgets, in instructions (at most 2^24 SysTick ticks, about
 *  99.8 M instructions, each), and the wall time a read may wait. */
typedef struct pil_m4_link_def {
    const char *image;         /**< the image's ELF file */
    uint64_t budget;           /**< instructions a step's exchange may take */
    uint64_t boot_budget;      /**< instructions from reset to HELLO (0: the most) */
    int timeout_ms;            /**< wall time a read may wait, ms */
    int boot_timeout_ms;       /**< wall time for the first frame, ms (0: as pil_avr_link's) */
} pil_m4_link_def_t;

/** Starts QEMU on the image: 0, or -1 with `err`. */
int pil_m4_link_open(pil_avr_link_t *l, const pil_m4_link_def_t *def, char err[PIL_HOST_ERR]);

#endif
