/* Stubs of platforms/epuck1/hal/epuck_lib.h (see epuck_stubs.h) and of the XC16-only
 * hal_epuck_flash_robot_id. */
#include <string.h>

#include "epuck_lib.h"
#include "epuck_lib_i2c.h"
#include "epuck_lib_sound.h"
#include "epuck_stubs.h"
#include "hal_epuck.h"

epuck_stub_state_t epuck_stub;

void epuck_stub_reset(void)
{
    memset(&epuck_stub, 0, sizeof epuck_stub);
    epuck_stub.cam_version = 0x6030;
    epuck_stub.cam_orientation = 1;
    epuck_stub.flash_id = 0xFFFFu;
}

void e_init_port(void) {}

int e_activate_agenda(void (*func)(void), int cycle)
{
    epuck_stub.agenda = func;
    epuck_stub.agenda_cycle = cycle;
    return 0;
}

void e_start_agendas_processing(void) { epuck_stub.agendas_started = 1; }

void e_init_motors(void) {}

void e_set_speed_left(int motor_speed)
{
    epuck_stub.speed_left = motor_speed;
    epuck_stub.speed_calls++;
}

void e_set_speed_right(int motor_speed)
{
    epuck_stub.speed_right = motor_speed;
    epuck_stub.speed_calls++;
}

int e_get_steps_left(void) { return epuck_stub.steps_left; }
int e_get_steps_right(void) { return epuck_stub.steps_right; }

void e_set_led(unsigned int led_number, unsigned int value)
{
    if (led_number < 8u) {
        epuck_stub.led[led_number] = value;
    }
    epuck_stub.led_calls++;
}

void e_set_body_led(unsigned int value) { epuck_stub.body_led = value; epuck_stub.led_calls++; }
void e_set_front_led(unsigned int value) { epuck_stub.front_led = value; epuck_stub.led_calls++; }

int e_poxxxx_init_cam(void) { return epuck_stub.cam_version; }

int e_poxxxx_config_cam(unsigned int sensor_x1, unsigned int sensor_y1,
                        unsigned int sensor_width, unsigned int sensor_height,
                        unsigned int zoom_fact_width, unsigned int zoom_fact_height,
                        int color_mode)
{
    (void)sensor_x1;
    (void)sensor_width;
    (void)color_mode;
    epuck_stub.cam_y1 = sensor_y1;
    epuck_stub.cam_h = sensor_height;
    epuck_stub.cam_zoom_w = zoom_fact_width;
    epuck_stub.cam_zoom_h = zoom_fact_height;
    return epuck_stub.cam_config_result;
}

void e_poxxxx_write_cam_registers(void) {}

void e_poxxxx_launch_capture(char *buf)
{
    epuck_stub.capture_buf = buf;
    epuck_stub.captures++;
    epuck_stub.img_ready = 0;
}

int e_poxxxx_is_img_ready(void) { return epuck_stub.img_ready; }
int e_poxxxx_get_orientation(void) { return epuck_stub.cam_orientation; }

void e_init_uart1(void) {}

void e_send_uart1_char(const char *buff, int length)
{
    epuck_stub.uart_buf = buff;
    epuck_stub.uart_len = length;
    epuck_stub.uart_sends++;
    if (epuck_stub.uart_log != NULL) {
        int i;
        for (i = 0; i < length && epuck_stub.uart_log_len < epuck_stub.uart_log_size; i++) {
            epuck_stub.uart_log[epuck_stub.uart_log_len++] = (unsigned char)buff[i];
        }
    }
}

int e_uart1_sending(void) { return epuck_stub.uart_busy; }

int e_getchar_uart1(char *car)
{
    if (epuck_stub.rx == NULL || epuck_stub.rx_pos >= epuck_stub.rx_len) {
        return 0;
    }
    *car = (char)epuck_stub.rx[epuck_stub.rx_pos++];
    return 1;
}

void e_init_sound(void) { epuck_stub.sound_inits++; }

/* Records the call only: the stub does not read the table (the images
 * link tone_speaker_table as the library's e_sound_sample, and only the
 * library's assembly reads it; on the AVR of the link gates const data
 * would take RAM).  test_hal_epuck.c checks what these words are. */
void e_play_sound(int sound_offset, int sound_length)
{
    epuck_stub.plays++;
    epuck_stub.play_offset = sound_offset;
    epuck_stub.play_len = sound_length;
}

int getselector(void) { return epuck_stub.selector; }

uint16_t hal_epuck_flash_robot_id(void) { return (uint16_t)epuck_stub.flash_id; }

void e_i2cp_init(void) { epuck_stub.i2c_inits++; }
void e_i2cp_enable(void) { epuck_stub.i2c_enabled = 1; }
void e_i2cp_disable(void) { epuck_stub.i2c_enabled = 0; }

char e_i2cp_read(char device_add, char reg)
{
    unsigned r = (unsigned char)reg;
    epuck_stub.i2c_reads++;
    if ((unsigned char)device_add != EPL_GROUND_I2C_ADDRESS || !epuck_stub.i2c_enabled || r >= 6u) {
        return 0;
    }
    return (char)epuck_stub.ground_reg[r];
}
