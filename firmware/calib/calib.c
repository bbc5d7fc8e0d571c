/* The calibration image's controller (calib.h). */
#include "calib.h"

#include "telemetry/robot_telemetry.h"

void calib_default_params(calib_params_t *params)
{
    params->window_steps = (uint8_t)ROBOT_TELEMETRY_STEPS;
    params->settle_windows = 1u;
}

void calib_init(calib_t *self, const calib_params_t *params, uint32_t seed)
{
    self->params = *params;
    if (self->params.window_steps == 0u) {
        self->params.window_steps = 1u;
    }
    self->seed = seed;
    calib_reset(self);
}

static void clear_window(calib_t *self)
{
    uint8_t k;
    self->samples = 0u;
    for (k = 0u; k < CALIB_CHANNELS; k++) {
        self->first[k] = 0.0f;
        self->sum[k] = 0.0f;
        self->sum2[k] = 0.0f;
    }
}

static void clear_values(calib_t *self)
{
    uint8_t k;
    for (k = 0u; k < CALIB_CHANNELS; k++) {
        self->mean[k] = 0.0f;
        self->var[k] = 0.0f;
    }
}

void calib_reset(calib_t *self)
{
    self->mode = CALIB_IDLE;
    self->arg = 0u;
    self->dropped = 0u;
    self->latched = 0u;
    self->unavailable = 0u;
    self->bad_msgs = 0u;
    self->drive_left = 0u;
    self->driven = 0u;
    self->cmd_left = self->cmd_right = 0;
    self->last_left = self->last_right = 0;
    self->steps_left = self->steps_right = 0;
    clear_window(self);
    clear_values(self);
}

/* A command starts a new measurement: nothing of the last one remains. */
static void take_command(calib_t *self, hal_t *hal, const calib_cmd_t *cmd)
{
    clear_window(self);
    clear_values(self);
    self->dropped = 0u;
    self->latched = 0u;
    self->unavailable = 0u;
    self->arg = cmd->arg;
    hal_set_wheel_speeds(hal, 0, 0);
    switch (cmd->kind) {
    case CALIB_MSG_PROX: self->mode = CALIB_PROX; break;
    case CALIB_MSG_AMBIENT: self->mode = CALIB_AMBIENT; break;
    case CALIB_MSG_MIC: self->mode = CALIB_MIC; break;
    case CALIB_MSG_CAMERA: self->mode = CALIB_CAMERA; break;
    case CALIB_MSG_FRAME: self->mode = CALIB_FRAME; break;
    case CALIB_MSG_DRIVE:
        self->mode = CALIB_DRIVE;
        self->cmd_left = cmd->left;
        self->cmd_right = cmd->right;
        self->drive_left = cmd->periods;
        self->driven = 0u;
        self->steps_left = self->steps_right = 0;
        hal_wheel_steps(hal, &self->last_left, &self->last_right);
        break;
    case CALIB_MSG_TONE:
        /* The speaker plays for another robot's calibration; this one streams
         * nothing but the band, the host's sign that it plays. */
        self->mode = CALIB_TONE;
        if (hal_speaker_set(hal, cmd->arg) != HAL_OK) {
            self->unavailable = 1u;
        }
        self->mean[0] = (float)cmd->arg;
        break;
    default:
        self->mode = CALIB_IDLE;
        break;
    }
}

static void poll_host(calib_t *self, hal_t *hal)
{
    uint8_t buf[HAL_HOST_MSG_MAX];
    uint8_t len = 0u;
    calib_cmd_t cmd;
    if (hal_host_receive(hal, buf, (uint8_t)sizeof buf, &len) != HAL_OK) {
        return;
    }
    if (calib_msg_decode(buf, len, &cmd) != 0) {
        self->bad_msgs++;
        return;
    }
    take_command(self, hal, &cmd);
}

/* This period's readings of the mode's channels into x; how many. */
static uint8_t read_channels(calib_t *self, hal_t *hal, float x[CALIB_CHANNELS])
{
    uint8_t k;
    switch (self->mode) {
    case CALIB_PROX:
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            x[k] = (float)hal_ir_proximity(hal, k);
        }
        return (uint8_t)HAL_IR_COUNT;
    case CALIB_AMBIENT:
        for (k = 0u; k < HAL_IR_COUNT; k++) {
            x[k] = (float)hal_ir_ambient(hal, k);
        }
        return (uint8_t)HAL_IR_COUNT;
    case CALIB_MIC:
        for (k = 0u; k < HAL_MIC_COUNT; k++) {
            uint32_t level = 0u;
            hal_status_t s = hal_mic_level(hal, k, self->arg, &level);
            if (s == HAL_ERR_UNAVAILABLE || s == HAL_ERR_RANGE) {
                self->unavailable = 1u;
            }
            x[k] = (float)level;
        }
        return (uint8_t)HAL_MIC_COUNT;
    case CALIB_CAMERA: {
        hal_blob_t widest;
        uint8_t n = hal_camera_widest(hal, self->arg, &widest);
        x[0] = n > 0u ? (float)widest.bearing_mrad : 0.0f;
        x[1] = n > 0u ? (float)widest.width_mrad : 0.0f;
        x[2] = (float)n;
        return 3u;
    }
    case CALIB_FRAME: {
        hal_colour_stats_t st;
        if (hal_camera_colour_stats(hal, self->arg, &st) != HAL_OK) {
            self->unavailable = 1u;
        }
        x[0] = (float)st.pixels;
        for (k = 0u; k < 3u; k++) {
            x[1u + k] = (float)st.mean[k];
            x[4u + k] = (float)st.sd[k];
        }
        return 7u;
    }
    default:
        return 0u;
    }
}

static void sample(calib_t *self, hal_t *hal)
{
    float x[CALIB_CHANNELS];
    uint8_t n = read_channels(self, hal, x);
    uint8_t k;
    for (k = 0u; k < n; k++) {
        float d;
        if (self->samples == 0u) {
            self->first[k] = x[k];
        }
        d = x[k] - self->first[k];
        self->sum[k] += d;
        self->sum2[k] += d * d;
    }
    self->samples++;
    if (self->samples < self->params.window_steps) {
        return;
    }
    if (self->dropped < self->params.settle_windows) {
        self->dropped++;
    } else {
        float m = (float)self->samples;
        for (k = 0u; k < n; k++) {
            float mu = self->sum[k] / m;
            self->mean[k] = self->first[k] + mu;
            self->var[k] = self->sum2[k] / m - mu * mu;
            if (self->var[k] < 0.0f) {
                self->var[k] = 0.0f;
            }
        }
        self->latched = 1u;
    }
    clear_window(self);
}

static void drive(calib_t *self, hal_t *hal)
{
    int16_t l, r;
    hal_wheel_steps(hal, &l, &r);
    /* 16-bit counters wrap: their difference in 16 bits is the period's steps. */
    self->steps_left += (int16_t)(uint16_t)((uint16_t)l - (uint16_t)self->last_left);
    self->steps_right += (int16_t)(uint16_t)((uint16_t)r - (uint16_t)self->last_right);
    self->last_left = l;
    self->last_right = r;
    if (self->drive_left > 0u) {
        hal_set_wheel_speeds(hal, self->cmd_left, self->cmd_right);
        self->drive_left--;
        self->driven++;
    } else {
        /* Stopped: this period's counts include the last period driven. */
        hal_set_wheel_speeds(hal, 0, 0);
        self->latched = 1u;
    }
    self->mean[0] = (float)self->steps_left;
    self->mean[1] = (float)self->steps_right;
    self->mean[2] = (float)self->driven;
}

void calib_step(calib_t *self, hal_t *hal)
{
    poll_host(self, hal);
    if (self->mode == CALIB_DRIVE) {
        drive(self, hal);
    } else if (self->mode != CALIB_IDLE && self->mode != CALIB_TONE) {
        hal_set_wheel_speeds(hal, 0, 0);
        sample(self, hal);
    } else {
        hal_set_wheel_speeds(hal, 0, 0);
    }
}

const char *calib_state_name(const calib_t *self)
{
    if (self->mode == CALIB_DRIVE) {
        return self->latched ? "driven" : "drive";
    }
    if (self->mode == CALIB_IDLE) {
        return "idle";
    }
    if (self->mode == CALIB_TONE) {
        return self->unavailable ? "no_sound" : "tone";
    }
    if (self->unavailable) {
        return self->mode == CALIB_FRAME ? "no_frame" : "no_sound";
    }
    if (!self->latched) {
        return "settle";
    }
    switch (self->mode) {
    case CALIB_PROX: return "prox";
    case CALIB_AMBIENT: return "ambient";
    case CALIB_MIC: return "mic";
    case CALIB_FRAME: return "frame";
    default: return "camera";
    }
}
