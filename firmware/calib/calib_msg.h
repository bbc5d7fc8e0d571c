/*
 * calib_msg.h - the host's commands to the calibration image (calib.h):
 * one host message (hal_host_receive) each, big-endian fields.
 *
 *   'P'                      stream proximity: each window the 8 sensors'
 *                            mean and variance, counts and counts^2
 *   'A'                      stream ambient light, as 'P'
 *   'M' band:u8              stream the three microphones' levels of
 *                            `band` (1..HAL_SOUND_BANDS-1): mean and
 *                            variance per mic, level counts
 *   'C' colour:u8            stream the widest blob of `colour`
 *                            (hal_colour_t): bearing and width (mrad) and
 *                            the blobs of that colour in view
 *   'F' colour:u8            stream the latest frame's pixel statistics
 *                            (hal_camera_colour_stats): every pixel's for
 *                            colour 0, else the pixels the detector gives
 *                            `colour`: their number and R, G, B mean and sd
 *   'D' l:i16 r:i16 n:u16    drive: wheel speeds l, r (steps/s) for
 *                            exactly n control periods, then stop; the
 *                            values are the steps counted since
 *   'S'                      stop: wheels off, stream nothing
 *   'T' band:u8              play `band` on the speaker (0: silence)
 *
 * The host tool (tools/swarmtools/calibrate/protocol.py) encodes the same
 * bytes.  A command of a wrong length or an unknown letter is counted and
 * ignored.
 */
#ifndef FW_CALIB_MSG_H
#define FW_CALIB_MSG_H

#include <stdint.h>

#define CALIB_MSG_PROX 'P'
#define CALIB_MSG_AMBIENT 'A'
#define CALIB_MSG_MIC 'M'
#define CALIB_MSG_CAMERA 'C'
#define CALIB_MSG_FRAME 'F'
#define CALIB_MSG_DRIVE 'D'
#define CALIB_MSG_STOP 'S'
#define CALIB_MSG_TONE 'T'

/** Bytes of a drive command. */
#define CALIB_MSG_DRIVE_LEN 7u

typedef struct calib_cmd {
    uint8_t kind;          /**< one of CALIB_MSG_* */
    int16_t left, right;   /**< drive: steps/s */
    uint16_t periods;      /**< drive: control periods */
    uint8_t arg;           /**< mic, tone: the band; camera, frame: the colour */
} calib_cmd_t;

/** Decodes one message: 0 and *out filled, or -1 for a malformed one. */
int8_t calib_msg_decode(const uint8_t *buf, uint8_t len, calib_cmd_t *out);

#endif
