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
 * idealised sensor, for a paper whose robots detect their targets every
 * simulation step: seed 002's).  A `camera_fail` fault hides the blobs either way.
 */
#include <errno.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "blob_detect.h"
#include "camera_internal.h"
#include "camera_picture.h"
#include "models/faults/faults.h"
#include "models/per_robot.h"
#include "models/robot/robot.h"
#include "units.h"

/* ---------------------------------------------------------------- keys */

/* The names of camera_kind_t, in its order. */
const char *const camera_kind_names[] = { "geometric", "rendered", NULL };

#define C camera_config_t
static const param_desc_t camera_params[] = {
    { .key = "fov", PARAM_FIELD(C, fov, float), .min = 1, .max = 360,
      .doc = "horizontal field of view, deg (up to 179 the e-puck's pinhole camera; wider: an "
             "all-round panoramic stand-in, lens on the robot's axis)" },
    { .key = "range", PARAM_FIELD(C, range, float), .min = 0.01, .max = 100,
      .doc = "objects farther away are not seen (their nearest point), m; the default is the "
             "e-puck detector's reach for a 3.5 x 4.2 cm cylinder (geometric; rendered draws to 5 m)" },
    { .key = "width_px", PARAM_FIELD(C, width_px, uint16_t), .min = 1, .max = 640,
      .doc = "the robot's frame width, pixels" },
    { .key = "height_px", PARAM_FIELD(C, height_px, uint16_t), .min = 1, .max = 480,
      .doc = "the robot's frame height, pixels" },
    { .key = "model", PARAM_ENUM_FIELD(C, model, camera_kind_names),
      .doc = "geometric (fast: blobs from angles) or rendered (OSMesa frame through hal/blob_detect.c)" },
    { .key = "fps", PARAM_FIELD(C, fps, float), .min = 0, .max = 1000,
      .doc = "frames per second, both models; blobs are a frame old and held until the next "
             "(unset: each robot model's, e-puck1 4.3, e-puck2 15 [?]; 0: fresh every control step)" },
    { .key = "noise", PARAM_FIELD(C, noise, float), .min = 0, .max = 255,
      .doc = "rendered: Gaussian sd added to each pixel's 8-bit channels, counts" },
    { .key = "gain_r", PARAM_FIELD(C, gain[0], float), .min = 0, .max = 10,
      .doc = "colour response: the drawn frame's red channel times this (rendered, frame statistics)" },
    { .key = "gain_g", PARAM_FIELD(C, gain[1], float), .min = 0, .max = 10,
      .doc = "colour response: the green channel's gain" },
    { .key = "gain_b", PARAM_FIELD(C, gain[2], float), .min = 0, .max = 10,
      .doc = "colour response: the blue channel's gain" },
    { .key = "min_value", PARAM_FIELD(C, min_value, uint8_t), .min = 0, .max = 255,
      .doc = "rendered: the detector's least dominant channel, 0..255 (hal/blob_detect.h; the robot image's 64)" },
    { .key = "min_margin", PARAM_FIELD(C, min_margin, uint8_t), .min = 0, .max = 255,
      .doc = "rendered: the dominant channel's least lead on the second, 0..255 (40)" },
    { .key = "min_saturation_q8", PARAM_FIELD(C, min_saturation_q8, uint8_t), .min = 0, .max = 255,
      .doc = "rendered: the least lead relative to the dominant channel, /256 (64: 25 %)" },
    PARAM_END
};
#undef C

#define RC camera_robot_cal_t
static const param_desc_t robot_params[] = {
    { .key = "id", PARAM_FIELD(RC, id, uint16_t), .min = 0, .max = 65535, .doc = "the robot's hal_robot_id" },
    { .key = "fov", PARAM_FIELD(RC, fov, float), .min = 1, .max = 179,
      .doc = "its horizontal field of view, deg (absent: the section's)" },
    { .key = "range", PARAM_FIELD(RC, range, float), .min = 0.01, .max = 100,
      .doc = "its reach, m (absent: the section's)" },
    { .key = "gain_r", PARAM_FIELD(RC, gain[0], float), .min = 0, .max = 10,
      .doc = "its colour response, red (absent: the section's)" },
    { .key = "gain_g", PARAM_FIELD(RC, gain[1], float), .min = 0, .max = 10,
      .doc = "its colour response, green (absent: the section's)" },
    { .key = "gain_b", PARAM_FIELD(RC, gain[2], float), .min = 0, .max = 10,
      .doc = "its colour response, blue (absent: the section's)" },
    PARAM_END
};
#undef RC
static const schema_t robot_schema = { robot_params, NULL, NULL, NULL };
static const camera_robot_cal_t robot_default = { 0, NAN, NAN, { NAN, NAN, NAN } };
static const seq_desc_t robots_seq = {
    "robots", PER_ROBOT_MAX, sizeof(camera_robot_cal_t), &robot_default, &robot_schema,
    offsetof(camera_config_t, robots), offsetof(camera_config_t, robot_count), NULL, 1, NULL
};
static const child_t camera_children[] = {
    { "robots", CHILD_SEQUENCE, NULL, &robots_seq, "reach, field of view (the geometric model) and colour "
      "response fitted to one robot id (the calibration kit)" },
    CHILD_END
};

MODEL_ONE_SECTION(camera_schema, "camera", camera_params, camera_children,
                  "front camera blobs");

void camera_lens(const camera_config_t *cfg, uint16_t id, float *fov_deg, float *range_m)
{
    *fov_deg = cfg->fov;
    *range_m = cfg->range;
    if (cfg->robot_count == 0) {
        return;
    }
    int32_t k = per_robot_find(cfg->robots, cfg->robot_count, sizeof *cfg->robots,
                               offsetof(camera_robot_cal_t, id), id);
    if (k >= 0) {
        const camera_robot_cal_t *e = &cfg->robots[k];
        *fov_deg = isnan(e->fov) ? *fov_deg : e->fov;
        *range_m = isnan(e->range) ? *range_m : e->range;
    }
}

void camera_colour_gain(const camera_config_t *cfg, uint16_t id, float gain[3])
{
    int32_t k = cfg->robot_count == 0 ? -1 : per_robot_find(cfg->robots, cfg->robot_count, sizeof *cfg->robots,
                                                             offsetof(camera_robot_cal_t, id), id);
    for (int ch = 0; ch < 3; ch++) {
        gain[ch] = k >= 0 && !isnan(cfg->robots[k].gain[ch]) ? cfg->robots[k].gain[ch] : cfg->gain[ch];
    }
}

static void camera_free_config(void *config)
{
    camera_config_t *c = config;
    free(c->robots);
    c->robots = NULL;
    c->robot_count = 0;
}

/* The e-puck image's camera: 56 deg, 40 x 20 pixels, the detector's
 * reach; the frame rate of each robot's model (platform.h). */
static void camera_defaults(void *config)
{
    camera_config_t *c = config;
    c->fov = (float)EPUCK1_CAMERA_FOV_DEG;
    c->range = CAMERA_EPUCK_REACH_M;
    c->width_px = EPUCK_CAMERA_WIDTH_PX;
    c->height_px = EPUCK_CAMERA_HEIGHT_PX;
    c->model = CAMERA_GEOMETRIC;
    c->fps = NAN;
    c->noise = 0.0f;
    blob_detect_params_t bp = blob_detect_default_params();
    c->min_value = bp.min_value;
    c->min_margin = bp.min_margin;
    c->min_saturation_q8 = bp.min_saturation_q8;
    c->gain[0] = c->gain[1] = c->gain[2] = 1.0f;
    c->robot_count = 0;
    c->robots = NULL;
}

/* The rendered camera is a pinhole camera over a frame the detector takes. */
static int camera_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    const camera_config_t *c = config;
    const char *key = NULL;
    (void)sc;
    int32_t dup = per_robot_duplicate(c->robots, c->robot_count, sizeof *c->robots,
                                      offsetof(camera_robot_cal_t, id));
    if (dup >= 0) {
        snprintf(path, SCHEMA_PATH_MAX, "camera.robots.%d.id", (int)dup);
        snprintf(msg, SIM_ERR_MAX, "robot id listed twice: one entry per robot");
        return -1;
    }
    if (c->model != CAMERA_RENDERED) {
        return 0;
    }
    for (uint32_t k = 0; k < c->robot_count; k++) {
        if (!isnan(c->robots[k].fov) || !isnan(c->robots[k].range)) {
            snprintf(path, SCHEMA_PATH_MAX, "camera.robots.%u", (unsigned)k);
            snprintf(msg, SIM_ERR_MAX, "per-robot lenses are the geometric model's: camera.model rendered "
                     "takes the section's fov and range (a robot's colour gains it takes)");
            return -1;
        }
    }
    if (c->fov > CAMERA_PINHOLE_MAX_DEG) {
        key = "camera.fov";
    } else if (c->width_px > CAMERA_RENDERED_MAX_PX) {
        key = "camera.width_px";
    } else if (c->height_px > CAMERA_RENDERED_MAX_PX) {
        key = "camera.height_px";
    }
    if (key == NULL) {
        return 0;
    }
    snprintf(path, SCHEMA_PATH_MAX, "%s", key);
    snprintf(msg, SIM_ERR_MAX, "camera.model rendered needs a pinhole camera (fov <= %g deg) and a frame of at "
             "most %u x %u pixels (hal/blob_detect.c's limit)", (double)CAMERA_PINHOLE_MAX_DEG,
             CAMERA_RENDERED_MAX_PX, CAMERA_RENDERED_MAX_PX);
    return -1;
}

/* ---------------------------------------------------------------- a run */

static void camera_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const camera_config_t *c = config;
    (void)sc;
    out->arrays = 1;
    out->elem_size[0] = sizeof(camera_robot_t);
    out->scratch_size = sizeof(camera_scratch_t);
    /* The renderer's frame: RGBA in GL, RGB, RGB565 (made at the first frame). */
    out->run_bytes = sizeof(camera_t) + (size_t)c->width_px * c->height_px * (4u + 3u + 2u);
}

static int camera_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    camera_t *cs = calloc(1, sizeof *cs);
    if (!cs) {
        snprintf(err, SIM_ERR_MAX, "out of memory for the cameras");
        return -1;
    }
    cs->cfg = config;
    cs->robot = sim_model_array(sim, SIM_MODEL_camera, 0);
    for (uint32_t i = 0; i < sim->n; i++) {
        cs->robot[i].fps = isnan(cs->cfg->fps) ? robot_camera_fps(robot_facts(sim, i)) : cs->cfg->fps;
    }
    cs->record_robot = -1;
    if (pthread_mutex_init(&cs->frame_lock, NULL) != 0) {
        free(cs);
        snprintf(err, SIM_ERR_MAX, "camera: cannot make a lock");
        return -1;
    }
    *self = cs;
    return 0;
}

static void camera_destroy(void *self)
{
    camera_t *cs = self;
    if (cs) {
        camera_render_destroy(cs->render);
        pthread_mutex_destroy(&cs->frame_lock);
        free(cs->rgb);
        free(cs->rgb565);
        free(cs);
    }
}

/* Robots' frames may be taken side by side with the geometric model and no
 * recorder (the renderer has one GL context per run). */
static int camera_serial(const sim_t *sim, const void *self)
{
    const camera_t *cs = self;
    (void)sim;
    return !(cs->cfg->model == CAMERA_GEOMETRIC && cs->record_robot < 0);
}

static const char *camera_error(const sim_t *sim, const void *self)
{
    const camera_t *cs = self;
    (void)sim;
    return cs->err[0] ? cs->err : NULL;
}

int sim_camera_record(sim_t *sim, uint32_t robot, const char *dir)
{
    camera_t *cs = sim_model_self(sim, SIM_MODEL_camera);
    if (robot >= sim->n || strlen(dir) >= CAMERA_DIR_MAX) {
        return -1;
    }
    cs->record_robot = robot;
    snprintf(cs->record_dir, sizeof cs->record_dir, "%s", dir);
    return 0;
}

/* Robot i's view into cs->rgb: 0, or -1 (the error kept). */
static int draw(struct sim *sim, camera_t *cs, uint32_t i)
{
    const camera_config_t *cfg = cs->cfg;
    size_t px = (size_t)cfg->width_px * cfg->height_px;
    char err[SIM_ERR_MAX];
    if (!cs->render) {
        cs->rgb = malloc(px * 3u);
        cs->rgb565 = malloc(px * 2u);
        cs->render = camera_render_create(cfg->width_px, cfg->height_px, err);
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

/* The drawn frame of robot i as its sensor gives it: its colour response
 * (camera.gain_*; 1: none, the frame untouched), sensor noise, RGB565 as
 * the robot's driver stores it. */
static void sensor_frame(const sim_t *sim, camera_t *cs, uint32_t i)
{
    const camera_config_t *cfg = cs->cfg;
    size_t px = (size_t)cfg->width_px * cfg->height_px;
    float sd = cfg->noise;
    float gain[3];
    camera_robot_t *r = &cs->robot[i];
    camera_colour_gain(cfg, sim->robots[i].id, gain);
    int gained = gain[0] != 1.0f || gain[1] != 1.0f || gain[2] != 1.0f;
    for (size_t k = 0; k < px; k++) {
        uint8_t *c = &cs->rgb[3u * k];
        if (gained) {
            for (int ch = 0; ch < 3; ch++) {
                float v = c[ch] * gain[ch];
                c[ch] = (uint8_t)(v >= 255.0f ? 255.0f : floorf(v + 0.5f));
            }
        }
        if (sd > 0.0f) {
            for (int ch = 0; ch < 3; ch++) {
                double v = c[ch] + sd * sim_rand_normal(&r->rand);
                c[ch] = (uint8_t)(v <= 0.0 ? 0.0 : v >= 255.0 ? 255.0 : floor(v + 0.5));
            }
        }
        uint16_t p = blob_rgb565(c[0], c[1], c[2]);
        cs->rgb565[2u * k] = (uint8_t)(p >> 8);
        cs->rgb565[2u * k + 1u] = (uint8_t)p;
    }
}

/* The robot image's detector (hal_epuck_default_config: blob_detect_default_params,
 * the frame's field of view) with the section's thresholds. */
static blob_detect_params_t detector_params(const camera_config_t *cfg)
{
    blob_detect_params_t bp = blob_detect_default_params();
    bp.fov_mrad = (uint16_t)lround(cfg->fov * UNITS_PI / 180.0 * 1000.0);
    bp.byte_order = BLOB_BYTE_ORDER_BIG;
    bp.min_value = cfg->min_value;
    bp.min_margin = cfg->min_margin;
    bp.min_saturation_q8 = cfg->min_saturation_q8;
    return bp;
}

/* The rendered model: the sensor's frame through the robot's own detector. */
static uint8_t rendered_blobs(const sim_t *sim, camera_t *cs, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS])
{
    const camera_config_t *cfg = cs->cfg;
    sensor_frame(sim, cs, i);
    blob_detect_params_t bp = detector_params(cfg);
    blob_detect_work_t work;
    return blob_detect(&bp, cs->rgb565, cfg->width_px, cfg->height_px, &work, out,
                       (uint8_t)HAL_MAX_BLOBS);
}

/* One frame of robot i now, by the scenario's model; pictures of the
 * recorded robot. */
static uint8_t capture(struct sim *sim, camera_t *cs, uint32_t i, hal_blob_t out[HAL_MAX_BLOBS])
{
    const camera_config_t *cfg = cs->cfg;
    int record = cs->record_robot == (int64_t)i && !cs->err[0];
    uint8_t n = 0;
    if (cfg->model == CAMERA_RENDERED) {
        if (cs->err[0] || draw(sim, cs, i) != 0) {
            return 0;
        }
        n = rendered_blobs(sim, cs, i, out);
    } else {
        n = camera_geometric_blobs(sim, i, out);
        if (record && draw(sim, cs, i) != 0) {   /* for the picture only */
            return n;
        }
    }
    if (record) {
        char path[CAMERA_DIR_MAX + 64], err[SIM_ERR_MAX];
        snprintf(path, sizeof path, "%s/frame_%06llu.png", cs->record_dir, (unsigned long long)sim->step);
        if (camera_picture_png(path, cs->rgb, cfg->width_px, cfg->height_px, cfg->fov, out, n, err) != 0) {
            snprintf(cs->err, sizeof cs->err, "%s", err);
        }
    }
    return n;
}

/* Robot i's camera clock and noise, drawn at its first frame (blobs or
 * frame statistics, whichever comes first). */
static void ready(const struct sim *sim, camera_robot_t *r, uint32_t i)
{
    if (!r->ready) {
        sim_rand_seed(&r->rand, sim->seed, i, RAND_CAMERA);
        r->phase_s = r->fps > 0.0f ? (1.0 / r->fps) * sim_rand_uniform(&r->rand) : 0.0;
        r->capture = INT64_MIN;
        r->blob_count = 0;         /* no frame complete yet */
        r->ready = 1;
    }
}

/* Brings robot i's blobs up to this step: a new frame when one is due. */
static void camera_update(struct sim *sim, camera_t *cs, uint32_t i)
{
    camera_robot_t *r = &cs->robot[i];
    float fps = r->fps;
    if (fps <= 0.0f) {
        /* Every step, fresh: the behaviour the golden hashes pin. */
        r->blob_count = faults_camera_blind(sim, i) ? 0 : capture(sim, cs, i, r->blobs);
        return;
    }
    double period = 1.0 / fps;
    ready(sim, r, i);
    double t = (double)sim->step * sim->sc->control_period_ms / 1000.0;
    int64_t k = (int64_t)floor((t - r->phase_s) / period);   /* the capture under way */
    if (k >= 0 && k != r->capture) {
        if (r->capture == k - 1) {
            memcpy(r->blobs, r->next, sizeof r->blobs);   /* it completed */
            r->blob_count = r->next_count;
        } else if (k >= 1) {
            r->blob_count = capture(sim, cs, i, r->blobs);       /* see the file comment */
        }
        r->next_count = capture(sim, cs, i, r->next);
        r->capture = k;
    }
    if (faults_camera_blind(sim, i)) {
        r->blob_count = 0;
    }
}

static void camera_moved(sim_t *sim, void *self, uint32_t robot)
{
    camera_t *cs = self;
    (void)sim;
    cs->robot[robot].stamp = 0;
}

static void camera_platform(const sim_t *sim, const void *self, uint32_t robot, uint64_t since,
                            robot_telemetry_platform_t *p)
{
    const camera_robot_t *r = &((const camera_t *)self)->robot[robot];
    (void)sim;
    p->blobs = r->stamp != 0 && r->stamp >= since ? (int8_t)r->blob_count : -1;
}

/* The blobs of its latest frame, and what the camera sees. */
static void camera_inspect(const sim_t *sim, const void *self, uint32_t robot, model_inspect_t *out)
{
    const camera_t *cs = self;
    const camera_robot_t *r = &cs->robot[robot];
    float fov, range;
    camera_lens(cs->cfg, sim->robots[robot].id, &fov, &range);
    out->camera_fov_rad = fov * (float)(UNITS_PI / 180.0);
    out->camera_range_m = range;
    out->n_blobs = r->stamp != 0 ? (int8_t)r->blob_count : -1;
    for (uint8_t k = 0; r->stamp != 0 && k < r->blob_count && k < HAL_MAX_BLOBS; k++) {
        out->blobs[k] = r->blobs[k];
    }
}

/* ---------------------------------------------------------------- HAL */

uint8_t hal_camera_blobs(hal_t *hal, hal_blob_t *out, uint8_t max)
{
    camera_t *cs = sim_model_self(hal->sim, SIM_MODEL_camera);
    camera_robot_t *r = &cs->robot[hal->index];
    if (r->stamp != sim_hal_stamp(hal)) {
        camera_update(hal->sim, cs, hal->index);   /* a frame only when one is due */
        r->stamp = sim_hal_stamp(hal);
    }
    uint8_t n = r->blob_count < max ? r->blob_count : max;
    for (uint8_t k = 0; k < n; k++) {
        out[k] = r->blobs[k];
    }
    return n;
}

hal_status_t hal_camera_frame_size(hal_t *hal, uint16_t *width_px, uint16_t *height_px)
{
    const camera_config_t *cfg = sim_model_config(hal->sim, SIM_MODEL_camera);
    *width_px = cfg->width_px;
    *height_px = cfg->height_px;
    return HAL_OK;
}

/* A frame drawn now, whatever camera.model says (the geometric model has
 * no pixels), through the robot's colour response and noise; the lock
 * keeps robots stepped side by side off each other's frame. */
hal_status_t hal_camera_colour_stats(hal_t *hal, uint8_t colour, hal_colour_stats_t *out)
{
    camera_t *cs = sim_model_self(hal->sim, SIM_MODEL_camera);
    const camera_config_t *cfg = cs->cfg;
    hal_status_t status = HAL_OK;
    memset(out, 0, sizeof *out);
    if (colour >= (uint8_t)HAL_COLOUR_COUNT) {
        return HAL_ERR_RANGE;
    }
    if (cfg->width_px > CAMERA_RENDERED_MAX_PX || cfg->height_px > CAMERA_RENDERED_MAX_PX ||
        cfg->fov > CAMERA_PINHOLE_MAX_DEG || faults_camera_blind(hal->sim, hal->index)) {
        return HAL_ERR_UNAVAILABLE;
    }
    pthread_mutex_lock(&cs->frame_lock);
    ready(hal->sim, &cs->robot[hal->index], hal->index);
    if (cs->err[0] || draw(hal->sim, cs, hal->index) != 0) {
        status = HAL_ERR_UNAVAILABLE;
    } else {
        sensor_frame(hal->sim, cs, hal->index);
        blob_detect_params_t bp = detector_params(cfg);
        if (blob_colour_stats(&bp, cs->rgb565, cfg->width_px, cfg->height_px, colour, out) != 0) {
            status = HAL_ERR_RANGE;
        }
    }
    pthread_mutex_unlock(&cs->frame_lock);
    return status;
}

static const char *const camera_hal_calls[] = { "hal_camera_blobs", "hal_camera_frame_size",
                                                "hal_camera_colour_stats", NULL };

static const model_field_t camera_fields[] = {
    { "camera.blob_count", "blobs", "blobs of the robot's latest frame", SIM_FIELD_U8, 0,
      offsetof(camera_robot_t, blob_count), 1 },
    { "camera.fps", "fps", "the robot's frame rate: camera.fps, or its robot model's", SIM_FIELD_F32, 0,
      offsetof(camera_robot_t, fps), 1 },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t camera_model = {
    .name = "camera",
    .doc = "the front camera's blobs: geometric, or rendered through the robot's own detector",
    .config_size = sizeof(camera_config_t),
    .default_config = camera_defaults,
    .schema = &camera_schema,
    .check = camera_check,
    .free_config = camera_free_config,
    .layout = camera_layout,
    .create = camera_create,
    .destroy = camera_destroy,
    .serial = camera_serial,
    .moved = camera_moved,
    .platform = camera_platform,
    .inspect = camera_inspect,
    .hal_calls = camera_hal_calls,
    .fields = camera_fields,
    .error = camera_error,
};
