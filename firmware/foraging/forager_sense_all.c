/*
 * forager_sense_all.c - the forager plus every sensor every step
 * (forager_sense_all.h).
 */
#include "foraging/forager_sense_all.h"

#include "foraging/nest_link.h"

void forager_sense_all_default_params(forager_sense_all_params_t *params) { forager_default_params(params); }

void forager_sense_all_init(forager_sense_all_t *self, const forager_sense_all_params_t *params, uint32_t seed)
{
    forager_init(&self->forager, params, seed);
    self->sensed = 0;
}

void forager_sense_all_reset(forager_sense_all_t *self)
{
    forager_reset(&self->forager);
    self->sensed = 0;
}

void forager_sense_all_step(forager_sense_all_t *self, hal_t *hal)
{
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint32_t level;
    forager_step(&self->forager, hal);
    for (uint8_t i = 0; i < HAL_IR_COUNT; i++) {
        self->sensed += hal_ir_proximity(hal, i) + hal_ir_ambient(hal, i);
    }
    self->sensed += hal_camera_blobs(hal, blobs, (uint8_t)HAL_MAX_BLOBS);
    for (uint8_t band = 1; band < HAL_SOUND_BANDS; band++) {
        if (hal_mic_level(hal, 0, band, &level) == HAL_OK) {
            self->sensed += level;
        }
    }
    /* A forager that already sent this step gets HAL_ERR_BUSY: one frame
     * a step either way. */
    (void)hal_ircom_send(hal, nest_link_encode_oaes(hal_robot_id(hal), self->forager.walk.oae_count));
    /* Out of the nest (searching or returning), a tone in one of the three
     * bands by id: emitters make the sound field's exponentials. */
    uint8_t out = self->forager.state != FORAGER_WAIT;
    (void)hal_speaker_set(hal, out ? (uint8_t)(1u + hal_robot_id(hal) % 3u) : 0u);
}

const char *forager_sense_all_state_name(const forager_sense_all_t *self)
{
    return forager_state_name(&self->forager);
}
