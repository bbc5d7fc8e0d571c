/*
 * pil_mirror.h - a PIL robot's controller state, copied from the emulated
 * MCU's RAM into the simulator's struct of the same type after every step,
 * by the field map its build wrote (platforms/pil_avr/state_map.py, from
 * the DWARF of the AVR image and of its host build): integers widened
 * where their sizes differ (an enum is 2 bytes on the AVR), a double
 * widened from the AVR's 32 bits, pointers left as the host's.  The
 * world-side code that reads a controller's state (a task, the summary's
 * counters, the simulator's telemetry) then reads the machine code's.
 */
#ifndef SIM_PIL_MIRROR_H
#define SIM_PIL_MIRROR_H

#include <stddef.h>
#include <stdint.h>

#include "swarmsim/sim.h"

typedef struct pil_mirror_op {
    uint8_t kind;            /**< PIL_MIRROR_COPY, _INT, _DOUBLE */
    uint8_t is_signed;
    uint16_t avr_off, host_off;
    uint16_t avr_size, host_size;
} pil_mirror_op_t;

enum { PIL_MIRROR_COPY = 1, PIL_MIRROR_INT = 2, PIL_MIRROR_DOUBLE = 3 };

typedef struct pil_mirror {
    uint16_t avr_size;       /**< the state's bytes on the MCU */
    size_t host_size;        /**< and here */
    uint32_t n;
    pil_mirror_op_t *ops;
} pil_mirror_t;

/** Reads the map at `path`: 0, or -1 with `err` naming the file and line. */
int pil_mirror_load(pil_mirror_t *m, const char *path, char err[SIM_ERR_MAX]);
void pil_mirror_free(pil_mirror_t *m);

/** Applies the map: the MCU's `avr` bytes (m->avr_size) into `host`. */
void pil_mirror_apply(const pil_mirror_t *m, const uint8_t *avr, void *host);

#endif
