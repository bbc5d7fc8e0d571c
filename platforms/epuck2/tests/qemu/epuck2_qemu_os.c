/*
 * epuck2_qemu_os.c - epuck2_os.h on QEMU's netduinoplus2 (an STM32F405, the
 * e-puck2's Cortex-M4F core) instead of ChibiOS: the processor-in-the-loop
 * check of an e-puck2 image (platforms/epuck2/tests/pil_qemu.sh).  The
 * image's run loop, HAL and telemetry run unchanged on the emulated core,
 * over the library's stubs (tests/stubs/epuck2_lib_stubs.c: no sensors, no
 * camera, no I2C turret: QEMU has none of them) and this glue:
 *   - the clock: the SysTick at 1 kHz (168 MHz core clock), counted here;
 *   - UART3 (the ESP32's Bluetooth serial) is QEMU's USART1 (0x40011000),
 *     which QEMU connects to its first serial port: the telemetry goes out
 *     there and the host's frames come in;
 *   - idle: wfi until the next SysTick;
 *   - after EPUCK2_QEMU_RUN_MS of emulated time the image stops QEMU
 *     (semihosting SYS_EXIT), so a run is bounded and needs no kill.
 * Test code: its clock is a mutable static (the firmware's hygiene rules
 * are the HAL's, which this file is not part of).
 */
#include <stdint.h>

#include "epuck2_os.h"

#ifndef EPUCK2_QEMU_RUN_MS
#define EPUCK2_QEMU_RUN_MS 3000u
#endif
#ifndef EPUCK2_QEMU_ROBOT_ID
#define EPUCK2_QEMU_ROBOT_ID 5u
#endif

#define REG(a) (*(volatile uint32_t *)(uintptr_t)(a))
#define SYST_CSR REG(0xE000E010u)
#define SYST_RVR REG(0xE000E014u)
#define SYST_CVR REG(0xE000E018u)
#define CPACR REG(0xE000ED88u)
#define USART1_SR REG(0x40011000u)
#define USART1_DR REG(0x40011004u)
#define USART1_CR1 REG(0x4001100Cu)
#define USART_SR_RXNE 0x20u
#define USART_SR_TXE 0x80u
#define USART_CR1_RUN 0x200Cu     /* UE, TE, RE */
#define CORE_HZ 168000000u

extern uint32_t epuck2_qemu_data_start[], epuck2_qemu_data_end[], epuck2_qemu_data_load[];
extern uint32_t epuck2_qemu_bss_start[], epuck2_qemu_bss_end[], epuck2_qemu_stack_top[];

int main(void);
void epuck2_qemu_reset(void);
void epuck2_qemu_systick(void);
void epuck2_qemu_fault(void);

static volatile uint32_t qemu_ms;

/* Semihosting SYS_EXIT (0x18) with ADP_Stopped_ApplicationExit: QEMU
 * ends (-semihosting-config enable=on,target=native). */
static void qemu_exit(void)
{
    register uint32_t r0 __asm__("r0") = 0x18u;
    register uint32_t r1 __asm__("r1") = 0x20026u;
    __asm__ __volatile__("bkpt 0xab" : : "r"(r0), "r"(r1) : "memory");
    for (;;) {
    }
}

void epuck2_qemu_systick(void)
{
    qemu_ms++;
}

void epuck2_qemu_fault(void)
{
    qemu_exit();
}

void epuck2_os_init(void)
{
    USART1_CR1 = USART_CR1_RUN;
    SYST_RVR = CORE_HZ / 1000u - 1u;
    SYST_CVR = 0u;
    SYST_CSR = 0x7u;   /* core clock, interrupt, enabled */
}

uint32_t epuck2_os_time_ms(void)
{
    return qemu_ms;
}

uint16_t epuck2_os_serial_write(const uint8_t *bytes, uint16_t len)
{
    uint16_t i;
    for (i = 0u; i < len; i++) {
        uint32_t guard = 0u;
        while ((USART1_SR & USART_SR_TXE) == 0u && guard++ < 100000u) {
        }
        USART1_DR = bytes[i];
    }
    return len;
}

uint16_t epuck2_os_serial_read(uint8_t *buf, uint16_t cap)
{
    uint16_t n = 0u;
    while (n < cap && (USART1_SR & USART_SR_RXNE) != 0u) {
        buf[n++] = (uint8_t)USART1_DR;
    }
    return n;
}

void epuck2_os_idle(void)
{
    if (qemu_ms >= EPUCK2_QEMU_RUN_MS) {
        qemu_exit();
    }
    __asm__ __volatile__("wfi");
}

uint16_t epuck2_os_robot_id(void)
{
    return (uint16_t)EPUCK2_QEMU_ROBOT_ID;
}

void epuck2_qemu_reset(void)
{
    uint32_t *s = epuck2_qemu_data_load, *d = epuck2_qemu_data_start;
    while (d < epuck2_qemu_data_end) {
        *d++ = *s++;
    }
    for (d = epuck2_qemu_bss_start; d < epuck2_qemu_bss_end; d++) {
        *d = 0u;
    }
    CPACR |= 0xFu << 20;   /* the FPU: the image is built for hard float */
    __asm__ __volatile__("dsb\n\tisb" ::: "memory");
    (void)main();
    qemu_exit();
}

/* The vector table: the stack, reset, the faults, SysTick. */
__attribute__((section(".vectors"), used)) static void (*const qemu_vectors[16])(void) = {
    (void (*)(void))(uintptr_t)epuck2_qemu_stack_top,
    epuck2_qemu_reset,
    epuck2_qemu_fault, epuck2_qemu_fault, epuck2_qemu_fault, epuck2_qemu_fault, epuck2_qemu_fault,
    0, 0, 0, 0,
    epuck2_qemu_fault, epuck2_qemu_fault, 0, epuck2_qemu_fault,
    epuck2_qemu_systick,
};
