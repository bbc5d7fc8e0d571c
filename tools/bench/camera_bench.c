/*
 * camera_bench.c - the cost of one robot-frame of each camera model in
 * seed 000's base world (20 foragers, the nest beacon, 20 food items),
 * after `warm` control steps have spread the robots out: every robot's
 * frame in turn, `rounds` times; the median of `reps` timings of each.
 * Rendered: draw (OSMesa), RGB565, hal/blob_detect.c; geometric:
 * camera_geometric_blobs.  Usage: camera_bench SCENARIO [reps rounds warm].
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "blob_detect.h"
#include "models/camera/camera.h"
#include "models/camera/camera_render.h"
#include "swarmsim/scenario.h"

/* Wall time, and this thread's CPU time: on a machine shared with other
 * work the wall time is inflated, the CPU time much less (llvmpipe renders
 * on the calling thread: camera_render_set_threads). */
static double now_s(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: camera_bench SCENARIO [reps rounds warm]\n");
        return 2;
    }
    int reps = argc > 2 ? atoi(argv[2]) : 5, rounds = argc > 3 ? atoi(argv[3]) : 100;
    int warm = argc > 4 ? atoi(argv[4]) : 1200;
    if (reps < 1 || reps > 101 || rounds < 1 || warm < 0) {
        fprintf(stderr, "camera_bench: bad reps, rounds or warm\n");
        return 2;
    }
    camera_render_set_threads();
    static scenario_t sc;
    char err[SIM_ERR_MAX];
    if (scenario_load(argv[1], NULL, 0, &sc, err) != 0) {
        fprintf(stderr, "camera_bench: %s\n", err);
        return 2;
    }
    sim_t *sim = sim_create(&sc, 1, err);
    if (!sim) {
        fprintf(stderr, "camera_bench: %s\n", err);
        return 1;
    }
    for (int s = 0; s < warm; s++) sim_step(sim);
    uint32_t n = sim_robot_count(sim);
    size_t px = (size_t)camera_config(&sc)->width_px * camera_config(&sc)->height_px;
    uint8_t *rgb = malloc(px * 3), *f565 = malloc(px * 2);
    camera_render_t *cr = camera_render_create(camera_config(&sc)->width_px, camera_config(&sc)->height_px, err);
    if (!cr || !rgb || !f565) {
        fprintf(stderr, "camera_bench: %s\n", cr ? "out of memory" : err);
        return 1;
    }
    blob_detect_params_t bp = blob_detect_default_params();
    double t_r[101], t_g[101], c_r[101], c_g[101];
    unsigned long blobs_r = 0, blobs_g = 0;
    hal_blob_t out[HAL_MAX_BLOBS];
    for (int r = 0; r < reps; r++) {
        double t0 = now_s(CLOCK_MONOTONIC), c0 = now_s(CLOCK_THREAD_CPUTIME_ID);
        for (int k = 0; k < rounds; k++) {
            for (uint32_t i = 0; i < n; i++) {
                if (camera_render_view(cr, sim, i, rgb, err) != 0) {
                    fprintf(stderr, "camera_bench: %s\n", err);
                    return 1;
                }
                for (size_t p = 0; p < px; p++) {
                    uint16_t v = blob_rgb565(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
                    f565[2 * p] = (uint8_t)(v >> 8);
                    f565[2 * p + 1] = (uint8_t)v;
                }
                blob_detect_work_t work;
                blobs_r += blob_detect(&bp, f565, camera_config(&sc)->width_px, camera_config(&sc)->height_px, &work, out, HAL_MAX_BLOBS);
            }
        }
        t_r[r] = (now_s(CLOCK_MONOTONIC) - t0) / ((double)rounds * n);
        c_r[r] = (now_s(CLOCK_THREAD_CPUTIME_ID) - c0) / ((double)rounds * n);
        t0 = now_s(CLOCK_MONOTONIC);
        c0 = now_s(CLOCK_THREAD_CPUTIME_ID);
        for (int k = 0; k < rounds; k++) {
            for (uint32_t i = 0; i < n; i++) blobs_g += camera_geometric_blobs(sim, i, out);
        }
        t_g[r] = (now_s(CLOCK_MONOTONIC) - t0) / ((double)rounds * n);
        c_g[r] = (now_s(CLOCK_THREAD_CPUTIME_ID) - c0) / ((double)rounds * n);
    }
    qsort(t_r, (size_t)reps, sizeof t_r[0], by_value);
    qsort(t_g, (size_t)reps, sizeof t_g[0], by_value);
    qsort(c_r, (size_t)reps, sizeof c_r[0], by_value);
    qsort(c_g, (size_t)reps, sizeof c_g[0], by_value);
    printf("robot-frame, rendered (%ux%u, OSMesa + RGB565 + blob_detect): %.1f us wall, %.1f us CPU "
           "(medians of %d x %d frames)\n", camera_config(&sc)->width_px, camera_config(&sc)->height_px, 1e6 * t_r[reps / 2],
           1e6 * c_r[reps / 2], reps, rounds * (int)n);
    printf("robot-frame, geometric: %.2f us wall, %.2f us CPU\n", 1e6 * t_g[reps / 2], 1e6 * c_g[reps / 2]);
    printf("blobs per frame: rendered %.2f, geometric %.2f\n", (double)blobs_r / ((double)reps * rounds * n),
           (double)blobs_g / ((double)reps * rounds * n));
    camera_render_destroy(cr);
    free(rgb);
    free(f565);
    sim_destroy(sim);
    scenario_free(&sc);
    return 0;
}
