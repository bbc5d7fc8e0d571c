/*
 * hal_epuck.c - hal.h on the e-puck1 over GCtronic's e-puck library: clock
 * and control loop, IR and light readings (sampled by the IR backend),
 * camera blobs, wheels, LEDs, telemetry.  IR communication is in the
 * backend (ircom_randb.c or ircom_libircom.c), the pose and the host's
 * messages in host_link.c.  See hal_epuck.h.
 *
 * No mutable static storage: the state is the caller's struct hal.
 */
#include "hal_epuck.h"
#include "units.h"

#include <stddef.h>

#include "epuck_lib.h"
#include "epuck_lib_i2c.h"
#include "epuck_lib_sound.h"
#include "tone_detect.h"

/* Tenths of a millisecond per millisecond: the agenda's unit. */
#define AGENDA_TICKS_PER_MS 10u
#define LEDS_UNKNOWN 0xFFFFu
#define LEDS_ALL 0x03FFu
/* Camera orientations reported by e_poxxxx_get_orientation. */
#define CAM_VERTICAL 0
#define CAM_HORIZONTAL_INVERTED 2

void hal_epuck_default_config(hal_epuck_config_t *cfg)
{
    cfg->period_ms = 100u;
    cfg->robot_id = HAL_EPUCK_NO_ID;
    cfg->camera = 1u;
    cfg->cam_width = HAL_EPUCK_CAM_WIDTH;
    cfg->cam_height = HAL_EPUCK_CAM_HEIGHT;
    cfg->cam_window_y = 80u;
    cfg->cam_window_h = 320u;
    cfg->cam_mirror = 0u;
    cfg->blob = blob_detect_default_params();
    cfg->randb_range = 0u;
    cfg->randb_range_mm_per_unit = 10u;
    cfg->sound = 0u;
    cfg->ircom_tx_per_period = 1u;
    cfg->ground = 0u;
}

/* The window is the sensor's full width (the whole field of view) and
 * cam_window_h rows from cam_window_y; both must divide into the frame. */
static uint8_t camera_config_valid(const hal_epuck_config_t *cfg)
{
    if (cfg->cam_width == 0u || cfg->cam_height == 0u
        || cfg->cam_width > BLOB_MAX_WIDTH || cfg->cam_height > BLOB_MAX_HEIGHT) {
        return 0u;
    }
    if (EPL_ARRAY_WIDTH % cfg->cam_width != 0u || cfg->cam_window_h % cfg->cam_height != 0u) {
        return 0u;
    }
    if ((uint32_t)cfg->cam_window_y + cfg->cam_window_h > EPL_ARRAY_HEIGHT) {
        return 0u;
    }
    return 1u;
}

int8_t hal_epuck_init(hal_t *hal, const hal_epuck_config_t *cfg, uint8_t *frames, uint16_t frames_bytes)
{
    uint8_t *b = (uint8_t *)hal;
    size_t i;
    uint32_t frame_bytes;
    int8_t result = 0;

    for (i = 0; i < sizeof *hal; i++) {
        b[i] = 0u;
    }
    hal->cfg = *cfg;
    if (hal->cfg.period_ms == 0u) {
        hal->cfg.period_ms = 100u;
    }
    if (cfg->ircom_tx_per_period == 0u || cfg->ircom_tx_per_period > HAL_EPUCK_TX_MAX) {
        result = -1;
        hal->cfg.ircom_tx_per_period = 1u;
    }
    hal->cam_complete = 0xFFu;
    hal->leds_applied = LEDS_UNKNOWN;
    hal->cam_state = HAL_EPUCK_CAM_OFF;
    if (cfg->camera != 0u && frames != NULL) {
        frame_bytes = (uint32_t)cfg->cam_width * cfg->cam_height * 2u;
        if (camera_config_valid(cfg) == 0u || (uint32_t)frames_bytes < 2u * frame_bytes) {
            result = -1;
        } else {
            hal->frames = frames;
            hal->frame_bytes = (uint16_t)frame_bytes;
        }
    } else if (cfg->camera != 0u) {
        result = -1;
    }
    return result;
}

static void camera_start(hal_t *hal)
{
    const hal_epuck_config_t *c = &hal->cfg;
    int orientation;

    if (hal->frames == NULL) {
        return;
    }
    (void)e_poxxxx_init_cam();
    orientation = e_poxxxx_get_orientation();
    if (orientation == CAM_VERTICAL) {
        /* The window would be a vertical strip: not supported. */
        hal->cam_state = HAL_EPUCK_CAM_FAILED;
        return;
    }
    if (e_poxxxx_config_cam(0u, c->cam_window_y, EPL_ARRAY_WIDTH, c->cam_window_h,
                            EPL_ARRAY_WIDTH / c->cam_width, c->cam_window_h / c->cam_height,
                            EPL_RGB_565_MODE) != 0) {
        hal->cam_state = HAL_EPUCK_CAM_FAILED;
        return;
    }
    e_poxxxx_write_cam_registers();
    hal->cam_negate = (uint8_t)((c->cam_mirror != 0u) ^ (orientation == CAM_HORIZONTAL_INVERTED));
    hal->cam_filling = 0u;
    hal->cam_complete = 0xFFu;
    hal->cam_state = HAL_EPUCK_CAM_RUNNING;
    e_poxxxx_launch_capture((char *)hal->frames);
}

void hal_epuck_start(hal_t *hal, void (*tick)(void))
{
    if (hal->cfg.robot_id == HAL_EPUCK_NO_ID) {
        hal->cfg.robot_id = hal_epuck_flash_robot_id();
        if (hal->cfg.robot_id == HAL_EPUCK_NO_ID) {
            hal->cfg.robot_id = 0u;   /* flashed without --robot-id */
        }
    }
    e_init_port();
    e_init_uart1();
    e_init_motors();
    hal_epuck_ir_start(hal);
    camera_start(hal);
    if (hal->cfg.sound != 0u) {
        e_init_sound();
    }
    if (hal->cfg.ground != 0u) {
        e_i2cp_init();
    }
    hal->ticks_seen = hal->ticks;
    (void)e_activate_agenda(tick, (int)(hal->cfg.period_ms * AGENDA_TICKS_PER_MS));
    e_start_agendas_processing();
}

void hal_epuck_tick(hal_t *hal)
{
    hal->ticks = (uint16_t)(hal->ticks + 1u);
}

uint8_t hal_epuck_step_due(hal_t *hal)
{
    uint16_t now = hal->ticks;
    uint16_t pending = (uint16_t)(now - hal->ticks_seen);
    if (pending == 0u) {
        return 0u;
    }
    if (pending > 1u) {
        hal->overruns = (uint16_t)(hal->overruns + (uint16_t)(pending - 1u));
    }
    hal->ticks_seen = now;
    return 1u;
}

void hal_epuck_poll(hal_t *hal)
{
    if (hal->cam_state == HAL_EPUCK_CAM_RUNNING && e_poxxxx_is_img_ready() != 0) {
        hal->cam_complete = hal->cam_filling;
        hal->cam_filling = (uint8_t)(hal->cam_filling ^ 1u);
        hal->cam_frames = (uint16_t)(hal->cam_frames + 1u);
        e_poxxxx_launch_capture((char *)(hal->frames + (size_t)hal->cam_filling * hal->frame_bytes));
    }
    hal_epuck_ir_poll(hal);
    hal_epuck_host_drain(hal, HAL_EPUCK_RX_POLL_BYTES);
}

void hal_epuck_begin_step(hal_t *hal)
{
    hal_epuck_host_drain(hal, hal_epuck_host_step_bytes(hal->cfg.period_ms));
    hal_epuck_ir_sample(hal);
    hal->steps_left = (int16_t)e_get_steps_left();
    hal->steps_right = (int16_t)e_get_steps_right();
    hal->blobs_step_valid = 0u;
    hal->mic_valid = 0u;
    hal->ground_valid = 0u;
}

uint16_t hal_epuck_tone_samples(uint16_t period_ms)
{
    uint32_t n = ((uint32_t)period_ms * SOUND_SPK_RATE_HZ + 999u) / 1000u;
    n = (n + 3u) & ~(uint32_t)3u;
    return n > TONE_SPK_LEN ? (uint16_t)(TONE_SPK_LEN & ~3u) : (uint16_t)n;
}

/* The tone set in this step plays during the next period: started here,
 * for one period of samples. */
static void speaker_end_step(hal_t *hal)
{
    hal->spk_sounding = hal->spk_band;
    if (hal->spk_band != 0u) {
        e_play_sound((int)((hal->spk_band - 1u) * TONE_SPK_STRIDE),
                     (int)hal_epuck_tone_samples(hal->cfg.period_ms));
        hal->spk_plays = (uint16_t)(hal->spk_plays + 1u);
    }
}

void hal_epuck_end_step(hal_t *hal)
{
    uint16_t changed;
    uint8_t i;

    if (hal->speed_left != hal->speeds_applied[0]) {
        e_set_speed_left(hal->speed_left);
        hal->speeds_applied[0] = hal->speed_left;
    }
    if (hal->speed_right != hal->speeds_applied[1]) {
        e_set_speed_right(hal->speed_right);
        hal->speeds_applied[1] = hal->speed_right;
    }
    /* Before the first step the LEDs' state is unknown: set them all. */
    changed = (hal->leds_applied == LEDS_UNKNOWN) ? LEDS_ALL
                                                  : (uint16_t)(hal->leds ^ hal->leds_applied);
    if (changed != 0u) {
        for (i = 0; i < HAL_LED_COUNT; i++) {
            if ((changed & (1u << i)) != 0u) {
                e_set_led(i, (hal->leds >> i) & 1u);
            }
        }
        if ((changed & (1u << HAL_LED_WORD_BODY_BIT)) != 0u) {
            e_set_body_led((hal->leds >> HAL_LED_WORD_BODY_BIT) & 1u);
        }
        if ((changed & (1u << HAL_LED_WORD_FRONT_BIT)) != 0u) {
            e_set_front_led((hal->leds >> HAL_LED_WORD_FRONT_BIT) & 1u);
        }
        hal->leds_applied = hal->leds;
    }
    if (hal->cfg.sound != 0u) {
        speaker_end_step(hal);
    }
    for (i = 0; i < hal->out_pending; i++) {
        hal_epuck_ir_transmit(hal, hal->out_value[i]);
    }
    hal->sent = (uint16_t)(hal->sent + hal->out_pending);
    hal->out_pending = 0u;
    hal->time_ms += hal->cfg.period_ms;
    hal->step++;
}

uint32_t hal_epuck_seed(hal_t *hal)
{
    /* The low bits of the ambient readings are noise; mixed by an
     * xorshift-multiply so that every bit of the seed depends on them. */
    uint32_t s = UINT32_C(0x9E3779B9) * (uint32_t)(hal_robot_id(hal) + 1u);
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        s ^= (uint32_t)hal->ambient[i] << ((i * 4u) % 29u);
        s ^= s >> 15;
        s *= UINT32_C(0x2C1B3C6D);
        s ^= s >> 12;
    }
    return s != 0u ? s : 1u;
}

uint8_t hal_epuck_selector(hal_t *hal)
{
    (void)hal;
    return (uint8_t)(getselector() & 0x0F);
}

uint16_t hal_epuck_overruns(const hal_t *hal)
{
    return hal->overruns;
}

uint8_t hal_epuck_inbox_push(hal_t *hal, const hal_ircom_msg_t *msg)
{
    if (hal->in_count >= HAL_EPUCK_INBOX) {
        hal->in_dropped = (uint16_t)(hal->in_dropped + 1u);
        return 0u;
    }
    hal->inbox[(hal->in_head + hal->in_count) % HAL_EPUCK_INBOX] = *msg;
    hal->in_count++;
    return 1u;
}

static int16_t wrap_mrad(int32_t m)
{
    while (m > UNITS_PI_MRAD) {
        m -= UNITS_TWO_PI_MRAD;
    }
    while (m <= -UNITS_PI_MRAD) {
        m += UNITS_TWO_PI_MRAD;
    }
    return (int16_t)m;
}

int16_t hal_epuck_rad_to_mrad(float rad)
{
    float m = rad * 1000.0f;
    if (!(m < 1.0e6f && m > -1.0e6f)) {
        return 0;   /* NaN, or no bearing a driver gives */
    }
    while (m > 3141.59f) {
        m -= 2000.0f * (float)UNITS_PI;
    }
    while (m <= -3141.59f) {
        m += 2000.0f * (float)UNITS_PI;
    }
    return wrap_mrad((int32_t)(m >= 0.0f ? m + 0.5f : m - 0.5f));
}

uint16_t hal_epuck_clamp_raw(int v)
{
    if (v < 0) {
        return 0u;
    }
    if (v > (int)HAL_RAW_MAX) {
        return (uint16_t)HAL_RAW_MAX;
    }
    return (uint16_t)v;
}

uint8_t hal_epuck_nearest_sensor(int16_t bearing_mrad)
{
    uint8_t best = 0u;
    uint16_t best_d = 0xFFFFu;
    uint8_t i;
    int16_t b = wrap_mrad(bearing_mrad);
    for (i = 0; i < HAL_IR_COUNT; i++) {
        int32_t d = (int32_t)wrap_mrad((int32_t)b - units_ir_bearing_mrad(i));
        uint16_t ad = (uint16_t)(d < 0 ? -d : d);
        if (ad < best_d) {
            best_d = ad;
            best = i;
        }
    }
    return best;
}

/* ------------------------------------------------------------ hal.h */

uint16_t hal_robot_id(hal_t *hal)
{
    return hal->cfg.robot_id;
}

uint32_t hal_time_ms(hal_t *hal)
{
    return hal->time_ms;
}

uint16_t hal_control_period_ms(hal_t *hal)
{
    return hal->cfg.period_ms;
}

uint16_t hal_ir_proximity(hal_t *hal, uint8_t index)
{
    return index < HAL_IR_COUNT ? hal->prox[index] : 0u;
}

uint16_t hal_ir_ambient(hal_t *hal, uint8_t index)
{
    return index < HAL_IR_COUNT ? hal->ambient[index] : (uint16_t)HAL_RAW_MAX;
}

uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max)
{
    uint8_t i;
    uint8_t n;
    if (hal->blobs_step_valid == 0u) {
        hal->n_blobs = 0u;
        if (hal->cam_state == HAL_EPUCK_CAM_RUNNING && hal->cam_complete <= 1u) {
            blob_detect_work_t work;
            hal->n_blobs = blob_detect(&hal->cfg.blob,
                                       hal->frames + (size_t)hal->cam_complete * hal->frame_bytes,
                                       hal->cfg.cam_width, hal->cfg.cam_height,
                                       &work, hal->blobs, (uint8_t)HAL_MAX_BLOBS);
            if (hal->cam_negate != 0u) {
                for (i = 0; i < hal->n_blobs; i++) {
                    hal->blobs[i].bearing_mrad = (int16_t)-hal->blobs[i].bearing_mrad;
                }
            }
        }
        hal->blobs_step_valid = 1u;
    }
    n = hal->n_blobs < max ? hal->n_blobs : max;
    for (i = 0; i < n; i++) {
        out[i] = hal->blobs[i];
    }
    return n;
}

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px)
{
    if (hal->cam_state != HAL_EPUCK_CAM_RUNNING) {
        *width_px = 0u;
        *height_px = 0u;
        return HAL_ERR_UNAVAILABLE;
    }
    *width_px = hal->cfg.cam_width;
    *height_px = hal->cfg.cam_height;
    return HAL_OK;
}

hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    const uint8_t *frame = hal->frames + (size_t)hal->cam_complete * hal->frame_bytes;
    if (hal->cam_state != HAL_EPUCK_CAM_RUNNING || hal->cam_complete > 1u) {
        (void)blob_colour_stats(&hal->cfg.blob, NULL, 0u, 0u, 0u, out);   /* zeroes *out */
        return HAL_ERR_UNAVAILABLE;
    }
    if (blob_colour_stats(&hal->cfg.blob, frame, hal->cfg.cam_width, hal->cfg.cam_height, colour, out) != 0) {
        return HAL_ERR_RANGE;
    }
    return HAL_OK;
}

/* Lazy: a microphone's block is copied and analysed at its first read in
 * a step (hal_epuck.h: the window). */
hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level)
{
    uint8_t bit;
    *level = 0;
    if (mic >= HAL_MIC_COUNT || band == 0u || band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (hal->cfg.sound == 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (hal->spk_sounding != 0u) {
        return HAL_ERR_BUSY;   /* our own tone drowned the microphones */
    }
    bit = (uint8_t)(1u << mic);
    if ((hal->mic_valid & bit) == 0u) {
        int16_t block[TONE_DETECT_N];
        hal->mic_valid = (uint8_t)(hal->mic_valid | bit);
        if (hal_epuck_mic_block(hal, mic, block) != 0u) {
            tone_detect_block(block, tone_band_coeffs, (uint8_t)SOUND_BAND_COUNT, hal->mic_level[mic]);
            hal->mic_ok = (uint8_t)(hal->mic_ok | bit);
        } else {
            hal->mic_ok = (uint8_t)(hal->mic_ok & ~bit);
        }
    }
    if ((hal->mic_ok & bit) == 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    *level = hal->mic_level[mic][band - 1u];
    return HAL_OK;
}

/* The ground-sensor module (cfg.ground): registers 0..5 of its I2C
 * device hold the three sensors' values, high byte first, read once a
 * step at the first call: seven single-byte reads, the first a dummy read
 * of register 0 as GCtronic's advanced sercom makes [?]. */
hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected)
{
    *reflected = 0;
    if (index >= HAL_GROUND_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (hal->cfg.ground == 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (hal->ground_valid == 0u) {
        uint8_t k;
        e_i2cp_enable();
        (void)e_i2cp_read((char)EPL_GROUND_I2C_ADDRESS, 0);
        for (k = 0; k < HAL_GROUND_COUNT; k++) {
            uint8_t hi = (uint8_t)e_i2cp_read((char)EPL_GROUND_I2C_ADDRESS, (char)(2u * k));
            uint8_t lo = (uint8_t)e_i2cp_read((char)EPL_GROUND_I2C_ADDRESS, (char)(2u * k + 1u));
            uint16_t v = (uint16_t)(((uint16_t)hi << 8) | lo);
            hal->ground[k] = v > HAL_RAW_MAX ? (uint16_t)HAL_RAW_MAX : v;
        }
        e_i2cp_disable();
        hal->ground_valid = 1u;
    }
    *reflected = hal->ground[index];
    return HAL_OK;
}

hal_status_t hal_speaker_set(hal_t *hal, uint8_t band)
{
    if (band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (hal->cfg.sound == 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    hal->spk_band = band;
    return HAL_OK;
}

hal_status_t hal_ircom_send(hal_t *hal, uint16_t value)
{
    uint8_t bits = hal_ircom_payload_bits(hal);
    if (hal->out_pending >= hal->cfg.ircom_tx_per_period) {
        return HAL_ERR_BUSY;
    }
    hal->out_value[hal->out_pending] = bits >= 16u ? value : (uint16_t)(value & ((1u << bits) - 1u));
    hal->out_pending++;
    return HAL_OK;
}

hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out)
{
    if (hal->in_count == 0u) {
        return HAL_ERR_EMPTY;
    }
    *out = hal->inbox[hal->in_head];
    hal->in_head = (uint8_t)((hal->in_head + 1u) % HAL_EPUCK_INBOX);
    hal->in_count--;
    return HAL_OK;
}

static int16_t clamp_speed(int16_t v)
{
    if (v > HAL_WHEEL_SPEED_MAX) {
        return HAL_WHEEL_SPEED_MAX;
    }
    if (v < -HAL_WHEEL_SPEED_MAX) {
        return (int16_t)-HAL_WHEEL_SPEED_MAX;
    }
    return v;
}

void hal_set_wheel_speeds(hal_t *hal, int16_t left_steps_s, int16_t right_steps_s)
{
    hal->speed_left = clamp_speed(left_steps_s);
    hal->speed_right = clamp_speed(right_steps_s);
}

void hal_wheel_steps(hal_t *hal, int16_t *left, int16_t *right)
{
    *left = hal->steps_left;
    *right = hal->steps_right;
}

static void set_led_bit(hal_t *hal, uint8_t bit, uint8_t on)
{
    if (on != 0u) {
        hal->leds = (uint16_t)(hal->leds | (1u << bit));
    } else {
        hal->leds = (uint16_t)(hal->leds & ~(1u << bit));
    }
}

void hal_set_led(hal_t *hal, uint8_t index, uint8_t on)
{
    if (index < HAL_LED_COUNT) {
        set_led_bit(hal, index, on);
    }
}

void hal_set_body_led(hal_t *hal, uint8_t on)
{
    set_led_bit(hal, (uint8_t)HAL_LED_WORD_BODY_BIT, on);
}

void hal_set_front_led(hal_t *hal, uint8_t on)
{
    set_led_bit(hal, (uint8_t)HAL_LED_WORD_FRONT_BIT, on);
}

uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len)
{
    uint16_t n;
    uint16_t i;
    if (len == 0u || bytes == NULL || e_uart1_sending() != 0) {
        return 0u;
    }
    n = len < HAL_EPUCK_TX_BYTES ? len : (uint16_t)HAL_EPUCK_TX_BYTES;
    for (i = 0; i < n; i++) {
        hal->tx[i] = bytes[i];
    }
    e_send_uart1_char((const char *)hal->tx, (int)n);
    return n;
}
