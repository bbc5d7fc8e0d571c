/* Stubs of platforms/epuck1/hal/epuck_lib_ircom.h (see epuck_stubs.h). */
#include "epuck_lib_ircom.h"
#include "epuck_stubs.h"

void ircomStart(void) {}
void ircomEnableContinuousListening(void) {}
void ircomListen(void) {}

void ircomSend(long int value)
{
    if (epuck_stub.ircom_sends < STUB_QUEUE) {
        epuck_stub.ircom_sent[epuck_stub.ircom_sends] = value;
    }
    epuck_stub.ircom_sends++;
}

int ircomIsSending(void) { return epuck_stub.ircom_sending; }

void ircomPopMessage(IrcomMessage *msg)
{
    int i;
    if (epuck_stub.ircom_count <= 0) {
        msg->error = -1;
        return;
    }
    msg->value = epuck_stub.ircom_value[0];
    msg->distance = epuck_stub.ircom_distance[0];
    msg->direction = epuck_stub.ircom_direction[0];
    msg->receivingSensor = epuck_stub.ircom_sensor[0];
    msg->error = epuck_stub.ircom_error[0];
    for (i = 1; i < epuck_stub.ircom_count; i++) {
        epuck_stub.ircom_value[i - 1] = epuck_stub.ircom_value[i];
        epuck_stub.ircom_distance[i - 1] = epuck_stub.ircom_distance[i];
        epuck_stub.ircom_direction[i - 1] = epuck_stub.ircom_direction[i];
        epuck_stub.ircom_sensor[i - 1] = epuck_stub.ircom_sensor[i];
        epuck_stub.ircom_error[i - 1] = epuck_stub.ircom_error[i];
    }
    epuck_stub.ircom_count--;
}

void e_init_ad_scan(void) { epuck_stub.ad_started = 1; }
void e_calibrate_ir(void) { epuck_stub.calibrated = 1; }

int e_get_calibrated_prox(int s)
{
    return (s >= 0 && s < 8) ? epuck_stub.prox[s] : 0;
}

int e_get_ambient_light(int s)
{
    return (s >= 0 && s < 8) ? epuck_stub.ambient[s] : 0;
}
