/* Platform-neutral parts of the HAL contract. */
#include "hal.h"

int16_t hal_ir_bearing_mrad(hal_t *hal, uint8_t index)
{
    (void)hal;   /* every e-puck has the same ring */
    /* -17, -50, -90, -150, +150, +90, +50, +17 degrees, in mrad.  A switch
     * rather than a table keeps the values in flash on every target. */
    switch (index) {
    case 0: return -297;
    case 1: return -873;
    case 2: return -1571;
    case 3: return -2618;
    case 4: return 2618;
    case 5: return 1571;
    case 6: return 873;
    case 7: return 297;
    default: return 0;
    }
}
