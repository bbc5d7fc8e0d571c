/*
 * pil_host.h - the simulator's end of the PIL protocol (pil_msg.h): boots
 * a robot (HELLO, CONFIG, READY), runs its control steps (STEP, each
 * REQUEST answered through the caller's callbacks, ACT), and says in one
 * line what went wrong when something does.
 *
 * The transport is the caller's (pil_host_io_t): on the emulated
 * ATmega2560 the emulator's pipe (platforms/pil_avr/link/), where an EMU
 * frame precedes each of the robot's frames; elsewhere a serial stream.
 * What a request reads is the caller's too (pil_host_ops_t): the
 * simulator's own HAL for that robot, or a test's script.
 *
 * Host code (callbacks, one 5 KB buffer per robot); no statics.
 */
#ifndef FW_PIL_HOST_H
#define FW_PIL_HOST_H

#include <stddef.h>
#include <stdint.h>

#include "hal.h"
#include "pil/pil_msg.h"

/** Length of an error line. */
#define PIL_HOST_ERR 200u

/** How frames reach the robot and come back. */
typedef struct pil_host_io {
    void *ctx;
    /** Sends one frame: 0, or -1 with `err` set. */
    int (*send)(void *ctx, const uint8_t *frame, uint16_t len, char *err);
    /** The robot's next frame into `buf` (room for `cap`), its length in
     *  *len; the emulator's report of how the core ran in *emu (event
     *  PIL_EMU_FRAME, the cycles; a transport without one leaves it
     *  untouched).  0, or -1 with `err` set (the core crashed, ran past
     *  its budget, the process died, nothing came in time...). */
    int (*recv)(void *ctx, uint8_t *buf, uint16_t cap, uint16_t *len, pil_emu_t *emu, char *err);
} pil_host_io_t;

/** What a robot's requests read.  Each is called at most once per
 *  request, in the robot's order. */
typedef struct pil_host_ops {
    void *ctx;
    void (*ir)(void *ctx, uint16_t out[HAL_IR_COUNT]);
    void (*ambient)(void *ctx, uint16_t out[HAL_IR_COUNT]);
    /** The camera's blobs, largest first: how many (HAL_MAX_BLOBS at most). */
    uint8_t (*blobs)(void *ctx, hal_blob_t out[HAL_MAX_BLOBS]);
    /** With PIL_SIM_FRAMES: the RGB565 frame (`bytes` of it, the driver's
     *  byte order) into `out`: 0, or -1 with `err` set. */
    int (*frame)(void *ctx, uint8_t *out, uint16_t bytes, char *err);
    hal_status_t (*pose)(void *ctx, hal_pose_t *out);
    hal_status_t (*ircom_receive)(void *ctx, hal_ircom_msg_t *out);
    hal_status_t (*host_receive)(void *ctx, uint8_t *buf, uint8_t cap, uint8_t *len);
    /** The ground sensors: HAL_OK, or HAL_ERR_UNAVAILABLE (no module). */
    hal_status_t (*ground)(void *ctx, uint16_t out[HAL_GROUND_COUNT]);
    /** Telemetry bytes for the sink: how many it took. */
    uint16_t (*telemetry)(void *ctx, const uint8_t *bytes, uint16_t len);
} pil_host_ops_t;

typedef struct pil_host {
    pil_host_io_t io;
    pil_hello_t hello;             /**< what the robot said it is */
    pil_config_t config;           /**< what it was told */
    pil_emu_t emu;                 /**< the emulator's last report */
    uint64_t step_cycles;          /**< cycles of the last step (its exchanges' sum) */
    uint64_t control_cycles;       /**< of them, between the robot's first and last mark: its
                                        controller's step with the requests it made (not the
                                        STEP's decoding, its telemetry, the ACT); step_cycles
                                        when it marks nothing */
    uint64_t mark_begin, mark_end; /**< where this step's marks fell, in step_cycles' count */
    uint64_t boot_cycles;          /**< cycles from reset to READY */
    uint32_t requests;             /**< requests in the last step */
    uint8_t marked;                /**< this step's first mark was seen */
    uint8_t act_telemetry[PIL_TELEMETRY_MAX];   /**< the last ACT's bytes (act.telemetry points here) */
    uint8_t buf[PIL_FRAME_MAX];
} pil_host_t;

/** Binds the transport. */
void pil_host_init(pil_host_t *h, const pil_host_io_t *io);

/** Reads the robot's HELLO into h->hello: 0, or -1 with `err`. */
int pil_host_hello(pil_host_t *h, char err[PIL_HOST_ERR]);

/** Sends CONFIG (h->config: the caller fills it after checking the HELLO)
 *  and waits for READY: 0, or -1 with `err`. */
int pil_host_config(pil_host_t *h, char err[PIL_HOST_ERR]);

/** Runs one control step: STEP, the requests (through `ops`), the ACT into
 *  *act (its telemetry bytes in h->act_telemetry, not yet given to the
 *  sink: the caller does, as with the wheels).  0, or -1 with `err`. */
int pil_host_step(pil_host_t *h, const pil_step_t *step, const pil_host_ops_t *ops, pil_act_t *act,
                  char err[PIL_HOST_ERR]);

/** One line for an emulator's event ("ran past its cycle budget"). */
const char *pil_emu_event_name(uint8_t event);

#endif
