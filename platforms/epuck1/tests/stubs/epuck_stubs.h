/*
 * epuck_stubs.h - stand-ins for the e-puck library functions platforms/epuck1/hal
 * declares (platforms/epuck1/hal/epuck_lib*.h), for the link gates of
 * `make firmware-check` (avr-gcc, arm-none-eabi-gcc) and the host tests of
 * platforms/epuck1/hal.  They do no I/O: each records what it is asked in
 * `epuck_stub` and returns what a test put there.  Test code, not
 * firmware: the mutable state is allowed here and is not counted as the
 * firmware's RAM by the footprint report.
 */
#ifndef EPUCK_STUBS_H
#define EPUCK_STUBS_H

#define STUB_QUEUE 8

typedef struct epuck_stub_state {
    /* motors, LEDs, selector */
    int speed_left, speed_right;
    int speed_calls;
    int steps_left, steps_right;
    unsigned led[8];
    unsigned body_led, front_led;
    int led_calls;
    int selector;
    /* agenda */
    void (*agenda)(void);
    int agenda_cycle;
    int agendas_started;
    /* camera */
    int cam_version, cam_orientation, cam_config_result;
    unsigned cam_zoom_w, cam_zoom_h, cam_y1, cam_h;
    char *capture_buf;
    int captures;
    int img_ready;
    /* UART1 */
    int uart_busy;
    const char *uart_buf;
    int uart_len;
    int uart_sends;
    unsigned char *uart_log;   /* when set, every byte sent is appended here */
    int uart_log_size;
    int uart_log_len;
    /* UART1 receive: e_getchar_uart1 hands out rx[rx_pos..rx_len) one byte a
     * call (the test's buffer; NULL: nothing received) */
    const unsigned char *rx;
    int rx_len;
    int rx_pos;
    /* A/D */
    int prox[8];
    int ambient[8];
    int ad_started;
    int calibrated;
    /* e-RandB: frames to deliver, in order */
    unsigned randb_data[STUB_QUEUE];
    float randb_bearing[STUB_QUEUE];
    unsigned randb_range[STUB_QUEUE];
    int randb_count;
    unsigned randb_sent[STUB_QUEUE];
    int randb_sends;
    /* libIrcom: messages to pop, in order */
    long ircom_value[STUB_QUEUE];
    float ircom_distance[STUB_QUEUE];
    float ircom_direction[STUB_QUEUE];
    int ircom_sensor[STUB_QUEUE];
    int ircom_error[STUB_QUEUE];
    int ircom_count;
    int ircom_sending;
    long ircom_sent[STUB_QUEUE];
    int ircom_sends;
    /* codec: e_init_sound, e_play_sound (offset and length in words of
     * the table linked as e_sound_sample) */
    int sound_inits;
    int plays;
    int play_offset, play_len;
    /* program memory word 0x17F36 */
    unsigned flash_id;
    /* I2C: registers of device 0xC0 (the ground-sensor module) */
    unsigned char ground_reg[6];
    int i2c_inits, i2c_reads, i2c_enabled;
} epuck_stub_state_t;

extern epuck_stub_state_t epuck_stub;

/** Clears every field: speeds 0, no frames, UART idle, flash id erased. */
void epuck_stub_reset(void);

#endif
