/*
 * robot.c - the robot model of each group (robot.h): the group key
 * `robot`, the table of facts, and per-robot fields that say which model
 * a robot is and what the models took from its facts.
 */
#include "robot.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/sim_internal.h"

#define ROBOT_MODEL_NAME(P) P##_NAME,
const char *const robot_model_names[ROBOT_MODEL_COUNT + 1] = { PLATFORM_MODELS(ROBOT_MODEL_NAME) NULL };
#undef ROBOT_MODEL_NAME

static const platform_facts_t facts_table[ROBOT_MODEL_COUNT] = { PLATFORM_MODELS(PLATFORM_FACTS_INIT) };

/* The simulator's camera draws one frame geometry for every robot of a run
 * (camera.fov, width_px, height_px are scenario-wide): the models agree on
 * it today.  A model with its own would need them per group. */
#define SAME_CAMERA(P)                                                                          \
    _Static_assert(P##_CAMERA_FOV_DEG == EPUCK1_CAMERA_FOV_DEG                                 \
                   && P##_CAMERA_FRAME_WIDTH_PX == EPUCK1_CAMERA_FRAME_WIDTH_PX                \
                   && P##_CAMERA_FRAME_HEIGHT_PX == EPUCK1_CAMERA_FRAME_HEIGHT_PX,             \
                   #P ": a camera geometry of its own needs camera.fov and the frame per group");
PLATFORM_MODELS(SAME_CAMERA)
#undef SAME_CAMERA

const platform_facts_t *robot_model_facts(robot_model_id_t id)
{
    return &facts_table[(unsigned)id < ROBOT_MODEL_COUNT ? id : ROBOT_MODEL_EPUCK1];
}

const platform_facts_t *robot_group_facts(const robot_group_t *g)
{
    const robot_group_config_t *gc = scenario_group_model_config(g, SIM_MODEL_robot);
    return robot_model_facts((robot_model_id_t)gc->model);
}

const platform_facts_t *robot_facts(const sim_t *sim, uint32_t robot)
{
    return robot_group_facts(&sim->sc->groups[sim->robots[robot].group]);
}

/* ---------------------------------------------------------------- keys */

#define PG robot_group_config_t
static const param_desc_t group_params[] = {
    { .key = "robot", PARAM_ENUM_FIELD(PG, model, robot_model_names),
      .doc = "the robot model its robots are (hal/platform_facts.h: the other models' defaults for them)" },
    PARAM_END
};
#undef PG
static const schema_t robot_group_schema = { group_params, NULL, NULL, NULL };
/* No section of its own: the facts are the robots', not the scenario's. */
static const schema_t robot_schema = { NULL, NULL, NULL, NULL };

/* ---------------------------------------------------------------- a run */

/* What a robot is, for the fields (4 bytes a robot). */
typedef struct robot_kind {
    uint8_t model;             /* robot_model_id_t */
    uint8_t mic_count;
    uint16_t mic_rate_hz;
} robot_kind_t;

static void robot_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    (void)config;
    (void)sc;
    out->arrays = 1;
    out->elem_size[0] = sizeof(robot_kind_t);
}

static int robot_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    robot_kind_t *r = sim_model_array(sim, SIM_MODEL_robot, 0);
    (void)config;
    (void)self;
    (void)err;
    for (uint32_t i = 0; i < sim->n; i++) {
        const robot_group_config_t *gc =
            scenario_group_model_config(&sim->sc->groups[sim->robots[i].group], SIM_MODEL_robot);
        const platform_facts_t *f = robot_model_facts((robot_model_id_t)gc->model);
        r[i].model = (uint8_t)gc->model;
        r[i].mic_count = f->mic_count;
        r[i].mic_rate_hz = f->mic_rate_hz;
    }
    return 0;
}

static const model_field_t robot_fields[] = {
    { "robot.model", "", "the robot model (robots[].robot): 0 e-puck1, 1 e-puck2", SIM_FIELD_U8, 0,
      offsetof(robot_kind_t, model), 1 },
    { "robot.mic_count", "", "microphones on the robot (hal.h reads the first 3)", SIM_FIELD_U8, 0,
      offsetof(robot_kind_t, mic_count), 1 },
    { "robot.mic_rate_hz", "Hz", "the microphones' sampling rate as the tone detector gets it", SIM_FIELD_U16,
      0, offsetof(robot_kind_t, mic_rate_hz), 1 },
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};

const model_def_t robot_model = {
    .name = "robot",
    .doc = "the robot model of each group (robots[].robot: e-puck1, e-puck2) and its facts",
    .config_size = 0,
    .schema = &robot_schema,
    .group_config_size = sizeof(robot_group_config_t),
    .group_schema = &robot_group_schema,
    .layout = robot_layout,
    .create = robot_create,
    .fields = robot_fields,
};
