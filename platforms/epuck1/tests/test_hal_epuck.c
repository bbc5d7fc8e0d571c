/*
 * test_hal_epuck.c - host tests of platforms/epuck1/hal over the scripted stubs of the
 * e-puck library (platforms/epuck1/tests/stubs/).  Built twice by
 * tools/make/firmware.mk: with the turret backend (ircom_randb.c, the
 * default) and, with -DTEST_LIBIRCOM, with the libIrcom backend.
 * Prints "N passed, M failed".
 */
#include <stdio.h>
#include <string.h>

#include "blob_detect.h"
#include "epuck_stubs.h"
#include "hal_epuck.h"
#include "tone_tables.h"
#ifndef TEST_LIBIRCOM
#include "epuck_lib_adscan.h"
#endif

static int passed, failed;

#define CHECK(cond) do { \
        if (cond) { passed++; } \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

static struct hal robot;
static uint8_t frames[2u * HAL_EPUCK_FRAME_BYTES];
static int ticks_seen_by_agenda;

static void tick(void)
{
    ticks_seen_by_agenda++;
    hal_epuck_tick(&robot);
}

static void start(uint16_t id, uint8_t camera)
{
    hal_epuck_config_t cfg;
    epuck_stub_reset();
    memset(frames, 0, sizeof frames);
    hal_epuck_default_config(&cfg);
    cfg.robot_id = id;
    cfg.camera = camera;
    CHECK(hal_epuck_init(&robot, &cfg, camera ? frames : NULL, camera ? (uint16_t)sizeof frames : 0u) == 0);
    hal_epuck_start(&robot, tick);
}

/* One control step with nothing done by a controller. */
static void idle_step(void)
{
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    hal_epuck_begin_step(&robot);
    hal_epuck_end_step(&robot);
}

static void test_start_and_clock(void)
{
    start(HAL_EPUCK_NO_ID, 1u);
    CHECK(epuck_stub.agenda == tick);
    CHECK(epuck_stub.agenda_cycle == 1000);   /* 100 ms in 0.1 ms */
    CHECK(epuck_stub.agendas_started == 1);
    CHECK(epuck_stub.ad_started == 1 && epuck_stub.calibrated == 1);
    CHECK(hal_robot_id(&robot) == 0u);        /* no id flashed */
    CHECK(hal_control_period_ms(&robot) == 100u);

    epuck_stub_reset();
    epuck_stub.flash_id = 17u;
    {
        hal_epuck_config_t cfg;
        hal_epuck_default_config(&cfg);
        (void)hal_epuck_init(&robot, &cfg, frames, (uint16_t)sizeof frames);
        hal_epuck_start(&robot, tick);
    }
    CHECK(hal_robot_id(&robot) == 17u);

    start(42u, 1u);
    CHECK(hal_robot_id(&robot) == 42u);
    CHECK(hal_epuck_step_due(&robot) == 0u);
    epuck_stub.agenda();
    CHECK(ticks_seen_by_agenda > 0);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    CHECK(hal_epuck_step_due(&robot) == 0u);
    CHECK(hal_time_ms(&robot) == 0u);
    hal_epuck_begin_step(&robot);
    hal_epuck_end_step(&robot);
    CHECK(hal_time_ms(&robot) == 100u);
    /* three periods pass during a long step: one step, two overruns */
    hal_epuck_tick(&robot);
    hal_epuck_tick(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    CHECK(hal_epuck_step_due(&robot) == 0u);
    CHECK(hal_epuck_overruns(&robot) == 2u);
    /* the tick counter wraps */
    robot.ticks = 0xFFFFu;
    robot.ticks_seen = 0xFFFFu;
    hal_epuck_tick(&robot);
    CHECK(robot.ticks == 0u);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    epuck_stub.selector = 0x13;
    CHECK(hal_epuck_selector(&robot) == 3u);
}

static void test_sensors_sampled_once_per_step(void)
{
    uint8_t i;
    int16_t l, r;
    start(1u, 0u);
    for (i = 0; i < 8u; i++) {
        epuck_stub.prox[i] = 100 * i;
        epuck_stub.ambient[i] = 3000 + i;
    }
    epuck_stub.prox[0] = -12;     /* calibration offset above the reading */
    epuck_stub.prox[7] = 5000;
    epuck_stub.steps_left = -5;
    epuck_stub.steps_right = 32767;
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ir_proximity(&robot, 0) == 0u);
    CHECK(hal_ir_proximity(&robot, 3) == 300u);
    CHECK(hal_ir_proximity(&robot, 7) == 4095u);
    CHECK(hal_ir_proximity(&robot, 8) == 0u);
    CHECK(hal_ir_ambient(&robot, 2) == 3002u);
    CHECK(hal_ir_ambient(&robot, 9) == 4095u);
    epuck_stub.prox[3] = 999;     /* the interrupt updates the library's value */
    CHECK(hal_ir_proximity(&robot, 3) == 300u);   /* ... not within a step */
    hal_wheel_steps(&robot, &l, &r);
    CHECK(l == -5 && r == 32767);
    hal_epuck_end_step(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ir_proximity(&robot, 3) == 999u);
    {
        uint32_t level = 77;
        hal_pose_t pose;
        uint16_t w = 0u, h = 0u;
        /* an image without sound (cfg.sound 0, the default) */
        CHECK(hal_mic_level(&robot, 0, 1, &level) == HAL_ERR_UNAVAILABLE && level == 0);
        CHECK(hal_mic_level(&robot, 3, 1, &level) == HAL_ERR_RANGE);
        CHECK(hal_speaker_set(&robot, 1) == HAL_ERR_UNAVAILABLE);
        CHECK(hal_speaker_set(&robot, 9) == HAL_ERR_RANGE);
        CHECK(hal_pose(&robot, &pose) == HAL_ERR_UNAVAILABLE);
        CHECK(hal_camera_frame_size(&robot, &w, &h) == HAL_ERR_UNAVAILABLE || (w == 40u && h == 20u));
    }
    CHECK(hal_epuck_seed(&robot) != 0u);
}

/* The ground-sensor module: unavailable unless the image declares it (a
 * read of a missing module would hang); declared, its registers are read
 * at the first call of a step, high byte first, clamped to 4095, once. */
static void test_ground_sensors(void)
{
    hal_epuck_config_t cfg;
    uint16_t v = 77u;
    int reads;
    start(1u, 0u);
    idle_step();
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ground(&robot, 0, &v) == HAL_ERR_UNAVAILABLE && v == 0u);
    CHECK(epuck_stub.i2c_reads == 0);
    hal_epuck_end_step(&robot);

    epuck_stub_reset();
    hal_epuck_default_config(&cfg);
    cfg.camera = 0u;
    cfg.ground = 1u;
    CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == 0);
    hal_epuck_start(&robot, tick);
    CHECK(epuck_stub.i2c_inits == 1);
    epuck_stub.ground_reg[0] = 0x03u;   /* GS0 1000 */
    epuck_stub.ground_reg[1] = 0xE8u;
    epuck_stub.ground_reg[2] = 0x00u;   /* GS1 17 */
    epuck_stub.ground_reg[3] = 0x11u;
    epuck_stub.ground_reg[4] = 0xFFu;   /* GS2 past the range: 4095 */
    epuck_stub.ground_reg[5] = 0xFFu;
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ground(&robot, 3, &v) == HAL_ERR_RANGE && v == 0u);
    CHECK(hal_ground(&robot, 0, &v) == HAL_OK && v == 1000u);
    reads = epuck_stub.i2c_reads;
    CHECK(reads == 7 && epuck_stub.i2c_enabled == 0);
    CHECK(hal_ground(&robot, 1, &v) == HAL_OK && v == 17u);
    CHECK(hal_ground(&robot, 2, &v) == HAL_OK && v == 4095u);
    epuck_stub.ground_reg[3] = 0x22u;
    CHECK(hal_ground(&robot, 1, &v) == HAL_OK && v == 17u);   /* once a step */
    CHECK(epuck_stub.i2c_reads == reads);
    hal_epuck_end_step(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ground(&robot, 1, &v) == HAL_OK && v == 0x22u);
    hal_epuck_end_step(&robot);
}

static void test_actuators_applied_at_end_of_step(void)
{
    int calls, led_calls, speed_calls;
    start(1u, 0u);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    hal_set_wheel_speeds(&robot, 1500, -2000);
    hal_set_led(&robot, 2, 1);
    hal_set_led(&robot, 9, 1);    /* no such LED: ignored */
    hal_set_body_led(&robot, 1);
    CHECK(epuck_stub.speed_calls == 0 && epuck_stub.led[2] == 0u);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.speed_left == 1000 && epuck_stub.speed_right == -1000);
    CHECK(epuck_stub.led[2] == 1u && epuck_stub.body_led == 1u && epuck_stub.front_led == 0u);
    led_calls = epuck_stub.led_calls;
    speed_calls = epuck_stub.speed_calls;
    calls = led_calls + speed_calls;
    idle_step();   /* nothing changed: no library call */
    CHECK(epuck_stub.led_calls + epuck_stub.speed_calls == calls);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    hal_set_led(&robot, 2, 0);
    hal_set_front_led(&robot, 1);
    hal_set_wheel_speeds(&robot, 300, -1000);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.led[2] == 0u && epuck_stub.front_led == 1u);
    CHECK(epuck_stub.led_calls == led_calls + 2);          /* only what changed */
    CHECK(epuck_stub.speed_left == 300 && epuck_stub.speed_calls == speed_calls + 1);
}

static void test_telemetry_never_blocks(void)
{
    uint8_t msg[100];
    uint16_t i;
    start(1u, 0u);
    for (i = 0; i < sizeof msg; i++) {
        msg[i] = (uint8_t)i;
    }
    epuck_stub.uart_busy = 1;
    CHECK(hal_telemetry_write(&robot, msg, 10) == 0u);
    CHECK(epuck_stub.uart_sends == 0);
    epuck_stub.uart_busy = 0;
    CHECK(hal_telemetry_write(&robot, msg, 100) == HAL_EPUCK_TX_BYTES);
    CHECK(epuck_stub.uart_sends == 1 && epuck_stub.uart_len == (int)HAL_EPUCK_TX_BYTES);
    CHECK(epuck_stub.uart_buf == (const char *)robot.tx);
    CHECK(memcmp(robot.tx, msg, HAL_EPUCK_TX_BYTES) == 0);
    CHECK(hal_telemetry_write(&robot, msg, 0) == 0u);
    CHECK(hal_telemetry_write(&robot, msg + 64, 36) == 36u);
    CHECK(robot.tx[0] == 64u);
}

/* A red rectangle of columns [c0, c1) over all rows of frame `k`. */
static void paint_red(uint8_t k, uint16_t c0, uint16_t c1)
{
    uint16_t x, y;
    uint8_t *f = frames + (size_t)k * HAL_EPUCK_FRAME_BYTES;
    memset(f, 0, HAL_EPUCK_FRAME_BYTES);
    for (y = 0; y < HAL_EPUCK_CAM_HEIGHT; y++) {
        for (x = c0; x < c1; x++) {
            f[2u * (y * HAL_EPUCK_CAM_WIDTH + x)] = 0xF8u;   /* RGB565 red, high byte first */
            f[2u * (y * HAL_EPUCK_CAM_WIDTH + x) + 1u] = 0x00u;
        }
    }
}

static void test_camera_double_buffer(void)
{
    hal_blob_t b[HAL_MAX_BLOBS];
    start(1u, 1u);
    CHECK(robot.cam_state == HAL_EPUCK_CAM_RUNNING);
    CHECK(epuck_stub.cam_zoom_w == 16u && epuck_stub.cam_zoom_h == 16u);
    CHECK(epuck_stub.cam_y1 == 80u && epuck_stub.cam_h == 320u);
    CHECK(epuck_stub.capture_buf == (char *)frames);
    /* no complete frame yet */
    idle_step();
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 0u);
    hal_epuck_end_step(&robot);
    /* frame 0 completes: the driver moves on to frame 1 */
    paint_red(0, 0, 8);   /* left edge of the image: positive bearing */
    hal_epuck_poll(&robot);
    CHECK(epuck_stub.captures == 1);   /* not ready yet: no swap */
    epuck_stub.img_ready = 1;
    hal_epuck_poll(&robot);
    CHECK(epuck_stub.captures == 2);
    CHECK(epuck_stub.capture_buf == (char *)frames + HAL_EPUCK_FRAME_BYTES);
    CHECK(robot.cam_complete == 0u);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 1u);
    CHECK(b[0].colour == HAL_COLOUR_RED && b[0].bearing_mrad > 300);
    CHECK(b[0].pixels == 8u * HAL_EPUCK_CAM_HEIGHT);
    /* the driver writes into the other frame during the step: no change */
    paint_red(1, 30, 40);
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 1u && b[0].bearing_mrad > 300);
    hal_epuck_end_step(&robot);
    epuck_stub.img_ready = 1;
    hal_epuck_poll(&robot);
    CHECK(robot.cam_complete == 1u && epuck_stub.capture_buf == (char *)frames);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_camera_blobs(&robot, b, 1) == 1u && b[0].bearing_mrad < -300);
    CHECK(hal_camera_blobs(&robot, b, 0) == 0u);
    hal_epuck_end_step(&robot);

    /* a sensor mounted upside down: bearings negated */
    epuck_stub_reset();
    epuck_stub.cam_orientation = 2;
    {
        hal_epuck_config_t cfg;
        hal_epuck_default_config(&cfg);
        (void)hal_epuck_init(&robot, &cfg, frames, (uint16_t)sizeof frames);
    }
    hal_epuck_start(&robot, tick);
    paint_red(0, 0, 8);
    epuck_stub.img_ready = 1;
    hal_epuck_poll(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 1u && b[0].bearing_mrad < -300);

    /* a vertical sensor or a refused window: no blobs, ever */
    epuck_stub_reset();
    epuck_stub.cam_orientation = 0;
    {
        hal_epuck_config_t cfg;
        hal_epuck_default_config(&cfg);
        (void)hal_epuck_init(&robot, &cfg, frames, (uint16_t)sizeof frames);
    }
    hal_epuck_start(&robot, tick);
    CHECK(robot.cam_state == HAL_EPUCK_CAM_FAILED && epuck_stub.captures == 0);
    epuck_stub_reset();
    epuck_stub.cam_config_result = -1;
    {
        hal_epuck_config_t cfg;
        hal_epuck_default_config(&cfg);
        (void)hal_epuck_init(&robot, &cfg, frames, (uint16_t)sizeof frames);
        hal_epuck_start(&robot, tick);
        CHECK(robot.cam_state == HAL_EPUCK_CAM_FAILED);
        /* frames too small, or a window that does not divide */
        CHECK(hal_epuck_init(&robot, &cfg, frames, 100u) == -1);
        cfg.cam_width = 48u;
        CHECK(hal_epuck_init(&robot, &cfg, frames, (uint16_t)sizeof frames) == -1);
        CHECK(robot.cam_state == HAL_EPUCK_CAM_OFF);
    }
}

static void start_sound(uint16_t period_ms)
{
    hal_epuck_config_t cfg;
    epuck_stub_reset();
    hal_epuck_default_config(&cfg);
    CHECK(cfg.sound == 0u);              /* off unless an image asks */
    cfg.robot_id = 3u;
    cfg.camera = 0u;
    cfg.sound = 1u;
    cfg.period_ms = period_ms;
    CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == 0);
    hal_epuck_start(&robot, tick);
    CHECK(epuck_stub.sound_inits == 1);
}

static void begin(void)
{
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot) == 1u);
    hal_epuck_begin_step(&robot);
}

/* 1 if e_play_sound's last call plays whole within the table linked as
 * e_sound_sample, into words[] its first 4 words (the library plays the
 * words after the offset: epuck_lib_sound.h). */
static int played(int16_t *words)
{
    const int16_t *table = &tone_speaker_table[0][0];
    long end = (long)epuck_stub.play_offset + epuck_stub.play_len;
    int i;
    if (epuck_stub.play_offset < 0 || epuck_stub.play_len < 4 || epuck_stub.play_len % 4 != 0
        || end >= (long)(SOUND_BAND_COUNT * TONE_SPK_STRIDE)) {
        return 0;
    }
    for (i = 0; i < 4; i++) {
        words[i] = table[epuck_stub.play_offset + 1 + i];
    }
    return 1;
}

static void test_speaker(void)
{
    uint8_t b;
    int16_t w[4];
    CHECK(hal_epuck_tone_samples(25u) == 180u);
    CHECK(hal_epuck_tone_samples(100u) == 720u);
    CHECK(hal_epuck_tone_samples(1000u) == 720u);
    CHECK(hal_epuck_tone_samples(30u) == 216u);
    CHECK(hal_epuck_tone_samples(1u) == 8u);     /* 7.2 -> 8 */
    for (b = 1u; b < HAL_SOUND_BANDS; b++) {
        uint16_t n = hal_epuck_tone_samples((uint16_t)(25u * b));
        CHECK(n % 4u == 0u);
    }
    start_sound(25u);
    begin();
    CHECK(hal_speaker_set(&robot, 4u) == HAL_ERR_RANGE);
    CHECK(hal_speaker_set(&robot, 2u) == HAL_OK);
    CHECK(epuck_stub.plays == 0);              /* from the next period on */
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.plays == 1);
    CHECK(epuck_stub.play_offset == (int)TONE_SPK_STRIDE);
    CHECK(epuck_stub.play_len == 180);
    CHECK(played(w) == 1);
    CHECK(w[0] == tone_speaker_table[1][1] && w[0] == 0);   /* phase 0 */
    CHECK(w[1] == tone_speaker_table[1][2] && w[1] > 0);
    CHECK(w[3] == tone_speaker_table[1][4]);
    /* still set: restarted every period */
    begin();
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.plays == 2 && epuck_stub.play_offset == (int)TONE_SPK_STRIDE);
    begin();
    CHECK(hal_speaker_set(&robot, 1u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.plays == 3 && epuck_stub.play_offset == 0);
    begin();
    CHECK(hal_speaker_set(&robot, 3u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.play_offset == 2 * (int)TONE_SPK_STRIDE && played(w) == 1);
    begin();
    CHECK(hal_speaker_set(&robot, 0u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.plays == 4);              /* silence: nothing started */
    /* a 100 ms period plays the whole table of the band */
    start_sound(100u);
    begin();
    CHECK(hal_speaker_set(&robot, 3u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.play_len == (int)TONE_SPK_LEN && played(w) == 1);
}

#ifndef TEST_LIBIRCOM
/* The ring of `mic` holds a tone (peak `amp` counts at band `band`'s
 * frequency; band 0: silence) around the A/D's middle, its oldest sample
 * at the write index: sample k in slot (e_last_mic_scan_id + k) % 100.
 * The sine comes from the detector's own constants (no libm here). */
static void fill_mic(uint8_t mic, uint8_t band, double amp)
{
    double c = band ? tone_band_coeffs[band - 1u].coeff_q14 / 16384.0 : 0.0;
    double x0 = 0.0, x1 = band ? amp * tone_band_coeffs[band - 1u].sin_q14 / 16384.0 : 0.0;
    unsigned k;
    for (k = 0; k < EPL_MIC_SAMP_NB; k++) {
        double v = x0, r;
        x0 = x1;
        x1 = c * x1 - v;
        r = 2048.0 + v;
        e_mic_scan[mic][(e_last_mic_scan_id + k) % EPL_MIC_SAMP_NB] = (int)(r + 0.5);
    }
}

static int near(uint32_t level, double expect, double tol)
{
    return level > expect - tol && level < expect + tol;
}

static void test_microphones(void)
{
    uint32_t lv = 0u;
    start_sound(25u);
    e_last_mic_scan_id = 37u;                  /* the ring wraps in the block */
    fill_mic(0u, 2u, 300.0);
    fill_mic(1u, 0u, 0.0);
    fill_mic(2u, 1u, 1000.0);
    begin();
    CHECK(hal_mic_level(&robot, 0u, 2u, &lv) == HAL_OK && near(lv, 300000.0, 9000.0));
    CHECK(hal_mic_level(&robot, 0u, 1u, &lv) == HAL_OK && lv < 3000u);
    CHECK(hal_mic_level(&robot, 0u, 3u, &lv) == HAL_OK && lv < 3000u);
    CHECK(hal_mic_level(&robot, 1u, 1u, &lv) == HAL_OK && lv == 0u);
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_OK && near(lv, 1000000.0, 30000.0));
    CHECK(hal_mic_level(&robot, 2u, 2u, &lv) == HAL_OK && lv < 10000u);
    CHECK(hal_mic_level(&robot, 3u, 1u, &lv) == HAL_ERR_RANGE && lv == 0u);
    CHECK(hal_mic_level(&robot, 0u, 0u, &lv) == HAL_ERR_RANGE);
    CHECK(hal_mic_level(&robot, 0u, 4u, &lv) == HAL_ERR_RANGE);
    /* the interrupt refills the ring during the step: not seen before the
     * next step (one block per microphone and step) */
    fill_mic(0u, 0u, 0.0);
    fill_mic(1u, 3u, 500.0);
    CHECK(hal_mic_level(&robot, 0u, 2u, &lv) == HAL_OK && near(lv, 300000.0, 9000.0));
    CHECK(hal_mic_level(&robot, 1u, 3u, &lv) == HAL_OK && lv == 0u);
    hal_epuck_end_step(&robot);
    begin();
    CHECK(hal_mic_level(&robot, 0u, 2u, &lv) == HAL_OK && lv == 0u);
    CHECK(hal_mic_level(&robot, 1u, 3u, &lv) == HAL_OK && near(lv, 500000.0, 15000.0));
    /* the 4 oldest samples of the ring are outside the window: a click
     * there is not heard */
    fill_mic(1u, 0u, 0.0);
    e_mic_scan[1][(e_last_mic_scan_id + 2u) % EPL_MIC_SAMP_NB] = 4095;
    /* this step emits: the next period's reads are drowned */
    CHECK(hal_speaker_set(&robot, 1u) == HAL_OK);
    hal_epuck_end_step(&robot);
    begin();
    lv = 5u;
    CHECK(hal_mic_level(&robot, 1u, 2u, &lv) == HAL_ERR_BUSY && lv == 0u);
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_ERR_BUSY && lv == 0u);
    CHECK(hal_speaker_set(&robot, 0u) == HAL_OK);   /* silent: heard again after */
    hal_epuck_end_step(&robot);
    begin();
    CHECK(hal_mic_level(&robot, 1u, 2u, &lv) == HAL_OK && lv == 0u);
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_OK && near(lv, 1000000.0, 30000.0));
    hal_epuck_end_step(&robot);
}
#else
static void test_microphones(void)
{
    uint32_t lv = 9u;
    start_sound(25u);
    begin();
    /* libIrcom's A/D module: no microphone levels, the speaker plays */
    CHECK(hal_mic_level(&robot, 0u, 1u, &lv) == HAL_ERR_UNAVAILABLE && lv == 0u);
    CHECK(hal_mic_level(&robot, 0u, 5u, &lv) == HAL_ERR_RANGE);
    CHECK(hal_speaker_set(&robot, 1u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.plays == 1);
    begin();
    CHECK(hal_mic_level(&robot, 0u, 1u, &lv) == HAL_ERR_BUSY);
}
#endif

static void test_bearings(void)
{
    CHECK(hal_epuck_rad_to_mrad(0.5f) == 500);
    CHECK(hal_epuck_rad_to_mrad(-0.5f) == -500);
    CHECK(hal_epuck_rad_to_mrad(3.5f) == 3500 - 6283);
    CHECK(hal_epuck_rad_to_mrad(-7.0f) == -7000 + 6283);
    CHECK(hal_epuck_rad_to_mrad(1.0e9f) == 0);
    CHECK(hal_epuck_nearest_sensor(0) == 0u || hal_epuck_nearest_sensor(0) == 7u);
    CHECK(hal_epuck_nearest_sensor(-300) == 0u);
    CHECK(hal_epuck_nearest_sensor(1500) == 5u);
    CHECK(hal_epuck_nearest_sensor(3100) == 4u);
    CHECK(hal_epuck_nearest_sensor(-3100) == 3u);
}

#ifndef TEST_LIBIRCOM
static void test_ircom_randb(void)
{
    hal_ircom_msg_t m;
    uint8_t i;
    start(5u, 0u);
    CHECK(hal_ircom_payload_bits(&robot) == 16u);
    epuck_stub.randb_data[0] = 0xC123u;
    epuck_stub.randb_bearing[0] = 1.571f;
    epuck_stub.randb_range[0] = 42u;
    epuck_stub.randb_data[1] = 7u;
    epuck_stub.randb_bearing[1] = -0.3f;
    epuck_stub.randb_range[1] = 10000u;
    epuck_stub.randb_count = 2;
    hal_epuck_poll(&robot);   /* one frame per poll, as the turret holds one */
    hal_epuck_poll(&robot);
    hal_epuck_poll(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 0xC123u && m.bearing_mrad == 1571 && m.range_mm == 420u && m.sensor == 5u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 7u && m.bearing_mrad == -300 && m.range_mm == 0xFFFEu && m.sensor == 0u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);
    CHECK(hal_ircom_send(&robot, 0xBEEFu) == HAL_OK);
    CHECK(hal_ircom_send(&robot, 0x1111u) == HAL_ERR_BUSY);   /* one per period */
    CHECK(epuck_stub.randb_sends == 0);              /* sent after the step */
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.randb_sends == 1 && epuck_stub.randb_sent[0] == 0xBEEFu);
    idle_step();
    CHECK(epuck_stub.randb_sends == 1);
    /* an image set for three messages a period sends them in order after
     * the step; a fourth is refused; 0 or more than the most is refused */
    {
        hal_epuck_config_t cfg;
        hal_epuck_default_config(&cfg);
        cfg.camera = 0u;
        cfg.ircom_tx_per_period = 0u;
        CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == -1);
        cfg.ircom_tx_per_period = HAL_EPUCK_TX_MAX + 1u;
        CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == -1);
        cfg.ircom_tx_per_period = 3u;
        CHECK(hal_epuck_init(&robot, &cfg, NULL, 0u) == 0);
        epuck_stub.randb_sends = 0;
        CHECK(hal_ircom_send(&robot, 0x0101u) == HAL_OK);
        CHECK(hal_ircom_send(&robot, 0x0202u) == HAL_OK);
        CHECK(hal_ircom_send(&robot, 0x0303u) == HAL_OK);
        CHECK(hal_ircom_send(&robot, 0x0404u) == HAL_ERR_BUSY);
        hal_epuck_end_step(&robot);
        CHECK(epuck_stub.randb_sends == 3 && epuck_stub.randb_sent[0] == 0x0101u
              && epuck_stub.randb_sent[1] == 0x0202u && epuck_stub.randb_sent[2] == 0x0303u);
        CHECK(hal_ircom_send(&robot, 0x0505u) == HAL_OK);   /* a new period */
    }
    /* a full inbox drops and counts */
    for (i = 0; i < HAL_EPUCK_INBOX + 3u; i++) {
        epuck_stub.randb_data[0] = i;
        epuck_stub.randb_count = 1;
        hal_epuck_poll(&robot);
    }
    CHECK(robot.in_count == HAL_EPUCK_INBOX && robot.in_dropped == 3u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK && m.value == 0u);
}
#else
static void test_ircom_libircom(void)
{
    hal_ircom_msg_t m;
    start(5u, 0u);
    CHECK(hal_ircom_payload_bits(&robot) == 8u);
    epuck_stub.ircom_value[0] = 0x1AB;
    epuck_stub.ircom_distance[0] = 12.34f;
    epuck_stub.ircom_direction[0] = 0.873f;
    epuck_stub.ircom_sensor[0] = 6;
    epuck_stub.ircom_error[0] = 0;
    epuck_stub.ircom_value[1] = 3;
    epuck_stub.ircom_error[1] = 1;        /* transmission error: dropped */
    epuck_stub.ircom_value[2] = 4;
    epuck_stub.ircom_distance[2] = -1.0f;
    epuck_stub.ircom_sensor[2] = 9;       /* out of range: from the bearing */
    epuck_stub.ircom_direction[2] = -1.571f;
    epuck_stub.ircom_error[2] = 0;
    epuck_stub.ircom_count = 3;
    hal_epuck_poll(&robot);
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 0xABu && m.range_mm == 123u && m.bearing_mrad == 873 && m.sensor == 6u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 4u && m.range_mm == 0u && m.sensor == 2u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);
    CHECK(hal_ircom_send(&robot, 0x1234u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.ircom_sends == 1 && epuck_stub.ircom_sent[0] == 0x34);
    epuck_stub.ircom_sending = 1;   /* the previous one still going out */
    hal_epuck_tick(&robot);
    CHECK(hal_epuck_step_due(&robot));
    hal_epuck_begin_step(&robot);
    CHECK(hal_ircom_send(&robot, 0x55u) == HAL_OK);
    hal_epuck_end_step(&robot);
    CHECK(epuck_stub.ircom_sends == 1);
}
#endif

int main(void)
{
    test_start_and_clock();
    test_sensors_sampled_once_per_step();
    test_ground_sensors();
    test_actuators_applied_at_end_of_step();
    test_telemetry_never_blocks();
    test_camera_double_buffer();
    test_bearings();
    test_speaker();
    test_microphones();
#ifndef TEST_LIBIRCOM
    test_ircom_randb();
    printf("platforms/epuck1/hal (turret backend): %d passed, %d failed\n", passed, failed);
#else
    test_ircom_libircom();
    printf("platforms/epuck1/hal (libIrcom backend): %d passed, %d failed\n", passed, failed);
#endif
    return failed == 0 ? 0 : 1;
}
