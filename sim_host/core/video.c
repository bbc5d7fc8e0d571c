/*
 * video.c - H.264 MP4 through an ffmpeg subprocess (video.h).
 *
 * Frames go to ffmpeg's standard input over a Unix socket pair rather than
 * a pipe: send() with MSG_NOSIGNAL reports a dead reader as EPIPE, where a
 * pipe would raise SIGPIPE and kill the whole simulator (ignoring SIGPIPE
 * instead would change the process for every other thread).  ffmpeg is
 * started with posix_spawnp and an argument vector, so no shell ever reads
 * the file name.  Its messages go to an anonymous temporary file and are
 * quoted when it fails.  It runs in its own process group with no signal
 * blocked: a Ctrl-C at the terminal reaches the simulator only, which then
 * ends the stream (and drops the file) itself, and a mask a worker thread
 * may hold does not reach ffmpeg.
 */
#include "video.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* x264 at its default quality (crf 23) with a faster preset: the pictures
 * are flat colours that compress well, and the run should not wait on the
 * encoder more than necessary. */
#define X264_PRESET "veryfast"
#define X264_CRF "23"

struct video {
    pid_t pid;
    int fd;             /**< our end of ffmpeg's standard input */
    FILE *log;          /**< ffmpeg's standard error */
    size_t frame_bytes;
    uint64_t frames;
    char *path, *tmp;   /**< owned */
    int dead;           /**< ffmpeg was reaped (status in `status`) */
    int status;
};

int video_find_ffmpeg(char *err)
{
    const char *path = getenv("PATH");
    if (!path || !*path) {
        path = "/usr/bin:/bin";   /* posix_spawnp's default search */
    }
    char buf[4096];
    for (const char *p = path; *p;) {
        const char *end = strchr(p, ':');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        int len = snprintf(buf, sizeof buf, "%.*s/ffmpeg", (int)(n ? n : 1), n ? p : ".");
        struct stat st;
        if (len > 0 && (size_t)len < sizeof buf && stat(buf, &st) == 0 && S_ISREG(st.st_mode)
            && access(buf, X_OK) == 0) {
            return 0;
        }
        p += n + (end ? 1 : 0);
    }
    snprintf(err, SIM_ERR_MAX, "--video needs ffmpeg, which is not on PATH "
             "(Debian package ffmpeg: apt-get install ffmpeg, or make deps)");
    return -1;
}

/* The last line ffmpeg wrote on its standard error, or "". */
static void last_words(FILE *log, char *out, size_t size)
{
    char buf[512];
    out[0] = '\0';
    if (!log || fseek(log, 0, SEEK_END) != 0) {
        return;
    }
    long end = ftell(log);
    long start = end > (long)sizeof buf - 1 ? end - (long)sizeof buf + 1 : 0;
    if (end <= 0 || fseek(log, start, SEEK_SET) != 0) {
        return;
    }
    size_t n = fread(buf, 1, sizeof buf - 1, log);
    buf[n] = '\0';
    while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == '\r' || buf[n - 1] == ' ')) {
        buf[--n] = '\0';
    }
    const char *line = strrchr(buf, '\n');
    line = line ? line + 1 : buf;
    size_t len = strlen(line) < size ? strlen(line) : size - 1;
    memcpy(out, line, len);
    out[len] = '\0';
}

/* Waits for ffmpeg once and keeps its status. */
static void reap(video_t *v)
{
    if (v->dead) {
        return;
    }
    int st = 0;
    while (waitpid(v->pid, &st, 0) < 0 && errno == EINTR) {
    }
    v->status = st;
    v->dead = 1;
}

/* "ffmpeg exited with status 1: <its last line>" and the like. */
static void describe_exit(const video_t *v, char *err)
{
    char words[200];
    last_words(v->log, words, sizeof words);
    if (WIFEXITED(v->status) && WEXITSTATUS(v->status) == 0) {
        snprintf(err, SIM_ERR_MAX, "%s: ffmpeg stopped reading after %llu frame(s)%s%s", v->path,
                 (unsigned long long)v->frames, *words ? ": " : "", words);
    } else if (WIFEXITED(v->status)) {
        snprintf(err, SIM_ERR_MAX, "%s: ffmpeg exited with status %d after %llu frame(s)%s%s", v->path,
                 WEXITSTATUS(v->status), (unsigned long long)v->frames, *words ? ": " : "", words);
    } else {
        snprintf(err, SIM_ERR_MAX, "%s: ffmpeg was killed by signal %d after %llu frame(s)%s%s", v->path,
                 WIFSIGNALED(v->status) ? WTERMSIG(v->status) : 0, (unsigned long long)v->frames,
                 *words ? ": " : "", words);
    }
}

static void video_free(video_t *v)
{
    if (v->fd >= 0) {
        close(v->fd);
    }
    if (v->log) {
        fclose(v->log);
    }
    free(v->path);
    free(v->tmp);
    free(v);
}

video_t *video_open(const char *path, int w, int h, double fps, char *err)
{
    if (w <= 0 || h <= 0 || w % 2 || h % 2 || !(fps > 0.0)) {
        snprintf(err, SIM_ERR_MAX, "%s: a video needs even sizes and a positive rate, not %dx%d at %g fps",
                 path, w, h, fps);
        return NULL;
    }
    video_t *v = calloc(1, sizeof *v);
    size_t n = strlen(path);
    if (!v || !(v->path = strdup(path)) || !(v->tmp = malloc(n + 5))) {
        if (v) {
            free(v->path);
            free(v);
        }
        snprintf(err, SIM_ERR_MAX, "%s: out of memory", path);
        return NULL;
    }
    memcpy(v->tmp, path, n);
    memcpy(v->tmp + n, ".tmp", 5);
    v->fd = -1;
    v->frame_bytes = (size_t)w * (size_t)h * 3;

    char size[32], rate[32];
    snprintf(size, sizeof size, "%dx%d", w, h);
    snprintf(rate, sizeof rate, "%.6g", fps);
    char *argv[] = {
        "ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
        "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size", size, "-framerate", rate, "-i", "pipe:0",
        "-an", "-c:v", "libx264", "-preset", X264_PRESET, "-crf", X264_CRF, "-pix_fmt", "yuv420p",
        "-movflags", "+faststart", "-f", "mp4", v->tmp, NULL,
    };
    int sv[2] = { -1, -1 };
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t attr;
    int fa_ok = 0, attr_ok = 0, rc = -1;
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    sigaddset(&defaults, SIGPIPE);
    v->log = tmpfile();
    if (v->log && socketpair(AF_UNIX, SOCK_STREAM, 0, sv) == 0
        && fcntl(sv[0], F_SETFD, FD_CLOEXEC) == 0 && fcntl(sv[1], F_SETFD, FD_CLOEXEC) == 0
        && posix_spawn_file_actions_init(&fa) == 0) {
        fa_ok = 1;
        attr_ok = posix_spawnattr_init(&attr) == 0;
        /* dup2 clears close-on-exec on the child's copies only. */
        if (posix_spawn_file_actions_adddup2(&fa, sv[1], STDIN_FILENO) == 0
            && posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0) == 0
            && posix_spawn_file_actions_adddup2(&fa, fileno(v->log), STDERR_FILENO) == 0
            && attr_ok && posix_spawnattr_setpgroup(&attr, 0) == 0
            && posix_spawnattr_setsigmask(&attr, &none) == 0
            && posix_spawnattr_setsigdefault(&attr, &defaults) == 0
            && posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK
                                                   | POSIX_SPAWN_SETSIGDEF) == 0) {
            rc = posix_spawnp(&v->pid, "ffmpeg", &fa, &attr, argv, environ);
            if (rc != 0) {
                errno = rc;
                rc = -1;
            }
        }
    }
    int e = errno;
    if (fa_ok) {
        posix_spawn_file_actions_destroy(&fa);
    }
    if (attr_ok) {
        posix_spawnattr_destroy(&attr);
    }
    if (sv[1] >= 0) {
        close(sv[1]);
    }
    v->fd = sv[0];
    if (rc != 0) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot start ffmpeg: %s", path, strerror(e));
        video_free(v);
        return NULL;
    }
    return v;
}

int video_write(video_t *v, const uint8_t *rgb, char *err)
{
    size_t off = 0;
    while (off < v->frame_bytes) {
        ssize_t k = send(v->fd, rgb + off, v->frame_bytes - off, MSG_NOSIGNAL);
        if (k < 0 && errno == EINTR) {
            continue;
        }
        if (k <= 0) {
            int e = errno;
            if (e == EPIPE || e == ECONNRESET) {   /* ffmpeg is gone: say why */
                reap(v);
                describe_exit(v, err);
            } else {
                snprintf(err, SIM_ERR_MAX, "%s: cannot send a frame to ffmpeg: %s", v->path, strerror(e));
            }
            return -1;
        }
        off += (size_t)k;
    }
    v->frames++;
    return 0;
}

uint64_t video_frame_count(const video_t *v)
{
    return v ? v->frames : 0;
}

int video_close(video_t *v, int keep, char *err)
{
    if (!v) {
        return 0;
    }
    close(v->fd);   /* end of input: ffmpeg finishes the file */
    v->fd = -1;
    reap(v);
    int ok = WIFEXITED(v->status) && WEXITSTATUS(v->status) == 0;
    int rc = 0;
    if (!ok) {
        describe_exit(v, err);
        rc = -1;
    } else if (keep && rename(v->tmp, v->path) != 0) {
        snprintf(err, SIM_ERR_MAX, "%s: cannot rename '%s' to it: %s", v->path, v->tmp, strerror(errno));
        rc = -1;
    }
    if (!ok || !keep || rc != 0) {
        remove(v->tmp);
    }
    video_free(v);
    return rc;
}
