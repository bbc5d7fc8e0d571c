/*
 * sim_video.c - a run on video (sim_video.h): the --video options, and the
 * recorder that renders frames at the cadence and feeds the encoder.
 */
#include "sim_video.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "sim_render.h"
#include "video.h"

struct sim_video {
    video_t *enc;
    render_ctx_t *ctx;
    uint8_t *rgb;              /**< one frame */
    uint32_t every;
    double fps;
    int quiet;
    const char *path;          /**< the options' (outlives the run) */
};

/* ---------------------------------------------------------------- options */

static int has_mp4_suffix(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && strcasecmp(path + n - 4, ".mp4") == 0;
}

int video_parse_option(const char *opt, const char *value, video_options_t *o, int *bad)
{
    char *end;
    if (!strcmp(opt, "--video")) {
        *bad = !has_mp4_suffix(value);
        if (*bad) {
            fprintf(stderr, "swarmsim: --video: '%s' is not a FILE.mp4 name (the video is H.264 in MP4)\n",
                    value);
        }
        o->path = value;
        return 1;
    }
    if (!strcmp(opt, "--video-every")) {
        errno = 0;
        unsigned long long v = (*value >= '0' && *value <= '9') ? strtoull(value, &end, 10) : 0;
        *bad = !(*value >= '0' && *value <= '9') || *end || errno || v < 1 || v > 1000000000ull;
        if (*bad) {
            fprintf(stderr, "swarmsim: --video-every: '%s' is not an integer in [1, 1000000000]\n", value);
        }
        o->every = *bad ? o->every : (uint32_t)v;
        o->every_set = 1;
        return 1;
    }
    if (!strcmp(opt, "--video-fps")) {
        double v = strtod(value, &end);
        *bad = *value == '\0' || *end || !(v >= 1.0 && v <= 240.0);
        if (*bad) {
            fprintf(stderr, "swarmsim: --video-fps: '%s' is not a frame rate in [1, 240]\n", value);
        }
        o->fps = *bad ? o->fps : v;
        o->fps_set = 1;
        return 1;
    }
    return 0;
}

int video_check_options(const video_options_t *o)
{
    if (!o->path) {
        if (o->every_set || o->fps_set) {
            fprintf(stderr, "swarmsim: %s needs --video FILE.mp4\n",
                    o->every_set ? "--video-every" : "--video-fps");
            return -1;
        }
        return 0;
    }
    /* The folder must exist: a mistyped one fails now, not after the run. */
    char dir[4096];
    const char *slash = strrchr(o->path, '/');
    size_t n = slash ? (size_t)(slash - o->path) : 1;
    if (n >= sizeof dir) {
        fprintf(stderr, "swarmsim: --video: '%s': the name is too long\n", o->path);
        return -1;
    }
    memcpy(dir, slash ? (n ? o->path : "/") : ".", n ? n : 1);
    dir[n ? n : 1] = '\0';
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "swarmsim: --video: '%s': the folder '%s' does not exist\n", o->path, dir);
        return -1;
    }
    if (stat(o->path, &st) == 0 && S_ISDIR(st.st_mode)) {
        fprintf(stderr, "swarmsim: --video: '%s' is a folder\n", o->path);
        return -1;
    }
    char err[SIM_ERR_MAX];
    if (video_find_ffmpeg(err) != 0) {
        fprintf(stderr, "swarmsim: %s\n", err);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- recorder */

/* "<path>: <msg>" in err, cut at SIM_ERR_MAX (the start says what failed). */
static void path_error(char *err, const char *path, const char *msg)
{
    int n = snprintf(err, SIM_ERR_MAX, "%s: %s", path, msg);
    if (n >= SIM_ERR_MAX) {
        memcpy(err + SIM_ERR_MAX - 4, "...", 4);
    }
}

static void recorder_free(sim_video_t *v)
{
    render_destroy(v->ctx);
    free(v->rgb);
    free(v);
}

sim_video_t *sim_video_open(const video_options_t *o, const sim_t *sim, uint32_t frame_px,
                            int quiet, char *err)
{
    const scenario_t *sc = sim_scenario(sim);
    /* yuv420p halves the colour planes: both sides must be even. */
    int w = (int)frame_px & ~1;
    int h = (int)fmax(RENDER_MIN_PX, floor(w * sc->arena.height / sc->arena.width)) & ~1;
    sim_video_t *v = calloc(1, sizeof *v);
    if (!v || !(v->rgb = malloc((size_t)w * (size_t)h * 3))) {
        free(v);
        snprintf(err, SIM_ERR_MAX, "%s: out of memory", o->path);
        return NULL;
    }
    v->every = o->every;
    v->fps = o->fps;
    v->quiet = quiet;
    v->path = o->path;
    char rerr[SIM_ERR_MAX];
    if (!(v->ctx = render_create(w, h, rerr))) {
        path_error(err, o->path, rerr);
        recorder_free(v);
        return NULL;
    }
    if (!(v->enc = video_open(o->path, w, h, o->fps, err))) {
        recorder_free(v);
        return NULL;
    }
    return v;
}

static int add_frame(sim_video_t *v, const sim_t *sim, char *err)
{
    char rerr[SIM_ERR_MAX];
    if (sim_render_rgb(sim, v->ctx, v->rgb, rerr) != 0) {
        path_error(err, v->path, rerr);
        return -1;
    }
    return video_write(v->enc, v->rgb, err);
}

int sim_video_step(sim_video_t *v, const sim_t *sim, char *err)
{
    return sim_step_count(sim) % v->every == 0 ? add_frame(v, sim, err) : 0;
}

int sim_video_close(sim_video_t *v, const sim_t *sim, int keep, char *err)
{
    if (!v) {
        return 0;
    }
    int rc = keep ? add_frame(v, sim, err) : 0;
    uint64_t frames = video_frame_count(v->enc);
    char cerr[SIM_ERR_MAX];
    if (video_close(v->enc, keep && rc == 0, cerr) != 0 && rc == 0) {
        memcpy(err, cerr, SIM_ERR_MAX);
        rc = -1;
    }
    if (rc == 0 && keep && !v->quiet) {
        fprintf(stderr, "swarmsim: video %s: %llu frames at %g fps, %.2f s\n", v->path,
                (unsigned long long)frames, v->fps, (double)frames / v->fps);
    }
    recorder_free(v);
    return rc;
}
