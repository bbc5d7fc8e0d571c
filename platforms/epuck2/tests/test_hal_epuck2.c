/*
 * test_hal_epuck2.c - host tests of platforms/epuck2/hal over the scripted
 * stubs of the e-puck2 library and the ChibiOS glue (tests/stubs/).  Built
 * twice by platform.mk: with the turret backend (ircom_randb.c) and, with
 * -DTEST_LIBIRCOM, with the library's libIrcom port.  Prints "N passed,
 * M failed".
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "epuck2_lib.h"
#include "epuck2_stubs.h"
#include "hal_epuck2.h"
#include "telemetry/telemetry_frame.h"
#include "telemetry/telemetry_host.h"

static int passed, failed;

#define CHECK(cond) do { \
        if (cond) { passed++; } \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)

static struct hal robot;
static uint8_t frame[HAL_EPUCK2_FRAME_BYTES];
/* The library's capture: 160 x 80 RGB565, high byte first. */
static uint8_t capture[HAL_EPUCK2_CAM_CAPTURE_WIDTH * 80u * 2u];
static hal_epuck2_host_t host;

static void start_cfg(const hal_epuck2_config_t *cfg)
{
    epuck2_stub_reset();
    epuck2_stub.now_ms = 5000u;
    memset(frame, 0, sizeof frame);
    CHECK(hal_epuck2_init(&robot, cfg, cfg->camera ? frame : NULL, cfg->camera ? (uint16_t)sizeof frame : 0u) == 0);
    hal_epuck2_start(&robot);
}

static void start(uint16_t id, uint8_t camera, uint8_t sound)
{
    hal_epuck2_config_t cfg;
    hal_epuck2_default_config(&cfg);
    cfg.robot_id = id;
    cfg.camera = camera;
    cfg.sound = sound;
    start_cfg(&cfg);
}

/* Waits (in the glue's clock) for the next period and begins its step. */
static void begin(void)
{
    int guard = 0;
    while (hal_epuck2_step_due(&robot) == 0u && guard++ < 100000) {
        epuck2_stub.now_ms++;
    }
    CHECK(guard < 100000);
    hal_epuck2_begin_step(&robot);
}

static void test_clock(void)
{
    start(HAL_EPUCK2_NO_ID, 0u, 0u);
    CHECK(hal_robot_id(&robot) == 0u);   /* the build's id: the stub's 0 */
    epuck2_stub_reset();
    epuck2_stub.robot_id = 23u;
    {
        hal_epuck2_config_t cfg;
        hal_epuck2_default_config(&cfg);
        cfg.camera = 0u;
        CHECK(hal_epuck2_init(&robot, &cfg, NULL, 0u) == 0);
        hal_epuck2_start(&robot);
    }
    CHECK(hal_robot_id(&robot) == 23u);

    start(42u, 0u, 0u);
    CHECK(hal_robot_id(&robot) == 42u && hal_control_period_ms(&robot) == 100u);
    CHECK(hal_epuck2_step_due(&robot) == 0u);
    epuck2_stub.now_ms = 5099u;
    CHECK(hal_epuck2_step_due(&robot) == 0u);
    epuck2_stub.now_ms = 5100u;
    CHECK(hal_epuck2_step_due(&robot) == 1u && hal_epuck2_step_due(&robot) == 0u);
    hal_epuck2_begin_step(&robot);
    hal_epuck2_end_step(&robot);
    CHECK(hal_time_ms(&robot) == 100u && hal_epuck2_overruns(&robot) == 0u);
    /* a step that overran two and a half periods: two missed, counted,
     * and the clock still one period a step */
    epuck2_stub.now_ms = 5450u;
    CHECK(hal_epuck2_step_due(&robot) == 1u && hal_epuck2_overruns(&robot) == 2u);
    hal_epuck2_begin_step(&robot);
    hal_epuck2_end_step(&robot);
    CHECK(hal_time_ms(&robot) == 200u);
    epuck2_stub.now_ms = 5499u;
    CHECK(hal_epuck2_step_due(&robot) == 0u);
    epuck2_stub.now_ms = 5500u;
    CHECK(hal_epuck2_step_due(&robot) == 1u);
    /* the clock's wrap at 2^32 ms */
    start(1u, 0u, 0u);
    epuck2_stub.now_ms = 0xFFFFFFF0u;
    robot.next_ms = 0xFFFFFFF0u + 100u;   /* the first period crosses the wrap */
    CHECK(hal_epuck2_step_due(&robot) == 0u);
    epuck2_stub.now_ms = 0x54u;
    CHECK(hal_epuck2_step_due(&robot) == 1u && hal_epuck2_overruns(&robot) == 0u);
    /* a bad configuration */
    {
        hal_epuck2_config_t cfg;
        hal_epuck2_default_config(&cfg);
        cfg.ircom_tx_per_period = 4u;
        CHECK(hal_epuck2_init(&robot, &cfg, frame, (uint16_t)sizeof frame) == -1);
        CHECK(robot.cfg.ircom_tx_per_period == 1u);
        hal_epuck2_default_config(&cfg);
        cfg.cam_window_h = 300u;   /* not whole frame rows */
        CHECK(hal_epuck2_init(&robot, &cfg, frame, (uint16_t)sizeof frame) == -1 && robot.frame == NULL);
        hal_epuck2_default_config(&cfg);
        CHECK(hal_epuck2_init(&robot, &cfg, frame, 100u) == -1);
    }
}

static void test_sensors_and_wheels(void)
{
    int16_t l = 0, r = 0;
    start(1u, 0u, 0u);
    CHECK(epuck2_stub.calibrated == 1);
#ifndef TEST_LIBIRCOM
    CHECK(epuck2_stub.prox_started == 1 && epuck2_stub.prox_mode == (int)EPUCK2_PROX_SLOW_UPDATE);
#else
    CHECK(epuck2_stub.prox_started == 0 && epuck2_stub.ircom_started == 1);
#endif
    epuck2_stub.prox[0] = 300;
    epuck2_stub.prox[7] = -5;     /* calibrated values may be negative */
    epuck2_stub.prox[3] = 5000;
    epuck2_stub.ambient[2] = 3900;
    epuck2_stub.pos_left = 70000;          /* 32-bit: wraps into hal.h's 16 bits */
    epuck2_stub.pos_right = -3;
    begin();
    epuck2_stub.prox[0] = 999;             /* changes during the step: not seen */
    CHECK(hal_ir_proximity(&robot, 0u) == 300u && hal_ir_proximity(&robot, 7u) == 0u);
    CHECK(hal_ir_proximity(&robot, 3u) == HAL_RAW_MAX && hal_ir_proximity(&robot, 8u) == 0u);
    CHECK(hal_ir_ambient(&robot, 2u) == 3900u && hal_ir_ambient(&robot, 9u) == HAL_RAW_MAX);
    hal_wheel_steps(&robot, &l, &r);
    CHECK(l == (int16_t)(70000 - 65536) && r == -3);

    hal_set_wheel_speeds(&robot, 1200, -2000);
    CHECK(epuck2_stub.speed_calls == 0);   /* applied at end_step */
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.speed_left == HAL_WHEEL_SPEED_MAX && epuck2_stub.speed_right == -HAL_WHEEL_SPEED_MAX);
    CHECK(epuck2_stub.speed_calls == 2);
    begin();
    hal_set_wheel_speeds(&robot, 1000, -1000);   /* unchanged: not sent again */
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.speed_calls == 2);
    CHECK(hal_epuck2_seed(&robot) != 0u);
    epuck2_stub.selector = 0x1B;
    CHECK(hal_epuck2_selector(&robot) == 0x0Bu);
}

static void test_leds(void)
{
    start(1u, 0u, 0u);
    begin();
    hal_set_led(&robot, 0u, 1u);   /* front: red LED1 */
    hal_set_led(&robot, 1u, 1u);   /* front-right: RGB LED2 in red */
    hal_set_led(&robot, 6u, 1u);   /* left: red LED7 */
    hal_set_led(&robot, 8u, 1u);   /* no such LED */
    hal_set_body_led(&robot, 1u);
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.led[0] == 1u && epuck2_stub.led[1] == 0u && epuck2_stub.led[3] == 1u);
    CHECK(epuck2_stub.rgb[0][0] == EPUCK2_RGB_MAX_INTENSITY && epuck2_stub.rgb[0][1] == 0u);
    CHECK(epuck2_stub.rgb[1][0] == 0u);
    CHECK(epuck2_stub.body_led == 1u && epuck2_stub.front_led == 0u);
    CHECK(epuck2_stub.led_calls == 10);    /* the first step sets all ten */
    begin();
    hal_set_led(&robot, 1u, 0u);
    hal_set_front_led(&robot, 1u);
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.led_calls == 12 && epuck2_stub.rgb[0][0] == 0u && epuck2_stub.front_led == 1u);
}

static void put_px(uint16_t x, uint16_t y, uint16_t rgb565)
{
    capture[2u * (y * HAL_EPUCK2_CAM_CAPTURE_WIDTH + x)] = (uint8_t)(rgb565 >> 8);
    capture[2u * (y * HAL_EPUCK2_CAM_CAPTURE_WIDTH + x) + 1u] = (uint8_t)rgb565;
}

/* The capture's columns [x0, x1) pure red, the rest grey. */
static void paint_capture(uint16_t x0, uint16_t x1)
{
    uint16_t x, y;
    for (y = 0; y < 80u; y++) {
        for (x = 0; x < HAL_EPUCK2_CAM_CAPTURE_WIDTH; x++) {
            put_px(x, y, (x >= x0 && x < x1) ? 0xF800u : 0x8410u);
        }
    }
}

static void test_camera(void)
{
    hal_blob_t b[HAL_MAX_BLOBS];
    uint16_t w = 0u, h = 0u;
    uint16_t px;
    start(1u, 1u, 0u);
    CHECK(robot.cam_state == HAL_EPUCK2_CAM_RUNNING);
    CHECK(epuck2_stub.cam_y1 == 80u && epuck2_stub.cam_h == 320u && epuck2_stub.cam_w == 640u);
    CHECK(epuck2_stub.cam_subx == EPUCK2_CAM_SUBSAMPLING_X4 && epuck2_stub.cam_suby == EPUCK2_CAM_SUBSAMPLING_X4);
    CHECK(epuck2_stub.captures == 1 && epuck2_stub.spi_suspended == 1);
    CHECK(hal_camera_frame_size(&robot, &w, &h) == HAL_OK && w == 40u && h == 20u);
    begin();
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 0u);   /* no frame yet */
    hal_epuck2_end_step(&robot);
    /* the capture completes: averaged into the frame, SPI resumed, the
     * next capture started (SPI suspended again) */
    paint_capture(0u, 32u);   /* the image's left: a positive bearing */
    epuck2_stub.img = capture;
    hal_epuck2_poll(&robot);
    CHECK(epuck2_stub.captures == 1);   /* not ready: nothing */
    epuck2_stub.img_ready = 1u;
    hal_epuck2_poll(&robot);
    CHECK(epuck2_stub.captures == 2 && epuck2_stub.releases == 1 && robot.cam_frames == 1u);
    CHECK(epuck2_stub.spi_resumes == 1 && epuck2_stub.spi_suspended == 1);
    px = (uint16_t)((frame[0] << 8) | frame[1]);
    CHECK(px == 0xF800u);
    px = (uint16_t)((frame[2u * 39u] << 8) | frame[2u * 39u + 1u]);
    CHECK(px == 0x8410u);
    begin();
    CHECK(hal_camera_blobs(&robot, b, HAL_MAX_BLOBS) == 1u);
    CHECK(b[0].colour == HAL_COLOUR_RED && b[0].bearing_mrad > 300 && b[0].pixels == 8u * 20u);
    /* a new capture during the step is not seen before the next poll */
    paint_capture(128u, 160u);
    CHECK(hal_camera_blobs(&robot, b, 1u) == 1u && b[0].bearing_mrad > 300);
    hal_epuck2_end_step(&robot);
    epuck2_stub.img_ready = 1u;
    hal_epuck2_poll(&robot);
    begin();
    CHECK(hal_camera_blobs(&robot, b, 1u) == 1u && b[0].bearing_mrad < -300);
    hal_epuck2_end_step(&robot);
    /* the driver will not lend the buffer: counted, the frame kept */
    epuck2_stub.img = NULL;
    epuck2_stub.img_ready = 1u;
    hal_epuck2_poll(&robot);
    CHECK(robot.cam_lost == 1u && robot.cam_frames == 2u && epuck2_stub.captures == 4);

    /* the average of a block, channel by channel: 16 pixels, half red
     * (31, 0, 0) and half blue (0, 0, 31): (15.5 -> 16, 0, 16) */
    {
        uint16_t x, y;
        memset(capture, 0, sizeof capture);
        for (y = 0; y < 4u; y++) {
            for (x = 0; x < 4u; x++) {
                put_px(x, y, (x < 2u) ? 0xF800u : 0x001Fu);
            }
        }
        hal_epuck2_cam_average(capture, 80u, frame);
        px = (uint16_t)((frame[0] << 8) | frame[1]);
        CHECK(px == (uint16_t)((16u << 11) | 16u));
    }
    /* a refused window: failed, no blobs, no frame size */
    {
        hal_epuck2_config_t cfg;
        hal_epuck2_default_config(&cfg);
        epuck2_stub_reset();
        epuck2_stub.cam_config_result = -1;
        CHECK(hal_epuck2_init(&robot, &cfg, frame, (uint16_t)sizeof frame) == 0);
        hal_epuck2_start(&robot);
        CHECK(robot.cam_state == HAL_EPUCK2_CAM_FAILED && epuck2_stub.captures == 0);
        CHECK(hal_camera_frame_size(&robot, &w, &h) == HAL_ERR_UNAVAILABLE && w == 0u);
    }
}

/* Microphone `lib_mic` (the library's index) of the 16 kHz buffer: a tone
 * of `hz` and `amp` counts (0: silence). */
static void fill_mic(uint8_t lib_mic, double hz, double amp)
{
    uint16_t i;
    for (i = 0; i < EPUCK2_MIC_BUFFER_LEN / 4u; i++) {
        epuck2_stub.mic_pcm[4u * i + lib_mic] =
            (int16_t)lround(amp * sin(2.0 * 3.14159265358979323846 * hz * i / EPUCK2_MIC_RATE_HZ));
    }
}

static int near(uint32_t v, double want, double tol)
{
    return fabs((double)v - want) <= tol;
}

static void test_sound(void)
{
    uint32_t lv = 0u;
    start(1u, 0u, 0u);
    begin();
    CHECK(hal_mic_level(&robot, 0u, 1u, &lv) == HAL_ERR_UNAVAILABLE);
    CHECK(hal_speaker_set(&robot, 1u) == HAL_ERR_UNAVAILABLE);
    hal_epuck2_end_step(&robot);

    start(1u, 0u, 1u);
    CHECK(epuck2_stub.mic_started == 1 && epuck2_stub.dac_started == 1);
    fill_mic(EPUCK2_MIC_RIGHT, SOUND_BAND2_HZ, 300.0);
    fill_mic(EPUCK2_MIC_LEFT, 0.0, 0.0);
    fill_mic(EPUCK2_MIC_BACK, SOUND_BAND1_HZ, 1000.0);
    fill_mic(EPUCK2_MIC_FRONT, SOUND_BAND3_HZ, 1000.0);   /* not one of hal.h's */
    begin();
    /* the detector's coefficients are the 16 kHz ones: 1000 x amplitude */
    CHECK(hal_mic_level(&robot, 0u, 2u, &lv) == HAL_OK && near(lv, 300000.0, 9000.0));
    CHECK(hal_mic_level(&robot, 0u, 1u, &lv) == HAL_OK && lv < 3000u);
    CHECK(hal_mic_level(&robot, 1u, 1u, &lv) == HAL_OK && lv == 0u);
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_OK && near(lv, 1000000.0, 30000.0));
    CHECK(hal_mic_level(&robot, 2u, 3u, &lv) == HAL_OK && lv < 10000u);
    CHECK(hal_mic_level(&robot, 3u, 1u, &lv) == HAL_ERR_RANGE && lv == 0u);
    CHECK(hal_mic_level(&robot, 0u, 0u, &lv) == HAL_ERR_RANGE);
    /* the buffer is refilled during the step: one block a step */
    fill_mic(EPUCK2_MIC_RIGHT, 0.0, 0.0);
    CHECK(hal_mic_level(&robot, 0u, 2u, &lv) == HAL_OK && near(lv, 300000.0, 9000.0));
    CHECK(hal_speaker_set(&robot, 4u) == HAL_ERR_RANGE);
    CHECK(hal_speaker_set(&robot, 2u) == HAL_OK);
    CHECK(epuck2_stub.plays == 0);   /* from end_step on */
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.plays == 1 && epuck2_stub.play_hz == SOUND_BAND2_HZ);
    begin();
    lv = 7u;
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_ERR_BUSY && lv == 0u);
    hal_epuck2_end_step(&robot);   /* still band 2: the DAC keeps playing */
    CHECK(epuck2_stub.plays == 1 && epuck2_stub.stops == 0);
    begin();
    CHECK(hal_speaker_set(&robot, 0u) == HAL_OK);
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.stops == 1);
    begin();
    CHECK(hal_mic_level(&robot, 2u, 1u, &lv) == HAL_OK && near(lv, 1000000.0, 30000.0));
    hal_epuck2_end_step(&robot);
}

static void test_ground(void)
{
    uint16_t v = 9u;
    hal_epuck2_config_t cfg;
    start(1u, 0u, 0u);
    begin();
    CHECK(hal_ground(&robot, 0u, &v) == HAL_ERR_UNAVAILABLE && v == 0u);
    hal_epuck2_end_step(&robot);
    hal_epuck2_default_config(&cfg);
    cfg.camera = 0u;
    cfg.ground = 1u;
    start_cfg(&cfg);
    CHECK(epuck2_stub.ground_started == 1);
    epuck2_stub.ground[0] = 900;
    epuck2_stub.ground[2] = 5000;
    begin();
    CHECK(hal_ground(&robot, 0u, &v) == HAL_OK && v == 900u);
    epuck2_stub.ground[0] = 100;   /* read once a step */
    CHECK(hal_ground(&robot, 0u, &v) == HAL_OK && v == 900u);
    CHECK(hal_ground(&robot, 2u, &v) == HAL_OK && v == HAL_RAW_MAX);
    CHECK(hal_ground(&robot, 3u, &v) == HAL_ERR_RANGE && v == 0u);
    hal_epuck2_end_step(&robot);
}

static void test_telemetry_and_host(void)
{
    uint8_t bytes[200];
    uint8_t payload[TELEMETRY_POSE_PAYLOAD];
    uint8_t wire[2 * TELEMETRY_HOST_MAX_BODY];
    uint8_t msg[HAL_HOST_MSG_MAX];
    uint8_t len = 9u;
    hal_pose_t p = { 1234, -567, 1571, 0u }, got;
    uint16_t n, m;
    memset(bytes, 0xA5, sizeof bytes);
    start(7u, 0u, 0u);
    CHECK(hal_telemetry_write(&robot, bytes, 200u) == 200u && epuck2_stub.tx_len == 200);
    epuck2_stub.tx_room = 50;   /* the output queue has room for 50 */
    CHECK(hal_telemetry_write(&robot, bytes, 200u) == 50u && epuck2_stub.tx_len == 250);
    CHECK(hal_telemetry_write(&robot, bytes, 0u) == 0u);

    /* no host link storage */
    begin();
    CHECK(hal_pose(&robot, &got) == HAL_ERR_UNAVAILABLE);
    CHECK(hal_host_receive(&robot, msg, sizeof msg, &len) == HAL_ERR_UNAVAILABLE && len == 0u);
    hal_epuck2_end_step(&robot);

    start(7u, 0u, 0u);
    hal_epuck2_host_attach(&robot, &host);
    telemetry_pose_pack(&p, payload);
    n = telemetry_frame_encode(wire, sizeof wire, TELEMETRY_CH_POSE, 7u, 1u, payload, sizeof payload);
    m = telemetry_frame_encode(wire + n, (uint16_t)(sizeof wire - n), TELEMETRY_CH_HOST_MSG, 7u, 2u,
                               (const uint8_t *)"route", 5u);
    CHECK(n > 0u && m > 0u);
    epuck2_stub.rx = wire;
    epuck2_stub.rx_len = (int)(n + m);
    hal_epuck2_poll(&robot);   /* the frames arrive between steps */
    CHECK(epuck2_stub.rx_pos == (int)(n + m));
    begin();
    CHECK(hal_pose(&robot, &got) == HAL_OK && got.x_mm == 1234 && got.y_mm == -567);
    CHECK(got.heading_mrad == 1571 && got.age_ms == 0u);
    CHECK(hal_host_receive(&robot, msg, 3u, &len) == HAL_ERR_RANGE && len == 0u);
    CHECK(hal_host_receive(&robot, msg, sizeof msg, &len) == HAL_OK && len == 5u && memcmp(msg, "route", 5) == 0);
    CHECK(hal_host_receive(&robot, msg, sizeof msg, &len) == HAL_ERR_EMPTY);
    hal_epuck2_end_step(&robot);
    /* the pose ages one period a step, and is gone after 1 s */
    begin();
    CHECK(hal_pose(&robot, &got) == HAL_OK && got.age_ms == 100u);
    hal_epuck2_end_step(&robot);
    while (hal_time_ms(&robot) <= HAL_POSE_MAX_AGE_MS) {
        begin();
        hal_epuck2_end_step(&robot);
    }
    begin();
    CHECK(hal_pose(&robot, &got) == HAL_ERR_UNAVAILABLE);
    hal_epuck2_end_step(&robot);
    /* another robot's frame: counted, not taken */
    n = telemetry_frame_encode(wire, sizeof wire, TELEMETRY_CH_POSE, 8u, 3u, payload, sizeof payload);
    epuck2_stub.rx = wire;
    epuck2_stub.rx_len = (int)n;
    epuck2_stub.rx_pos = 0;
    hal_epuck2_poll(&robot);
    CHECK(host.not_ours == 1u && host.poses == 1u);
    CHECK(hal_epuck2_host_step_bytes(100u) == 1152u);
}

#ifndef TEST_LIBIRCOM
static void test_ircom_randb(void)
{
    hal_ircom_msg_t m;
    int i;
    start(1u, 0u, 0u);
    /* start: range, on-board calculation, light conditions */
    CHECK(epuck2_stub.i2c_writes == 3);
    CHECK(epuck2_stub.i2c_written_reg[0] == 12u && epuck2_stub.i2c_written_val[0] == 150u);
    CHECK(epuck2_stub.i2c_written_reg[1] == 17u && epuck2_stub.i2c_written_val[1] == 0u);
    CHECK(hal_ircom_payload_bits(&robot) == 16u);
    /* a frame: data 0xBEEF, bearing 1.5708 rad (left), range 25 units */
    epuck2_stub.randb_reg[1] = 0xBEu;
    epuck2_stub.randb_reg[2] = 0xEFu;
    epuck2_stub.randb_reg[3] = (uint8_t)(15708u >> 8);
    epuck2_stub.randb_reg[4] = (uint8_t)(15708u & 0xFFu);
    epuck2_stub.randb_reg[5] = 0u;
    epuck2_stub.randb_reg[6] = 25u;
    epuck2_stub.randb_frames = 1;
    begin();
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);   /* only between steps */
    hal_epuck2_end_step(&robot);
    hal_epuck2_poll(&robot);
    hal_epuck2_poll(&robot);   /* taken once */
    begin();
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 0xBEEFu && m.bearing_mrad == 1571 && m.range_mm == 250u && m.sensor == 5u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);
    /* a bearing past pi wraps to negative: 4.7124 rad = -pi/2 */
    epuck2_stub.randb_reg[3] = (uint8_t)(47124u >> 8);
    epuck2_stub.randb_reg[4] = (uint8_t)(47124u & 0xFFu);
    epuck2_stub.randb_frames = 1;
    /* sends: up to cfg.ircom_tx_per_period (1), 16 bits, high then low */
    CHECK(hal_ircom_send(&robot, 0x1234u) == HAL_OK && hal_ircom_send(&robot, 1u) == HAL_ERR_BUSY);
    epuck2_stub.i2c_writes = 0;
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.i2c_writes == 2 && epuck2_stub.i2c_written_reg[0] == 13u && epuck2_stub.i2c_written_val[0] == 0x12u);
    CHECK(epuck2_stub.i2c_written_reg[1] == 14u && epuck2_stub.i2c_written_val[1] == 0x34u);
    hal_epuck2_poll(&robot);
    begin();
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK && m.bearing_mrad == -1571 && m.sensor == 2u);
    hal_epuck2_end_step(&robot);
    /* a bus error: nothing taken, nothing hangs */
    epuck2_stub.randb_frames = 1;
    epuck2_stub.i2c_error = 1;
    hal_epuck2_poll(&robot);
    begin();
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);
    hal_epuck2_end_step(&robot);
    /* a full inbox drops and counts */
    epuck2_stub.i2c_error = 0;
    for (i = 0; i < (int)HAL_EPUCK2_INBOX + 2; i++) {
        epuck2_stub.randb_frames = 1;
        hal_epuck2_poll(&robot);
    }
    CHECK(robot.in_count == HAL_EPUCK2_INBOX && robot.in_dropped == 2u);
}
#else
static void test_ircom_libircom(void)
{
    hal_ircom_msg_t m;
    start(1u, 0u, 0u);
    CHECK(hal_ircom_payload_bits(&robot) == 8u);
    epuck2_stub.ircom_value[0] = 0x1A5;   /* 8 bits kept */
    epuck2_stub.ircom_distance[0] = 12.34f;
    epuck2_stub.ircom_direction[0] = -1.5708f;
    epuck2_stub.ircom_sensor[0] = 2;
    epuck2_stub.ircom_error[0] = 0;
    epuck2_stub.ircom_value[1] = 7;
    epuck2_stub.ircom_error[1] = 1;        /* a transmission error: dropped */
    epuck2_stub.ircom_count = 2;
    hal_epuck2_poll(&robot);
    begin();
    CHECK(hal_ircom_receive(&robot, &m) == HAL_OK);
    CHECK(m.value == 0xA5u && m.range_mm == 123u && m.bearing_mrad == -1571 && m.sensor == 2u);
    CHECK(hal_ircom_receive(&robot, &m) == HAL_ERR_EMPTY);
    CHECK(hal_ircom_send(&robot, 0x1FFu) == HAL_OK);
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.ircom_sends == 1 && epuck2_stub.ircom_sent[0] == 0xFF);
    begin();
    epuck2_stub.ircom_sending = 1;   /* still sending: the next is dropped */
    CHECK(hal_ircom_send(&robot, 3u) == HAL_OK);
    hal_epuck2_end_step(&robot);
    CHECK(epuck2_stub.ircom_sends == 1);
}
#endif

int main(void)
{
    test_clock();
    test_sensors_and_wheels();
    test_leds();
    test_camera();
    test_sound();
    test_ground();
    test_telemetry_and_host();
#ifndef TEST_LIBIRCOM
    test_ircom_randb();
    printf("platforms/epuck2/hal (turret backend): %d passed, %d failed\n", passed, failed);
#else
    test_ircom_libircom();
    printf("platforms/epuck2/hal (libIrcom backend): %d passed, %d failed\n", passed, failed);
#endif
    return failed == 0 ? 0 : 1;
}
