/*
 * pil_port_m4.c - pil_port_exchange on QEMU's netduinoplus2: the frames go
 * over USART1 (no baud timing in QEMU), and the robot itself says how it
 * ran, because QEMU, unlike simavr, is a program we only talk to.
 *
 * Before each of its frames the robot sends an EMU frame (pil_msg.h) as
 * the AVR's emulator does: the instructions it ran since the last answer
 * (SysTick, counting the core clock; with `-icount shift=0` one
 * instruction is one emulated nanosecond: PIL_M4_TICKS_TO_INSNS), its
 * marks, the stack used (painting) and the instructions since reset.
 * While it waits for the answer the SysTick is stopped and the core
 * sleeps in WFI (woken by USART1's interrupt, which BASEPRI never lets be
 * taken), so the wait costs neither instructions nor the host's CPU.  The
 * SysTick's reload is the exchange's budget: running past it takes the
 * SysTick exception, which reports PIL_EMU_BUDGET and halts
 * (pil_m4_startup.c).  A PEEK that comes while it waits is answered from
 * its own SRAM with a MEMORY frame (the SysTick stopped: it costs the
 * step nothing), as a debugger's read would be.
 *
 * No mutable statics: the port's state is the scratch words of pil_m4.h.
 */
#include <stdint.h>

#include "pil/pil_frame.h"
#include "pil/pil_msg.h"
#include "pil/pil_robot.h"
#include "pil_m4.h"
#include "telemetry/telemetry_frame.h"

extern uint32_t pil_m4_stack_bottom[], pil_m4_stack_top[];

static void put_byte(uint8_t b)
{
    while ((PIL_M4_USART_SR & PIL_M4_USART_TXE) == 0u) {
    }
    PIL_M4_USART_DR = b;
}

static void put_bytes(const uint8_t *p, uint32_t n)
{
    for (uint32_t k = 0u; k < n; k++) {
        put_byte(p[k]);
    }
}

/* The next byte from the simulator, the core asleep until it comes. */
static uint8_t get_byte(void)
{
    while ((PIL_M4_USART_SR & PIL_M4_USART_RXNE) == 0u) {
        __asm__ __volatile__("wfi" ::: "memory");
        PIL_M4_NVIC_ICPR(PIL_M4_USART1_IRQ / 32u) = 1u << (PIL_M4_USART1_IRQ % 32u);
    }
    return (uint8_t)(PIL_M4_USART_DR & 0xFFu);
}

/* Ticks since the SysTick was resumed (it reads 0 until its first tick
 * loads the reload value). */
static uint32_t ticks_since(uint32_t cvr)
{
    return cvr == 0u ? 0u : PIL_M4_SYST_RVR + 1u - cvr;
}

static uint32_t mark_insns(uint32_t w)
{
    uint32_t v = PIL_M4_SCRATCH(w);
    return v == 0u ? PIL_NO_MARK : PIL_M4_TICKS_TO_INSNS(ticks_since(v));
}

/* Bytes of stack ever used: from the bottom, the first word not painted. */
static uint32_t stack_used(void)
{
    const volatile uint32_t *p = pil_m4_stack_bottom;
    while (p < pil_m4_stack_top && *p == PIL_M4_PAINT) {
        p++;
    }
    return (uint32_t)((uintptr_t)pil_m4_stack_top - (uintptr_t)p);
}

void pil_m4_report(uint8_t event, uint32_t pc);
void pil_m4_report(uint8_t event, uint32_t pc)
{
    uint8_t buf[PIL_FRAME_BYTES(32u)];
    pil_emu_t m;
    uint32_t cvr = PIL_M4_SYST_CVR;
    PIL_M4_SYST_CSR = 0u;                 /* stopped until the answer */
    /* Past the budget, the SysTick has wrapped: it ran its whole reload. */
    uint32_t insns = PIL_M4_TICKS_TO_INSNS(event == PIL_EMU_BUDGET ? PIL_M4_SYST_RVR + 1u : ticks_since(cvr));
    uint64_t total = ((uint64_t)PIL_M4_SCRATCH(PIL_M4_TOTAL_HI) << 32 | PIL_M4_SCRATCH(PIL_M4_TOTAL_LO)) + insns;
    PIL_M4_SCRATCH(PIL_M4_TOTAL_LO) = (uint32_t)total;
    PIL_M4_SCRATCH(PIL_M4_TOTAL_HI) = (uint32_t)(total >> 32);
    uint32_t used = stack_used();
    if (used > PIL_M4_SCRATCH(PIL_M4_STACK_MAX)) {
        PIL_M4_SCRATCH(PIL_M4_STACK_MAX) = used;
    }
    m.event = event;
    m.cycles = insns;
    m.total = total;
    m.stack_max = (uint16_t)(PIL_M4_SCRATCH(PIL_M4_STACK_MAX) > 0xFFFFu ? 0xFFFFu : PIL_M4_SCRATCH(PIL_M4_STACK_MAX));
    m.pc = pc;
    m.first_mark = mark_insns(PIL_M4_FIRST_MARK);
    m.last_mark = mark_insns(PIL_M4_LAST_MARK);
    uint16_t n = pil_emu_encode(buf + PIL_HEADER_BYTES, 32u, &m);
    put_bytes(buf, pil_frame_seal(buf, sizeof buf, PIL_EMU, 0u, n));
}

void pil_m4_resume(void)
{
    uint32_t b = PIL_M4_SCRATCH(PIL_M4_SCRATCH(PIL_M4_STEPPING) ? PIL_M4_STEP_BUDGET : PIL_M4_BOOT_BUDGET);
    PIL_M4_SCRATCH(PIL_M4_FIRST_MARK) = PIL_M4_SCRATCH(PIL_M4_LAST_MARK) = 0u;
    PIL_M4_SYST_RVR = b == 0u || b > PIL_M4_SYST_MAX + 1u ? PIL_M4_SYST_MAX : b - 1u;
    PIL_M4_SYST_CVR = 0u;
    PIL_M4_SYST_CSR = PIL_M4_SYST_RUN;
}

/* A PEEK's bytes (those inside the SRAM), streamed as a MEMORY frame. */
static void answer_peek(const uint8_t *frame, uint16_t n)
{
    pil_frame_t f;
    pil_peek_t q = { 0u, 0u };
    uint8_t head[PIL_HEADER_BYTES], crc[2];
    uint32_t len = 0u;
    if (pil_frame_check(frame, n, &f) == PIL_FRAME_OK && pil_peek_decode(f.payload, f.len, &q) == 0
        && q.addr >= PIL_M4_RAM_START && q.addr < PIL_M4_RAM_END) {
        len = PIL_M4_RAM_END - q.addr < q.len ? PIL_M4_RAM_END - q.addr : q.len;
    }
    const uint8_t *at = (const uint8_t *)(uintptr_t)q.addr;
    head[0] = PIL_MAGIC;
    head[1] = PIL_VERSION;
    head[2] = PIL_MEMORY;
    head[3] = 0u;
    pil_put_u16(head + 4, (uint16_t)len);
    uint16_t c = telemetry_crc16(0xFFFFu, head, PIL_HEADER_BYTES);
    c = len ? telemetry_crc16(c, at, (uint16_t)len) : c;
    pil_put_u16(crc, c);
    put_bytes(head, PIL_HEADER_BYTES);
    put_bytes(at, len);
    put_bytes(crc, 2u);
}

void pil_port_exchange(uint8_t *mailbox, uint16_t cap, uint16_t len)
{
    pil_m4_report(PIL_EMU_FRAME, 0u);
    put_bytes(mailbox, len);
    for (;;) {
        /* The answer's header, then as many bytes as it says (only the
         * header when it is not a frame's: the robot's check says so). */
        uint16_t k, n;
        for (k = 0u; k < PIL_HEADER_BYTES; k++) {
            mailbox[k < cap ? k : cap - 1u] = get_byte();
        }
        n = pil_frame_size(mailbox);
        n = n < PIL_HEADER_BYTES ? PIL_HEADER_BYTES : n;
        for (; k < n; k++) {
            uint8_t b = get_byte();
            if (k < cap) {
                mailbox[k] = b;
            }
        }
        if (mailbox[2] == PIL_PEEK && n <= cap) {
            answer_peek(mailbox, n);
            continue;
        }
        if (mailbox[2] == PIL_STEP) {
            PIL_M4_SCRATCH(PIL_M4_STEPPING) = 1u;
        }
        break;
    }
    pil_m4_resume();
}

void pil_port_mark(void)
{
    uint32_t v = PIL_M4_SYST_CVR;
    v = v == 0u ? PIL_M4_SYST_RVR + 1u : v;   /* before the first tick: none elapsed */
    if (PIL_M4_SCRATCH(PIL_M4_FIRST_MARK) == 0u) {
        PIL_M4_SCRATCH(PIL_M4_FIRST_MARK) = v;
    }
    PIL_M4_SCRATCH(PIL_M4_LAST_MARK) = v;
}
