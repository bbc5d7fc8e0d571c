/*
 * pil_robot.h - the robot's end of the PIL protocol (pil_msg.h): what a
 * PIL platform's HAL does behind each hal.h call, so that every emulated
 * core (platforms/pil_avr/, and any other) shares it and its HAL is a thin
 * layer over it.
 *
 * One control step's answers are cached, so reads are consistent within
 * the step as hal.h asks; the lazy channels (IR, ambient, camera, pose)
 * are asked for at their first read, the inboxes one message at a time;
 * the actuators are kept and sent in the step's ACT, with the telemetry
 * bytes written during it (a TELEMETRY request carries them earlier when
 * they do not fit).  The telemetry sink's room for the step comes in STEP,
 * so hal_telemetry_write answers at once what the simulator's own HAL
 * would.
 *
 * The frames travel through one buffer, the mailbox, and one call the
 * platform defines (bound at link time, like hal.h): pil_port_exchange
 * hands the robot's frame to the simulator and returns when the
 * simulator's answer is in the mailbox.  On an emulated MCU it stops the
 * core until then, so the wait costs the robot no cycles.
 *
 * What the image declared and does not have stays unavailable whatever
 * the simulator offers (hal.h's HAL_ERR_UNAVAILABLE, no camera blobs), as
 * on the robot: a swarm where that matters shows it.
 *
 * A frame from the simulator that does not check out is answered with a
 * FAULT frame (the simulator stops the run and names the robot and step)
 * and the robot goes on with nothing read.
 */
#ifndef FW_PIL_ROBOT_H
#define FW_PIL_ROBOT_H

#include <stdint.h>

#include "hal.h"
#include "pil/pil_msg.h"

/** Channels read this step (pil_robot_t.have). */
#define PIL_HAVE_IR 0x01u
#define PIL_HAVE_AMBIENT 0x02u
#define PIL_HAVE_CAMERA 0x04u
#define PIL_HAVE_POSE 0x08u
#define PIL_HAVE_GROUND 0x10u

/** Largest payload a robot sends: an ACT with every IR message and a full
 *  telemetry buffer. */
#define PIL_ROBOT_PAYLOAD_MAX (8u + 2u * PIL_TX_MAX + 2u + PIL_TELEMETRY_MAX)
/** Mailbox bytes a robot needs: the largest frame it takes (a camera
 *  frame of `frame_bytes` after its reply's byte; 0 without frames) or
 *  sends. */
#define PIL_MAILBOX_BYTES(frame_bytes) \
    PIL_FRAME_BYTES((frame_bytes) + 1u > PIL_ROBOT_PAYLOAD_MAX ? (frame_bytes) + 1u : PIL_ROBOT_PAYLOAD_MAX)

typedef struct pil_robot {
    uint8_t *mailbox;              /**< the frames' buffer (the platform's) */
    uint16_t mailbox_cap;
    uint8_t image_flags;           /**< PIL_HAS_* of the image */
    uint8_t ircom_bits;            /**< the image's IR backend's */
    uint8_t tx_per_period;         /**< the image's */
    pil_config_t cfg;              /**< from CONFIG */
    pil_step_t step;               /**< this step's STEP */
    uint8_t seq;                   /**< its low 8 bits */
    uint8_t running;               /**< a step is being run */
    uint8_t faults;                /**< FAULT frames sent */
    uint8_t have;                  /**< PIL_HAVE_* this step */
    uint16_t ir[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint8_t blob_count;
    hal_status_t pose_status;
    hal_pose_t pose;
    hal_status_t ground_status;
    uint16_t ground[HAL_GROUND_COUNT];
    /* The actuators, kept across steps as the robot's are. */
    int16_t wheel_left, wheel_right;
    uint16_t leds;
    uint8_t speaker;
    uint8_t tx_count;
    uint16_t tx[PIL_TX_MAX];
    /* Telemetry written this step, and the room left. */
    uint16_t telemetry_room;
    uint16_t telemetry_len;
    uint8_t telemetry[PIL_TELEMETRY_MAX];
} pil_robot_t;

/** The platform's transport: hands the `len`-byte frame at the start of
 *  `mailbox` to the simulator, and returns once the simulator's next frame
 *  is there (the mailbox holds `cap` bytes). */
void pil_port_exchange(uint8_t *mailbox, uint16_t cap, uint16_t len);

/** The platform's mark, called by a run loop just before its controller's
 *  step and just after: an emulator notes the cycles (so that a step's
 *  controller is told apart from the protocol's frames and the image's
 *  telemetry); elsewhere it does nothing. */
void pil_port_mark(void);

/** Binds the robot to its mailbox and the image's declaration: its
 *  PIL_HAS_* flags, its IR message bits and messages per period. */
void pil_robot_init(pil_robot_t *r, uint8_t *mailbox, uint16_t cap, uint8_t image_flags, uint8_t ircom_bits,
                    uint8_t tx_per_period);

/** Sends HELLO (`hello`'s name, controller, period and state; the flags,
 *  bits and mailbox from pil_robot_init) and reads CONFIG: 0, or -1 when
 *  the answer did not check out (a FAULT went back). */
int8_t pil_robot_hello(pil_robot_t *r, pil_hello_t *hello);

/** After set-up: READY, and the first step's STEP.  Then pil_robot_end_step
 *  hands over each step's ACT and reads the next STEP.  0, or -1 (FAULT
 *  sent: the step runs with nothing read). */
int8_t pil_robot_ready(pil_robot_t *r);
int8_t pil_robot_end_step(pil_robot_t *r);

/* The hal.h calls, for the platform's HAL to forward. */
uint16_t pil_robot_ir(pil_robot_t *r, uint8_t index);
uint16_t pil_robot_ambient(pil_robot_t *r, uint8_t index);
uint8_t pil_robot_blobs(pil_robot_t *r, hal_blob_t *out, uint8_t max);
hal_status_t pil_robot_frame_size(pil_robot_t *r, uint16_t *width_px, uint16_t *height_px);
hal_status_t pil_robot_ground(pil_robot_t *r, uint8_t index, uint16_t *reflected);
hal_status_t pil_robot_mic_level(pil_robot_t *r, uint8_t mic, uint8_t band, uint32_t *level);
hal_status_t pil_robot_speaker_set(pil_robot_t *r, uint8_t band);
uint8_t pil_robot_ircom_bits(pil_robot_t *r);
hal_status_t pil_robot_ircom_send(pil_robot_t *r, uint16_t value);
hal_status_t pil_robot_ircom_receive(pil_robot_t *r, hal_ircom_msg_t *out);
void pil_robot_wheels(pil_robot_t *r, int16_t left, int16_t right);
void pil_robot_led_bit(pil_robot_t *r, uint8_t bit, uint8_t on);
hal_status_t pil_robot_pose(pil_robot_t *r, hal_pose_t *out);
hal_status_t pil_robot_host_receive(pil_robot_t *r, uint8_t *buf, uint8_t cap, uint8_t *len);
uint16_t pil_robot_telemetry_write(pil_robot_t *r, const uint8_t *bytes, uint16_t len);

#endif
