/*
 * camera.c - the camera's frames: when a robot gets new blobs, and from
 * which model (camera.model).
 *
 * Timing (camera.fps > 0).  The e-puck's driver captures frame after frame
 * into two buffers; hal_camera_blobs runs the detector on the last complete
 * one.  So blobs change a few times a second (4.3 fps in the robot image's
 * configuration), and what they show was in front of the lens while that
 * frame was captured, one frame period before it completed.  Here capture
 * k of robot i begins at phase_i + k T (T = 1 / fps; phase_i uniform in
 * [0, T), each robot's camera runs on its own clock) and completes at
 * phase_i + (k + 1) T; the blobs of a step come from the last capture
 * completed by the step's start.  A capture shows the world at the first
 * step within it at which the controller asked for blobs: the frame is
 * rendered (or the geometric model evaluated) then, only then, and only
 * for a robot whose controller asks.  A controller that stops asking and
 * asks again gets, in its first step back, a frame of that step (the
 * capture before it was never made): the only case in which a frame is
 * younger than on the robot.
 *
 * camera.fps 0: blobs of the current state every control step (an
 * idealised sensor: RepAtt's scenarios, whose paper detects targets every
 * simulation step).  A `camera_fail` fault hides the blobs either way.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "blob_detect.h"
#include "camera_picture.h"
#include "camera_render.h"
#include "models/faults/faults.h"
#include "sim_internal.h"
#include "units.h"

#define DIR_MAX 1024

struct camera_state {
    camera_render_t *render;       /**< NULL until the first frame is drawn */
    uint8_t *rgb;                  /**< one frame, 8-bit RGB */
    uint8_t *rgb565;               /**< the same, RGB565 big-endian as the e-puck's driver */
    int64_t record_robot;          /**< -1: no pictures */
    char record_dir[DIR_MAX];
    char err[512];                 /**< the first error; empty: none */
};

static struct camera_state *state(struct sim *sim)
{
    if (!sim->camera) {
        sim->camera = calloc(1, sizeof *sim->camera);
        if (sim->camera) {
            sim->camera->record_robot = -1;
        }
    }
    return sim->camera;
}

void camera_destroy(struct sim *sim)
{
    if (sim->camera) {
        camera_render_destroy(sim->camera->render);
        free(sim->camera->rgb);
        free(sim->camera->rgb565);
        free(sim->camera);
        sim->camera = NULL;
    }
}

int camera_parallel(const struct sim *sim)
{
    return sim->sc->camera.model == CAMERA_GEOMETRIC && (!sim->camera || sim->camera->record_robot < 0);
}

int sim_camera_record(sim_t *sim, uint32_t robot, const char *dir)
{
    struct camera_state *cs = state(sim);
    if (!cs || robot >= sim->n || strlen(dir) >= DIR_MAX) {
        return -1;
    }
    cs->record_robot = robot;
    snprintf(cs->record_dir, sizeof cs->record_dir, "%s", dir);
    return 0;
}

const char *sim_camera_error(const sim_t *sim)
{
    return sim->camera && sim->camera->err[0] ? sim->camera->err : NULL;
}

/* Robot i's view into cs->rgb: 0, or -1 (the error kept). */
static int draw(struct sim *sim, struct camera_state *cs, uint32_t i)
{
    const scenario_t *sc = sim->sc;
    size_t px = (size_t)sc->camera.width_px * sc->camera.height_px;
    char err[256];
    if (!cs->render) {
        cs->rgb = malloc(px * 3u);
        cs->rgb565 = malloc(px * 2u);
        cs->render = camera_render_create(sc->camera.width_px, sc->camera.height_px, err);
        if (!cs->render || !cs->rgb || !cs->rgb565) {
            snprintf(cs->err, sizeof cs->err, "%s", cs->render ? "camera: out of memory" : err);
            return -1;
        }
    }
    if (camera_render_view(cs->render, sim, i, cs->rgb, err) != 0) {
        snprintf(cs->err, sizeof cs->err, "%s", err);
        return -1;
    }
    return 0;
}

/* The rendered model: sensor noise, RGB565 as the robot's driver stores
 * it, and the robot's own detector with the robot image's parameters
 * (hal_epuck_default_config: blob_detect_default_params, the frame's field
 * of view). */
static uint8_t rendered_blobs(struct sim *sim, struct camera_state *cs, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS])
{
    const scenario_t *sc = sim->sc;
    size_t px = (size_t)sc->camera.width_px * sc->camera.height_px;
    float sd = sc->camera.noise;
    sim_robot_t *r = &sim->robots[i];
    for (size_t k = 0; k < px; k++) {
        uint8_t *c = &cs->rgb[3u * k];
        if (sd > 0.0f) {
            for (int ch = 0; ch < 3; ch++) {
                double v = c[ch] + sd * sim_rand_normal(&r->cam_rand);
                c[ch] = (uint8_t)(v <= 0.0 ? 0.0 : v >= 255.0 ? 255.0 : floor(v + 0.5));
            }
        }
        uint16_t p = blob_rgb565(c[0], c[1], c[2]);
        cs->rgb565[2u * k] = (uint8_t)(p >> 8);
        cs->rgb565[2u * k + 1u] = (uint8_t)p;
    }
    blob_detect_params_t bp = blob_detect_default_params();
    bp.fov_mrad = (uint16_t)lround(sc->camera.fov * UNITS_PI / 180.0 * 1000.0);
    bp.byte_order = BLOB_BYTE_ORDER_BIG;
    blob_detect_work_t work;
    return blob_detect(&bp, cs->rgb565, sc->camera.width_px, sc->camera.height_px, &work, out,
                       (uint8_t)HAL_MAX_BLOBS);
}

/* One frame of robot i now, by the scenario's model; pictures of the
 * recorded robot. */
static uint8_t capture(struct sim *sim, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS])
{
    const scenario_t *sc = sim->sc;
    struct camera_state *cs = sim->camera;
    int record = cs && cs->record_robot == (int64_t)i && !cs->err[0];
    uint8_t n = 0;
    if (sc->camera.model == CAMERA_RENDERED) {
        cs = state(sim);
        if (!cs) {
            return 0;
        }
        if (cs->err[0] || draw(sim, cs, i) != 0) {
            return 0;
        }
        n = rendered_blobs(sim, cs, i, out);
    } else {
        n = sensors_camera(sim, i, out);
        if (record && draw(sim, cs, i) != 0) {   /* for the picture only */
            return n;
        }
    }
    if (record) {
        char path[DIR_MAX + 64], err[256];
        snprintf(path, sizeof path, "%s/frame_%06llu.png", cs->record_dir, (unsigned long long)sim->step);
        if (camera_picture_png(path, cs->rgb, sc->camera.width_px, sc->camera.height_px, sc->camera.fov, out, n,
                               err) != 0) {
            snprintf(cs->err, sizeof cs->err, "%s", err);
        }
    }
    return n;
}

void camera_update(struct sim *sim, uint32_t i)
{
    sim_robot_t *r = &sim->robots[i];
    float fps = sim->sc->camera.fps;
    if (fps <= 0.0f) {
        /* Every step, fresh: the behaviour the golden hashes pin. */
        r->blob_count = faults_camera_blind(sim, i) ? 0 : capture(sim, i, r->blobs);
        return;
    }
    double period = 1.0 / fps;
    if (!r->cam_ready) {
        sim_rand_seed(&r->cam_rand, sim->seed, i, RAND_CAMERA);
        r->cam_phase_s = period * sim_rand_uniform(&r->cam_rand);
        r->cam_capture = INT64_MIN;
        r->blob_count = 0;         /* no frame complete yet */
        r->cam_ready = 1;
    }
    double t = (double)sim->step * sim->sc->control_period_ms / 1000.0;
    int64_t k = (int64_t)floor((t - r->cam_phase_s) / period);   /* the capture under way */
    if (k >= 0 && k != r->cam_capture) {
        if (r->cam_capture == k - 1) {
            memcpy(r->blobs, r->cam_next, sizeof r->blobs);   /* it completed */
            r->blob_count = r->cam_next_count;
        } else if (k >= 1) {
            r->blob_count = capture(sim, i, r->blobs);       /* see the file comment */
        }
        r->cam_next_count = capture(sim, i, r->cam_next);
        r->cam_capture = k;
    }
    if (faults_camera_blind(sim, i)) {
        r->blob_count = 0;
    }
}
