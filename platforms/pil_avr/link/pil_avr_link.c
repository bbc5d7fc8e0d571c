/* pil_avr_link.c - pil_avr_link.h. */
#define _GNU_SOURCE
#include "pil_avr_link.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

pil_avr_link_def_t pil_avr_link_default_def(void)
{
    pil_avr_link_def_t d;
    memset(&d, 0, sizeof d);
    d.budget = 1600000u;
    d.boot_budget = 16000000u;
    d.timeout_ms = 20000;
    d.boot_timeout_ms = PIL_LINK_BOOT_TIMEOUT_MS;
    return d;
}

int pil_avr_link_open(pil_avr_link_t *l, const pil_avr_link_def_t *def, char err[PIL_HOST_ERR])
{
    int in[2], out[2];
    char budget[24], boot[24];
    memset(l, 0, sizeof *l);
    l->pid = -1;
    l->to = l->from = -1;
    l->timeout_ms = def->timeout_ms > 0 ? def->timeout_ms : 20000;
    l->boot_timeout_ms = def->boot_timeout_ms > 0 ? def->boot_timeout_ms : PIL_LINK_BOOT_TIMEOUT_MS;
    if (def->boot_timeout_ms <= 0 && l->boot_timeout_ms < l->timeout_ms) {
        l->boot_timeout_ms = l->timeout_ms;
    }
    snprintf(l->image, sizeof l->image, "%s", def->image);
    snprintf(l->what, sizeof l->what, "%s", def->what ? def->what : "pil_avr_emu");
    snprintf(l->unit, sizeof l->unit, "%s", def->unit ? def->unit : "cycles");
    if (def->argv) {
        /* Found on PATH by execvp; one that is not there exits 127. */
    } else if (access(def->emulator, X_OK) != 0) {
        snprintf(err, PIL_HOST_ERR, "the AVR emulator %s: %s (make pil-avr builds it; it needs simavr: "
                 "Debian's libsimavr-dev)", def->emulator, strerror(errno));
        return -1;
    }
    if (access(def->image, R_OK) != 0) {
        snprintf(err, PIL_HOST_ERR, "image %s: %s (make pil-avr builds the images)", def->image, strerror(errno));
        return -1;
    }
    if (pipe2(in, O_CLOEXEC) != 0) {
        snprintf(err, PIL_HOST_ERR, "pipe: %s", strerror(errno));
        return -1;
    }
    if (pipe2(out, O_CLOEXEC) != 0) {
        snprintf(err, PIL_HOST_ERR, "pipe: %s", strerror(errno));
        close(in[0]);
        close(in[1]);
        return -1;
    }
    snprintf(budget, sizeof budget, "%" PRIu64, def->budget);
    snprintf(boot, sizeof boot, "%" PRIu64, def->boot_budget);
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(err, PIL_HOST_ERR, "fork: %s", strerror(errno));
        close(in[0]); close(in[1]); close(out[0]); close(out[1]);
        return -1;
    }
    if (pid == 0) {
        /* Never outlive the simulator, even when it is killed. */
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent) {
            _exit(1);
        }
        dup2(in[0], 0);
        dup2(out[1], 1);
        if (def->argv) {
            execvp(def->argv[0], (char *const *)def->argv);
        } else {
            execl(def->emulator, def->emulator, "--budget", budget, "--boot-budget", boot, def->image, (char *)NULL);
        }
        _exit(127);
    }
    close(in[0]);
    close(out[1]);
    l->pid = pid;
    l->to = in[1];
    l->from = out[0];
    return 0;
}

void pil_avr_link_close(pil_avr_link_t *l)
{
    if (l->to >= 0) {
        close(l->to);
    }
    if (l->from >= 0) {
        close(l->from);
    }
    if (l->pid > 0) {
        kill(l->pid, SIGKILL);
        while (waitpid(l->pid, NULL, 0) < 0 && errno == EINTR) {
        }
    }
    l->to = l->from = -1;
    l->pid = -1;
}

/* Why the emulator is gone, for an error: its exit status (a process whose
 * output has closed is exiting: waited for up to a second). */
static void gone(pil_avr_link_t *l, char *err, const char *what)
{
    int status = 0;
    pid_t r = 0;
    /* Its pipes closed, it is dying: a busy machine can take seconds to
     * reap QEMU's threads, so wait up to 10 s for its status. */
    for (int k = 0; k < 1000 && r == 0; k++) {
        r = waitpid(l->pid, &status, WNOHANG);
        if (r == 0) {
            struct timespec ten_ms = { 0, 10000000 };
            nanosleep(&ten_ms, NULL);
        }
    }
    if (r == l->pid) {
        l->pid = -1;
        if (WIFSIGNALED(status)) {
            snprintf(err, PIL_HOST_ERR, "its emulator was killed by signal %d%s%s", WTERMSIG(status), *what ? " " : "",
                     what);
        } else if (WEXITSTATUS(status) == 127) {
            snprintf(err, PIL_HOST_ERR, "its emulator %s could not be started (is it installed?)", l->what);
        } else {
            snprintf(err, PIL_HOST_ERR, "its emulator exited (status %d)%s%s (its messages are on standard error)",
                     WEXITSTATUS(status), *what ? " " : "", what);
        }
    } else {
        snprintf(err, PIL_HOST_ERR, "its emulator closed its output%s%s", *what ? " " : "", what);
    }
}

static int64_t now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (int64_t)t.tv_sec * 1000 + t.tv_nsec / 1000000;
}

/* The wall time the next read may wait, ms: the first frame's, then a step's. */
static int read_bound(const pil_avr_link_t *l)
{
    return l->answered ? l->timeout_ms : l->boot_timeout_ms;
}

/* n bytes from the emulator, within the link's wall-time bound: 0, or -1. */
static int read_n(pil_avr_link_t *l, uint8_t *p, size_t n, int64_t deadline, char *err)
{
    int bound = read_bound(l);
    size_t got = 0;
    while (got < n) {
        int left = (int)(deadline - now_ms());
        struct pollfd pfd = { .fd = l->from, .events = POLLIN };
        if (left <= 0) {
            snprintf(err, PIL_HOST_ERR, "its emulator gave no answer within %d ms of wall time", bound);
            return -1;
        }
        int r = poll(&pfd, 1, left);
        if (r < 0 && errno == EINTR) {
            continue;
        }
        if (r < 0) {
            snprintf(err, PIL_HOST_ERR, "poll: %s", strerror(errno));
            return -1;
        }
        if (r == 0) {
            continue;
        }
        ssize_t k = read(l->from, p + got, n - got);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            gone(l, err, got ? "in the middle of a frame" : "");
            return -1;
        }
        got += (size_t)k;
    }
    return 0;
}

/* One frame: its header, then the rest its length says. */
static int read_frame(pil_avr_link_t *l, uint8_t *buf, uint16_t cap, uint16_t *len, int64_t deadline, char *err)
{
    if (read_n(l, buf, PIL_HEADER_BYTES, deadline, err) != 0) {
        return -1;
    }
    uint16_t n = pil_frame_size(buf);
    if (n == 0u || n > cap) {
        /* Not a frame's header: what there is, for the caller's check to name. */
        *len = PIL_HEADER_BYTES;
        return 0;
    }
    if (read_n(l, buf + PIL_HEADER_BYTES, (size_t)(n - PIL_HEADER_BYTES), deadline, err) != 0) {
        return -1;
    }
    *len = n;
    return 0;
}

/* A write into a pipe whose reader has died raises SIGPIPE, which kills
 * the simulator without a word.  Blocked around the write, it becomes
 * EPIPE (reported as the emulator's death), and the signal the write left
 * pending for this thread is taken back; one pending before is left. */
static ssize_t write_quietly(int fd, const void *buf, size_t n)
{
    sigset_t pipe_only, old, pending;
    sigemptyset(&pipe_only);
    sigaddset(&pipe_only, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_only, &old);
    int was_pending = sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1;
    ssize_t k = write(fd, buf, n);
    int saved = errno;
    if (k < 0 && saved == EPIPE && !was_pending) {
        struct timespec now = { 0, 0 };
        while (sigtimedwait(&pipe_only, NULL, &now) < 0 && errno == EINTR) {
        }
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    errno = saved;
    return k;
}

static int link_send(void *ctx, const uint8_t *frame, uint16_t len, char *err)
{
    pil_avr_link_t *l = ctx;
    size_t done = 0;
    while (done < len) {
        ssize_t k = write_quietly(l->to, frame + done, len - done);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            gone(l, err, "before it took the simulator's frame");
            return -1;
        }
        done += (size_t)k;
    }
    return 0;
}

static int link_recv(void *ctx, uint8_t *buf, uint16_t cap, uint16_t *len, pil_emu_t *emu, char *err)
{
    pil_avr_link_t *l = ctx;
    int64_t deadline = now_ms() + read_bound(l);
    pil_frame_t f;
    if (read_frame(l, buf, cap, len, deadline, err) != 0) {
        return -1;
    }
    l->answered = 1;
    if (pil_frame_check(buf, *len, &f) != PIL_FRAME_OK || f.type != PIL_EMU
        || pil_emu_decode(f.payload, f.len, emu) != 0) {
        snprintf(err, PIL_HOST_ERR, "its emulator sent something that is not its report (is %s this build's?)",
                 l->what);
        return -1;
    }
    if (emu->event != PIL_EMU_FRAME) {
        snprintf(err, PIL_HOST_ERR, "its MCU %s after %" PRIu32 " %s (pc 0x%05" PRIx32 ", %" PRIu64
                 " %s since reset, %u bytes of stack used)", pil_emu_event_name(emu->event), emu->cycles, l->unit,
                 emu->pc, emu->total, l->unit, emu->stack_max);
        return -1;
    }
    return read_frame(l, buf, cap, len, deadline, err);
}

int pil_avr_link_peek(pil_avr_link_t *l, uint32_t addr, uint16_t len, uint8_t *out, char err[PIL_HOST_ERR])
{
    uint8_t buf[PIL_FRAME_MAX];
    pil_peek_t q = { addr, len };
    pil_frame_t f;
    uint16_t n = pil_peek_encode(buf + PIL_HEADER_BYTES, 32u, &q);
    n = pil_frame_seal(buf, sizeof buf, PIL_PEEK, 0u, n);
    if (link_send(l, buf, n, err) != 0 || read_frame(l, buf, sizeof buf, &n, now_ms() + l->timeout_ms, err) != 0) {
        return -1;
    }
    if (pil_frame_check(buf, n, &f) != PIL_FRAME_OK || f.type != PIL_MEMORY || f.len != len) {
        snprintf(err, PIL_HOST_ERR, "its emulator did not answer a read of %u bytes at 0x%04" PRIx32 " (is the "
                 "emulator this build's?)", len, addr);
        return -1;
    }
    memcpy(out, f.payload, len);
    return 0;
}

pil_host_io_t pil_avr_link_io(pil_avr_link_t *l)
{
    pil_host_io_t io = { .ctx = l, .send = link_send, .recv = link_recv };
    return io;
}
