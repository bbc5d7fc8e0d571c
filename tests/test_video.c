/*
 * test_video.c - the ffmpeg encoder (core/video.h) and a run's recorder
 * (core/sim_video.h), here so that they run under ASan/UBSan too: frames
 * in, a file under its name only when kept and ffmpeg succeeded; a failing
 * ffmpeg (a fake one first on PATH) reported with its own words and its
 * file removed; the options' checks.  tests/video/video.sh reads the
 * videos back with ffprobe.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "swarmsim/scenario.h"
#include "swarmsim/sim.h"
#include "core/sim_video.h"
#include "core/video.h"

#define W 64
#define H 48

static char g_dir[64];
static char g_path_env[8192];   /* PATH as the tests found it */

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void in_dir(char *buf, size_t len, const char *name)
{
    snprintf(buf, len, "%s/%s", g_dir, name);
}

/* A fake ffmpeg first on PATH, running `body` (sh; $out is its output). */
static void fake_ffmpeg(const char *body)
{
    char bin[128], exe[160];
    in_dir(bin, sizeof bin, "bin");
    mkdir(bin, 0777);
    snprintf(exe, sizeof exe, "%s/ffmpeg", bin);
    FILE *f = fopen(exe, "w");
    assert_non_null(f);
    fprintf(f, "#!/bin/sh\nfor a; do out=$a; done\n%s\n", body);
    fclose(f);
    chmod(exe, 0755);
    char path[8400];
    snprintf(path, sizeof path, "%s:%s", bin, g_path_env);
    setenv("PATH", path, 1);
}

static void real_ffmpeg(void)
{
    setenv("PATH", g_path_env, 1);
}

static void frame(uint8_t *rgb, int k)
{
    for (int i = 0; i < W * H * 3; i++)
        rgb[i] = (uint8_t)(i * 7 + k * 31);
}

static void test_frames_to_file(void **state)
{
    (void)state;
    char path[128], tmp[160], err[SIM_ERR_MAX] = "";
    in_dir(path, sizeof path, "ok.mp4");
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    real_ffmpeg();
    video_t *v = video_open(path, W, H, 20.0, err);
    if (!v)
        print_error("video_open: %s\n", err);
    assert_non_null(v);
    static uint8_t rgb[W * H * 3];
    for (int k = 0; k < 5; k++) {
        frame(rgb, k);
        assert_int_equal(video_write(v, rgb, err), 0);
    }
    assert_int_equal(video_frame_count(v), 5);
    assert_false(exists(path));   /* not under its name before the close */
    assert_int_equal(video_close(v, 1, err), 0);
    assert_true(exists(path));
    assert_false(exists(tmp));
    remove(path);
}

static void test_not_kept(void **state)
{
    (void)state;
    char path[128], tmp[160], err[SIM_ERR_MAX] = "";
    in_dir(path, sizeof path, "dropped.mp4");
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    real_ffmpeg();
    video_t *v = video_open(path, W, H, 20.0, err);
    assert_non_null(v);
    static uint8_t rgb[W * H * 3];
    frame(rgb, 0);
    assert_int_equal(video_write(v, rgb, err), 0);
    assert_int_equal(video_close(v, 0, err), 0);
    assert_false(exists(path));
    assert_false(exists(tmp));
    assert_int_equal(video_close(NULL, 1, err), 0);
}

static void test_bad_sizes(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "", path[128];
    in_dir(path, sizeof path, "odd.mp4");
    assert_null(video_open(path, W + 1, H, 20.0, err));
    assert_non_null(strstr(err, "even sizes"));
    assert_null(video_open(path, W, H, 0.0, err));
    assert_non_null(strstr(err, "positive rate"));
}

/* ffmpeg dies after reading part of the stream: the write that finds it
 * gone, or the close, says so with ffmpeg's last line; no file is left. */
static void test_ffmpeg_dies(void **state)
{
    (void)state;
    char path[128], tmp[160], err[SIM_ERR_MAX] = "";
    in_dir(path, sizeof path, "dies.mp4");
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    fake_ffmpeg("head -c 20000 >/dev/null; echo partial >\"$out\"; echo 'fake: disk full' >&2; exit 1");
    video_t *v = video_open(path, W, H, 20.0, err);
    assert_non_null(v);
    static uint8_t rgb[W * H * 3];
    int failed = 0;
    for (int k = 0; k < 200 && !failed; k++) {   /* more than any socket buffer holds */
        frame(rgb, k);
        failed = video_write(v, rgb, err) != 0;
    }
    assert_true(failed);
    assert_non_null(strstr(err, "ffmpeg exited with status 1"));
    assert_non_null(strstr(err, "fake: disk full"));
    char err2[SIM_ERR_MAX] = "";
    assert_int_equal(video_close(v, 1, err2), -1);
    assert_non_null(strstr(err2, "status 1"));
    assert_false(exists(path));
    assert_false(exists(tmp));
    real_ffmpeg();
}

static void test_no_ffmpeg(void **state)
{
    (void)state;
    char err[SIM_ERR_MAX] = "", empty[128], path[128];
    in_dir(empty, sizeof empty, "empty");
    in_dir(path, sizeof path, "never.mp4");
    mkdir(empty, 0777);
    setenv("PATH", empty, 1);
    assert_int_equal(video_find_ffmpeg(err), -1);
    assert_non_null(strstr(err, "Debian package ffmpeg"));
    assert_null(video_open(path, W, H, 20.0, err));
    assert_non_null(strstr(err, "cannot start ffmpeg"));
    real_ffmpeg();
    assert_int_equal(video_find_ffmpeg(err), 0);
    rmdir(empty);
}

static void test_options(void **state)
{
    (void)state;
    video_options_t o = VIDEO_OPTIONS_DEFAULT;
    int bad = 0;
    assert_int_equal(o.every, VIDEO_DEFAULT_EVERY);
    assert_int_equal(video_parse_option("--frames", "3", &o, &bad), 0);
    assert_int_equal(video_parse_option("--video-every", "7", &o, &bad), 1);
    assert_int_equal(bad, 0);
    assert_int_equal(o.every, 7);
    assert_int_equal(video_check_options(&o), -1);   /* no --video */
    assert_int_equal(video_parse_option("--video-fps", "12.5", &o, &bad), 1);
    assert_int_equal(bad, 0);
    assert_true(o.fps == 12.5);
    assert_int_equal(video_parse_option("--video", "clip.MP4", &o, &bad), 1);
    assert_int_equal(bad, 0);
    assert_int_equal(video_check_options(&o), 0);
    assert_int_equal(video_parse_option("--video-every", "-1", &o, &bad), 1);
    assert_int_equal(bad, 1);
    assert_int_equal(o.every, 7);
    assert_int_equal(video_parse_option("--video", "clip.mkv", &o, &bad), 1);
    assert_int_equal(bad, 1);
}

/* A short run filmed through the recorder, the way the runner does it. */
static void test_recorder(void **state)
{
    (void)state;
    scenario_t *sc = malloc(sizeof *sc);
    assert_non_null(sc);
    char err[SIM_ERR_MAX];
    int rc = scenario_load("../sim_host/scenarios/random_walk.yaml", NULL, 0, sc, err);
    if (rc != 0)
        print_error("%s\n", err);
    assert_int_equal(rc, 0);
    sim_t *sim = sim_create(sc, 1, err);
    assert_non_null(sim);
    char path[128];
    in_dir(path, sizeof path, "run.mp4");
    video_options_t o = VIDEO_OPTIONS_DEFAULT;
    o.path = path;
    o.every = 4;
    real_ffmpeg();
    sim_video_t *v = sim_video_open(&o, sim, 97, 1, err);
    assert_non_null(v);
    for (int s = 0; s < 10; s++) {
        assert_int_equal(sim_video_step(v, sim, err), 0);
        sim_step(sim);
    }
    assert_int_equal(sim_video_close(v, sim, 1, err), 0);
    assert_true(exists(path));
    remove(path);
    assert_int_equal(sim_video_close(NULL, sim, 1, err), 0);
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

static int group_setup(void **state)
{
    (void)state;
    const char *p = getenv("PATH");
    snprintf(g_path_env, sizeof g_path_env, "%s", p ? p : "/usr/bin:/bin");
    snprintf(g_dir, sizeof g_dir, "/tmp/test_video_XXXXXX");
    return mkdtemp(g_dir) ? 0 : -1;
}

static int group_teardown(void **state)
{
    (void)state;
    char bin[128], exe[160];
    in_dir(bin, sizeof bin, "bin");
    snprintf(exe, sizeof exe, "%s/ffmpeg", bin);
    remove(exe);
    rmdir(bin);
    rmdir(g_dir);
    real_ffmpeg();
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frames_to_file),
        cmocka_unit_test(test_not_kept),
        cmocka_unit_test(test_bad_sizes),
        cmocka_unit_test(test_ffmpeg_dies),
        cmocka_unit_test(test_no_ffmpeg),
        cmocka_unit_test(test_options),
        cmocka_unit_test(test_recorder),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
