/*
 * pil_port_avr.h - the doorbell of the emulated ATmega2560's mailbox
 * (pil_port_avr.c), which the emulator (platforms/pil_avr/emu/) watches.
 */
#ifndef PIL_PORT_AVR_H
#define PIL_PORT_AVR_H

/** The value written to GPIOR0 to hand a frame over. */
#define PIL_AVR_BELL 0xB5u
/** The value written to GPIOR0 to mark where the controller's step begins
 *  and ends (the emulator notes the cycle and does not stop). */
#define PIL_AVR_MARK 0x4Du
/** Data-space addresses of GPIOR0, GPIOR1 and GPIOR2 on the ATmega2560. */
#define PIL_AVR_GPIOR0 0x3Eu
#define PIL_AVR_GPIOR1 0x4Au
#define PIL_AVR_GPIOR2 0x4Bu
/** The register at data-space address `a` (the data-space addresses are
 *  the ones the emulator sees; avr/io.h is not needed). */
#define PIL_AVR_REG(a) (*(volatile uint8_t *)(uintptr_t)(a))

#endif
