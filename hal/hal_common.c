/* Platform-neutral parts of the HAL contract. */
#include "hal.h"
#include "units.h"

int16_t hal_ir_bearing_mrad(hal_t *hal, uint8_t index)
{
    (void)hal;   /* every e-puck has the same ring */
    return units_ir_bearing_mrad(index);
}

uint8_t hal_camera_widest(hal_t *hal, uint8_t colour, hal_blob_t *widest)
{
    hal_blob_t blobs[HAL_MAX_BLOBS];
    uint8_t n = hal_camera_blobs(hal, blobs, (uint8_t)HAL_MAX_BLOBS);
    uint8_t found = 0u;
    uint8_t i;
    for (i = 0; i < n && i < HAL_MAX_BLOBS; i++) {
        if (blobs[i].colour == colour) {
            if (found == 0u || blobs[i].width_mrad > widest->width_mrad) {
                *widest = blobs[i];
            }
            found++;
        }
    }
    return found;
}
