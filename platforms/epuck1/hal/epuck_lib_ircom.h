/*
 * epuck_lib_ircom.h - libIrcom (IR local communication through the
 * e-puck's own 8 proximity sensors; Campo, Gutierrez, Longchamp), with the
 * A/D module it ships (its e_ad_conv replaces the library's advance A/D
 * scan: no microphones).  User-supplied (IRCOM_DIR, tools/make/firmware.mk).
 * Declarations only.
 *
 * 8 data bits per message, about 25 cm; received messages wait in the
 * library's queue of 20.  ircomPopMessage sets error to -1 when the queue
 * is empty, 0 for a good message, 1 for a transmission error.
 */
#ifndef EPUCK_LIB_IRCOM_H
#define EPUCK_LIB_IRCOM_H

/* ircom.h: one received message (long 32-bit, float 32-bit, int 16-bit on
 * XC16). */
typedef struct {
    long int value;
    float distance;        /* cm */
    float direction;       /* rad, the receiving sensor's bearing */
    int receivingSensor;   /* 0..7 */
    int error;             /* -1 none, 0 ok, 1 transmission error */
} IrcomMessage;

/* ircom.h / ircomReceive.h / ircomSend.h / ircomMessages.h */
void ircomStart(void);
void ircomEnableContinuousListening(void);
void ircomListen(void);
void ircomSend(long int value);
int ircomIsSending(void);
void ircomPopMessage(IrcomMessage *msg);

/* libIrcom's e_ad_conv.h: its own A/D scan (IR only) and the proximity
 * readings, same meaning as the advance A/D module's. */
void e_init_ad_scan(void);
void e_calibrate_ir(void);
int e_get_calibrated_prox(int s);
int e_get_ambient_light(int s);

#endif
