/*
 * ircom_libircom.c - IR backend of the images on libIrcom: the e-puck2
 * library's port of it (src/ircom/), 8-bit messages through the robot's
 * own proximity sensors, about 25 cm.  It runs the proximity sensors
 * itself (the proximity module must not run beside it), sampling them for
 * the controller at most 5 Hz (ircomEnableProximity): obstacle readings
 * can be two 100 ms periods old.
 *
 * Its receiver queues messages (20); poll moves them into the HAL's inbox
 * between steps, converting distance (cm) and direction (rad, the
 * receiving sensor's bearing) to hal.h's units; messages received with a
 * transmission error are dropped.  A send starts in end_step unless the
 * previous one is still going out (then it is dropped: one message per
 * period at most, as hal.h allows).
 */
#include "hal_epuck2.h"

#include "epuck2_lib_ircom.h"

/* ircomPopMessage's error codes. */
#define IRCOM_NONE (-1)
#define IRCOM_OK 0

void hal_epuck2_ir_start(hal_t *hal)
{
    (void)hal;
    ircomStart();
    ircomEnableProximity();
    ircom_calibrate_ir();
    ircomEnableContinuousListening();
    ircomListen();
}

void hal_epuck2_ir_sample(hal_t *hal)
{
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        hal->prox[i] = hal_epuck2_clamp_raw(ircom_get_calibrated_prox(i));
        hal->ambient[i] = hal_epuck2_clamp_raw(ircom_get_ambient_light(i));
    }
}

void hal_epuck2_ir_poll(hal_t *hal)
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
        mm = in.direction * 1000.0f;
        m.bearing_mrad = (mm < 1.0e6f && mm > -1.0e6f)
                         ? hal_epuck2_wrap_mrad((int32_t)(mm >= 0.0f ? mm + 0.5f : mm - 0.5f)) : 0;
        m.sensor = (in.receivingSensor >= 0 && in.receivingSensor < (int)HAL_IR_COUNT)
                   ? (uint8_t)in.receivingSensor : hal_epuck2_nearest_sensor(m.bearing_mrad);
        mm = in.distance * 10.0f;
        m.range_mm = (mm > 0.0f && mm < 65534.0f) ? (uint16_t)(mm + 0.5f)
                                                    : (uint16_t)(mm > 0.0f ? 0xFFFEu : 0u);
        (void)hal_epuck2_inbox_push(hal, &m);
    }
}

void hal_epuck2_ir_transmit(hal_t *hal, uint16_t value)
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
