/*
 * pil_msg.h - the payloads of the PIL frames (pil_frame.h), one encoder
 * and one decoder per message, shared by the robot's end (pil_robot.h) and
 * the simulator's (pil_host.h).
 *
 * One control step, as the simulator drives it:
 *
 *   simulator                         robot (the image's run loop and HAL)
 *   ---------                         -----
 *                  <- HELLO           once, after reset: what the image is
 *   CONFIG ->                         the robot's id, seed and channels
 *                  <- READY           set up (the controller's init done)
 *   STEP ->                           time, wheel counters, microphones
 *                  <- REQUEST         the first read of a lazy channel
 *   REPLY ->                          (IR, ambient, camera, pose, an IR
 *                  ...                message, a host message)
 *                  <- ACT             wheels, LEDs, speaker, IR messages
 *                                     to send, telemetry bytes
 *   STEP ->                           the next step ...
 *
 * Lazy channels are asked for when the controller first reads them, as the
 * simulator's own HAL computes them, because their noise comes from a
 * per-robot random stream: a frame that carried every sensor every step
 * would draw noise the host-built robot never draws, and the two runs
 * could not agree bit for bit.  Everything a step's first read cannot
 * change (time, wheel counters, the sound levels, which the simulator
 * computes before any controller runs) comes in STEP.  An inbox pop is
 * asked for one message at a time: what stays in the inbox is the
 * simulator's to keep.
 *
 * Layouts (little-endian, byte offsets in each payload):
 *
 *   HELLO    0 period_ms u16, 2 ircom_bits u8, 3 tx_per_period u8,
 *            4 flags u8 (PIL_HAS_*), 5 mailbox u16 (largest frame taken),
 *            7 state_addr u32, 11 state_size u16, 13 storage_addr u32,
 *            17 storage_size u16, 19 name_len u8, 20 name, then
 *            controller_len u8 and controller
 *   CONFIG   0 robot_id u16, 2 seed u32, 6 period_ms u16, 8 ircom_bits u8,
 *            9 tx_per_period u8, 10 flags u8 (PIL_SIM_*), 11 cam_width u16,
 *            13 cam_height u16, 15 fov_mrad u16, 17 selector u8
 *   STEP     0 step u32, 4 time_ms u32, 8 steps_left i16, 10 steps_right
 *            i16, 12 telemetry_room u16, 14 mic_count u8 (0 or
 *            PIL_MIC_CELLS), 15 per cell (mic-major, bands 1..3): status i8,
 *            level u32
 *   REQUEST  0 what u8 (pil_what_t), 1 arg u8 (HOST: room; TELEMETRY: 0),
 *            2 the telemetry bytes (TELEMETRY only)
 *   REPLY    0 what u8, then by what:
 *              IR, AMBIENT  1 eight u16
 *              BLOBS        1 count u8, per blob colour u8, bearing i16,
 *                           width u16, pixels u16
 *              FRAME        1 the RGB565 frame, cam_width x cam_height x 2
 *                           bytes, as the camera's driver stores it
 *              POSE         1 status i8, x i32, y i32, heading i16, age u16
 *              RX           1 status i8, value u16, sensor u8, bearing i16,
 *                           range u16
 *              HOST         1 status i8, len u8, len bytes
 *              TELEMETRY    1 accepted u16
 *              GROUND       1 status i8, three u16
 *   ACT      0 wheel_left i16, 2 wheel_right i16, 4 leds u16, 6 speaker u8,
 *            7 tx_count u8, 8 tx_count u16 values, then telemetry_len u16
 *            and the bytes
 *   FAULT    0 code u8 (pil_fault_code_t), 1 the frame type it was reading
 *   PEEK     0 addr u32 (the MCU's data address), 4 len u16
 *   MEMORY   the len bytes
 *   EMU      0 event u8 (pil_emu_event_t), 1 cycles u32 (since resumed),
 *            5 total u64 as two u32 (low first), 13 stack_max u16 (bytes
 *            used at most, by painting), 15 pc u32 (byte address),
 *            19 first_mark u32, 23 last_mark u32 (cycles from the resume to
 *            the robot's first and last mark, PIL_NO_MARK when it made none)
 */
#ifndef FW_PIL_MSG_H
#define FW_PIL_MSG_H

#include <stdint.h>

#include "hal.h"
#include "pil/pil_frame.h"

/** HELLO flags: what the image was built with (its declaration). */
#define PIL_HAS_CAMERA 0x01u      /**< camera yes: blobs, or frames into its mailbox */
#define PIL_HAS_SOUND 0x02u       /**< sound yes: microphones and speaker */
#define PIL_HAS_HOST_LINK 0x04u   /**< host_link yes: a pose and host messages */
#define PIL_HAS_TELEMETRY 0x08u   /**< telemetry yes: it writes telemetry bytes */
#define PIL_HAS_GROUND 0x10u      /**< the ground-sensor module (hal_ground) */

/** CONFIG flags: what the simulator gives this robot. */
#define PIL_SIM_SOUND 0x01u       /**< the scenario has a sound field */
#define PIL_SIM_FRAMES 0x02u      /**< the camera sends RGB565 frames (else blobs) */
#define PIL_SIM_SELF_MASK 0x04u   /**< (informative) its own tone masks its microphones */

/** Microphone cells of a STEP: every microphone and band 1..3. */
#define PIL_MIC_CELLS (HAL_MIC_COUNT * (HAL_SOUND_BANDS - 1u))
/** Longest image or controller name carried. */
#define PIL_NAME_MAX 24u
/** Most IR messages an ACT carries (the platforms' ircom_tx_per_period cap). */
#define PIL_TX_MAX 3u
/** Telemetry bytes an ACT or a TELEMETRY request carries at most. */
#define PIL_TELEMETRY_MAX 256u
/** "Unlimited" in STEP's telemetry_room. */
#define PIL_ROOM_UNLIMITED 0xFFFFu

/** What a REQUEST asks for. */
typedef enum pil_what {
    PIL_WHAT_IR = 1,         /**< the 8 proximities (hal_ir_proximity) */
    PIL_WHAT_AMBIENT = 2,    /**< the 8 ambient readings (hal_ir_ambient) */
    PIL_WHAT_CAMERA = 3,     /**< blobs, or the frame with PIL_SIM_FRAMES */
    PIL_WHAT_POSE = 4,       /**< the tracker's pose (hal_pose) */
    PIL_WHAT_RX = 5,         /**< one IR message popped (hal_ircom_receive) */
    PIL_WHAT_HOST = 6,       /**< one host message (hal_host_receive), arg = room */
    PIL_WHAT_TELEMETRY = 7,  /**< bytes for the telemetry sink, before ACT's */
    PIL_WHAT_GROUND = 8      /**< the 3 ground sensors (hal_ground) */
} pil_what_t;

/** A FAULT's code: the robot could not use the simulator's last frame. */
typedef enum pil_fault_code {
    PIL_FAULT_FRAME = 1,     /**< it failed pil_frame_check */
    PIL_FAULT_TYPE = 2,      /**< not the frame the robot waited for */
    PIL_FAULT_PAYLOAD = 3,   /**< its payload does not decode */
    PIL_FAULT_SEQ = 4        /**< of another step */
} pil_fault_code_t;

/** What the emulator reports after the MCU stopped running. */
typedef enum pil_emu_event {
    PIL_EMU_FRAME = 0,       /**< the MCU handed over a frame (it follows) */
    PIL_EMU_BUDGET = 1,      /**< it ran past the cycle budget without one */
    PIL_EMU_CRASH = 2,       /**< the emulator's "crashed" state (bad access, PC past flash) */
    PIL_EMU_RESET = 3,       /**< it jumped to the reset vector */
    PIL_EMU_HALT = 4,        /**< it stopped (sleep with interrupts off, main returned) */
    PIL_EMU_STACK = 5,       /**< its stack ran into its static data */
    PIL_EMU_BAD_MAILBOX = 6  /**< it rang with a frame its mailbox does not hold */
} pil_emu_event_t;

typedef struct pil_hello {
    uint16_t period_ms;      /**< the image's control period */
    uint8_t ircom_bits;      /**< 16 (randb), 8 (libircom) */
    uint8_t tx_per_period;
    uint8_t flags;           /**< PIL_HAS_* */
    uint16_t mailbox;        /**< largest frame the robot takes, bytes */
    uint32_t state_addr;     /**< the controller's state in the MCU's memory (a debugger's view) */
    uint16_t state_size;
    uint32_t storage_addr;   /**< its storage (image key `storage`), or 0 */
    uint16_t storage_size;
    char name[PIL_NAME_MAX + 1u];        /**< the image */
    char controller[PIL_NAME_MAX + 1u];  /**< its controller */
} pil_hello_t;

typedef struct pil_config {
    uint16_t robot_id;
    uint32_t seed;           /**< the controller's seed when the image's is `random` */
    uint16_t period_ms;
    uint8_t ircom_bits;
    uint8_t tx_per_period;
    uint8_t flags;           /**< PIL_SIM_* */
    uint16_t cam_width, cam_height;
    uint16_t fov_mrad;
    uint8_t selector;        /**< the selector switch's position (images with a selector) */
} pil_config_t;

typedef struct pil_mic_cell {
    int8_t status;           /**< hal_mic_level's */
    uint32_t level;
} pil_mic_cell_t;

typedef struct pil_step {
    uint32_t step;
    uint32_t time_ms;
    int16_t steps_left, steps_right;
    uint16_t telemetry_room;       /**< bytes the sink takes this step, or PIL_ROOM_UNLIMITED */
    uint8_t mic_count;             /**< 0 (no sound) or PIL_MIC_CELLS */
    pil_mic_cell_t mic[PIL_MIC_CELLS];   /**< [mic * 3 + band - 1] */
} pil_step_t;

typedef struct pil_request {
    uint8_t what;            /**< pil_what_t */
    uint8_t arg;
    const uint8_t *bytes;    /**< TELEMETRY: the bytes (in the frame's buffer) */
    uint16_t len;
} pil_request_t;

typedef struct pil_act {
    int16_t wheel_left, wheel_right;
    uint16_t leds;                 /**< hal.h's LED word */
    uint8_t speaker;               /**< band */
    uint8_t tx_count;
    uint16_t tx[PIL_TX_MAX];
    uint16_t telemetry_len;
    const uint8_t *telemetry;      /**< in the frame's buffer (decoded) or the robot's (encoded) */
} pil_act_t;

/** EMU's mark when the robot made none in that run. */
#define PIL_NO_MARK 0xFFFFFFFFu

typedef struct pil_emu {
    uint8_t event;                 /**< pil_emu_event_t */
    uint32_t cycles;               /**< since the MCU was last resumed */
    uint64_t total;                /**< since reset */
    uint16_t stack_max;            /**< bytes of stack ever used (painting) */
    uint32_t pc;
    uint32_t first_mark;           /**< cycles from the resume to the robot's first mark (pil_port_mark) */
    uint32_t last_mark;            /**< ... and to its last */
} pil_emu_t;

/** A debugger's read of the MCU's RAM (the emulator answers, the core stays
 *  stopped): the simulator mirrors the controller's state so. */
typedef struct pil_peek {
    uint32_t addr;
    uint16_t len;
} pil_peek_t;

uint16_t pil_peek_encode(uint8_t *p, uint16_t cap, const pil_peek_t *m);
int8_t pil_peek_decode(const uint8_t *p, uint16_t n, pil_peek_t *m);

/* Encoders: write the payload at `p` (room for `cap`) and return its
 * length, 0 when it does not fit. */
uint16_t pil_hello_encode(uint8_t *p, uint16_t cap, const pil_hello_t *m);
uint16_t pil_config_encode(uint8_t *p, uint16_t cap, const pil_config_t *m);
uint16_t pil_step_encode(uint8_t *p, uint16_t cap, const pil_step_t *m);
uint16_t pil_request_encode(uint8_t *p, uint16_t cap, const pil_request_t *m);
uint16_t pil_act_encode(uint8_t *p, uint16_t cap, const pil_act_t *m);
uint16_t pil_emu_encode(uint8_t *p, uint16_t cap, const pil_emu_t *m);

/* Decoders: read a payload of `n` bytes; 0 when it is well formed (its
 * length is exactly the layout's, counts within their limits), -1 not. */
int8_t pil_hello_decode(const uint8_t *p, uint16_t n, pil_hello_t *m);
int8_t pil_config_decode(const uint8_t *p, uint16_t n, pil_config_t *m);
int8_t pil_step_decode(const uint8_t *p, uint16_t n, pil_step_t *m);
int8_t pil_request_decode(const uint8_t *p, uint16_t n, pil_request_t *m);
int8_t pil_act_decode(const uint8_t *p, uint16_t n, pil_act_t *m);
int8_t pil_emu_decode(const uint8_t *p, uint16_t n, pil_emu_t *m);

/* Replies, by what they answer: the writers fill the payload at `p`. */
uint16_t pil_reply_readings(uint8_t *p, uint16_t cap, uint8_t what, const uint16_t v[HAL_IR_COUNT]);
uint16_t pil_reply_blobs(uint8_t *p, uint16_t cap, const hal_blob_t *blobs, uint8_t n);
uint16_t pil_reply_pose(uint8_t *p, uint16_t cap, hal_status_t st, const hal_pose_t *pose);
uint16_t pil_reply_rx(uint8_t *p, uint16_t cap, hal_status_t st, const hal_ircom_msg_t *msg);
uint16_t pil_reply_host(uint8_t *p, uint16_t cap, hal_status_t st, const uint8_t *bytes, uint8_t len);
uint16_t pil_reply_accepted(uint8_t *p, uint16_t cap, uint16_t accepted);
uint16_t pil_reply_ground(uint8_t *p, uint16_t cap, hal_status_t st, const uint16_t v[HAL_GROUND_COUNT]);
/** FRAME: the `bytes` of the frame after the `what` byte (the caller
 *  writes them at p + 1, often straight from the renderer). */
uint16_t pil_reply_frame(uint8_t *p, uint16_t cap, uint16_t bytes);

/* ...and the readers, each checking that the reply answers `what` and has
 * its layout's length: 0, or -1. */
int8_t pil_read_readings(const uint8_t *p, uint16_t n, uint8_t what, uint16_t out[HAL_IR_COUNT]);
int8_t pil_read_blobs(const uint8_t *p, uint16_t n, hal_blob_t *out, uint8_t max, uint8_t *count);
int8_t pil_read_pose(const uint8_t *p, uint16_t n, hal_status_t *st, hal_pose_t *out);
int8_t pil_read_rx(const uint8_t *p, uint16_t n, hal_status_t *st, hal_ircom_msg_t *out);
int8_t pil_read_host(const uint8_t *p, uint16_t n, hal_status_t *st, uint8_t *buf, uint8_t cap, uint8_t *len);
int8_t pil_read_accepted(const uint8_t *p, uint16_t n, uint16_t *accepted);
int8_t pil_read_ground(const uint8_t *p, uint16_t n, hal_status_t *st, uint16_t out[HAL_GROUND_COUNT]);
/** FRAME: where the frame's `bytes` start in the payload, or 0. */
const uint8_t *pil_read_frame(const uint8_t *p, uint16_t n, uint16_t bytes);

#endif
