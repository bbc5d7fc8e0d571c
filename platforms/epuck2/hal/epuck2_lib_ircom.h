/*
 * epuck2_lib_ircom.h - the e-puck2 library's port of libIrcom (src/ircom/:
 * IR local communication through the 8 proximity sensors; Campo,
 * Gutierrez, Longchamp), declared from its public headers (ircom.h,
 * ircomSend.h, ircomReceive.h, ircomMessages.h).  Declarations only; see
 * epuck2_lib.h.
 *
 * It replaces the proximity module (proximity_start must not run with it):
 * with ircomEnableProximity it samples the sensors too, at most 5 Hz, read
 * through its own ircom_get_* functions.  8 data bits a message; its queue
 * holds IRCOM_MESSAGES_MAX = 20.  IrcomMessage as in ircom.h (long and int
 * are 32 bits, float 32 bits on the STM32): error -1 none, 0 ok, 1 a
 * transmission error.
 */
#ifndef EPUCK2_LIB_IRCOM_H
#define EPUCK2_LIB_IRCOM_H

typedef struct {
    long int value;
    float distance;        /* cm */
    float direction;       /* rad, the receiving sensor's bearing */
    int receivingSensor;   /* 0..7 */
    int error;
} IrcomMessage;

/* ircom.h */
void ircomStart(void);
void ircomEnableContinuousListening(void);
void ircomEnableProximity(void);
void ircom_calibrate_ir(void);
int ircom_get_calibrated_prox(unsigned int sensor_number);
int ircom_get_ambient_light(unsigned int sensor_number);
/* ircomReceive.h, ircomSend.h, ircomMessages.h */
void ircomListen(void);
void ircomSend(long int value);
int ircomIsSending(void);
void ircomPopMessage(IrcomMessage *msg);

#endif
