/*
 * pil_avr_link.h - the simulator's end of the emulated ATmega2560: starts
 * the emulator program (platforms/pil_avr/emu/, GPL-3: a program of its
 * own, so nothing that links it is linked here) on a robot's image, and is
 * the pil_host_io_t (wire/pil/pil_host.h) over its pipes.
 *
 * Every read waits at most `timeout_ms` of wall time, the first (the
 * emulator starting and the image booting to its first frame) at most
 * `boot_timeout_ms`: a hung or stopped emulator is an error, never a hang,
 * and a loaded machine's slow start of a process is not taken for one; the emulator dies with its parent
 * (PR_SET_PDEATHSIG) and is killed by pil_avr_link_close, so none outlives
 * the simulator.  POSIX and Linux; host code.
 */
#ifndef PIL_AVR_LINK_H
#define PIL_AVR_LINK_H

#include <stdint.h>
#include <sys/types.h>

#include "pil/pil_host.h"

/** The first frame's default wall-time bound, ms: starting an emulator (QEMU
 *  above all) takes seconds on a loaded machine. */
#define PIL_LINK_BOOT_TIMEOUT_MS 60000

typedef struct pil_avr_link {
    pid_t pid;
    int to, from;            /**< the emulator's standard input and output */
    int timeout_ms;
    int boot_timeout_ms;     /**< for the first frame */
    int answered;            /**< the first frame came */
    char image[256];         /**< for errors */
    char what[64];           /**< the emulator's name, for errors */
    char unit[16];           /**< what its counts count, for errors */
} pil_avr_link_t;

/** The emulator's options. */
typedef struct pil_avr_link_def {
    const char *emulator;    /**< the program (build/firmware/pil_avr/pil_avr_emu) */
    const char *image;       /**< the image's ELF file */
    uint64_t budget;         /**< cycles a step's exchange may take */
    uint64_t boot_budget;    /**< cycles from reset to HELLO */
    int timeout_ms;          /**< wall time a read may wait, ms */
    int boot_timeout_ms;     /**< wall time for the first frame, ms (0: 60 s, or timeout_ms if longer) */
    /** Another emulator that speaks the same frames on its standard input
     *  and output (QEMU for platforms/pil_m4/): its program, looked for
     *  on PATH, and its arguments, NULL-terminated; `emulator` and the
     *  budgets are then not used, and `what` names it in errors. */
    const char *const *argv;
    const char *what;
    const char *unit;        /**< what its EMU frames count ("cycles", the default) */
} pil_avr_link_def_t;

/** Defaults: 1,600,000 cycles a step (100 ms at 16 MHz), 16,000,000 to
 *  boot, reads waiting 20 s (the first 60 s). */
pil_avr_link_def_t pil_avr_link_default_def(void);

/** Starts the emulator: 0, or -1 with `err` (no such program or image). */
int pil_avr_link_open(pil_avr_link_t *l, const pil_avr_link_def_t *def, char err[PIL_HOST_ERR]);

/** Kills and reaps the emulator (a link never opened: nothing). */
void pil_avr_link_close(pil_avr_link_t *l);

/** Reads `len` bytes of the stopped MCU's RAM at `addr` into `out` (a
 *  debugger's read: between a frame the MCU handed over and the answer
 *  to it): 0, or -1 with `err`. */
int pil_avr_link_peek(pil_avr_link_t *l, uint32_t addr, uint16_t len, uint8_t *out, char err[PIL_HOST_ERR]);

/** The transport over this link. */
pil_host_io_t pil_avr_link_io(pil_avr_link_t *l);

#endif
