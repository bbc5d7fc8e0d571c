/*
 * epuck2_stubs.h - stand-ins for the e-puck2 library and the ChibiOS glue
 * that platforms/epuck2/hal declares (epuck2_lib*.h, epuck2_os.h), for the
 * link gates of `make firmware-check` and the host tests of the HAL.  They
 * do no I/O: each records what it is asked in `epuck2_stub` and returns
 * what a test put there.  Test code, not firmware: the mutable state is
 * allowed here and not counted as the firmware's RAM.
 */
#ifndef EPUCK2_STUBS_H
#define EPUCK2_STUBS_H

#include <stdint.h>

#define EPUCK2_STUB_QUEUE 8
#define EPUCK2_STUB_LOG 4096

typedef struct epuck2_stub_state {
    /* ChibiOS glue */
    uint32_t now_ms;             /* epuck2_os_time_ms */
    uint32_t idle_step_ms;       /* epuck2_os_idle advances now_ms by this */
    int os_inits, idles;
    uint16_t robot_id;
    uint8_t tx_log[EPUCK2_STUB_LOG];   /* every byte epuck2_os_serial_write took */
    int tx_len;
    int tx_room;                 /* bytes the output queue takes per write (-1: all) */
    const uint8_t *rx;           /* bytes epuck2_os_serial_read hands out */
    int rx_len, rx_pos;
    /* motors, LEDs, selector */
    int speed_left, speed_right, speed_calls;
    int32_t pos_left, pos_right;
    unsigned led[4];
    uint8_t rgb[4][3];
    unsigned body_led, front_led;
    int led_calls;
    int selector;
    int spi_suspended, spi_suspends, spi_resumes;
    /* proximity (and the ircom module's) */
    int prox[8], ambient[8];
    int prox_mode, prox_started, calibrated;
    /* camera */
    int cam_config_result, cam_prepare_result;
    unsigned cam_y1, cam_h, cam_w, cam_subx, cam_suby;
    int captures;
    uint8_t img_ready;
    uint8_t *img;                /* what dcmi_get_last_image_ptr lends (NULL: refuses) */
    int releases;
    /* microphones, speaker */
    int16_t mic_pcm[640];
    int mic_started, dac_started;
    uint16_t play_hz;
    int plays, stops;
    /* I2C: the turret's registers (address 0x20), writes logged */
    uint8_t randb_reg[32];
    int i2c_error;               /* non-zero: every transfer fails */
    uint8_t i2c_written_reg[EPUCK2_STUB_QUEUE * 4];
    uint8_t i2c_written_val[EPUCK2_STUB_QUEUE * 4];
    int i2c_writes;
    int randb_frames;            /* frames left: register 0 reads non-zero while > 0 */
    /* ircom */
    long ircom_value[EPUCK2_STUB_QUEUE];
    float ircom_distance[EPUCK2_STUB_QUEUE];
    float ircom_direction[EPUCK2_STUB_QUEUE];
    int ircom_sensor[EPUCK2_STUB_QUEUE];
    int ircom_error[EPUCK2_STUB_QUEUE];
    int ircom_count, ircom_next;   /* messages queued, the next to pop */
    int ircom_sending;
    long ircom_sent[EPUCK2_STUB_QUEUE];
    int ircom_sends, ircom_started;
    /* ground */
    int ground[5];
    int ground_started;
} epuck2_stub_state_t;

extern epuck2_stub_state_t epuck2_stub;

/** Clears every field; the output queue takes everything. */
void epuck2_stub_reset(void);

#endif
