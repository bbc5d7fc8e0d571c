/* Stubs of platforms/epuck1/hal/epuck_lib_adscan.h (see epuck_stubs.h). */
#include "epuck_lib_adscan.h"
#include "epuck_stubs.h"

/* The library's microphone ring buffers (e_ad_conv.c): tests write samples
 * and the write index directly. */
int e_mic_scan[3][EPL_MIC_SAMP_NB];
unsigned int e_last_mic_scan_id;

void e_init_ad_scan(unsigned char only_micro)
{
    (void)only_micro;
    epuck_stub.ad_started = 1;
}

void e_calibrate_ir(void) { epuck_stub.calibrated = 1; }

int e_get_calibrated_prox(unsigned int sensor_number)
{
    return sensor_number < 8u ? epuck_stub.prox[sensor_number] : 0;
}

int e_get_ambient_light(unsigned int sensor_number)
{
    return sensor_number < 8u ? epuck_stub.ambient[sensor_number] : 0;
}
