/*
 * pil_frame.h - the frames of processor-in-the-loop (PIL): a controller's
 * image running as machine code on an emulated microcontroller, stepped in
 * lockstep with the simulator (docs/reference/pil.md).
 *
 * Both ends speak the same frames, whatever carries them: on the emulated
 * ATmega2560 (platforms/pil_avr/) a mailbox in the MCU's RAM that the
 * emulator fills and empties between two instructions; on a core whose
 * emulator offers only a serial port, the same bytes over that port.
 *
 *   [0]      PIL_MAGIC
 *   [1]      PIL_VERSION
 *   [2]      type (pil_type_t)
 *   [3]      the low 8 bits of the control step the frame belongs to (a
 *            stale or early answer is caught)
 *   [4..5]   payload length N, little-endian, at most PIL_MAX_PAYLOAD
 *   [6..]    payload: N bytes (pil_msg.h lays out each type's)
 *   [-2..-1] CRC-16/CCITT-FALSE (telemetry_crc16) of every byte before
 *            it, little-endian
 *
 * Every multi-byte field of a frame is little-endian and read or written
 * a byte at a time (pil_put_* / pil_get_*): no frame is ever cast to a
 * struct, so neither end depends on the other's alignment, padding or int
 * size (the dsPIC traps on a misaligned 16-bit access).
 *
 * Pure functions over caller-owned buffers: no HAL, no statics.
 */
#ifndef FW_PIL_FRAME_H
#define FW_PIL_FRAME_H

#include <stdint.h>

/** First byte of every frame. */
#define PIL_MAGIC 0xA7u
/** Protocol version; a frame of another version is an error, never read. */
#define PIL_VERSION 1u
/** Bytes before the payload. */
#define PIL_HEADER_BYTES 6u
/** Bytes after it (the CRC). */
#define PIL_CRC_BYTES 2u
/** Bytes of a frame of `n` payload bytes. */
#define PIL_FRAME_BYTES(n) ((uint16_t)((n) + PIL_HEADER_BYTES + PIL_CRC_BYTES))
/** Largest payload: a 64 x 40 RGB565 camera frame and its reply header. */
#define PIL_MAX_PAYLOAD 5136u
/** Largest frame. */
#define PIL_FRAME_MAX PIL_FRAME_BYTES(PIL_MAX_PAYLOAD)

/** Frame types.  Below 0x80 the robot sends, from 0x80 the simulator,
 *  from 0xC0 the emulator itself (its own report beside the MCU's
 *  frames: not seen by the MCU). */
typedef enum pil_type {
    PIL_HELLO = 0x01,     /**< robot: booted; what the image is (pil_hello_t) */
    PIL_REQUEST = 0x02,   /**< robot: a sensor or inbox read this step (pil_request_t) */
    PIL_ACT = 0x03,       /**< robot: the step is done; its actuators (pil_act_t) */
    PIL_FAULT = 0x04,     /**< robot: it could not read the simulator's last frame (FAULT) */
    PIL_READY = 0x05,     /**< robot: set up, waiting for its first step (no payload) */
    PIL_CONFIG = 0x81,    /**< simulator: the answer to HELLO (pil_config_t) */
    PIL_STEP = 0x82,      /**< simulator: run one control step (pil_step_t) */
    PIL_REPLY = 0x83,     /**< simulator: the answer to a REQUEST (pil_reply_t) */
    PIL_EMU = 0xC0,       /**< emulator: how the MCU ran since it was last resumed (pil_emu_t) */
    PIL_PEEK = 0xC1,      /**< simulator to emulator: send this much of the MCU's RAM (a debugger's
                               read, while the core is stopped: pil_peek_t) */
    PIL_MEMORY = 0xC2     /**< emulator: those bytes */
} pil_type_t;

/** What pil_frame_check found. */
typedef enum pil_frame_error {
    PIL_FRAME_OK = 0,
    PIL_FRAME_SHORT = -1,      /**< fewer bytes than a header and a CRC, or than its length says */
    PIL_FRAME_MAGIC = -2,      /**< byte 0 is not PIL_MAGIC */
    PIL_FRAME_VERSION = -3,    /**< another protocol version */
    PIL_FRAME_LENGTH = -4,     /**< payload longer than PIL_MAX_PAYLOAD or than the buffer */
    PIL_FRAME_CRC = -5         /**< the CRC does not match */
} pil_frame_error_t;

/** One frame read in place: its payload points into the caller's buffer. */
typedef struct pil_frame {
    uint8_t type;              /**< pil_type_t */
    uint8_t seq;               /**< low 8 bits of its control step */
    uint16_t len;              /**< payload bytes */
    const uint8_t *payload;
} pil_frame_t;

/** Writes the header and CRC around the `len` payload bytes already at
 *  `buf + PIL_HEADER_BYTES` (room for `cap` bytes in all); returns the
 *  frame's length, or 0 when it does not fit. */
uint16_t pil_frame_seal(uint8_t *buf, uint16_t cap, uint8_t type, uint8_t seq, uint16_t len);

/** Checks the `n` bytes at `buf` as one frame and reads its header into
 *  `out` (its payload stays in `buf`): PIL_FRAME_OK or what is wrong.
 *  Bytes after the frame's CRC are not read. */
pil_frame_error_t pil_frame_check(const uint8_t *buf, uint16_t n, pil_frame_t *out);

/** Bytes of the frame starting at `buf` by its header (at least
 *  PIL_HEADER_BYTES there), or 0 when the header is not a frame's (magic,
 *  version, length).  A stream reader reads a header, then this many. */
uint16_t pil_frame_size(const uint8_t *header);

/** One line, for errors: "bad CRC", "version 3 (this build speaks 1)". */
const char *pil_frame_error_name(pil_frame_error_t e);

/* Little-endian fields, a byte at a time. */
void pil_put_u16(uint8_t *p, uint16_t v);
void pil_put_u32(uint8_t *p, uint32_t v);
uint16_t pil_get_u16(const uint8_t *p);
uint32_t pil_get_u32(const uint8_t *p);

#endif
