/*
 * hal.h - the contract between portable e-puck controllers and a platform.
 *
 * Controllers include this header (and firmware headers) only.  Every call
 * takes the robot as an opaque `hal_t *`; a platform defines `struct hal` and
 * every function below, and is bound at link time.  The platforms are the
 * folders of platforms/ (platforms/platforms.list):
 *   - epuck1/   the e-puck1 (dsPIC30F6014A) over GCtronic's e-puck library;
 *   - epuck2/   the e-puck2 (STM32F407) over GCtronic's e-puck2 library;
 *   - host/     the simulator (sim_host/), one hal_t per simulated robot.
 *
 * Units are integers at the boundary (the dsPIC has no FPU) and are named on
 * every channel.  Angles are in milliradians, counter-clockwise positive, zero
 * straight ahead (x forward, y to the robot's left).  Distances are in
 * millimetres, times in milliseconds.
 *
 * Reads are consistent within one control step: a platform samples a sensor
 * at most once per step, so two reads of the same channel in one step return
 * the same value.  No call blocks.
 *
 * Status: every call that can fail, or that a platform may lack, returns a
 * hal_status_t, HAL_OK (0) or a negative HAL_ERR_*, and gives its result
 * through a pointer.  Calls that cannot fail return their result directly:
 * identity and time, the IR and ambient readings every e-puck has (an index
 * out of range reads as "nothing there"), and counts (blobs found, bytes
 * accepted).
 */
#ifndef HAL_H
#define HAL_H

#include <stdint.h>

/** The robot a controller runs on.  Opaque: defined by the platform. */
typedef struct hal hal_t;

/** Result of a call that can fail: HAL_OK or one of HAL_ERR_*. */
typedef int8_t hal_status_t;
#define HAL_OK 0
/** The platform has no such channel, or does not model it (no tracker on a
 *  bare e-puck, no camera on an image built without frames). */
#define HAL_ERR_UNAVAILABLE (-1)
/** Busy: try again next step (one IR message per control period). */
#define HAL_ERR_BUSY (-2)
/** Nothing to read (an empty IR inbox). */
#define HAL_ERR_EMPTY (-3)
/** An argument out of range (a microphone or band that does not exist). */
#define HAL_ERR_RANGE (-4)

/* ------------------------------------------------------------------ */
/* Identity and time                                                   */
/* ------------------------------------------------------------------ */

/** Robot id, 0..65534 (the simulator numbers robots from 0). */
uint16_t hal_robot_id(hal_t *hal);

/** Milliseconds since the controller was started.  Advances by one control
 *  period per step; wraps after 49.7 days. */
uint32_t hal_time_ms(hal_t *hal);

/** The control period in milliseconds: the time between two `*_step` calls
 *  (100 ms by default, the 10 Hz of seeds 000 and 003). */
uint16_t hal_control_period_ms(hal_t *hal);

/* ------------------------------------------------------------------ */
/* IR proximity and ambient light (the 8 TCRT1000 sensors)            */
/* ------------------------------------------------------------------ */

/** Number of IR sensors.  Bearings (degrees, CCW positive): IR0 -17,
 *  IR1 -50, IR2 -90, IR3 -150, IR4 +150, IR5 +90, IR6 +50, IR7 +17. */
#define HAL_IR_COUNT 8u

/** Largest raw value of the 12-bit A/D converter. */
#define HAL_RAW_MAX 4095u

/** Calibrated proximity of sensor `index` (0..7) in raw counts 0..4095:
 *  larger is closer (about 4095 at contact, 235 at 30 mm, near 0 beyond
 *  ~80 mm).  Out-of-range index returns 0. */
uint16_t hal_ir_proximity(hal_t *hal, uint8_t index);

/** Ambient light at sensor `index` (0..7) in raw counts 0..4095.  The value
 *  FALLS as light rises (about 4000 in the dark).  Out-of-range index
 *  returns HAL_RAW_MAX. */
uint16_t hal_ir_ambient(hal_t *hal, uint8_t index);

/** Bearing of IR sensor `index` on this robot in milliradians (CCW
 *  positive), so that controllers need not carry the table.  Out-of-range
 *  index returns 0. */
int16_t hal_ir_bearing_mrad(hal_t *hal, uint8_t index);

/* ------------------------------------------------------------------ */
/* Camera colour blobs                                                 */
/* ------------------------------------------------------------------ */

/** Colour classes the blob detector reports. */
typedef enum hal_colour {
    HAL_COLOUR_NONE = 0,
    HAL_COLOUR_RED = 1,
    HAL_COLOUR_GREEN = 2,
    HAL_COLOUR_BLUE = 3,
    HAL_COLOUR_COUNT = 4
} hal_colour_t;

/** One coloured region seen by the front camera. */
typedef struct hal_blob {
    uint8_t colour;        /**< hal_colour_t */
    int16_t bearing_mrad;  /**< centre of the blob, CCW positive, 0 ahead */
    uint16_t width_mrad;   /**< apparent angular width */
    uint16_t pixels;       /**< area in pixels of the platform's frame */
} hal_blob_t;

/** Most blobs a platform reports per step. */
#define HAL_MAX_BLOBS 8u

/** Fills up to `max` blobs, largest first, and returns how many (0 when
 *  the robot has no camera).  The frame behind them is the latest complete
 *  one (on the e-puck a capture runs in the background; the simulator
 *  computes it on request). */
uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max);

/** The widest blob of `colour` (hal_colour_t) in view into *widest (the
 *  nearest of same-sized things), and how many blobs of that colour are in
 *  view (0: *widest untouched).  Platform-neutral (hal/hal_common.c), built
 *  on hal_camera_blobs. */
uint8_t hal_camera_widest(hal_t *hal, uint8_t colour, hal_blob_t *widest);

/** Size of the frame the blobs come from, pixels (the e-puck image: 40 x
 *  20): HAL_OK, or HAL_ERR_UNAVAILABLE without a camera. */
hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px);

/** Raw statistics of the pixels of one frame (hal_camera_colour_stats):
 *  each 8-bit channel (R, G, B, expanded from RGB565 as the detector
 *  expands them) over the pixels counted. */
typedef struct hal_colour_stats {
    uint16_t pixels;       /**< pixels counted */
    uint8_t mean[3];       /**< R, G, B mean, rounded; 0 when none counted */
    uint8_t sd[3];         /**< R, G, B standard deviation, rounded down */
} hal_colour_stats_t;

/** Statistics of the latest complete frame's pixels: with `colour` 0
 *  (HAL_COLOUR_NONE) every pixel of the frame, else the pixels the blob
 *  detector classifies as `colour` (its thresholds, hal/blob_detect.h).
 *  For the calibration image (camera thresholds and colour response);
 *  a frame's worth of work, not for a controller's every step.  HAL_OK,
 *  HAL_ERR_RANGE for a colour above HAL_COLOUR_BLUE, HAL_ERR_UNAVAILABLE
 *  without a camera or where the platform does not pass frames on (the
 *  processor-in-the-loop robots); *out is zeroed unless HAL_OK. */
hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out);

/* ------------------------------------------------------------------ */
/* Ground sensors (the ground-sensor module, an extension)             */
/* ------------------------------------------------------------------ */

/** Number of ground sensors: three IR emitter/receivers under the front
 *  of the robot looking down, 10 mm apart: GS0 left, GS1 centre, GS2
 *  right. */
#define HAL_GROUND_COUNT 3u

/** How much IR the floor under ground sensor `index` (0..2) reflects, in
 *  raw counts 0..4095 into *reflected: larger is a lighter floor (about
 *  1000 over white paper, near 0 over black; coloured paper reads nearly
 *  as white).  Returns HAL_OK; HAL_ERR_RANGE for a sensor that does not
 *  exist; HAL_ERR_UNAVAILABLE on a robot without the module (or an image
 *  built without it), with *reflected 0 either way. */
hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected);

/* ------------------------------------------------------------------ */
/* Microphones and speaker                                             */
/* ------------------------------------------------------------------ */

/** Number of microphones (e-puck1: 3). */
#define HAL_MIC_COUNT 3u
/** Sound bands a controller can emit and listen to (band 0 is silence).
 *  Each band is one tone; its frequency is the platform's (hal/sound_bands.h
 *  on the e-puck, below the codec's Nyquist limit). */
#define HAL_SOUND_BANDS 4u

/** How loud band `band` (1..HAL_SOUND_BANDS-1) was at microphone `mic`
 *  (0..2) over the last control period, in level counts >= 0, into *level.
 *  Scale: in the simulator 1 count = 0.001 of the sound model's unit (seed
 *  002's eq 1: a source gives A0 = 299.18 units at 0 m); on the e-puck the
 *  tone detector's amplitude (see platforms/epuck1/hal).  Only changes of a level are
 *  meant to be compared, never levels across platforms.
 *  Returns HAL_OK; HAL_ERR_BUSY when this robot's own speaker played during
 *  that period (its tone drowns the microphones: a controller that listens
 *  keeps its speaker silent for a period first), with *level 0;
 *  HAL_ERR_RANGE for a microphone or band that does not exist;
 *  HAL_ERR_UNAVAILABLE on a platform or image without sound. */
hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level);

/** Plays the tone of `band` (0 = silence) from the next control period on,
 *  until changed: HAL_OK, HAL_ERR_RANGE, or HAL_ERR_UNAVAILABLE. */
hal_status_t hal_speaker_set(hal_t *hal, uint8_t band);

/* ------------------------------------------------------------------ */
/* IR local communication                                              */
/* ------------------------------------------------------------------ */

/** Data bits a platform carries per message: 8 with libIrcom on the bare
 *  e-puck, 16 with the range-and-bearing turret (e-RandB).  Bits above the
 *  platform's width are dropped by the sender. */
uint8_t hal_ircom_payload_bits(hal_t *hal);

/** A received message with the receiver's estimate of where it came from. */
typedef struct hal_ircom_msg {
    uint16_t value;        /**< the data bits (see hal_ircom_payload_bits) */
    uint8_t sensor;        /**< IR sensor that received it, 0..7 */
    int16_t bearing_mrad;  /**< bearing of the sender, CCW positive */
    uint16_t range_mm;     /**< estimated range to the sender */
} hal_ircom_msg_t;

/** Queues one message for transmission during this control period:
 *  HAL_OK, or HAL_ERR_BUSY when the period's messages are all queued: one,
 *  unless the platform is set for more (the simulator's
 *  `ircom.tx_per_period`, the turret images' `cfg.ircom_tx_per_period`,
 *  up to 3).  A controller with several messages sends until BUSY. */
hal_status_t hal_ircom_send(hal_t *hal, uint16_t value);

/** Pops the oldest received message into `out`: HAL_OK, or HAL_ERR_EMPTY
 *  when the inbox is empty. */
hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out);

/* ------------------------------------------------------------------ */
/* Wheels (stepper motors)                                             */
/* ------------------------------------------------------------------ */

/** Largest wheel speed magnitude in steps/s (e-puck1). */
#define HAL_WHEEL_SPEED_MAX 1000

/** Sets both wheel speeds in steps/s (1000 steps per revolution of a
 *  41 mm wheel: 1 step = 0.1288 mm).  Clamped to +-HAL_WHEEL_SPEED_MAX. */
void hal_set_wheel_speeds(hal_t *hal, int16_t left_steps_s, int16_t right_steps_s);

/** Step counters in steps since start, 16-bit, wrapping as on the robot.
 *  They count commanded motor steps, which a blocked wheel still makes. */
void hal_wheel_steps(hal_t *hal, int16_t *left, int16_t *right);

/* ------------------------------------------------------------------ */
/* LEDs                                                                */
/* ------------------------------------------------------------------ */

/** Number of red ring LEDs (LED0 front, counting clockwise seen from above). */
#define HAL_LED_COUNT 8u
/** The LED word platforms report (telemetry, pictures): bit k = ring LED k,
 *  then these two. */
#define HAL_LED_WORD_BODY_BIT 8u
#define HAL_LED_WORD_FRONT_BIT 9u

/** Switches ring LED `index` (0..7) on (non-zero) or off. */
void hal_set_led(hal_t *hal, uint8_t index, uint8_t on);
/** Switches the green body LED. */
void hal_set_body_led(hal_t *hal, uint8_t on);
/** Switches the red front LED. */
void hal_set_front_led(hal_t *hal, uint8_t on);

/* ------------------------------------------------------------------ */
/* Pose from an overhead tracker, messages from the host               */
/* ------------------------------------------------------------------ */

/** Where the robot is, as an external tracker sees it, in the arena's
 *  frame (origin at the centre, x right, y up seen from above). */
typedef struct hal_pose {
    int32_t x_mm;
    int32_t y_mm;
    int16_t heading_mrad;  /**< CCW from +x, (-3142, 3142] */
    uint16_t age_ms;       /**< how old the fix is when read: 0 from the
                                simulator's tracker (a fix every step); on
                                the e-puck the time since its pose frame
                                arrived over Bluetooth */
} hal_pose_t;

/** A pose older than this is not given (HAL_ERR_UNAVAILABLE), ms. */
#define HAL_POSE_MAX_AGE_MS 1000u

/** The tracker's pose this step: HAL_OK, or HAL_ERR_UNAVAILABLE when there
 *  is no tracker (a bare e-puck), it lost the robot this step, or its last
 *  fix is older than HAL_POSE_MAX_AGE_MS. */
hal_status_t hal_pose(hal_t *hal, hal_pose_t *out);

/** Longest message from the host, bytes. */
#define HAL_HOST_MSG_MAX 64u

/** The oldest message the host (the PC running a study: a planner, an
 *  operator) sent this robot and it has not yet taken, copied into `buf`
 *  (room for `cap` bytes) with its length in `*len`: HAL_OK; HAL_ERR_EMPTY
 *  when none is waiting; HAL_ERR_RANGE when it is longer than `cap` (it
 *  stays); HAL_ERR_UNAVAILABLE on a platform with no host link.  What the
 *  bytes mean is the controller's (a route: firmware/waypoint/route_msg.h).
 *  On the e-puck they arrive over Bluetooth (platforms/epuck1/hal/host_link.h), in the
 *  simulator from the scenario's `host.messages` file. */
hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len);

/* ------------------------------------------------------------------ */
/* Telemetry                                                           */
/* ------------------------------------------------------------------ */

/** Offers `len` bytes to the telemetry sink (Bluetooth UART on the robot,
 *  the LCM publisher in the simulator).  Never blocks: returns how many
 *  bytes were accepted, which may be fewer than `len` (0 when busy). */
uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len);

#endif /* HAL_H */
