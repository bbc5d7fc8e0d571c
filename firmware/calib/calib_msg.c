/* The calibration image's commands (calib_msg.h). */
#include "calib_msg.h"

static int16_t be16(const uint8_t *p) { return (int16_t)(uint16_t)(((uint16_t)p[0] << 8) | p[1]); }

int8_t calib_msg_decode(const uint8_t *buf, uint8_t len, calib_cmd_t *out)
{
    if (len < 1u) {
        return -1;
    }
    out->kind = buf[0];
    out->left = out->right = 0;
    out->periods = 0u;
    out->arg = 0u;
    switch (buf[0]) {
    case CALIB_MSG_PROX:
    case CALIB_MSG_AMBIENT:
    case CALIB_MSG_STOP:
        return len == 1u ? 0 : -1;
    case CALIB_MSG_MIC:
    case CALIB_MSG_CAMERA:
    case CALIB_MSG_FRAME:
    case CALIB_MSG_TONE:
        if (len != 2u) {
            return -1;
        }
        out->arg = buf[1];
        return 0;
    case CALIB_MSG_DRIVE:
        if (len != CALIB_MSG_DRIVE_LEN) {
            return -1;
        }
        out->left = be16(buf + 1);
        out->right = be16(buf + 3);
        out->periods = (uint16_t)be16(buf + 5);
        return 0;
    default:
        return -1;
    }
}
