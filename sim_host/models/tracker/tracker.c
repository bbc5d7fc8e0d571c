/*
 * tracker.c - the overhead tracker (tracker.h).
 */
#include "tracker.h"

#include <math.h>

#include "core/sim_internal.h"
#include "units.h"

/* What the tracker told one robot this step. */
typedef struct tracker_robot {
    uint64_t stamp;        /* the step stamp of `pose` (0: none yet) */
    hal_pose_t pose;
    int8_t status;
    sim_rand_t rand;       /* RAND_TRACKER */
} tracker_robot_t;

#define T tracker_config_t
static const param_desc_t tracker_params[] = {
    { .key = "enabled", PARAM_BOOL_FIELD(T, enabled),
      .doc = "an overhead tracker gives every robot its pose (hal_pose)" },
    { .key = "noise_mm", PARAM_FIELD(T, noise_mm, float), .min = 0, .max = 10000,
      .doc = "Gaussian sd of the tracked x and y, mm" },
    { .key = "noise_deg", PARAM_FIELD(T, noise_deg, float), .min = 0, .max = 180,
      .doc = "Gaussian sd of the tracked heading, deg" },
    { .key = "dropout", PARAM_FIELD(T, dropout, float), .min = 0, .max = 1,
      .doc = "probability the tracker loses a robot for a step" },
    PARAM_END
};
#undef T

MODEL_ONE_SECTION(tracker_schema, "tracker", tracker_params, NULL,
                  "overhead tracker (hal_pose)");

static void tracker_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    (void)config;
    (void)sc;
    out->arrays = 1;
    out->elem_size[0] = sizeof(tracker_robot_t);
}

static tracker_robot_t *robots(const struct sim *sim)
{
    return sim_model_array(sim, SIM_MODEL_tracker, 0);
}

static int tracker_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    (void)config;
    (void)self;
    (void)err;
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&robots(sim)[i].rand, sim->seed, i, RAND_TRACKER);
    }
    return 0;
}

static void tracker_moved(sim_t *sim, void *self, uint32_t robot)
{
    (void)self;
    robots(sim)[robot].stamp = 0;
}

/* Ground truth, with Gaussian noise and dropout drawn from the robot's own
 * stream (only when the tracker is on: a run without it is unchanged). */
hal_status_t hal_pose(hal_t *hal, hal_pose_t *out)
{
    const tracker_config_t *cfg = sim_model_config(hal->sim, SIM_MODEL_tracker);
    const sim_robot_t *r = sim_hal_robot(hal);
    tracker_robot_t *t = &robots(hal->sim)[hal->index];
    if (!cfg->enabled) {
        return HAL_ERR_UNAVAILABLE;
    }
    if (t->stamp != sim_hal_stamp(hal)) {
        t->stamp = sim_hal_stamp(hal);
        t->status = HAL_ERR_UNAVAILABLE;
        if (cfg->dropout <= 0.0f || sim_rand_uniform(&t->rand) >= cfg->dropout) {
            double x = 1000.0 * r->x + cfg->noise_mm * sim_rand_normal(&t->rand);
            double y = 1000.0 * r->y + cfg->noise_mm * sim_rand_normal(&t->rand);
            double h = r->theta + cfg->noise_deg * UNITS_PI / 180.0 * sim_rand_normal(&t->rand);
            h = atan2(sin(h), cos(h));
            t->pose.x_mm = (int32_t)lround(x);
            t->pose.y_mm = (int32_t)lround(y);
            t->pose.heading_mrad = (int16_t)lround(1000.0 * h);
            t->pose.age_ms = 0;   /* a fix every control step */
            t->status = HAL_OK;
        }
    }
    *out = t->pose;
    return t->status;
}

static const char *const tracker_hal_calls[] = { "hal_pose", NULL };

const model_def_t tracker_model = {
    .name = "tracker",
    .doc = "an overhead tracker: every robot's pose with noise and dropout",
    .config_size = sizeof(tracker_config_t),
    .schema = &tracker_schema,
    .layout = tracker_layout,
    .create = tracker_create,
    .moved = tracker_moved,
    .hal_calls = tracker_hal_calls,
};
