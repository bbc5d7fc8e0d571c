/*
 * cpu_harness.c - runs each controller's step many times against a scripted
 * HAL on the host, for `make firmware-cpu` (tests/firmware/cpu_report.py
 * runs it under valgrind --tool=callgrind and turns the per-step dumps
 * into instructions per step).  Natively (no valgrind) it is a smoke test:
 * the client requests are no-ops.
 *
 * Each measured call is bracketed by CALLGRIND_ZERO_STATS and
 * CALLGRIND_DUMP_STATS_AT(label), so every dump holds exactly one step.
 * The scripted world is reactive enough to drive every state:
 *   forager      in the nest it hears the beacon (2 tokens of food: it
 *                leaves at its first decision) and 10 reports of other
 *                robots per step; searching, a red blob appears after 20
 *                steps and widens until grasped; returning, the nest light
 *                is on its left and after 15 steps beacon frames come from
 *                inside the nest; depositing, the token vanishes once it
 *                backs; an obstacle in front every 37 steps for 5 steps;
 *   nest_beacon  20 robots report every step (deposits, OAEs);
 *   random_walk  an obstacle in front every 37 steps for 5 steps;
 *   blob_detect  one 40 x 20 RGB565 frame with a red token and a green
 *                and a blue patch: what hal_camera_blobs adds on the robot
 *                in a step that asks for blobs;
 *   repatt       seed 002's controller at its 25 ms period, the paper's
 *                duplex listening with Q40: band levels that rise and fall
 *                (every gain branch), a red target that appears every 300
 *                steps and widens until it is picked up, an obstacle in
 *                front every 37 steps for 5 steps;
 *   tone_detect  3 microphones x 3 bands: hal_mic_level's work in a step
 *                that reads every microphone (the copy of each one's 96
 *                newest samples out of its 100-sample ring, then
 *                tone_detect_block), on blocks with two tones and noise.
 *
 * usage: cpu_harness STEPS
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "blob_detect.h"
#include "foraging/forager.h"
#include "hal.h"
#include "foraging/nest_beacon.h"
#include "foraging/nest_link.h"
#include "common/random_walk.h"
#include "repatt/repatt.h"
#include "tone_detect.h"

#define INBOX 64u

struct hal {
    uint16_t id;
    uint32_t time_ms;
    uint16_t prox[HAL_IR_COUNT];
    uint16_t ambient[HAL_IR_COUNT];
    hal_blob_t blob;
    uint8_t n_blobs;
    int16_t left, right;
    hal_ircom_msg_t inbox[INBOX];
    uint32_t in_head, in_count;
    uint8_t sent;
    uint8_t sound;         /**< 1: the microphones answer (repatt) */
    uint32_t mic_level[HAL_SOUND_BANDS];
    uint16_t period_ms;
};

uint16_t hal_robot_id(hal_t *hal) { return hal->id; }
uint32_t hal_time_ms(hal_t *hal) { return hal->time_ms; }
uint16_t hal_control_period_ms(hal_t *hal) { return hal->period_ms; }
uint16_t hal_ir_proximity(hal_t *hal, uint8_t i) { return i < HAL_IR_COUNT ? hal->prox[i] : 0u; }
uint16_t hal_ir_ambient(hal_t *hal, uint8_t i) { return i < HAL_IR_COUNT ? hal->ambient[i] : 4095u; }

uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max)
{
    if (hal->n_blobs == 0u || max == 0u) {
        return 0u;
    }
    out[0] = hal->blob;
    return 1u;
}

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *w, uint16_t *h) { (void)hal; *w = 40u; *h = 20u; return HAL_OK; }
hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    (void)hal;
    (void)colour;
    out->pixels = 0u;
    out->mean[0] = out->mean[1] = out->mean[2] = 0u;
    out->sd[0] = out->sd[1] = out->sd[2] = 0u;
    return HAL_ERR_UNAVAILABLE;
}
hal_status_t hal_mic_level(hal_t *hal, uint8_t mic, uint8_t band, uint32_t *level)
{
    *level = 0;
    if (mic >= HAL_MIC_COUNT || band == 0u || band >= HAL_SOUND_BANDS) {
        return HAL_ERR_RANGE;
    }
    if (!hal->sound) {
        return HAL_ERR_UNAVAILABLE;
    }
    *level = hal->mic_level[band];
    return HAL_OK;
}
hal_status_t hal_speaker_set(hal_t *hal, uint8_t band)
{ return !hal->sound ? HAL_ERR_UNAVAILABLE : band >= HAL_SOUND_BANDS ? HAL_ERR_RANGE : HAL_OK; }
hal_status_t hal_pose(hal_t *hal, hal_pose_t *out) { (void)hal; (void)out; return HAL_ERR_UNAVAILABLE; }
/* No host in the CPU report: its controllers take no messages. */
hal_status_t hal_host_receive(hal_t *hal, uint8_t *buf, uint8_t cap, uint8_t *len)
{ (void)hal; (void)buf; (void)cap; *len = 0u; return HAL_ERR_UNAVAILABLE; }
uint8_t hal_ircom_payload_bits(hal_t *hal) { (void)hal; return 16u; }

hal_status_t hal_ircom_send(hal_t *hal, uint16_t value)
{
    (void)value;
    if (hal->sent) {
        return HAL_ERR_BUSY;
    }
    hal->sent = 1u;
    return HAL_OK;
}

hal_status_t hal_ircom_receive(hal_t *hal, hal_ircom_msg_t *out)
{
    if (hal->in_count == 0u) {
        return HAL_ERR_EMPTY;
    }
    *out = hal->inbox[hal->in_head];
    hal->in_head = (hal->in_head + 1u) % INBOX;
    hal->in_count--;
    return HAL_OK;
}

void hal_set_wheel_speeds(hal_t *hal, int16_t l, int16_t r) { hal->left = l; hal->right = r; }
void hal_wheel_steps(hal_t *hal, int16_t *l, int16_t *r) { *l = hal->left; *r = hal->right; }
void hal_set_led(hal_t *hal, uint8_t i, uint8_t on) { (void)hal; (void)i; (void)on; }
void hal_set_body_led(hal_t *hal, uint8_t on) { (void)hal; (void)on; }
void hal_set_front_led(hal_t *hal, uint8_t on) { (void)hal; (void)on; }
uint16_t hal_telemetry_write(hal_t *hal, const uint8_t *b, uint16_t n) { (void)hal; (void)b; return n; }

static void push(hal_t *hal, uint16_t value, uint16_t range_mm)
{
    hal_ircom_msg_t *m;
    if (hal->in_count >= INBOX) {
        return;
    }
    m = &hal->inbox[(hal->in_head + hal->in_count) % INBOX];
    m->value = value;
    m->sensor = 0u;
    m->bearing_mrad = 100;
    m->range_mm = range_mm;
    hal->in_count++;
}

static void world_reset(hal_t *hal, uint16_t id)
{
    uint8_t i;
    memset(hal, 0, sizeof *hal);
    hal->id = id;
    hal->period_ms = 100u;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->ambient[i] = 4000u;
    }
}

static void obstacles(hal_t *hal, uint32_t t)
{
    uint16_t v = (t % 37u) < 5u ? 600u : 20u;
    hal->prox[0] = v;
    hal->prox[7] = (uint16_t)(v / 2u);
}

static void end_step(hal_t *hal)
{
    hal->time_ms += hal->period_ms;
    hal->sent = 0u;
}

static void run_forager(uint32_t steps)
{
    hal_t hal;
    forager_t f;
    forager_params_t p;
    uint32_t t, in_state = 0, backing = 0;
    uint8_t last = 0xFF, r;
    uint32_t visits[4] = {0, 0, 0, 0};

    world_reset(&hal, 3u);
    forager_default_params(&p);
    forager_init(&f, &p, 12345u);
    for (t = 0; t < steps; t++) {
        if (f.state != last) {
            in_state = 0;
            last = f.state;
        }
        in_state++;
        visits[f.state & 3u]++;
        obstacles(&hal, t);
        hal.ambient[5] = 4000u;
        for (r = 0; r < 10u; r++) {
            push(&hal, nest_link_encode_oaes((uint16_t)(r + 10u), t), 900u);
        }
        switch (f.state) {
        case FORAGER_WAIT:
            hal.n_blobs = 0u;
            push(&hal, nest_link_encode_food(32), 300u);            /* 2 tokens */
            push(&hal, nest_link_encode_waiting(12u), 300u);
            push(&hal, nest_link_encode_mean_oae(64u), 300u);
            break;
        case FORAGER_SEARCH:
            if (in_state > 20u) {
                hal.n_blobs = 1u;
                hal.blob.colour = HAL_COLOUR_RED;
                hal.blob.bearing_mrad = 120;
                hal.blob.width_mrad = (uint16_t)(60u * (in_state - 20u));
                hal.blob.pixels = (uint16_t)(hal.blob.width_mrad / 10u);
            }
            break;
        case FORAGER_RETURN:
            hal.ambient[5] = 1200u;   /* the nest lamp on the left */
            if (in_state > 15u) {
                push(&hal, nest_link_encode_food(32), 200u);
            }
            backing = 0;
            break;
        default:   /* DEPOSIT */
            if (hal.left < 0 && hal.right < 0 && ++backing >= 2u) {
                hal.n_blobs = 0u;
            }
            break;
        }
        CALLGRIND_ZERO_STATS;
        forager_step(&f, &hal);
        CALLGRIND_DUMP_STATS_AT("forager");
        end_step(&hal);
    }
    printf("forager: %u steps (wait %u, search %u, return %u, deposit %u), %u deposits, %u OAEs\n",
           (unsigned)steps, (unsigned)visits[0], (unsigned)visits[1], (unsigned)visits[2],
           (unsigned)visits[3], (unsigned)f.deposits, (unsigned)f.walk.oae_count);
}

static void run_nest_beacon(uint32_t steps)
{
    hal_t hal;
    nest_beacon_t b;
    nest_beacon_params_t p;
    uint32_t t;
    uint16_t r;

    world_reset(&hal, 0u);
    nest_beacon_default_params(&p);
    nest_beacon_init(&b, &p, 0u);
    for (t = 0; t < steps; t++) {
        for (r = 1; r <= 20u; r++) {
            push(&hal, (t + r) % 2u ? nest_link_encode_deposits(r, t / 50u)
                                    : nest_link_encode_oaes(r, t / 7u), 500u);
        }
        CALLGRIND_ZERO_STATS;
        nest_beacon_step(&b, &hal);
        CALLGRIND_DUMP_STATS_AT("nest_beacon");
        end_step(&hal);
    }
    printf("nest_beacon: %u steps, %u deposits and %u OAEs reported, N_W %u\n", (unsigned)steps,
           (unsigned)b.deposits_total, (unsigned)b.oae_total, (unsigned)b.n_waiting);
}

static void run_random_walk(uint32_t steps)
{
    hal_t hal;
    random_walk_t w;
    random_walk_params_t p;
    uint32_t t;

    world_reset(&hal, 1u);
    random_walk_default_params(&p);
    random_walk_init(&w, &p, 777u);
    for (t = 0; t < steps; t++) {
        obstacles(&hal, t);
        CALLGRIND_ZERO_STATS;
        random_walk_step(&w, &hal);
        CALLGRIND_DUMP_STATS_AT("random_walk");
        end_step(&hal);
    }
    printf("random_walk: %u steps, %u OAEs\n", (unsigned)steps, (unsigned)w.oae_count);
}

static void run_repatt(uint32_t steps)
{
    static repatt_host_t r;   /* with its Q120 storage, as in the simulator */
    hal_t hal;
    repatt_params_t p;
    uint32_t t, phase, waited = 0u;

    world_reset(&hal, 2u);
    hal.period_ms = 25u;
    hal.sound = 1u;
    repatt_default_params(&p);
    p.listening = (uint8_t)REPATT_DUPLEX;
    p.queue_size = 40u;
    p.reach_width_mrad = 400u;   /* the scenarios' reach */
    p.approach_mm = 0u;
    repatt_attach_queue(&r.ctrl, r.queue, (uint16_t)REPATT_QUEUE_MAX);
    repatt_init(&r.ctrl, &p, 4242u);
    for (t = 0; t < steps; t++) {
        obstacles(&hal, t);
        /* levels on slow opposite ramps: the filtered changes take both signs */
        hal.mic_level[1] = 300000u + (t % 400u) * 50u;
        hal.mic_level[2] = 320000u - (t % 260u) * 40u;
        phase = t % 300u;
        if (r.ctrl.state == REPATT_PICK) {
            if (++waited > 200u) {
                hal.n_blobs = 0u;   /* the task took it after the 5 s wait */
            }
        } else {
            waited = 0u;
            hal.n_blobs = (uint8_t)(phase >= 100u);
            hal.blob.colour = HAL_COLOUR_RED;
            hal.blob.bearing_mrad = 90;
            hal.blob.width_mrad = (uint16_t)(80u + 2u * phase);
            hal.blob.pixels = 12u;
        }
        CALLGRIND_ZERO_STATS;
        repatt_step(&r.ctrl, &hal);
        CALLGRIND_DUMP_STATS_AT("repatt");
        end_step(&hal);
    }
    printf("repatt: %u steps, %lu readings, %lu pick-ups, %lu OAEs\n", (unsigned)steps,
           (unsigned long)r.ctrl.readings, (unsigned long)r.ctrl.pickups, (unsigned long)r.ctrl.oae_count);
}

#define FW 40u
#define FH 20u

static void run_blob_detect(uint32_t frames)
{
    static uint8_t frame[FW * FH * 2u];
    blob_detect_params_t p = blob_detect_default_params();
    blob_detect_work_t work;
    hal_blob_t out[HAL_MAX_BLOBS];
    uint32_t k, x, y;
    uint8_t n = 0;

    for (k = 0; k < frames; k++) {
        for (y = 0; y < FH; y++) {
            for (x = 0; x < FW; x++) {
                uint16_t px = blob_rgb565(90, 90, 90);
                if (x >= 12u + k % 5u && x < 22u + k % 5u && y >= 8u) {
                    px = blob_rgb565(200, 30, 30);
                } else if (x < 4u && y < 6u) {
                    px = blob_rgb565(20, 180, 40);
                } else if (x > 34u && y > 14u) {
                    px = blob_rgb565(20, 40, 200);
                } else if ((x * 7u + y * 3u + k) % 11u == 0u) {
                    px = blob_rgb565(100, 85, 95);   /* grey noise */
                }
                frame[2u * (y * FW + x)] = (uint8_t)(px >> 8);
                frame[2u * (y * FW + x) + 1u] = (uint8_t)px;
            }
        }
        CALLGRIND_ZERO_STATS;
        n = blob_detect(&p, frame, FW, FH, &work, out, HAL_MAX_BLOBS);
        CALLGRIND_DUMP_STATS_AT("blob_detect");
    }
    printf("blob_detect: %u frames of %ux%u, %u blobs in the last\n", (unsigned)frames, FW, FH, n);
}

static void run_tone_detect(uint32_t steps)
{
    static int16_t ring[HAL_MIC_COUNT][SOUND_MIC_RING];
    int16_t block[TONE_DETECT_N];
    uint32_t levels[HAL_MIC_COUNT][SOUND_BAND_COUNT];
    uint32_t t, x = 1u;
    uint16_t i, m;

    for (t = 0; t < steps; t++) {
        /* the A/D's ring: a square-ish tone at ~1960 Hz (period ~8.4
         * samples) and a slower one, plus noise */
        for (m = 0; m < HAL_MIC_COUNT; m++) {
            for (i = 0; i < SOUND_MIC_RING; i++) {
                x = x * 1103515245u + 12345u;
                ring[m][i] = (int16_t)(2048 + ((i * 10u / 42u) % 2u ? 300 : -300)
                                       + ((i / 7u) % 2u ? 100 : -100) + (int16_t)((x >> 16) % 64u) - 32);
            }
        }
        CALLGRIND_ZERO_STATS;
        for (m = 0; m < HAL_MIC_COUNT; m++) {
            uint16_t j = (uint16_t)((t + SOUND_MIC_RING - TONE_DETECT_N) % SOUND_MIC_RING);
            for (i = 0; i < TONE_DETECT_N; i++) {
                block[i] = ring[m][j];
                if (++j >= SOUND_MIC_RING) {
                    j = 0u;
                }
            }
            tone_detect_block(block, tone_band_coeffs, (uint8_t)SOUND_BAND_COUNT, levels[m]);
        }
        CALLGRIND_DUMP_STATS_AT("tone_detect");
    }
    printf("tone_detect: %u steps of 3 mics x 3 bands, last band-2 level of mic 0: %lu\n",
           (unsigned)steps, (unsigned long)levels[0][1]);
}

int main(int argc, char **argv)
{
    uint32_t steps = argc > 1 ? (uint32_t)strtoul(argv[1], NULL, 10) : 1000u;
    run_forager(steps);
    run_nest_beacon(steps);
    run_random_walk(steps);
    run_repatt(steps);
    run_blob_detect(steps / 10u + 1u);
    run_tone_detect(steps / 10u + 1u);
    return 0;
}
