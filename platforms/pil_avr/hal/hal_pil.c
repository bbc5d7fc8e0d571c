/* hal_pil.c - hal.h over the PIL protocol (hal_pil.h, pil_robot.h). */
#include "hal_pil.h"

void hal_pil_default_config(hal_pil_config_t *cfg)
{
    cfg->period_ms = 100u;
    cfg->ircom_bits = 16u;
    cfg->tx_per_period = 1u;
    cfg->flags = 0u;
}

void hal_pil_init(hal_t *hal, const hal_pil_config_t *cfg, uint8_t *mailbox, uint16_t cap)
{
    pil_robot_init(&hal->link, mailbox, cap, cfg->flags, cfg->ircom_bits, cfg->tx_per_period);
    hal->period_ms = cfg->period_ms;
}

int8_t hal_pil_hello(hal_t *hal, pil_hello_t *hello)
{
    hello->period_ms = hal->period_ms;
    return pil_robot_hello(&hal->link, hello);
}

uint32_t hal_pil_seed(hal_t *hal) { return hal->link.cfg.seed; }
uint8_t hal_pil_selector(hal_t *hal) { return hal->link.cfg.selector; }
void hal_pil_ready(hal_t *hal) { (void)pil_robot_ready(&hal->link); }
void hal_pil_end_step(hal_t *hal) { (void)pil_robot_end_step(&hal->link); }

uint16_t hal_robot_id(hal_t *hal) { return hal->link.cfg.robot_id; }
uint32_t hal_time_ms(hal_t *hal) { return hal->link.step.time_ms; }
uint16_t hal_control_period_ms(hal_t *hal) { return hal->period_ms; }

uint16_t hal_ir_proximity(hal_t *hal, uint8_t index) { return pil_robot_ir(&hal->link, index); }
uint16_t hal_ir_ambient(hal_t *hal, uint8_t index) { return pil_robot_ambient(&hal->link, index); }

/* hal_ir_bearing_mrad and hal_camera_widest: hal/hal_common.c. */

uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max) { return pil_robot_blobs(&hal->link, out, max); }

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px)
{
    return pil_robot_frame_size(&hal->link, width_px, height_px);
}

/* The link carries blobs, not frames: no frame statistics on the PIL robot. */
hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    uint8_t i;
    (void)hal;
    (void)colour;
    out->pixels = 0u;
    for (i = 0u; i < 3u; i++) {
        out->mean[i] = 0u;
        out->sd[i] = 0u;
    }
    return HAL_ERR_UNAVAILABLE;
}

hal_status_t hal_ground(hal_t *hal, uint8_t index, uint16_t *reflected)
{
    return pil_robot_ground(&hal->link, index, reflected);
}

hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level)
{
    return pil_robot_mic_level(&hal->link, mic, band, level);
}

hal_status_t hal_speaker_set(hal_t *hal, uint8_t band) { return pil_robot_speaker_set(&hal->link, band); }
uint8_t hal_ircom_payload_bits(hal_t *hal) { return pil_robot_ircom_bits(&hal->link); }
hal_status_t hal_ircom_send(hal_t *hal, uint16_t value) { return pil_robot_ircom_send(&hal->link, value); }
hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out) { return pil_robot_ircom_receive(&hal->link, out); }

void hal_set_wheel_speeds(hal_t *hal, int16_t left_steps_s, int16_t right_steps_s)
{
    pil_robot_wheels(&hal->link, left_steps_s, right_steps_s);
}

void hal_wheel_steps(hal_t *hal, int16_t *left, int16_t *right)
{
    *left = hal->link.step.steps_left;
    *right = hal->link.step.steps_right;
}

void hal_set_led(hal_t *hal, uint8_t index, uint8_t on)
{
    if (index < HAL_LED_COUNT) {
        pil_robot_led_bit(&hal->link, index, on);
    }
}

void hal_set_body_led(hal_t *hal, uint8_t on) { pil_robot_led_bit(&hal->link, HAL_LED_WORD_BODY_BIT, on); }
void hal_set_front_led(hal_t *hal, uint8_t on) { pil_robot_led_bit(&hal->link, HAL_LED_WORD_FRONT_BIT, on); }
hal_status_t hal_pose(hal_t *hal, hal_pose_t *out) { return pil_robot_pose(&hal->link, out); }

hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len)
{
    return pil_robot_host_receive(&hal->link, buf, cap, len);
}

uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *bytes, uint16_t len)
{
    return pil_robot_telemetry_write(&hal->link, bytes, len);
}
