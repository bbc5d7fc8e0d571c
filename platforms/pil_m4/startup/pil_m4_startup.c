/*
 * pil_m4_startup.c - bare-metal start of a PIL image on QEMU's
 * netduinoplus2 (Cortex-M4F): the vector table, the reset handler (paint
 * the stack, copy .data, zero .bss, enable the FPU, set the stack's MPU
 * guard, move the image to the process stack, start the SysTick on the
 * boot budget, call main) and the handlers of what can go wrong.  Each
 * tells the simulator in an EMU frame (pil_msg.h) and halts: a fault
 * (PIL_EMU_CRASH, with the faulting PC; in the stack's guard,
 * PIL_EMU_STACK), the SysTick reaching zero (PIL_EMU_BUDGET: the exchange
 * ran past its budget), main returning (PIL_EMU_HALT), a reset after the
 * image had run (PIL_EMU_RESET).  Our own code, no vendor start-up file:
 * the e-puck2's port builds on it.
 */
#include <stdint.h>

#include "pil/pil_msg.h"
#include "pil_m4.h"

extern uint32_t pil_m4_stack_guard[], pil_m4_stack_bottom[], pil_m4_stack_top[], pil_m4_handler_stack_top[];
extern uint32_t pil_m4_data_start[], pil_m4_data_end[], pil_m4_data_load[];
extern uint32_t pil_m4_bss_start[], pil_m4_bss_end[];

int main(void);
void pil_m4_reset(void);
void pil_m4_fault(void);
void pil_m4_fault_c(const uint32_t *frame);
void pil_m4_systick(void);
void pil_m4_unexpected(void);

/* The FPU's coprocessors CP10 and CP11: full access. */
#define PIL_M4_CPACR_FPU (0xFu << 20)

void pil_m4_halt(void)
{
    PIL_M4_SYST_CSR = 0u;
    __asm__ __volatile__("cpsid i" ::: "memory");
    for (;;) {
        __asm__ __volatile__("wfi");
    }
}

void pil_m4_fatal(uint8_t event, uint32_t pc)
{
    pil_m4_report(event, pc);     /* reads the SysTick, then stops it */
    pil_m4_halt();
}

/* A fault, on the handlers' stack: the stacked frame's PC from the stack
 * the core was on (the image's, the process stack, unless a handler
 * faulted).  A MemManage fault in the stack's guard, or one while
 * stacking, is the stack's overflow. */
__attribute__((naked)) void pil_m4_fault(void)
{
    __asm__ __volatile__("tst lr, #4\n\tite eq\n\tmrseq r0, msp\n\tmrsne r0, psp\n\tb pil_m4_fault_c");
}

/* MMFSR (CFSR's low byte): MSTKERR (4), DACCVIOL (1), MMARVALID (7). */
#define PIL_M4_MSTKERR 0x10u
#define PIL_M4_DACCVIOL 0x02u
#define PIL_M4_MMARVALID 0x80u

void pil_m4_fault_c(const uint32_t *frame)
{
    uint32_t cfsr = PIL_M4_CFSR, at = PIL_M4_MMFAR;
    uintptr_t guard = (uintptr_t)pil_m4_stack_guard, bottom = (uintptr_t)pil_m4_stack_bottom;
    int overflow = (cfsr & PIL_M4_MSTKERR) != 0u
                   || ((cfsr & (PIL_M4_DACCVIOL | PIL_M4_MMARVALID)) == (PIL_M4_DACCVIOL | PIL_M4_MMARVALID)
                       && at >= guard && at < bottom);
    uint32_t pc = !overflow && (uintptr_t)frame >= bottom && (uintptr_t)frame + 32u <= (uintptr_t)pil_m4_handler_stack_top
                      ? frame[6] : 0u;
    pil_m4_fatal(overflow ? PIL_EMU_STACK : PIL_EMU_CRASH, pc);
}

void pil_m4_systick(void)
{
    pil_m4_fatal(PIL_EMU_BUDGET, 0u);
}

void pil_m4_unexpected(void)
{
    pil_m4_fatal(PIL_EMU_CRASH, 0u);
}

void pil_m4_reset(void)
{
    /* Paint the stack below this function's own frame (not its guard). */
    volatile uint32_t *p = pil_m4_stack_bottom;
    volatile uint32_t *here = (volatile uint32_t *)__builtin_frame_address(0) - 16;
    while (p < here) {
        *p++ = PIL_M4_PAINT;
    }
    for (uint32_t *d = pil_m4_data_start, *s = pil_m4_data_load; d < pil_m4_data_end;) {
        *d++ = *s++;
    }
    for (uint32_t *d = pil_m4_bss_start; d < pil_m4_bss_end;) {
        *d++ = 0u;
    }
    /* QEMU keeps the SRAM across a system reset: a count since reset
     * there means the image reset itself (the budgets are the loader's). */
    if (PIL_M4_SCRATCH(PIL_M4_TOTAL_LO) != 0u || PIL_M4_SCRATCH(PIL_M4_TOTAL_HI) != 0u) {
        pil_m4_fatal(PIL_EMU_RESET, 0u);
    }
    for (uint32_t w = PIL_M4_STEPPING; w < PIL_M4_SCRATCH_WORDS; w++) {
        PIL_M4_SCRATCH(w) = 0u;
    }
    PIL_M4_CPACR |= PIL_M4_CPACR_FPU;
    /* The stack's guard: MPU region 0, 32 bytes (SIZE 4), no access, never
     * executed; the rest of memory as without an MPU (PRIVDEFENA).
     * MemManage faults taken as such. */
    PIL_M4_MPU_RNR = 0u;
    PIL_M4_MPU_RBAR = (uint32_t)(uintptr_t)pil_m4_stack_guard;
    PIL_M4_MPU_RASR = (1u << 28) | (4u << 1) | 1u;
    PIL_M4_MPU_CTRL = (1u << 2) | 1u;
    PIL_M4_SHCSR |= 1u << 16;
    __asm__ __volatile__("dsb\n\tisb" ::: "memory");
    /* The SysTick's exception (the budget) at the highest priority. */
    PIL_M4_SHPR3 &= 0x00FFFFFFu;
    /* The image on the process stack, from here down; the handlers on
     * their own (the main stack). */
    __asm__ __volatile__("mrs r0, msp\n\tmsr psp, r0\n\tmovs r0, #2\n\tmsr control, r0\n\tisb\n\tmsr msp, %0"
                         : : "r"(pil_m4_handler_stack_top) : "r0", "memory");
    pil_m4_resume();
    (void)main();
    pil_m4_fatal(PIL_EMU_HALT, 0u);
}

/* The vector table: the initial stack pointer, then the handlers (ARMv7-M's
 * 16 system vectors, then room for the STM32F405's 82 interrupts, none of
 * which is enabled). */
typedef void (*pil_m4_vector_t)(void);
#define PIL_M4_VECTORS (16u + 82u)
__attribute__((section(".vectors"), used)) static const pil_m4_vector_t pil_m4_vectors[PIL_M4_VECTORS] = {
    [0] = (pil_m4_vector_t)(uintptr_t)pil_m4_stack_top,
    [1] = pil_m4_reset,
    [2] = pil_m4_unexpected,   /* NMI */
    [3] = pil_m4_fault,        /* HardFault */
    [4] = pil_m4_fault,        /* MemManage */
    [5] = pil_m4_fault,        /* BusFault */
    [6] = pil_m4_fault,        /* UsageFault */
    [11] = pil_m4_unexpected,  /* SVCall */
    [12] = pil_m4_unexpected,  /* DebugMon */
    [14] = pil_m4_unexpected,  /* PendSV */
    [15] = pil_m4_systick,
};
