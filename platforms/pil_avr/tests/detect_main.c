/*
 * detect_main.c - what the e-puck1's detectors cost on the emulated
 * ATmega2560, for the CPU report (pil_tests.sh, pil_report.py): a test
 * image on the PIL HAL whose steps run, in turn, nothing, the camera's
 * blob detector over a 40 x 20 RGB565 frame (hal/blob_detect.h, with the
 * parameters the e-puck1's HAL uses) and the tone detector over a 96-sample
 * block of each of the 3 microphones (hal/tone_detect.h, as the e-puck1's
 * HAL runs it at a step's first microphone read).  The simulator's script
 * answers nothing: the frame and the samples are made here.  Robot id 0
 * runs the blob detector only, 1 the tone detector only (so that each one's
 * stack is painted on its own), 2 both.
 */
#include <stdint.h>

#include "blob_detect.h"
#include "hal_pil.h"
#include "sound_bands.h"
#include "tone_detect.h"
#include "tone_tables.h"
#include "units.h"

#define W EPUCK_CAMERA_WIDTH_PX
#define H EPUCK_CAMERA_HEIGHT_PX

static struct hal app_hal;
static uint8_t app_mailbox[PIL_MAILBOX_BYTES(0u)];
static uint8_t camera_frames[2u * W * H];
static hal_blob_t app_blobs[HAL_MAX_BLOBS];
static uint32_t app_levels[HAL_MIC_COUNT][SOUND_BAND_COUNT];

/* A grey frame with a red and a green bar, as the camera's driver stores it. */
static void make_frame(void)
{
    uint16_t x, y, px;
    for (y = 0u; y < H; y++) {
        for (x = 0u; x < W; x++) {
            px = (x >= 8u && x < 14u) ? 0xF800u : (x >= 25u && x < 28u && y > 5u) ? 0x07E0u : 0x8410u;
            camera_frames[2u * (y * W + x)] = (uint8_t)(px >> 8);
            camera_frames[2u * (y * W + x) + 1u] = (uint8_t)px;
        }
    }
}

static void blobs(void)
{
    blob_detect_params_t bp = blob_detect_default_params();
    blob_detect_work_t work;
    bp.fov_mrad = 977u;
    bp.byte_order = BLOB_BYTE_ORDER_BIG;
    (void)blob_detect(&bp, camera_frames, W, H, &work, app_blobs, (uint8_t)HAL_MAX_BLOBS);
}

/* A block per microphone: the A/D's offset, a tone and some noise. */
static void tones(uint16_t step)
{
    int16_t block[TONE_DETECT_N];
    uint8_t mic, k;
    for (mic = 0u; mic < HAL_MIC_COUNT; mic++) {
        for (k = 0u; k < TONE_DETECT_N; k++) {
            block[k] = (int16_t)(2048 + ((k * 7u + mic * 13u + step) % 32u) * 8 - 128);
        }
        tone_detect_block(block, tone_band_coeffs, (uint8_t)SOUND_BAND_COUNT, app_levels[mic]);
    }
}

int main(void)
{
    hal_pil_config_t cfg;
    pil_hello_t hello = { 100u, 16u, 1u, 0u, 0u, 0u, 0u, 0u, 0u, "detect", "none" };
    uint16_t step = 0u, id;
    hal_pil_default_config(&cfg);
    hal_pil_init(&app_hal, &cfg, app_mailbox, (uint16_t)sizeof app_mailbox);
    (void)hal_pil_hello(&app_hal, &hello);
    make_frame();
    hal_pil_ready(&app_hal);
    id = hal_robot_id(&app_hal);
    for (;;) {
        /* step % 3: 0 nothing (the marks' own cost), 1 blobs, 2 tones */
        pil_port_mark();
        if (step % 3u == 1u && id != 1u) {
            blobs();
        } else if (step % 3u == 2u && id != 0u) {
            tones(step);
        }
        pil_port_mark();
        step++;
        hal_pil_end_step(&app_hal);
    }
}
