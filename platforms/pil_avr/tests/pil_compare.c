/*
 * pil_compare.c - runs one image on the emulated ATmega2560 and, beside
 * it, the same image built for this PC, each served by its own scripted
 * world of the same seed (pil_script.h), and compares them step by step:
 * every request, its order, and every actuator frame (wheels, LEDs,
 * speaker, IR messages, telemetry bytes).  The first difference is named
 * with its step and both sides' logs, and the exit is 1.  It also reports
 * what the emulator measured: cycles per step and the stack's high-water
 * mark (painting).
 *
 *   pil_compare (--emu EMU --avr IMAGE.elf | --m4 IMAGE.elf) [--host IMAGE_EXE] [--steps N]
 *               [--seed S] [--robot ID] [--frames] [--budget CYCLES]
 *               [--corrupt STEP:KIND] [--kill-at STEP] [--stop-at STEP]
 *               [--timeout MS] [--expect TEXT] [--json FILE] [--cycles FILE.csv]
 *
 * --m4 runs the image's Cortex-M4F build on QEMU (platforms/pil_m4/) in
 * place of the AVR's; its counts are then instructions, not cycles.
 * --corrupt damages the simulator's STEP frame of that step before the
 * AVR gets it (KIND crc, version, type, seq, length): the robot must
 * answer FAULT and the run stop with an error naming robot and step.
 * --kill-at kills the emulator (SIGKILL) before that step, --stop-at stops
 * it (SIGSTOP: a hung emulator, caught by the wall-time bound --timeout,
 * ms a read may wait once the first frame came; that one may take 60 s).
 * --expect TEXT: the run must fail, with TEXT in its error (exit 0 then).
 * --json: the measurement, one object; --cycles: each step's cycles, and
 * those of its controller's step (to the run loop's mark), as CSV.
 */
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "pil/pil_host.h"
#include "pil_avr_link.h"
#include "pil_m4_link.h"
#include "pil_script.h"

typedef struct side {
    const char *name;
    pil_avr_link_t link;
    pil_host_t host;
    pil_script_t script;
    pil_host_ops_t ops;
} side_t;

typedef struct corrupt {
    long step;
    char kind[16];
} corrupt_t;

/* The AVR side's io, which may damage one STEP frame on its way. */
typedef struct damaging_io {
    pil_host_io_t inner;
    const corrupt_t *c;
    uint32_t *step;
} damaging_io_t;

static int damaging_send(void *ctx, const uint8_t *frame, uint16_t len, char *err)
{
    damaging_io_t *d = ctx;
    uint8_t copy[PIL_FRAME_MAX];
    if (d->c->step < 0 || (long)*d->step != d->c->step || frame[2] != PIL_STEP) {
        return d->inner.send(d->inner.ctx, frame, len, err);
    }
    memcpy(copy, frame, len);
    if (!strcmp(d->c->kind, "crc")) {
        copy[len - 1] ^= 0x5Au;
    } else if (!strcmp(d->c->kind, "version")) {
        copy[1] = PIL_VERSION + 1u;
    } else if (!strcmp(d->c->kind, "type")) {
        copy[2] = PIL_REPLY;
        uint16_t crc_at = (uint16_t)(len - 2u);
        (void)pil_frame_seal(copy, sizeof copy, PIL_REPLY, copy[3], (uint16_t)(crc_at - PIL_HEADER_BYTES));
    } else if (!strcmp(d->c->kind, "seq")) {
        (void)pil_frame_seal(copy, sizeof copy, PIL_STEP, (uint8_t)(copy[3] + 7u),
                             (uint16_t)(len - PIL_HEADER_BYTES - PIL_CRC_BYTES));
    } else if (!strcmp(d->c->kind, "length")) {
        /* A STEP whose payload is one byte short of its layout. */
        (void)pil_frame_seal(copy, sizeof copy, PIL_STEP, copy[3], (uint16_t)(len - PIL_HEADER_BYTES - PIL_CRC_BYTES - 1u));
        len = (uint16_t)(len - 1u);
    }
    return d->inner.send(d->inner.ctx, copy, len, err);
}

static int damaging_recv(void *ctx, uint8_t *buf, uint16_t cap, uint16_t *len, pil_emu_t *emu, char *err)
{
    damaging_io_t *d = ctx;
    return d->inner.recv(d->inner.ctx, buf, cap, len, emu, err);
}

static void usage(void)
{
    fprintf(stderr, "usage: pil_compare (--emu EMU --avr IMAGE.elf | --m4 IMAGE.elf) [--host IMAGE_EXE] [--steps N] [--seed S] "
                    "[--robot ID] [--frames] [--budget CYCLES] [--corrupt STEP:KIND] [--kill-at STEP] [--stop-at STEP] "
                    "[--timeout MS] [--expect TEXT] [--json FILE] [--cycles FILE.csv]\n");
    exit(2);
}

static long number(const char *s)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < 0) {
        fprintf(stderr, "pil_compare: '%s' is not a whole number >= 0\n", s);
        exit(2);
    }
    return v;
}

/* Boots one side; 0, or -1 with err. */
static int boot(side_t *s, char *err)
{
    char e[PIL_HOST_ERR];
    if (pil_host_hello(&s->host, e) != 0) {
        snprintf(err, 512, "%s robot %u, boot: %s", s->name, s->script.robot, e);
        return -1;
    }
    s->script.period_ms = s->host.hello.period_ms;
    s->host.config = pil_script_config(&s->script, &s->host.hello);
    if (pil_host_config(&s->host, e) != 0) {
        snprintf(err, 512, "%s robot %u, boot: %s", s->name, s->script.robot, e);
        return -1;
    }
    s->ops = pil_script_ops(&s->script);
    return 0;
}

static int step(side_t *s, char *err)
{
    char e[PIL_HOST_ERR];
    pil_act_t act;
    uint32_t k = s->script.step;
    pil_step_t st = pil_script_begin(&s->script);
    if (pil_host_step(&s->host, &st, &s->ops, &act, e) != 0) {
        snprintf(err, 512, "%s robot %u, step %u: %s", s->name, s->script.robot, k, e);
        return -1;
    }
    pil_script_end(&s->script, &act);
    return 0;
}

int main(int argc, char **argv)
{
    const char *emu = NULL, *avr = NULL, *m4 = NULL, *host = NULL, *expect = NULL, *json = NULL, *cycles_path = NULL;
    long steps = 200, seed = 1, robot = 3, budget = 0, kill_at = -1, stop_at = -1, timeout = 0;
    int frames = 0;
    corrupt_t corrupt = { .step = -1 };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (i + 1 >= argc && strcmp(a, "--frames")) {
            usage();
        }
        if (!strcmp(a, "--emu")) emu = argv[++i];
        else if (!strcmp(a, "--avr")) avr = argv[++i];
        else if (!strcmp(a, "--m4")) m4 = argv[++i];
        else if (!strcmp(a, "--host")) host = argv[++i];
        else if (!strcmp(a, "--steps")) steps = number(argv[++i]);
        else if (!strcmp(a, "--seed")) seed = number(argv[++i]);
        else if (!strcmp(a, "--robot")) robot = number(argv[++i]);
        else if (!strcmp(a, "--budget")) budget = number(argv[++i]);
        else if (!strcmp(a, "--kill-at")) kill_at = number(argv[++i]);
        else if (!strcmp(a, "--stop-at")) stop_at = number(argv[++i]);
        else if (!strcmp(a, "--timeout")) timeout = number(argv[++i]);
        else if (!strcmp(a, "--frames")) frames = 1;
        else if (!strcmp(a, "--expect")) expect = argv[++i];
        else if (!strcmp(a, "--json")) json = argv[++i];
        else if (!strcmp(a, "--cycles")) cycles_path = argv[++i];
        else if (!strcmp(a, "--corrupt")) {
            const char *c = argv[++i], *colon = strchr(c, ':');
            if (!colon || strlen(colon + 1) >= sizeof corrupt.kind) usage();
            char num[24];
            snprintf(num, sizeof num, "%.*s", (int)(colon - c), c);
            corrupt.step = number(num);
            snprintf(corrupt.kind, sizeof corrupt.kind, "%s", colon + 1);
        } else usage();
    }
    if ((!emu || !avr) == !m4) {
        usage();
    }
    static side_t sides[2];
    side_t *a = &sides[0], *h = host ? &sides[1] : NULL;
    static char err[2 * PIL_SCRIPT_LOG + 512] = "";
    int failed = 0;
    damaging_io_t dio;

    a->name = m4 ? "m4" : "avr";
    const char *mcu = m4 ? "the M4" : "the AVR";
    pil_avr_link_def_t def = pil_avr_link_default_def();
    def.emulator = emu;
    def.image = avr;
    if (budget > 0) {
        def.budget = (uint64_t)budget;
    }
    if (timeout > 0) {
        def.timeout_ms = (int)timeout;
    }
    char e[PIL_HOST_ERR];
    pil_m4_link_def_t m4def = { .image = m4, .budget = budget > 0 ? (uint64_t)budget : 100000000u,
                                .boot_budget = 0u, .timeout_ms = def.timeout_ms };
    if ((m4 ? pil_m4_link_open(&a->link, &m4def, e) : pil_avr_link_open(&a->link, &def, e)) != 0) {
        fprintf(stderr, "pil_compare: %s\n", e);
        return 2;
    }
    pil_script_init(&a->script, (uint64_t)seed, (uint32_t)robot, 100, frames);
    dio.inner = pil_avr_link_io(&a->link);
    dio.c = &corrupt;
    dio.step = &a->script.step;
    pil_host_io_t io = { .ctx = &dio, .send = damaging_send, .recv = damaging_recv };
    pil_host_init(&a->host, &io);
    if (h) {
        h->name = "host";
        pil_avr_link_def_t hd = def;
        hd.emulator = host;
        hd.image = host;
        if (pil_avr_link_open(&h->link, &hd, e) != 0) {
            fprintf(stderr, "pil_compare: %s\n", e);
            return 2;
        }
        pil_script_init(&h->script, (uint64_t)seed, (uint32_t)robot, 100, frames);
        pil_host_io_t hio = pil_avr_link_io(&h->link);
        pil_host_init(&h->host, &hio);
    }

    uint64_t cycles_sum = 0, cycles_max = 0, requests = 0, control_sum = 0, control_max = 0;
    long done = 0;
    FILE *csv = cycles_path ? fopen(cycles_path, "w") : NULL;
    if (cycles_path && !csv) {
        fprintf(stderr, "pil_compare: %s: %s\n", cycles_path, strerror(errno));
        return 2;
    }
    if (csv) {
        fprintf(csv, "step,cycles,control_cycles\n");
    }
    failed = boot(a, err) != 0 || (h && boot(h, err) != 0);
    if (!failed && h && (memcmp(&a->host.hello, &h->host.hello, sizeof a->host.hello) != 0
                         && (strcmp(a->host.hello.name, h->host.hello.name)
                             || a->host.hello.flags != h->host.hello.flags))) {
        snprintf(err, sizeof err, "the two builds say different things in HELLO");
        failed = 1;
    }
    for (; !failed && done < steps; done++) {
        if (done == kill_at || done == stop_at) {
            kill(a->link.pid, done == kill_at ? SIGKILL : SIGSTOP);
            /* kill returns before every thread of the emulator (QEMU's
             * are several) has stopped: one still running could answer
             * this step.  The stop is whole when waitpid reports it. */
            int st;
            while (done == stop_at && waitpid(a->link.pid, &st, WUNTRACED) < 0 && errno == EINTR) {
            }
            /* A kill is whole when the emulator is a zombie (its pipes
             * closed): the step then always meets a dead robot, at its
             * send (EPIPE) or its read (end of file), never a live one.
             * WNOWAIT leaves the status for the link to report. */
            siginfo_t info;
            while (done == kill_at && waitid(P_PID, (id_t)a->link.pid, &info, WEXITED | WNOWAIT) < 0
                   && errno == EINTR) {
            }
        }
        if (step(a, err) != 0 || (h && step(h, err) != 0)) {
            failed = 1;
            break;
        }
        cycles_sum += a->host.step_cycles;
        cycles_max = a->host.step_cycles > cycles_max ? a->host.step_cycles : cycles_max;
        requests += a->host.requests;
        control_sum += a->host.control_cycles;
        control_max = a->host.control_cycles > control_max ? a->host.control_cycles : control_max;
        if (csv) {
            fprintf(csv, "%ld,%" PRIu64 ",%" PRIu64 "\n", done, a->host.step_cycles, a->host.control_cycles);
        }
        if (h && (a->script.log_len != h->script.log_len || memcmp(a->script.log, h->script.log, a->script.log_len))) {
            snprintf(err, sizeof err, "image %s robot %ld, step %ld: %s and the host build differ\n"
                     "--- host\n%s--- %s\n%s", a->host.hello.name, robot, done, mcu, h->script.log, a->name,
                     a->script.log);
            failed = 1;
        }
    }
    if (csv) {
        fclose(csv);
    }
    pil_avr_link_close(&a->link);
    if (h) {
        pil_avr_link_close(&h->link);
    }
    if (expect) {
        if (failed && strstr(err, expect)) {
            printf("pil_compare: failed as expected: %s\n", err);
            return 0;
        }
        fprintf(stderr, "pil_compare: expected an error with \"%s\", got %s\n", expect, failed ? err : "none");
        return 1;
    }
    if (failed) {
        fprintf(stderr, "pil_compare: %s\n", err);
        return 1;
    }
    printf("image %-12s %ld steps%s: %s; %s per step mean %.0f max %" PRIu64 " (boot %" PRIu64
           "), stack %u bytes, %.2f requests per step, %" PRIu64 " telemetry bytes\n",
           a->host.hello.name, done, frames ? " (camera frames)" : "",
           h ? (m4 ? "identical on the M4 and the host build" : "identical on the AVR and the host build")
             : (m4 ? "ran on the M4" : "ran on the AVR"), m4 ? "instructions" : "cycles",
           done ? (double)cycles_sum / (double)done : 0.0, cycles_max, a->host.boot_cycles, a->host.emu.stack_max,
           done ? (double)requests / (double)done : 0.0, a->script.telemetry_bytes);
    if (json) {
        FILE *f = fopen(json, "w");
        if (!f) {
            fprintf(stderr, "pil_compare: %s: %s\n", json, strerror(errno));
            return 1;
        }
        fprintf(f, "{\"image\": \"%s\", \"controller\": \"%s\", \"frames\": %d, \"steps\": %ld, "
                   "\"cycles_mean\": %.1f, \"cycles_max\": %" PRIu64 ", \"control_mean\": %.1f, "
                   "\"control_max\": %" PRIu64 ", \"boot_cycles\": %" PRIu64 ", "
                   "\"stack_bytes\": %u, \"requests_per_step\": %.3f}\n",
                a->host.hello.name, a->host.hello.controller, frames, done,
                done ? (double)cycles_sum / (double)done : 0.0, cycles_max,
                done ? (double)control_sum / (double)done : 0.0, control_max, a->host.boot_cycles,
                a->host.emu.stack_max, done ? (double)requests / (double)done : 0.0);
        fclose(f);
    }
    return 0;
}
