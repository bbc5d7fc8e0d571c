/*
 * pil_avr_emu.c - one emulated ATmega2560 running a PIL image, driven by
 * the simulator over a pipe (processor-in-the-loop, docs/reference/pil.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * This program links simavr's libsimavr, which is GPL-3.0, so this file
 * and the program built from it are GPL-3.0-or-later (platforms/pil_avr/
 * emu/COPYING).  Nothing else in the project links libsimavr: the
 * simulator (MIT) starts this program and talks to it through its standard
 * input and output, so the two are separate programs and the simulator's
 * licence is unchanged.
 *
 *   pil_avr_emu [--budget CYCLES] [--boot-budget CYCLES] IMAGE.elf
 *
 * --boot-budget bounds each exchange until the first STEP (reset to HELLO,
 * CONFIG to READY: the C runtime and the controller's init), --budget each
 * one after (a step's, or a request's within it).
 *
 * The image's frames (wire/pil/pil_frame.h) pass through unchanged: when
 * the MCU rings its doorbell (platforms/pil_avr/hal/pil_port_avr.c) the
 * core stops before its next instruction; this program writes an EMU frame
 * (pil_msg.h: why the core stopped, the cycles it ran since it was
 * resumed, the stack it has used, by painting) and then the MCU's frame to
 * standard output (the EMU frame also says when the robot marked the end of
 * its controller's step, a write of PIL_AVR_MARK that does not stop it),
 * reads the simulator's next frame from standard input
 * into the mailbox and resumes the core.  When the core runs past its
 * cycle budget without ringing, crashes (simavr's crashed state: an access
 * outside RAM, the PC past the flash), jumps to the reset vector, halts
 * (sleep with interrupts off) or its stack runs into its static data, the
 * EMU frame says which, no MCU frame follows, and the program exits 3.  At
 * the end of its input it exits 0.  While the core is stopped the simulator
 * may read its RAM (a PEEK frame, answered with a MEMORY frame: a
 * debugger's read, which costs the core nothing): it mirrors the
 * controller's state so.  Its own errors (no image, a bad
 * option) are a line on standard error and exit 2.
 *
 * The stack is painted: every byte between the end of the image's static
 * data (__bss_end, or __heap_start, __noinit_end when higher) and the top of RAM is PIL_AVR_PAINT before the core
 * starts, and after each exchange the lowest byte that is not is the
 * stack's high-water mark.  (A stack byte that happens to hold the paint
 * value at the very bottom is not seen: the usual caveat.)
 *
 * simavr's own messages go to standard error; standard output carries
 * frames only.
 */
#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_io.h>

#include "pil/pil_frame.h"
#include "pil/pil_msg.h"
#include "pil_port_avr.h"

/** The paint the stack area is filled with before the core starts. */
#define PIL_AVR_PAINT 0xA5u
/** The core's clock, Hz (the ATmega2560's largest). */
#define PIL_AVR_HZ 16000000u
/** Stack pointer's data-space addresses. */
#define SPL 0x5Du
#define SPH 0x5Eu

typedef struct emu {
    avr_t *avr;
    int out;                  /**< the protocol's output (standard output, moved) */
    uint64_t budget, boot_budget;
    uint16_t heap_start;      /**< first byte above the static data */
    int rang;
    uint64_t resumed;         /**< the cycle the core was last resumed at */
    uint64_t first_mark, last_mark;   /**< the cycles of its first and last mark since, 0: none */
    int stepping;             /**< a STEP has been delivered: the step budget applies, not the boot's */
    uint8_t frame[PIL_FRAME_MAX];
} emu_t;

static void die(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("pil_avr_emu: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(2);
}

/* simavr's messages, to standard error (standard output is the protocol's). */
static void logger(avr_t *avr, const int level, const char *fmt, va_list ap)
{
    if (level <= (avr ? avr->log : LOG_ERROR)) {
        vfprintf(stderr, fmt, ap);
    }
}

static void bell(avr_t *avr, avr_io_addr_t addr, uint8_t v, void *param)
{
    emu_t *e = param;
    avr->data[addr] = v;
    if (v == PIL_AVR_BELL) {
        e->rang = 1;
    } else if (v == PIL_AVR_MARK) {
        e->first_mark = e->first_mark ? e->first_mark : avr->cycle;
        e->last_mark = avr->cycle;
    }
}

static void write_all(int fd, const uint8_t *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            exit(0);   /* the simulator has gone: nothing to tell */
        }
        p += k;
        n -= (size_t)k;
    }
}

/* 1 with n bytes read, 0 at the end of the input before any byte. */
static int read_all(uint8_t *p, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = read(0, p + got, n - got);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            if (got == 0) {
                return 0;
            }
            die("the simulator's frame ended after %zu of %zu bytes", got, n);
        }
        got += (size_t)k;
    }
    return 1;
}

static uint16_t stack_max(const emu_t *e)
{
    const avr_t *avr = e->avr;
    uint32_t a = e->heap_start;
    while (a <= avr->ramend && avr->data[a] == PIL_AVR_PAINT) {
        a++;
    }
    return (uint16_t)(avr->ramend + 1u - a);
}

static void report(emu_t *e, uint8_t event, uint64_t cycles)
{
    uint8_t buf[PIL_FRAME_BYTES(32u)];
    pil_emu_t m;
    m.event = event;
    m.cycles = cycles > UINT32_MAX ? UINT32_MAX : (uint32_t)cycles;
    m.total = e->avr->cycle;
    m.stack_max = stack_max(e);
    m.pc = e->avr->pc;
    m.first_mark = e->first_mark ? (uint32_t)(e->first_mark - e->resumed) : PIL_NO_MARK;
    m.last_mark = e->last_mark ? (uint32_t)(e->last_mark - e->resumed) : PIL_NO_MARK;
    uint16_t n = pil_emu_encode(buf + PIL_HEADER_BYTES, 32u, &m);
    write_all(e->out, buf, pil_frame_seal(buf, sizeof buf, PIL_EMU, 0u, n));
}

static void fatal(emu_t *e, uint8_t event, uint64_t cycles)
{
    report(e, event, cycles);
    exit(3);
}

/* Runs the core until it rings; reports and exits on anything else. */
static void run(emu_t *e, uint64_t budget)
{
    avr_t *avr = e->avr;
    uint64_t start = avr->cycle;
    e->rang = 0;
    e->resumed = start;
    e->first_mark = e->last_mark = 0;
    while (!e->rang) {
        int state = avr_run(avr);
        uint64_t ran = avr->cycle - start;
        if (state == cpu_Crashed) {
            fatal(e, PIL_EMU_CRASH, ran);
        }
        if (state == cpu_Done || state == cpu_Stopped) {
            fatal(e, PIL_EMU_HALT, ran);
        }
        if (avr->pc == 0 && avr->cycle > 0) {
            fatal(e, PIL_EMU_RESET, ran);
        }
        uint16_t sp = (uint16_t)(avr->data[SPL] | (avr->data[SPH] << 8));
        if (sp < e->heap_start) {
            fatal(e, PIL_EMU_STACK, ran);
        }
        if (ran > budget) {
            fatal(e, PIL_EMU_BUDGET, ran);
        }
    }
}

/* The frame the MCU rang with: its descriptor (pil_port_avr.c), checked
 * against the RAM, then the frame itself, to the simulator. */
static void hand_over(emu_t *e, uint64_t cycles, uint16_t *mailbox, uint16_t *cap)
{
    avr_t *avr = e->avr;
    uint16_t d = (uint16_t)(avr->data[PIL_AVR_GPIOR1] | (avr->data[PIL_AVR_GPIOR2] << 8));
    if (d < 0x200u || (uint32_t)d + 6u > avr->ramend + 1u) {
        fatal(e, PIL_EMU_BAD_MAILBOX, cycles);
    }
    const uint8_t *desc = avr->data + d;
    *mailbox = pil_get_u16(desc);
    *cap = pil_get_u16(desc + 2);
    uint16_t len = pil_get_u16(desc + 4);
    if (*mailbox < 0x200u || *cap > PIL_FRAME_MAX || len > *cap || (uint32_t)*mailbox + *cap > avr->ramend + 1u) {
        fatal(e, PIL_EMU_BAD_MAILBOX, cycles);
    }
    report(e, PIL_EMU_FRAME, cycles);
    write_all(e->out, avr->data + *mailbox, len);
}

/* A PEEK: the bytes asked for (those inside RAM), in a MEMORY frame. */
static void peek(emu_t *e, const pil_frame_t *f)
{
    pil_peek_t q;
    uint8_t *out = e->frame;
    const avr_t *avr = e->avr;
    uint16_t n = 0;
    if (pil_peek_decode(f->payload, f->len, &q) == 0 && q.addr <= avr->ramend) {
        n = (uint16_t)(q.addr + q.len > avr->ramend + 1u ? avr->ramend + 1u - q.addr : q.len);
        memmove(out + PIL_HEADER_BYTES, avr->data + q.addr, n);
    }
    write_all(e->out, out, pil_frame_seal(out, sizeof e->frame, PIL_MEMORY, 0u, n));
}

/* The simulator's next frame into the mailbox: as many bytes as its header
 * says (only the header when that is not a frame's: the MCU will say so),
 * at most the mailbox's; PEEKs before it are answered.  0 at the end of
 * the input. */
static int take_answer(emu_t *e, uint16_t mailbox, uint16_t cap)
{
    uint8_t *f = e->frame;
    for (;;) {
        if (!read_all(f, PIL_HEADER_BYTES)) {
            return 0;
        }
        uint16_t n = pil_frame_size(f);
        if (n > PIL_HEADER_BYTES && !read_all(f + PIL_HEADER_BYTES, (size_t)(n - PIL_HEADER_BYTES))) {
            die("the simulator's input ended inside a frame");
        }
        if (n < PIL_HEADER_BYTES) {
            n = PIL_HEADER_BYTES;
        }
        pil_frame_t pf;
        if (f[2] == PIL_PEEK && pil_frame_check(f, n, &pf) == PIL_FRAME_OK) {
            peek(e, &pf);
            continue;
        }
        memcpy(e->avr->data + mailbox, f, n < cap ? n : cap);
        e->stepping |= f[2] == PIL_STEP;
        return 1;
    }
}

static uint64_t number(const char *opt, const char *s)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || end == s || *end || v == 0) {
        die("%s: '%s' is not a positive whole number of cycles", opt, s);
    }
    return v;
}

int main(int argc, char **argv)
{
    static emu_t e;
    const char *image = NULL;
    e.budget = 1600000u;          /* 100 ms at 16 MHz */
    e.boot_budget = 16000000u;    /* 1 s */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--budget") && i + 1 < argc) {
            e.budget = number("--budget", argv[++i]);
        } else if (!strcmp(argv[i], "--boot-budget") && i + 1 < argc) {
            e.boot_budget = number("--boot-budget", argv[++i]);
        } else if (argv[i][0] == '-' || image) {
            die("usage: pil_avr_emu [--budget CYCLES] [--boot-budget CYCLES] IMAGE.elf");
        } else {
            image = argv[i];
        }
    }
    if (!image) {
        die("usage: pil_avr_emu [--budget CYCLES] [--boot-budget CYCLES] IMAGE.elf");
    }
    /* Frames on the original standard output; anything else printed goes
     * to standard error. */
    e.out = dup(1);
    if (e.out < 0 || dup2(2, 1) < 0) {
        die("cannot set up its output: %s", strerror(errno));
    }
    avr_global_logger_set(logger);

    elf_firmware_t fw;
    memset(&fw, 0, sizeof fw);
    if (access(image, R_OK) != 0) {
        die("%s: %s", image, strerror(errno));
    }
    if (elf_read_firmware(image, &fw) != 0) {
        die("%s: not an AVR ELF image simavr can load", image);
    }
    e.avr = avr_make_mcu_by_name("atmega2560");
    if (!e.avr) {
        die("this libsimavr has no atmega2560");
    }
    avr_init(e.avr);
    e.avr->log = LOG_ERROR;
    fw.frequency = PIL_AVR_HZ;
    avr_load_firmware(e.avr, &fw);
    e.avr->frequency = PIL_AVR_HZ;
    for (uint32_t k = 0; k < fw.symbolcount; k++) {
        const char *name = fw.symbol[k]->symbol;
        uint16_t at = (uint16_t)(fw.symbol[k]->addr & 0xFFFFu);
        if ((!strcmp(name, "__heap_start") || !strcmp(name, "__bss_end") || !strcmp(name, "__noinit_end"))
            && at > e.heap_start) {
            e.heap_start = at;
        }
    }
    if (e.heap_start < 0x200u || e.heap_start > e.avr->ramend) {
        die("%s: no __bss_end symbol in RAM (is it an avr-gcc atmega2560 image?)", image);
    }
    memset(e.avr->data + e.heap_start, PIL_AVR_PAINT, (size_t)(e.avr->ramend + 1u - e.heap_start));
    avr_register_io_write(e.avr, PIL_AVR_GPIOR0, bell, &e);

    uint16_t mailbox, cap;
    uint64_t mark = e.avr->cycle;
    run(&e, e.boot_budget);
    for (;;) {
        hand_over(&e, e.avr->cycle - mark, &mailbox, &cap);
        if (!take_answer(&e, mailbox, cap)) {
            return 0;
        }
        mark = e.avr->cycle;
        run(&e, e.stepping ? e.budget : e.boot_budget);
    }
}
