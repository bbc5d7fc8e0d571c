/*
 * pil_m4.h - the few registers of QEMU's netduinoplus2 (an STM32F405,
 * Cortex-M4F) that processor-in-the-loop uses, and the port's scratch words
 * (startup/m4.ld).  (Its USART1, at 0x40011000, works in QEMU and has no
 * baud timing, but the frames do not go through it: hal/pil_port_m4.c
 * says why.)  Register addresses are the STM32F405's and ARMv7-M's.
 */
#ifndef PIL_M4_H
#define PIL_M4_H

#include <stdint.h>

#define PIL_M4_REG(a) (*(volatile uint32_t *)(uintptr_t)(a))

/* SysTick, counting the core clock (CLKSOURCE 1). */
#define PIL_M4_SYST_CSR PIL_M4_REG(0xE000E010u)
#define PIL_M4_SYST_RVR PIL_M4_REG(0xE000E014u)
#define PIL_M4_SYST_CVR PIL_M4_REG(0xE000E018u)
#define PIL_M4_SYST_RUN 0x7u          /**< ENABLE, TICKINT, CLKSOURCE */
#define PIL_M4_SYST_MAX 0xFFFFFFu     /**< 24 bits */

/* The system control block. */
#define PIL_M4_SHPR3 PIL_M4_REG(0xE000ED20u)
#define PIL_M4_CPACR PIL_M4_REG(0xE000ED88u)
#define PIL_M4_SHCSR PIL_M4_REG(0xE000ED24u)
#define PIL_M4_MMFAR PIL_M4_REG(0xE000ED34u)
/* The MPU (ARMv7-M PMSAv7): control, region number, base, attributes. */
#define PIL_M4_MPU_CTRL PIL_M4_REG(0xE000ED94u)
#define PIL_M4_MPU_RNR PIL_M4_REG(0xE000ED98u)
#define PIL_M4_MPU_RBAR PIL_M4_REG(0xE000ED9Cu)
#define PIL_M4_MPU_RASR PIL_M4_REG(0xE000EDA0u)
#define PIL_M4_CFSR PIL_M4_REG(0xE000ED28u)

/** The SysTick's clock on QEMU's netduinoplus2, Hz (its SYSCLK).  With
 *  `-icount shift=0` each instruction is 1 ns of emulated time, so an
 *  instruction count is ticks * 10^9 / 168 MHz = ticks * 125 / 21. */
#define PIL_M4_SYSCLK_HZ 168000000u
#define PIL_M4_TICKS_TO_INSNS(t) ((uint32_t)(((uint64_t)(t) * 125u) / 21u))

/** The stack paint (startup/pil_m4_startup.c) and what the port measures. */
#define PIL_M4_PAINT 0xA5A5A5A5u

/** The port's scratch words, at pil_m4_scratch (the SRAM's last 64 bytes;
 *  QEMU's loader device writes the two budgets there before reset). */
enum pil_m4_scratch_word {
    PIL_M4_STEP_BUDGET = 0,   /**< SysTick ticks a step's exchange may take (0: the most, 2^24) */
    PIL_M4_BOOT_BUDGET = 1,   /**< ... an exchange before the first STEP */
    PIL_M4_STEPPING = 2,      /**< a STEP has come: the step budget applies */
    PIL_M4_FIRST_MARK = 3,    /**< SysTick's value at the first mark since resumed, 0: none */
    PIL_M4_LAST_MARK = 4,     /**< ... at the last */
    PIL_M4_TOTAL_LO = 5,      /**< instructions since reset (64 bits) */
    PIL_M4_TOTAL_HI = 6,
    PIL_M4_STACK_MAX = 7,     /**< bytes of stack used, by painting */
    PIL_M4_IN = 8,            /**< the semihosting handles of QEMU's standard input and output, +1 */
    PIL_M4_OUT = 9,
    PIL_M4_SCRATCH_WORDS = 16
};
/** Where the QEMU loader writes the budgets: keep equal to m4.ld's SCRATCH. */
#define PIL_M4_SCRATCH_ADDR 0x2001FFC0u
#define PIL_M4_SCRATCH(w) PIL_M4_REG(PIL_M4_SCRATCH_ADDR + 4u * (uint32_t)(w))

/** The SRAM a PEEK may read. */
#define PIL_M4_RAM_START 0x20000000u
#define PIL_M4_RAM_END 0x20020000u

/** Starts the SysTick on a new exchange's budget (the startup at reset,
 *  the port after each answer). */
void pil_m4_resume(void);
/** Reports `event` (pil_emu_event_t) with `pc` and halts for good: the
 *  fault and SysTick handlers. */
void pil_m4_fatal(uint8_t event, uint32_t pc);
/** Sends the EMU frame of how the core ran since it was resumed (event
 *  pil_emu_event_t, pc where it stopped, 0: not known) and stops the
 *  SysTick until pil_m4_resume. */
void pil_m4_report(uint8_t event, uint32_t pc);
/** Halts for good, saying nothing (the simulator has gone). */
void pil_m4_halt(void);

#endif
