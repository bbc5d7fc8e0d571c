/*
 * epuck_lib_adscan.h - GCtronic e-puck library, advance A/D scan module
 * (library/a_d/advance_ad_scan/): IR proximity, ambient light and
 * microphones sampled by the A/D interrupt.  Used by the images with the
 * range-and-bearing turret (ircom_randb.c).  libIrcom images use libIrcom's
 * own A/D module instead (epuck_lib_ircom.h): the two cannot be linked
 * together.  Declarations only; see epuck_lib.h.
 */
#ifndef EPUCK_LIB_ADSCAN_H
#define EPUCK_LIB_ADSCAN_H

/* a_d/advance_ad_scan/e_ad_conv.h: starts the A/D scan; EPL_ALL_ADC samples
 * IR, accelerometer and microphones. */
void e_init_ad_scan(unsigned char only_micro);
/** e_ad_conv.h: `only_micro` value that samples every channel. */
#define EPL_ALL_ADC 0

/* a_d/advance_ad_scan/e_prox.h: proximity minus the offsets measured by
 * e_calibrate_ir (larger = closer; may be slightly negative), ambient light
 * (raw 12-bit, falls as light rises), and the calibration itself (the
 * robot must see nothing within ~10 cm while it runs). */
void e_calibrate_ir(void);
int e_get_calibrated_prox(unsigned int sensor_number);
int e_get_ambient_light(unsigned int sensor_number);

/* a_d/advance_ad_scan/e_ad_conv.c: the microphones' ring buffers, which
 * the A/D interrupt fills at 16384 Hz (ALL_ADC; e_ad_conv.h MIC_SAMP_FREQ),
 * one 12-bit sample per microphone every 61 us, and the index of the slot
 * it writes next (the oldest sample).  e_ad_conv.h documents that the
 * module's files share them as extern globals; the module's own reader
 * (e_get_micro_last_values) re-reads the index for every sample, so a copy
 * during which the interrupt fires slips by a sample: platforms/epuck1/hal copies with
 * one snapshot of the index instead (ircom_randb.c). */
#define EPL_MIC_SAMP_NB 100
extern int e_mic_scan[3][EPL_MIC_SAMP_NB];
extern unsigned int e_last_mic_scan_id;

#endif
