/*
 * hal_epuck.h - hal.h on a real e-puck1 (dsPIC30F6014A) over GCtronic's
 * e-puck library.
 *
 * An image (its main generated from platforms/epuck1/images.list over the
 * run loop run/image_main.h) defines the one `struct hal` of the robot and
 * the controller's state as static storage (on bare metal there is nowhere
 * else to keep them: no heap, and main never returns), and runs:
 *
 *     hal_epuck_init(&robot, &cfg, frames, sizeof frames);   struct only
 *     hal_epuck_start(&robot, app_tick);                      hardware on
 *     ...controller_init(&ctl, &params, hal_epuck_seed(&robot));
 *     for (;;) {
 *         if (hal_epuck_step_due(&robot)) {
 *             hal_epuck_begin_step(&robot);   sample the sensors once
 *             ...the controller's step and the image's telemetry
 *             hal_epuck_end_step(&robot);     actuators, IR send, clock
 *         } else {
 *             hal_epuck_poll(&robot);         background work
 *         }
 *     }
 *
 * with `static void app_tick(void) { hal_epuck_tick(&robot); }` registered
 * as a timer-2 agenda of the control period.  The agenda runs in the timer
 * interrupt, so it only counts ticks; the step itself runs in the main
 * loop, where it can take its time without delaying the motors' agendas,
 * and where every library call that busy-waits (I2C to the turret and the
 * camera) is made.
 *
 * Timing: the step starts within one poll of its tick (a poll is a few ms
 * at most: the turret's I2C read).  A step that overruns its period is
 * counted (hal_epuck_overruns); the missed ticks are dropped and
 * hal_time_ms still advances by one period per step, as hal.h says.
 *
 * Sensors are sampled once per step (begin_step) into this struct: IR
 * proximity and ambient light, the step counters.  Camera blobs are
 * computed at the first hal_camera_blobs call of a step, on the last
 * complete frame, and kept for the rest of the step.  The camera captures
 * into two buffers in turn: while the controller's step reads one, the
 * driver fills the other; poll() swaps them when the driver reports a
 * complete frame.  Received IR messages are moved into the inbox by poll(),
 * between steps, so the inbox does not change during a step.  The message
 * a step queues is sent by end_step (the turret's send busy-waits ~4 ms).
 *
 * Telemetry (hal_telemetry_write): bytes are copied into a buffer of
 * HAL_EPUCK_TX_BYTES and handed to the UART1 driver, which sends them in
 * the background; while it is busy the call accepts 0 bytes.  Pump a
 * telemetry sender from the idle loop (hal_epuck_poll's caller) to keep
 * the link busy.
 *
 * Poses and messages from a host (hal_pose, hal_host_receive) come over
 * UART1 into storage an image attaches: host_link.h.  The received bytes
 * are read by poll() and at the start of begin_step.
 *
 * Sound (cfg.sound = 1; 0 by default: both calls HAL_ERR_UNAVAILABLE).  The
 * library's A/D interrupt keeps the last 100 samples of each microphone
 * (16384 Hz: 6.1 ms).  The first hal_mic_level call of a step for a
 * microphone copies its newest TONE_DETECT_N = 96 samples (5.86 ms) and
 * runs the tone detector (hal/tone_detect.h) over them for all bands; the
 * step's other reads of that microphone return the same levels.  So the
 * window a robot gets is the 5.86 ms before its first read in a step, not
 * the whole control period: with no timer to tell when the ring has been
 * refilled, blocks are not accumulated.  hal_speaker_set(b) plays band b's
 * tone (hal/tone_tables.h) from end_step on, for one control period (at
 * most TONE_SPK_LEN = 100 ms); end_step restarts it every period while the
 * band is set, so a period that is a multiple of 25 ms plays seamlessly.
 * A step that follows a period in which the speaker played reads
 * HAL_ERR_BUSY.  (The tone of period t ends ~one period after end_step t;
 * a step that takes longer than period - 6 ms from its tick to end_step
 * would let its tail into the next window.)  Microphone levels need the
 * advance A/D module (turret images); on libIrcom images they are
 * HAL_ERR_UNAVAILABLE.
 *
 * The sources of platforms/epuck1/hal have no mutable static storage (hygiene.sh
 * checks it): all state is in this struct.
 */
#ifndef HAL_EPUCK_H
#define HAL_EPUCK_H

#include <stdint.h>

#include "blob_detect.h"
#include "hal.h"
#include "host_link.h"
#include "sound_bands.h"
#include "units.h"

/** Received IR messages kept between two steps (libIrcom's queue is 20). */
#define HAL_EPUCK_INBOX 16u
/** Most IR messages one control period may send (cfg.ircom_tx_per_period).
 *  An e-RandB frame is 16 data bits, a 3-bit header and a 4-bit CRC,
 *  Manchester coded at 100 us a half bit (455 kHz receivers): 4.6 ms on the
 *  air, and the library's send busy-waits about 4 ms; three sends take about
 *  12 ms of a 100 ms period.  libIrcom sends one at a time (the rest wait). */
#define HAL_EPUCK_TX_MAX 3u
/** Telemetry bytes handed to the UART at once. */
#define HAL_EPUCK_TX_BYTES 64u
/** Camera frame of the default configuration: the whole width of the
 *  sensor (the full field of view) subsampled by 16, and a band of 320
 *  sensor rows around the horizon subsampled by 16: 40 x 20 RGB565 pixels,
 *  1600 bytes.  Two of them (double buffering) take 3200 bytes, the RAM of
 *  one 40 x 40 frame. */
#define HAL_EPUCK_CAM_WIDTH EPUCK_CAMERA_WIDTH_PX
#define HAL_EPUCK_CAM_HEIGHT EPUCK_CAMERA_HEIGHT_PX
#define HAL_EPUCK_FRAME_BYTES (HAL_EPUCK_CAM_WIDTH * HAL_EPUCK_CAM_HEIGHT * 2u)
/** Value of hal_robot_id when no id was flashed (the word is erased). */
#define HAL_EPUCK_NO_ID 0xFFFFu

/** Configuration of the e-puck HAL.  Start from hal_epuck_default_config. */
typedef struct hal_epuck_config {
    uint16_t period_ms;            /**< control period, ms (100) */
    uint16_t robot_id;             /**< hal_robot_id (HAL_EPUCK_NO_ID: the id
                                        the flasher wrote, read by
                                        hal_epuck_start; 0 if none was) */
    uint8_t camera;                /**< 1: capture and detect blobs (1) */
    uint16_t cam_width;            /**< frame columns (HAL_EPUCK_CAM_WIDTH) */
    uint16_t cam_height;           /**< frame rows (HAL_EPUCK_CAM_HEIGHT) */
    uint16_t cam_window_y;         /**< first sensor row of the window (80) */
    uint16_t cam_window_h;         /**< sensor rows of the window (320) */
    uint8_t cam_mirror;            /**< 1: column 0 is the robot's RIGHT: negate
                                        bearings (0) [?] check on your robot:
                                        an object on its left must give a
                                        positive bearing */
    blob_detect_params_t blob;     /**< detector parameters (defaults; fov
                                        977 mrad [?], big-endian pixels) */
    uint8_t randb_range;           /**< turret emission range, 0 = full (0) */
    uint16_t randb_range_mm_per_unit; /**< mm per unit of the turret's range
                                        (10: cm) [?] */
    uint8_t sound;                 /**< 1: speaker (codec started) and
                                        microphone levels (0) */
    uint8_t ircom_tx_per_period;   /**< messages hal_ircom_send accepts per
                                        control period, 1..HAL_EPUCK_TX_MAX (1);
                                        sent one after another after the step.
                                        The simulator's ircom.tx_per_period */
    uint8_t ground;                /**< 1: the ground-sensor module is fitted
                                        (hal_ground reads it over I2C at its
                                        first call of a step; 0: HAL_ERR_UNAVAILABLE).
                                        Never probed: reading a missing module
                                        hangs (0) */
} hal_epuck_config_t;

/** The robot.  Fields are private to platforms/epuck1/hal; an image only defines one
 *  (static storage) and passes its address. */
struct hal {
    hal_epuck_config_t cfg;

    /* Clock.  `ticks` is written only by the agenda (interrupt), `ticks_seen`
     * only by the main loop: a 16-bit word is read and written atomically on
     * the dsPIC, so no interrupt masking is needed. */
    volatile uint16_t ticks;
    uint16_t ticks_seen;
    uint16_t overruns;           /**< periods missed because a step overran */
    uint32_t time_ms;            /**< hal_time_ms */
    uint32_t step;               /**< steps done */

    /* Sensors sampled at begin_step. */
    uint16_t prox[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    int16_t steps_left, steps_right;

    /* Camera: two buffers of frame_bytes in `frames`. */
    uint8_t *frames;
    uint16_t frame_bytes;
    uint8_t cam_state;           /**< hal_epuck_cam_state_t */
    uint8_t cam_negate;          /**< negate blob bearings (mirror, inverted sensor) */
    uint8_t cam_filling;         /**< buffer the driver is filling, 0/1 */
    uint8_t cam_complete;        /**< buffer with the last complete frame, 0/1,
                                      or 0xFF before the first */
    uint16_t cam_frames;         /**< complete frames so far (wraps) */
    uint8_t blobs_step_valid;    /**< blobs[] computed in this step */
    uint8_t n_blobs;
    hal_blob_t blobs[HAL_MAX_BLOBS];

    /* Actuators: set during a step, applied by end_step. */
    int16_t speed_left, speed_right;
    uint16_t leds;               /**< bits 0-7 ring, 8 body, 9 front */
    uint16_t leds_applied;       /**< what the LEDs show (0xFFFF: unknown) */
    int16_t speeds_applied[2];

    /* IR communication. */
    hal_ircom_msg_t inbox[HAL_EPUCK_INBOX];
    uint8_t in_head, in_count;
    uint16_t in_dropped;         /**< messages lost because the inbox was full */
    uint16_t out_value[HAL_EPUCK_TX_MAX];
    uint8_t out_pending;         /**< messages queued for end_step */
    uint16_t sent;               /**< messages sent (wraps) */

    /* Sound (cfg.sound). */
    uint8_t spk_band;            /**< band set this step: plays from end_step */
    uint8_t spk_sounding;        /**< band playing in the current period
                                      (what the last end_step started) */
    uint8_t mic_valid;           /**< bit m: mic m's levels computed this step */
    uint8_t mic_ok;              /**< bit m: ... and the A/D gave samples */
    uint16_t spk_plays;          /**< tones started (wraps) */
    uint32_t mic_level[HAL_MIC_COUNT][SOUND_BAND_COUNT];   /**< level counts */

    /* Ground sensors (cfg.ground). */
    uint8_t ground_valid;        /**< ground[] read in this step */
    uint16_t ground[HAL_GROUND_COUNT];

    /* Telemetry: the buffer the UART driver reads while it sends. */
    uint8_t tx[HAL_EPUCK_TX_BYTES];

    /* Poses and messages from the host: the image's storage, or NULL
     * (host_link.h). */
    hal_epuck_host_t *host;
};

/** Camera states (struct hal.cam_state). */
typedef enum hal_epuck_cam_state {
    HAL_EPUCK_CAM_OFF = 0,       /**< not configured, or no frames given */
    HAL_EPUCK_CAM_RUNNING = 1,   /**< capturing */
    HAL_EPUCK_CAM_FAILED = 2     /**< the driver refused the window, or the
                                      sensor is mounted vertically (some
                                      PO3030K robots): blobs are never seen */
} hal_epuck_cam_state_t;

/** 100 ms, camera on with the 40 x 20 window, blob defaults, id from flash,
 *  full turret range, turret range in cm, no sound. */
void hal_epuck_default_config(hal_epuck_config_t *cfg);

/** Sets up the struct (no hardware access).  `frames` holds two frames of
 *  cfg->cam_width * cam_height * 2 bytes (`frames_bytes` >= twice that), or
 *  is NULL for an image without camera.  Returns 0, or -1 if the frames
 *  are too small for the configured window (the camera is then off). */
int8_t hal_epuck_init(hal_t *hal, const hal_epuck_config_t *cfg, uint8_t *frames, uint16_t frames_bytes);

/** Starts the hardware: ports, UART1, motors, A/D (and IR calibration: keep
 *  the robot clear of obstacles for the first second), IR communication,
 *  camera, then the agenda `tick` every control period.  `tick` must call
 *  hal_epuck_tick on this struct. */
void hal_epuck_start(hal_t *hal, void (*tick)(void));

/** Counts one control period.  Called from the agenda (interrupt context). */
void hal_epuck_tick(hal_t *hal);

/** 1 if a control period has elapsed since the last step (then the caller
 *  runs begin_step, the controller's step, end_step), else 0. */
uint8_t hal_epuck_step_due(hal_t *hal);

/** Background work between steps: swaps the camera buffers when a frame is
 *  complete, moves received IR messages into the inbox, reads what the
 *  host sent (host_link.h).  Never blocks for more than the IR driver's
 *  own busy-waits (a few ms on the turret). */
void hal_epuck_poll(hal_t *hal);

/** Reads what the host sent (bounded: host_link.h), samples the sensors
 *  of this step. */
void hal_epuck_begin_step(hal_t *hal);

/** Applies wheel speeds and LEDs, sends the queued IR message, advances the
 *  clock by one period. */
void hal_epuck_end_step(hal_t *hal);

/** 32 bits for a controller's seed: the robot id mixed with the noise of
 *  the ambient light readings (call after begin_step). */
uint32_t hal_epuck_seed(hal_t *hal);

/** Position of the selector switch, 0..15. */
uint8_t hal_epuck_selector(hal_t *hal);

/** Control periods missed because a step (or a poll) overran. */
uint16_t hal_epuck_overruns(const hal_t *hal);

/** The robot id the flasher wrote into program memory (word 0x17F36; see
 *  tools/flash/epuck_flash.py --robot-id), HAL_EPUCK_NO_ID if none.
 *  Defined in platforms/epuck1/hal/xc16/robot_id.c (XC16 only: it reads program
 *  memory); the portable link gates use a stub. */
uint16_t hal_epuck_flash_robot_id(void);

/** Speaker samples (7200 Hz) a tone plays per control period of
 *  `period_ms`: rounded up to a multiple of 4 (the library's playback
 *  counts down by 4), at most TONE_SPK_LEN.  25 ms: 180. */
uint16_t hal_epuck_tone_samples(uint16_t period_ms);

/* ---- IR backend: defined by ircom_randb.c or ircom_libircom.c ---- */

/** Starts the A/D scan, calibrates the IR sensors, starts IR communication. */
void hal_epuck_ir_start(hal_t *hal);
/** Reads the 8 proximity and ambient values into hal->prox / ambient. */
void hal_epuck_ir_sample(hal_t *hal);
/** Moves received messages into the inbox (hal_epuck_inbox_push). */
void hal_epuck_ir_poll(hal_t *hal);
/** Sends one message (the IR backend's). */
void hal_epuck_ir_transmit(hal_t *hal, uint16_t value);

/** Copies the newest TONE_DETECT_N samples of microphone `mic` (0..2,
 *  oldest first, raw 12-bit A/D counts) into `out`: 1, or 0 when the
 *  image's A/D module does not sample the microphones (libIrcom). */
uint8_t hal_epuck_mic_block(hal_t *hal, uint8_t mic, int16_t *out);

/** Appends a received message to the inbox; when full, the message is
 *  dropped and counted (in_dropped).  Returns 1 if kept. */
uint8_t hal_epuck_inbox_push(hal_t *hal, const hal_ircom_msg_t *msg);

/** Index 0..7 of the e-puck IR sensor whose bearing is nearest to
 *  `bearing_mrad` (any value; wrapped to (-pi, pi]). */
uint8_t hal_epuck_nearest_sensor(int16_t bearing_mrad);

/** A library A/D reading clamped to the contract's 0..HAL_RAW_MAX. */
uint16_t hal_epuck_clamp_raw(int v);

/** `rad` radians (any float) as mrad wrapped to (-3142, 3142]. */
int16_t hal_epuck_rad_to_mrad(float rad);

#endif
