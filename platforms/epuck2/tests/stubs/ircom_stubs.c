/* ircom_stubs.c - epuck2_stubs.h: the library's libIrcom port. */
#include "epuck2_stubs.h"

#include "epuck2_lib_ircom.h"

void ircomStart(void) { epuck2_stub.ircom_started++; }
void ircomEnableContinuousListening(void) {}
void ircomEnableProximity(void) {}
void ircom_calibrate_ir(void) { epuck2_stub.calibrated++; }
int ircom_get_calibrated_prox(unsigned int sensor_number) { return sensor_number < 8u ? epuck2_stub.prox[sensor_number] : 0; }
int ircom_get_ambient_light(unsigned int sensor_number) { return sensor_number < 8u ? epuck2_stub.ambient[sensor_number] : 0; }
void ircomListen(void) {}
int ircomIsSending(void) { return epuck2_stub.ircom_sending; }
void ircomSend(long int value)
{
    if (epuck2_stub.ircom_sends < EPUCK2_STUB_QUEUE) {
        epuck2_stub.ircom_sent[epuck2_stub.ircom_sends] = value;
    }
    epuck2_stub.ircom_sends++;
}
/* Pops the test's messages in order, then "none" (error -1). */
void ircomPopMessage(IrcomMessage *msg)
{
    int next = epuck2_stub.ircom_next;
    if (next >= epuck2_stub.ircom_count) {
        msg->error = -1;
        return;
    }
    msg->value = epuck2_stub.ircom_value[next];
    msg->distance = epuck2_stub.ircom_distance[next];
    msg->direction = epuck2_stub.ircom_direction[next];
    msg->receivingSensor = epuck2_stub.ircom_sensor[next];
    msg->error = epuck2_stub.ircom_error[next];
    epuck2_stub.ircom_next = next + 1;
}
