/*
 * hal_epuck2.h - hal.h on a real e-puck2 (STM32F407, Cortex-M4F, 168 MHz)
 * over GCtronic's e-puck2 main-processor library (its native API,
 * epuck2_lib.h) and ChibiOS (epuck2_os.h).
 *
 * An image (its main generated from the e-puck1's images.list over this
 * platform's run loop, run/image_main.h) defines the one `struct hal` of
 * the robot and the controller's state as static storage, and runs:
 *
 *     epuck2_os_init();                                       ChibiOS, bus
 *     hal_epuck2_init(&robot, &cfg, frame, sizeof frame);     struct only
 *     hal_epuck2_start(&robot);                               hardware on
 *     ...controller_init(&ctl, &params, hal_epuck2_seed(&robot));
 *     for (;;) {
 *         if (hal_epuck2_step_due(&robot)) {
 *             hal_epuck2_begin_step(&robot);   sample the sensors once
 *             ...the controller's step and the image's telemetry
 *             hal_epuck2_end_step(&robot);     actuators, IR send, clock
 *         } else {
 *             hal_epuck2_poll(&robot);         background work
 *             epuck2_os_idle();                1 ms for the library's threads
 *         }
 *     }
 *
 * The image's main runs as ChibiOS's main thread (NORMALPRIO); the
 * library's modules (motors, proximity, microphones, the ESP32's SPI link)
 * run in their own threads and interrupts, which is why the idle loop
 * sleeps a tick between polls instead of spinning.
 *
 * Timing: a step is due when ChibiOS's clock (1 ms) reaches the next
 * period; a step that overruns its period is counted (hal_epuck2_overruns),
 * the missed periods are dropped, and hal_time_ms still advances by one
 * period per step, as hal.h says.
 *
 * Sensors are sampled once per step (begin_step): IR proximity and
 * ambient light from the library's proximity thread (100 Hz; 20 Hz with
 * the turret, as the library's own turret demo runs it; at most 5 Hz from
 * the ircom module on libIrcom images), the 32-bit motor position counters
 * (given as hal.h's wrapping 16-bit step counters).
 *
 * Camera (cfg.camera): the PO8030 captures a window of the sensor's whole
 * width (640 columns, the full field of view) and cfg.cam_window_h rows
 * from cfg.cam_window_y, subsampled by 4 (the most the sensor does):
 * 160 x 80 RGB565 pixels (25,600 B) in the library's DCMI buffer, one
 * frame at a time.  poll() averages each 4 x 4 block of it into the
 * image's frame, the e-puck1's 40 x 20 (1,600 B), so the blob detector
 * (hal/blob_detect.h) and its parameters see the frame they see on the
 * e-puck1, and starts the next capture.  Blobs are computed at the first
 * hal_camera_blobs call of a step, on the last averaged frame.  The SPI
 * link to the ESP32 (the RGB LEDs) is suspended while the DCMI captures,
 * as the library requires.
 *
 * Sound (cfg.sound): the four microphones' PCM at 16 kHz, 10 ms a buffer.
 * hal.h's microphones 0, 1, 2 are the library's MIC_RIGHT, MIC_LEFT and
 * MIC_BACK (the front one is not used: hal.h has three).  The first
 * hal_mic_level call of a step for a microphone takes its newest
 * TONE_DETECT_N = 96 samples (6.0 ms) and runs the tone detector over them
 * with coefficients for 16 kHz (tone_coeffs_16k.c).  hal_speaker_set(b)
 * plays band b's tone (hal/sound_bands.h) through the DAC from end_step
 * on, until changed; a step that follows a period in which the speaker
 * played reads HAL_ERR_BUSY, as on the e-puck1.
 *
 * LEDs: hal.h's ring LED k is the red LED k/2 (LED1 front, LED3, LED5,
 * LED7) for even k, and the RGB LED (k-1)/2 (LED2 front-right, LED4, LED6,
 * LED8) lit red for odd k, so the ring looks as on the e-puck1.
 *
 * Telemetry and the host link: UART3, the ESP32's Bluetooth serial
 * (host_link.h).  hal_telemetry_write queues what fits in ChibiOS's output
 * queue (128 B) without waiting.
 *
 * Wheels: hal.h's limit (+-HAL_WHEEL_SPEED_MAX = 1000 steps/s) applies,
 * below the library's 1100, so a controller moves as on the e-puck1.
 *
 * The sources of platforms/epuck2/hal have no mutable static storage
 * (hygiene.sh checks it): all state is in this struct.
 */
#ifndef HAL_EPUCK2_H
#define HAL_EPUCK2_H

#include <stdint.h>

#include "blob_detect.h"
#include "hal.h"
#include "host_link.h"
#include "sound_bands.h"
#include "tone_tables.h"
#include "units.h"

/** Received IR messages kept between two steps. */
#define HAL_EPUCK2_INBOX 16u
/** Most IR messages one control period may send (cfg.ircom_tx_per_period). */
#define HAL_EPUCK2_TX_MAX 3u
/** The frame the blobs come from: the e-puck1's, 40 x 20 RGB565. */
#define HAL_EPUCK2_CAM_WIDTH EPUCK_CAMERA_WIDTH_PX
#define HAL_EPUCK2_CAM_HEIGHT EPUCK_CAMERA_HEIGHT_PX
#define HAL_EPUCK2_FRAME_BYTES (HAL_EPUCK2_CAM_WIDTH * HAL_EPUCK2_CAM_HEIGHT * 2u)
/** The camera's subsampling (SUBSAMPLING_X4) and the columns it captures:
 *  640 / 4 = 160. */
#define HAL_EPUCK2_CAM_SUBSAMPLE 4u
#define HAL_EPUCK2_CAM_CAPTURE_WIDTH (EPUCK2_PO8030_WIDTH / HAL_EPUCK2_CAM_SUBSAMPLE)
/** Value of cfg.robot_id that means "the build's id" (epuck2_os_robot_id). */
#define HAL_EPUCK2_NO_ID 0xFFFFu

/** Configuration of the e-puck2 HAL.  Start from hal_epuck2_default_config. */
typedef struct hal_epuck2_config {
    uint16_t period_ms;            /**< control period, ms (100) */
    uint16_t robot_id;             /**< hal_robot_id (HAL_EPUCK2_NO_ID: the
                                        build's, epuck2_os_robot_id) */
    uint8_t camera;                /**< 1: capture and detect blobs (1) */
    uint16_t cam_window_y;         /**< first sensor row of the window (80) */
    uint16_t cam_window_h;         /**< sensor rows of the window (320): a
                                        multiple of 80 (4 subsampled rows per
                                        frame row, 20 rows), at most 480 */
    uint8_t cam_mirror;            /**< 1: column 0 is the robot's RIGHT:
                                        negate bearings (0) [?] check on your
                                        robot: an object on its left must give
                                        a positive bearing */
    blob_detect_params_t blob;     /**< detector parameters (the e-puck1's) */
    uint8_t randb_range;           /**< turret emission range register (150,
                                        the library's demo) */
    uint16_t randb_range_mm_per_unit; /**< mm per unit of the turret's range
                                        (10: cm) [?] */
    uint8_t sound;                 /**< 1: speaker and microphone levels (0) */
    uint8_t ircom_tx_per_period;   /**< messages hal_ircom_send accepts per
                                        period, 1..HAL_EPUCK2_TX_MAX (1) */
    uint8_t ground;                /**< 1: the ground-sensor module is fitted
                                        (the library's ground thread reads it);
                                        0: HAL_ERR_UNAVAILABLE (0) */
} hal_epuck2_config_t;

/** Camera states (struct hal.cam_state). */
typedef enum hal_epuck2_cam_state {
    HAL_EPUCK2_CAM_OFF = 0,       /**< not configured, or no frame given */
    HAL_EPUCK2_CAM_RUNNING = 1,   /**< capturing */
    HAL_EPUCK2_CAM_FAILED = 2     /**< the driver refused the window */
} hal_epuck2_cam_state_t;

/** The robot.  Fields are private to platforms/epuck2/hal (and the run
 *  loop's telemetry); an image only defines one and passes its address. */
struct hal {
    hal_epuck2_config_t cfg;

    /* Clock: the next period's start on ChibiOS's clock. */
    uint32_t next_ms;
    uint16_t overruns;           /**< periods missed because a step overran */
    uint32_t time_ms;            /**< hal_time_ms */
    uint32_t step;               /**< steps done */

    /* Sensors sampled at begin_step. */
    uint16_t prox[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    int16_t steps_left, steps_right;

    /* Camera: the averaged frame (the image's storage). */
    uint8_t *frame;
    uint8_t cam_state;           /**< hal_epuck2_cam_state_t */
    uint8_t cam_have_frame;      /**< frame holds a complete frame */
    uint16_t cam_frames;         /**< frames taken (wraps) */
    uint16_t cam_lost;           /**< completed captures the driver would not lend */
    uint8_t blobs_step_valid;
    uint8_t n_blobs;
    hal_blob_t blobs[HAL_MAX_BLOBS];

    /* Actuators: set during a step, applied by end_step. */
    int16_t speed_left, speed_right;
    uint16_t leds;               /**< bits 0-7 ring, 8 body, 9 front */
    uint16_t leds_applied;       /**< what the LEDs show (0xFFFF: unknown) */
    int16_t speeds_applied[2];

    /* IR communication. */
    hal_ircom_msg_t inbox[HAL_EPUCK2_INBOX];
    uint8_t in_head, in_count;
    uint16_t in_dropped;
    uint16_t out_value[HAL_EPUCK2_TX_MAX];
    uint8_t out_pending;
    uint16_t sent;

    /* Sound (cfg.sound). */
    uint8_t spk_band;            /**< band set this step: plays from end_step */
    uint8_t spk_sounding;        /**< band playing in the current period */
    uint8_t mic_valid;           /**< bit m: mic m's levels computed this step */
    uint16_t spk_plays;          /**< tones started (wraps) */
    uint32_t mic_level[HAL_MIC_COUNT][SOUND_BAND_COUNT];

    /* Ground sensors (cfg.ground). */
    uint8_t ground_valid;
    uint16_t ground[HAL_GROUND_COUNT];

    /* Poses and messages from the host: the image's storage, or NULL. */
    hal_epuck2_host_t *host;
};

/** 100 ms, camera on (the 40 x 20 frame of 640 x 320 sensor pixels),
 *  blob defaults, the build's robot id, turret range 150 in cm, no sound,
 *  one IR message a period, no ground sensors. */
void hal_epuck2_default_config(hal_epuck2_config_t *cfg);

/** Sets up the struct (no hardware access).  `frame` holds one frame of
 *  HAL_EPUCK2_FRAME_BYTES (`frame_bytes` at least that), or is NULL for an
 *  image without camera.  Returns 0, or -1 for a configuration it cannot
 *  run (the camera is then off; the IR messages a period 1). */
int8_t hal_epuck2_init(hal_t *hal, const hal_epuck2_config_t *cfg, uint8_t *frame, uint16_t frame_bytes);

/** Starts the hardware (after epuck2_os_init): motors, LEDs, the IR
 *  backend (and the IR calibration: keep the robot clear of obstacles for
 *  the first second), camera, sound, ground sensors; the first period
 *  starts now. */
void hal_epuck2_start(hal_t *hal);

/** 1 if a control period has begun since the last step (then the caller
 *  runs begin_step, the controller's step, end_step), else 0. */
uint8_t hal_epuck2_step_due(hal_t *hal);

/** Background work between steps: the camera's frame, received IR
 *  messages into the inbox, what the host sent (host_link.h).  Never
 *  waits (the turret's I2C transfers take their bus time). */
void hal_epuck2_poll(hal_t *hal);

/** Reads what the host sent, samples the sensors of this step. */
void hal_epuck2_begin_step(hal_t *hal);

/** Applies wheel speeds, LEDs and the speaker, sends the queued IR
 *  messages, advances the clock by one period. */
void hal_epuck2_end_step(hal_t *hal);

/** 32 bits for a controller's seed: the robot id mixed with the noise of
 *  the ambient light readings (call after begin_step). */
uint32_t hal_epuck2_seed(hal_t *hal);

/** Position of the selector switch, 0..15. */
uint8_t hal_epuck2_selector(hal_t *hal);

/** Control periods missed because a step (or a poll) overran. */
uint16_t hal_epuck2_overruns(const hal_t *hal);

/** Averages the library's 160 x (4 x frame rows) capture `src` (RGB565,
 *  high byte first) into the 40 x 20 `dst`, each pixel the mean of a
 *  4 x (src rows / 20) block, channel by channel. */
void hal_epuck2_cam_average(const uint8_t *src, uint16_t src_rows, uint8_t *dst);

/* ---- IR backend: defined by ircom_randb.c or ircom_libircom.c ---- */

/** Starts proximity sampling, calibrates the IR sensors, starts IR
 *  communication. */
void hal_epuck2_ir_start(hal_t *hal);
/** Reads the 8 proximity and ambient values into hal->prox / ambient. */
void hal_epuck2_ir_sample(hal_t *hal);
/** Moves received messages into the inbox (hal_epuck2_inbox_push). */
void hal_epuck2_ir_poll(hal_t *hal);
/** Sends one message (the IR backend's). */
void hal_epuck2_ir_transmit(hal_t *hal, uint16_t value);

/** Appends a received message to the inbox; when full, the message is
 *  dropped and counted (in_dropped).  Returns 1 if kept. */
uint8_t hal_epuck2_inbox_push(hal_t *hal, const hal_ircom_msg_t *msg);

/** Index 0..7 of the IR sensor whose bearing is nearest `bearing_mrad`. */
uint8_t hal_epuck2_nearest_sensor(int16_t bearing_mrad);

/** A library reading clamped to the contract's 0..HAL_RAW_MAX. */
uint16_t hal_epuck2_clamp_raw(int v);

/** `mrad` (any value) wrapped to (-3142, 3142]. */
int16_t hal_epuck2_wrap_mrad(int32_t mrad);

/** The Goertzel constants of the bands at the e-puck2's 16 kHz
 *  (tone_coeffs_16k.c, generated by tools/sound/gen_tone_tables.py). */
extern const tone_band_coeffs_t tone_band_coeffs_16k[SOUND_BAND_COUNT];

#endif
