/* Platform-neutral parts of the HAL contract. */
#include "hal.h"
#include "units.h"

int16_t hal_ir_bearing_mrad(hal_t *hal, uint8_t index)
{
    (void)hal;   /* every e-puck has the same ring */
    return units_ir_bearing_mrad(index);
}
