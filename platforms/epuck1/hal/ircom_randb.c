/*
 * ircom_randb.c - IR backend of the images with the e-RandB
 * range-and-bearing turret (16-bit messages, ~1 m): the forager and the
 * nest beacon.  Proximity and light come from the e-puck library's advance
 * A/D scan, which also samples the microphones (hal_epuck_mic_block).
 *
 * The turret's driver busy-waits inside every call (I2C transfers plus nop
 * loops: ~2 ms per reception check, ~4 ms per send), so reception is polled
 * from the main loop between steps (hal_epuck_poll) and the step's message
 * is sent after the step (hal_epuck_end_step).  The turret keeps one frame:
 * a frame that arrives while an earlier one has not been polled replaces
 * it, as on the turret itself.
 *
 * Bearings: the turret computes them on its own processor, in radians,
 * counter-clockwise positive with 0 ahead [?] (check: a sender on the
 * robot's left must give a positive bearing).  Range: the board's units
 * times cfg.randb_range_mm_per_unit (10: the units are taken as cm [?]).
 */
#include "hal_epuck.h"

#include "epuck_lib_adscan.h"
#include "epuck_lib_randb.h"
#include "sound_bands.h"

/* Slots of the ring the A/D interrupt may overwrite while we copy: the
 * oldest SOUND_MIC_RING - TONE_DETECT_N are left out. */
#define MIC_MARGIN (SOUND_MIC_RING - TONE_DETECT_N)

uint8_t hal_epuck_mic_block(hal_t *hal, uint8_t mic, int16_t *out)
{
    uint8_t attempt;
    (void)hal;
    if (mic >= HAL_MIC_COUNT) {
        return 0u;
    }
    /* One snapshot of the write index: e_mic_scan[mic][first] is the oldest
     * sample and the next the interrupt overwrites (one every 61 us; the
     * copy of 96 words takes a few us).  If more than MIC_MARGIN samples
     * arrived during the copy (an interrupt held it up), the copy may mix
     * old and new samples: copy again, up to 3 times, then use the last. */
    for (attempt = 0; attempt < 3u; attempt++) {
        unsigned int first = e_last_mic_scan_id;
        unsigned int j = first + MIC_MARGIN;
        unsigned int moved;
        uint16_t i;
        if (j >= SOUND_MIC_RING) {
            j -= SOUND_MIC_RING;
        }
        for (i = 0; i < TONE_DETECT_N; i++) {
            out[i] = (int16_t)e_mic_scan[mic][j];
            if (++j >= SOUND_MIC_RING) {
                j = 0u;
            }
        }
        moved = (e_last_mic_scan_id + SOUND_MIC_RING - first) % SOUND_MIC_RING;
        if (moved <= MIC_MARGIN) {
            break;
        }
    }
    return 1u;
}

void hal_epuck_ir_start(hal_t *hal)
{
    e_init_ad_scan(EPL_ALL_ADC);
    e_calibrate_ir();
    e_init_randb(EPL_RANDB_I2C);
    e_randb_set_range(hal->cfg.randb_range);
    e_randb_set_calculation(EPL_RANDB_ON_BOARD);
    e_randb_store_light_conditions();
}

void hal_epuck_ir_sample(hal_t *hal)
{
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->prox[i] = hal_epuck_clamp_raw(e_get_calibrated_prox(i));
        hal->ambient[i] = hal_epuck_clamp_raw(e_get_ambient_light(i));
    }
}

void hal_epuck_ir_poll(hal_t *hal)
{
    finalDataRegister r;
    hal_ircom_msg_t m;
    uint32_t range;
    if (e_randb_reception(&r) == 0u) {
        return;
    }
    m.value = (uint16_t)r.data;
    m.bearing_mrad = hal_epuck_rad_to_mrad(r.bearing);
    m.sensor = hal_epuck_nearest_sensor(m.bearing_mrad);
    range = (uint32_t)(uint16_t)r.range * hal->cfg.randb_range_mm_per_unit;
    m.range_mm = range > 0xFFFEu ? (uint16_t)0xFFFEu : (uint16_t)range;
    (void)hal_epuck_inbox_push(hal, &m);
}

void hal_epuck_ir_transmit(hal_t *hal, uint16_t value)
{
    (void)hal;
    e_randb_send_all_data(value);
}

uint8_t hal_ircom_payload_bits(hal_t *hal)
{
    (void)hal;
    return 16u;
}
