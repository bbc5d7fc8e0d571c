/*
 * pil_port_m4.c - pil_port_exchange on QEMU's netduinoplus2: a mailbox and
 * a doorbell, as on the emulated AVR (platforms/pil_avr/hal/pil_port_avr.c),
 * here ARM semihosting's trap (`bkpt 0xAB`), which QEMU serves between two
 * instructions: it writes the robot's frame to its standard output in one
 * write, reads the simulator's answer from its standard input straight
 * into the mailbox, and resumes the core.  The core is stopped meanwhile,
 * so an exchange costs the robot the trap's instruction, not a byte loop.
 * Not USART1: QEMU's USART (no baud timing) takes a byte per main-loop turn
 * of the emulator, 60 forager steps took 1.3 s over it and take 0.2 s so
 * (a 3,200-byte camera frame 145 ms a step over it, 2 ms so), and a UART
 * would charge the core a loop per byte that no real robot spends on its
 * sensors.
 *
 * Before each of its frames the robot sends an EMU frame (pil_msg.h) as the
 * AVR's emulator does, because QEMU, unlike simavr, is a program we only
 * talk to: the instructions it ran since the last answer (the SysTick,
 * counting the core clock; with `-icount shift=0` one instruction is one
 * emulated nanosecond: PIL_M4_TICKS_TO_INSNS), its marks, the stack used
 * (painting) and the instructions since reset.  The SysTick is stopped
 * from the report to the answer, so neither the report nor the exchange
 * is counted.  Its reload is the exchange's budget: running past it takes
 * the SysTick exception, which reports PIL_EMU_BUDGET and halts
 * (pil_m4_startup.c).  A PEEK that comes while it waits is answered from
 * its own SRAM with a MEMORY frame, uncounted, as a debugger's read is.
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

/* ARM semihosting (the `bkpt 0xAB` trap, which QEMU serves itself):
 * the operation in r0, its argument block in r1, the result in r0. */
#define PIL_M4_SYS_OPEN 0x01u
#define PIL_M4_SYS_WRITE 0x05u
#define PIL_M4_SYS_READ 0x06u
static uint32_t semihost(uint32_t op, const uint32_t *args)
{
    register uint32_t r0 __asm__("r0") = op;
    register const uint32_t *r1 __asm__("r1") = args;
    __asm__ __volatile__("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* QEMU's standard input or output, opened once (its handle in a scratch
 * word, +1: 0 is none yet). */
static uint32_t handle(uint32_t word, const char *path, uint32_t len, uint32_t mode)
{
    if (PIL_M4_SCRATCH(word) == 0u) {
        const uint32_t args[3] = { (uint32_t)(uintptr_t)path, mode, len };
        PIL_M4_SCRATCH(word) = semihost(PIL_M4_SYS_OPEN, args) + 1u;
    }
    return PIL_M4_SCRATCH(word) - 1u;
}

static void put_bytes(const uint8_t *p, uint32_t n)
{
    uint32_t h = handle(PIL_M4_OUT, "/proc/self/fd/1", 15u, 8u /* "a" */);
    while (n > 0u) {
        const uint32_t args[3] = { h, (uint32_t)(uintptr_t)p, n };
        uint32_t left = semihost(PIL_M4_SYS_WRITE, args);
        if (left >= n) {
            pil_m4_halt();    /* the simulator has gone */
        }
        p += n - left;
        n = left;
    }
}

static void get_bytes(uint8_t *p, uint32_t n)
{
    uint32_t h = handle(PIL_M4_IN, "/proc/self/fd/0", 15u, 1u /* "rb" */);
    while (n > 0u) {
        const uint32_t args[3] = { h, (uint32_t)(uintptr_t)p, n };
        uint32_t left = semihost(PIL_M4_SYS_READ, args);
        if (left >= n) {
            pil_m4_halt();    /* the end of its input */
        }
        p += n - left;
        n = left;
    }
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
    if (len) {
        put_bytes(at, len);
    }
    put_bytes(crc, 2u);
}

void pil_port_exchange(uint8_t *mailbox, uint16_t cap, uint16_t len)
{
    pil_m4_report(PIL_EMU_FRAME, 0u);
    put_bytes(mailbox, len);
    for (;;) {
        /* The answer's header, then as many bytes as it says (only the
         * header when it is not a frame's: the robot's check says so);
         * what does not fit the mailbox is read and dropped. */
        uint8_t head[PIL_HEADER_BYTES];
        get_bytes(head, PIL_HEADER_BYTES);
        uint16_t n = pil_frame_size(head), k;
        n = n < PIL_HEADER_BYTES ? PIL_HEADER_BYTES : n;
        for (k = 0u; k < PIL_HEADER_BYTES; k++) {
            mailbox[k < cap ? k : cap - 1u] = head[k];
        }
        uint16_t fits = n <= cap ? n : cap;
        get_bytes(mailbox + PIL_HEADER_BYTES, (uint32_t)(fits - PIL_HEADER_BYTES));
        for (k = fits; k < n; k++) {
            get_bytes(head, 1u);
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
