/*
 * ircom_libircom.c - IR backend of the images with libIrcom: 8-bit
 * messages through the e-puck's own proximity sensors, about 25 cm.
 * libIrcom brings its own A/D module (IR only: no microphones), which
 * replaces the library's advance A/D scan, so proximity and light are read
 * through it here.
 *
 * libIrcom receives in interrupts into its own queue of 20 messages; poll
 * moves them into the HAL's inbox between steps, converting distance (cm)
 * and direction (rad, the receiving sensor's bearing) to hal.h's units.
 * Messages received with a transmission error are dropped.  A send starts
 * in end_step unless the previous one is still going out (then it is
 * dropped: one message per period at most, as hal.h allows); while libIrcom
 * sends, it pauses the proximity sampling, so readings can be one period
 * old.
 */
#include "hal_epuck.h"

#include "epuck_lib_ircom.h"

/* ircomPopMessage's error codes. */
#define IRCOM_NONE (-1)
#define IRCOM_OK 0

void hal_epuck_ir_start(hal_t *hal)
{
    (void)hal;
    e_init_ad_scan();
    e_calibrate_ir();
    ircomStart();
    ircomEnableContinuousListening();
    ircomListen();
}

void hal_epuck_ir_sample(hal_t *hal)
{
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->prox[i] = hal_epuck_clamp_raw(e_get_calibrated_prox((int)i));
        hal->ambient[i] = hal_epuck_clamp_raw(e_get_ambient_light((int)i));
    }
}

void hal_epuck_ir_poll(hal_t *hal)
{
    IrcomMessage in;
    hal_ircom_msg_t m;
    float mm;
    for (;;) {
        ircomPopMessage(&in);
        if (in.error == IRCOM_NONE) {
            return;
        }
        if (in.error != IRCOM_OK) {
            continue;
        }
        m.value = (uint16_t)(in.value & 0xFFL);
        m.bearing_mrad = hal_epuck_rad_to_mrad(in.direction);
        m.sensor = (in.receivingSensor >= 0 && in.receivingSensor < (int)HAL_IR_COUNT)
                   ? (uint8_t)in.receivingSensor : hal_epuck_nearest_sensor(m.bearing_mrad);
        mm = in.distance * 10.0f;
        m.range_mm = (mm > 0.0f && mm < 65534.0f) ? (uint16_t)(mm + 0.5f)
                                                    : (uint16_t)(mm > 0.0f ? 0xFFFEu : 0u);
        (void)hal_epuck_inbox_push(hal, &m);
    }
}

/* libIrcom sends one message at a time: while one is going out the others
 * of the period are dropped (images on libIrcom keep tx_per_period 1). */
void hal_epuck_ir_transmit(hal_t *hal, uint16_t value)
{
    (void)hal;
    if (ircomIsSending() == 0) {
        ircomSend((long int)(value & 0xFFu));
    }
}

uint8_t hal_ircom_payload_bits(hal_t *hal)
{
    (void)hal;
    return 8u;
}

/* libIrcom replaces the library's A/D module by its own, which samples the
 * IR receivers for demodulation; whether and how it fills the microphone
 * buffers is not established [?]: microphone levels are
 * HAL_ERR_UNAVAILABLE on libIrcom images (the speaker still plays). */
uint8_t hal_epuck_mic_block(hal_t *hal, uint8_t mic, int16_t *out)
{
    (void)hal;
    (void)mic;
    (void)out;
    return 0u;
}
