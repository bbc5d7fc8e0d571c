/*
 * hal_epuck2.c - hal.h on the e-puck2 over GCtronic's e-puck2 library:
 * clock and control loop, IR and light readings (sampled by the IR
 * backend), camera blobs, microphones and speaker, wheels, LEDs, ground
 * sensors, telemetry.  IR communication is in the backend (ircom_randb.c
 * or ircom_libircom.c), the pose and the host's messages in host_link.c.
 * See hal_epuck2.h.
 *
 * No mutable static storage: the state is the caller's struct hal.
 */
#include "hal_epuck2.h"

#include <stddef.h>

#include "epuck2_lib.h"
#include "epuck2_os.h"
#include "tone_detect.h"

#define LEDS_UNKNOWN 0xFFFFu
#define LEDS_ALL 0x03FFu
/* Rows of the library's capture per frame row, and its bytes. */
#define CAPTURE_ROWS(window_h) ((window_h) / HAL_EPUCK2_CAM_SUBSAMPLE)
#define CAPTURE_BYTES(window_h) ((uint32_t)HAL_EPUCK2_CAM_CAPTURE_WIDTH * CAPTURE_ROWS(window_h) * 2u)

void hal_epuck2_default_config(hal_epuck2_config_t *cfg)
{
    cfg->period_ms = 100u;
    cfg->robot_id = HAL_EPUCK2_NO_ID;
    cfg->camera = 1u;
    cfg->cam_window_y = 80u;
    cfg->cam_window_h = 320u;
    cfg->cam_mirror = 0u;
    cfg->blob = blob_detect_default_params();
    cfg->randb_range = 150u;
    cfg->randb_range_mm_per_unit = 10u;
    cfg->sound = 0u;
    cfg->ircom_tx_per_period = 1u;
    cfg->ground = 0u;
}

/* The window: whole rows of 20 frame rows of 4 subsampled rows each,
 * within the sensor, and a capture the library's buffer holds. */
static uint8_t camera_config_valid(const hal_epuck2_config_t *cfg)
{
    uint16_t rows_per_frame_row = HAL_EPUCK2_CAM_SUBSAMPLE * HAL_EPUCK2_CAM_HEIGHT;
    return (uint8_t)(cfg->cam_window_h != 0u && cfg->cam_window_h % rows_per_frame_row == 0u
                     && (uint32_t)cfg->cam_window_y + cfg->cam_window_h <= EPUCK2_PO8030_HEIGHT
                     && CAPTURE_BYTES(cfg->cam_window_h) <= EPUCK2_DCMI_BUFFER_BYTES);
}

int8_t hal_epuck2_init(hal_t *hal, const hal_epuck2_config_t *cfg, uint8_t *frame, uint16_t frame_bytes)
{
    uint8_t *b = (uint8_t *)hal;
    size_t i;
    int8_t result = 0;

    for (i = 0; i < sizeof *hal; i++) {
        b[i] = 0u;
    }
    hal->cfg = *cfg;
    if (hal->cfg.period_ms == 0u) {
        hal->cfg.period_ms = 100u;
    }
    if (cfg->ircom_tx_per_period == 0u || cfg->ircom_tx_per_period > HAL_EPUCK2_TX_MAX) {
        result = -1;
        hal->cfg.ircom_tx_per_period = 1u;
    }
    hal->leds_applied = LEDS_UNKNOWN;
    hal->cam_state = HAL_EPUCK2_CAM_OFF;
    if (cfg->camera != 0u) {
        if (frame == NULL || frame_bytes < HAL_EPUCK2_FRAME_BYTES || camera_config_valid(cfg) == 0u) {
            result = -1;
        } else {
            hal->frame = frame;
        }
    }
    return result;
}

/* One frame at a time, in one-shot mode (the library's e-puck1 layer
 * configures it so too); the SPI link rests while the DCMI runs. */
static void camera_capture(void)
{
    spi_comm_suspend();
    dcmi_capture_start();
}

static void camera_start(hal_t *hal)
{
    const hal_epuck2_config_t *c = &hal->cfg;
    if (hal->frame == NULL) {
        return;
    }
    (void)dcmi_start();
    cam_start();
    if (cam_advanced_config(EPUCK2_CAM_FORMAT_COLOR, 0u, c->cam_window_y, EPUCK2_PO8030_WIDTH, c->cam_window_h,
                            EPUCK2_CAM_SUBSAMPLING_X4, EPUCK2_CAM_SUBSAMPLING_X4) != 0) {
        hal->cam_state = HAL_EPUCK2_CAM_FAILED;
        return;
    }
    (void)dcmi_disable_double_buffering();
    dcmi_set_capture_mode(EPUCK2_DCMI_CAPTURE_ONE_SHOT);
    if (dcmi_prepare() != 0) {
        hal->cam_state = HAL_EPUCK2_CAM_FAILED;
        return;
    }
    hal->cam_state = HAL_EPUCK2_CAM_RUNNING;
    camera_capture();
}

void hal_epuck2_start(hal_t *hal)
{
    if (hal->cfg.robot_id == HAL_EPUCK2_NO_ID) {
        hal->cfg.robot_id = epuck2_os_robot_id();
    }
    motors_init();
    spi_comm_start();
    clear_leds();
    hal_epuck2_ir_start(hal);
    camera_start(hal);
    if (hal->cfg.sound != 0u) {
        dac_start();
        mic_start(NULL);
    }
    if (hal->cfg.ground != 0u) {
        ground_start();
    }
    hal->next_ms = epuck2_os_time_ms() + hal->cfg.period_ms;
}

uint8_t hal_epuck2_step_due(hal_t *hal)
{
    uint32_t late = epuck2_os_time_ms() - hal->next_ms;
    uint32_t missed;
    if (late >= UINT32_C(0x80000000)) {
        return 0u;   /* the next period has not begun */
    }
    missed = late / hal->cfg.period_ms;
    hal->overruns = (uint16_t)(hal->overruns + (uint16_t)missed);
    hal->next_ms += (missed + 1u) * hal->cfg.period_ms;
    return 1u;
}

void hal_epuck2_cam_average(const uint8_t *src, uint16_t src_rows, uint8_t *dst)
{
    uint16_t block_rows = (uint16_t)(src_rows / HAL_EPUCK2_CAM_HEIGHT);
    uint16_t n = (uint16_t)(block_rows * HAL_EPUCK2_CAM_SUBSAMPLE);
    uint16_t x, y, dx, dy;
    for (y = 0u; y < HAL_EPUCK2_CAM_HEIGHT; y++) {
        for (x = 0u; x < HAL_EPUCK2_CAM_WIDTH; x++) {
            uint32_t r = 0u, g = 0u, b = 0u;
            uint16_t p;
            for (dy = 0u; dy < block_rows; dy++) {
                const uint8_t *row = src + ((uint32_t)(y * block_rows + dy) * HAL_EPUCK2_CAM_CAPTURE_WIDTH
                                            + (uint32_t)x * HAL_EPUCK2_CAM_SUBSAMPLE) * 2u;
                for (dx = 0u; dx < HAL_EPUCK2_CAM_SUBSAMPLE; dx++) {
                    p = (uint16_t)(((uint16_t)row[2u * dx] << 8) | row[2u * dx + 1u]);
                    r += (uint32_t)(p >> 11);
                    g += (uint32_t)((p >> 5) & 0x3Fu);
                    b += (uint32_t)(p & 0x1Fu);
                }
            }
            p = (uint16_t)((((r + n / 2u) / n) << 11) | (((g + n / 2u) / n) << 5) | ((b + n / 2u) / n));
            dst[2u * (y * HAL_EPUCK2_CAM_WIDTH + x)] = (uint8_t)(p >> 8);
            dst[2u * (y * HAL_EPUCK2_CAM_WIDTH + x) + 1u] = (uint8_t)p;
        }
    }
}

/* A complete capture: averaged into the image's frame, then the next. */
static void camera_poll(hal_t *hal)
{
    const uint8_t *img;
    if (hal->cam_state != HAL_EPUCK2_CAM_RUNNING || image_is_ready() == 0u) {
        return;
    }
    img = dcmi_get_last_image_ptr();
    if (img != NULL) {
        hal_epuck2_cam_average(img, (uint16_t)CAPTURE_ROWS(hal->cfg.cam_window_h), hal->frame);
        dcmi_release_last_image_ptr();
        hal->cam_have_frame = 1u;
        hal->cam_frames = (uint16_t)(hal->cam_frames + 1u);
    } else {
        hal->cam_lost = (uint16_t)(hal->cam_lost + 1u);
    }
    spi_comm_resume();
    camera_capture();
}

void hal_epuck2_poll(hal_t *hal)
{
    camera_poll(hal);
    hal_epuck2_ir_poll(hal);
    hal_epuck2_host_drain(hal, HAL_EPUCK2_RX_POLL_BYTES);
}

void hal_epuck2_begin_step(hal_t *hal)
{
    hal_epuck2_host_drain(hal, hal_epuck2_host_step_bytes(hal->cfg.period_ms));
    hal_epuck2_ir_sample(hal);
    /* hal.h's counters are 16-bit and wrap: the low half of the library's. */
    hal->steps_left = (int16_t)(uint16_t)((uint32_t)left_motor_get_pos() & 0xFFFFu);
    hal->steps_right = (int16_t)(uint16_t)((uint32_t)right_motor_get_pos() & 0xFFFFu);
    hal->blobs_step_valid = 0u;
    hal->mic_valid = 0u;
    hal->ground_valid = 0u;
}

/* Ring LED k: the red LED k/2 (k even) or the RGB LED (k-1)/2 in red. */
static void ring_led_apply(uint8_t k, uint8_t on)
{
    if ((k & 1u) == 0u) {
        set_led((int)(k / 2u), on);
    } else {
        set_rgb_led((int)(k / 2u), on != 0u ? (uint8_t)EPUCK2_RGB_MAX_INTENSITY : 0u, 0u, 0u);
    }
}

static void leds_end_step(hal_t *hal)
{
    /* Before the first step the LEDs' state is unknown: set them all. */
    uint16_t changed = (hal->leds_applied == LEDS_UNKNOWN) ? LEDS_ALL
                                                           : (uint16_t)(hal->leds ^ hal->leds_applied);
    uint8_t i;
    if (changed == 0u) {
        return;
    }
    for (i = 0; i < HAL_LED_COUNT; i++) {
        if ((changed & (1u << i)) != 0u) {
            ring_led_apply(i, (uint8_t)((hal->leds >> i) & 1u));
        }
    }
    if ((changed & (1u << HAL_LED_WORD_BODY_BIT)) != 0u) {
        set_body_led((hal->leds >> HAL_LED_WORD_BODY_BIT) & 1u);
    }
    if ((changed & (1u << HAL_LED_WORD_FRONT_BIT)) != 0u) {
        set_front_led((hal->leds >> HAL_LED_WORD_FRONT_BIT) & 1u);
    }
    hal->leds_applied = hal->leds;
}

/* The band set in this step sounds from now on: the DAC is told only
 * when it changes (it plays until stopped). */
static void speaker_end_step(hal_t *hal)
{
    static const uint16_t band_hz[SOUND_BAND_COUNT] = { SOUND_BAND1_HZ, SOUND_BAND2_HZ, SOUND_BAND3_HZ };
    if (hal->spk_band != hal->spk_sounding) {
        if (hal->spk_band == 0u) {
            dac_stop();
        } else {
            dac_play(band_hz[hal->spk_band - 1u]);
            hal->spk_plays = (uint16_t)(hal->spk_plays + 1u);
        }
    }
    hal->spk_sounding = hal->spk_band;
}

void hal_epuck2_end_step(hal_t *hal)
{
    uint8_t i;
    if (hal->speed_left != hal->speeds_applied[0]) {
        left_motor_set_speed(hal->speed_left);
        hal->speeds_applied[0] = hal->speed_left;
    }
    if (hal->speed_right != hal->speeds_applied[1]) {
        right_motor_set_speed(hal->speed_right);
        hal->speeds_applied[1] = hal->speed_right;
    }
    leds_end_step(hal);
    if (hal->cfg.sound != 0u) {
        speaker_end_step(hal);
    }
    for (i = 0; i < hal->out_pending; i++) {
        hal_epuck2_ir_transmit(hal, hal->out_value[i]);
    }
    hal->sent = (uint16_t)(hal->sent + hal->out_pending);
    hal->out_pending = 0u;
    hal->time_ms += hal->cfg.period_ms;
    hal->step++;
}

uint32_t hal_epuck2_seed(hal_t *hal)
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

uint8_t hal_epuck2_selector(hal_t *hal)
{
    (void)hal;
    return (uint8_t)(get_selector() & 0x0F);
}

uint16_t hal_epuck2_overruns(const hal_t *hal)
{
    return hal->overruns;
}

uint8_t hal_epuck2_inbox_push(hal_t *hal, const hal_ircom_msg_t *msg)
{
    if (hal->in_count >= HAL_EPUCK2_INBOX) {
        hal->in_dropped = (uint16_t)(hal->in_dropped + 1u);
        return 0u;
    }
    hal->inbox[(hal->in_head + hal->in_count) % HAL_EPUCK2_INBOX] = *msg;
    hal->in_count++;
    return 1u;
}

int16_t hal_epuck2_wrap_mrad(int32_t m)
{
    m %= UNITS_TWO_PI_MRAD;
    if (m > UNITS_PI_MRAD) {
        m -= UNITS_TWO_PI_MRAD;
    } else if (m <= -UNITS_PI_MRAD) {
        m += UNITS_TWO_PI_MRAD;
    }
    return (int16_t)m;
}

uint16_t hal_epuck2_clamp_raw(int v)
{
    if (v < 0) {
        return 0u;
    }
    return v > (int)HAL_RAW_MAX ? (uint16_t)HAL_RAW_MAX : (uint16_t)v;
}

uint8_t hal_epuck2_nearest_sensor(int16_t bearing_mrad)
{
    uint8_t best = 0u;
    uint16_t best_d = 0xFFFFu;
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        int16_t d = hal_epuck2_wrap_mrad((int32_t)bearing_mrad - units_ir_bearing_mrad(i));
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
        if (hal->cam_state == HAL_EPUCK2_CAM_RUNNING && hal->cam_have_frame != 0u) {
            blob_detect_work_t work;
            hal->n_blobs = blob_detect(&hal->cfg.blob, hal->frame, HAL_EPUCK2_CAM_WIDTH, HAL_EPUCK2_CAM_HEIGHT,
                                       &work, hal->blobs, (uint8_t)HAL_MAX_BLOBS);
            if (hal->cfg.cam_mirror != 0u) {
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
    if (hal->cam_state != HAL_EPUCK2_CAM_RUNNING) {
        *width_px = 0u;
        *height_px = 0u;
        return HAL_ERR_UNAVAILABLE;
    }
    *width_px = HAL_EPUCK2_CAM_WIDTH;
    *height_px = HAL_EPUCK2_CAM_HEIGHT;
    return HAL_OK;
}

hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    if (hal->cam_state != HAL_EPUCK2_CAM_RUNNING || hal->cam_have_frame == 0u) {
        (void)blob_colour_stats(&hal->cfg.blob, NULL, 0u, 0u, 0u, out);   /* zeroes *out */
        return HAL_ERR_UNAVAILABLE;
    }
    if (blob_colour_stats(&hal->cfg.blob, hal->frame, HAL_EPUCK2_CAM_WIDTH, HAL_EPUCK2_CAM_HEIGHT, colour,
                          out) != 0) {
        return HAL_ERR_RANGE;
    }
    return HAL_OK;
}

/* The newest TONE_DETECT_N samples of hal.h's microphone `mic` (the
 * library's MIC_RIGHT, MIC_LEFT, MIC_BACK: indices 0..2 of each group of
 * four), oldest first. */
static void mic_block(uint8_t mic, int16_t *out)
{
    const int16_t *pcm = mic_get_buffer_ptr();
    uint16_t first = (uint16_t)(EPUCK2_MIC_BUFFER_LEN / EPUCK2_MIC_COUNT - TONE_DETECT_N);
    uint16_t i;
    for (i = 0u; i < TONE_DETECT_N; i++) {
        out[i] = pcm[(uint32_t)(first + i) * EPUCK2_MIC_COUNT + mic];
    }
}

/* Lazy: a microphone's block is copied and analysed at its first read in
 * a step. */
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
        return HAL_ERR_BUSY;   /* our own tone drowns the microphones */
    }
    bit = (uint8_t)(1u << mic);
    if ((hal->mic_valid & bit) == 0u) {
        int16_t block[TONE_DETECT_N];
        mic_block(mic, block);
        tone_detect_block(block, tone_band_coeffs_16k, (uint8_t)SOUND_BAND_COUNT, hal->mic_level[mic]);
        hal->mic_valid = (uint8_t)(hal->mic_valid | bit);
    }
    *level = hal->mic_level[mic][band - 1u];
    return HAL_OK;
}

/* The library's ground thread reads the module; its sensors 0..2 are
 * hal.h's GS0..GS2 (3 and 4, the cliff sensors, are not in hal.h). */
hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected)
{
    uint8_t k;
    *reflected = 0;
    if (index >= HAL_GROUND_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (hal->cfg.ground == 0u) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (hal->ground_valid == 0u) {
        for (k = 0; k < HAL_GROUND_COUNT; k++) {
            hal->ground[k] = hal_epuck2_clamp_raw(get_ground_prox(k));
        }
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
    hal->in_head = (uint8_t)((hal->in_head + 1u) % HAL_EPUCK2_INBOX);
    hal->in_count--;
    return HAL_OK;
}

/* hal.h's limit, which the motors reach (EPUCK2_MOTOR_SPEED_LIMIT,
 * platform_facts.h): the build fails if a change of either breaks that. */
typedef char hal_epuck2_speed_within_motors[(HAL_WHEEL_SPEED_MAX <= EPUCK2_MOTOR_SPEED_LIMIT) ? 1 : -1];

static int16_t clamp_speed(int16_t v)
{
    if (v > HAL_WHEEL_SPEED_MAX) {
        return HAL_WHEEL_SPEED_MAX;
    }
    return v < -HAL_WHEEL_SPEED_MAX ? (int16_t)-HAL_WHEEL_SPEED_MAX : v;
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
    (void)hal;
    if (len == 0u || bytes == NULL) {
        return 0u;
    }
    return epuck2_os_serial_write(bytes, len);
}
