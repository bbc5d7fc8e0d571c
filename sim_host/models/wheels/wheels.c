/*
 * wheels.c - the wheels and their actuation noise (wheels.h).
 */
#include "wheels.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "core/pool.h"
#include "core/sim_internal.h"
#include "models/faults/faults.h"
#include "models/per_robot.h"
#include "models/robot/robot.h"
#include "units.h"

#define W wheels_config_t
static const param_desc_t wheels_params[] = {
    { .key = "speed_noise_rel", PARAM_FIELD(W, speed_noise_rel, float), .min = 0, .max = 1,
      .doc = "per-wheel relative speed noise (sd)" },
    { .key = "bias_sd", PARAM_FIELD(W, bias_sd, float), .min = 0, .max = 1,
      .doc = "sd of a per-robot, per-wheel speed bias drawn once a run, m/s (seed 003's eq 3; "
             "the e-puck saturates at 0.129 m/s)" },
    { .key = "bias_per_step", PARAM_BOOL_FIELD(W, bias_per_step),
      .doc = "draw the bias anew every control step instead of once a run (another reading of eq 3)" },
    { .key = "gain_left", PARAM_FIELD(W, gain_left, float), .min = 0, .max = 10,
      .doc = "actual over commanded speed of the left wheel (its true diameter over 41 mm)" },
    { .key = "gain_right", PARAM_FIELD(W, gain_right, float), .min = 0, .max = 10,
      .doc = "the same for the right wheel" },
    PARAM_END
};
#undef W

#define RC wheels_robot_cal_t
static const param_desc_t robot_params[] = {
    { .key = "id", PARAM_FIELD(RC, id, uint16_t), .min = 0, .max = 65535, .doc = "the robot's hal_robot_id" },
    { .key = "gain_left", PARAM_FIELD(RC, gain_left, float), .min = 0, .max = 10,
      .doc = "its left wheel's gain (absent: the section's)" },
    { .key = "gain_right", PARAM_FIELD(RC, gain_right, float), .min = 0, .max = 10,
      .doc = "its right wheel's gain (absent: the section's)" },
    { .key = "speed_noise_rel", PARAM_FIELD(RC, speed_noise_rel, float), .min = 0, .max = 1,
      .doc = "its relative speed noise (absent: the section's)" },
    PARAM_END
};
#undef RC
static const schema_t robot_schema = { robot_params, NULL, NULL, NULL };
static void robot_init(void *elem)
{
    wheels_robot_cal_t *e = elem;
    e->gain_left = e->gain_right = e->speed_noise_rel = NAN;
}
static const wheels_robot_cal_t robot_default = { 0, 0.0f, 0.0f, 0.0f };
static const seq_desc_t robots_seq = {
    "robots", PER_ROBOT_MAX, sizeof(wheels_robot_cal_t), &robot_default, &robot_schema,
    offsetof(wheels_config_t, robots), offsetof(wheels_config_t, robot_count), NULL, 1, robot_init
};
static const child_t wheels_children[] = {
    { "robots", CHILD_SEQUENCE, NULL, &robots_seq, "parameters fitted to one robot id (the calibration kit)" },
    CHILD_END
};

MODEL_ONE_SECTION(wheels_schema, "wheels", wheels_params, wheels_children,
                  "wheel motors");

/* No noise, no bias, true wheels. */
static void wheels_defaults(void *config)
{
    wheels_config_t *c = config;
    c->speed_noise_rel = 0.0f;
    c->bias_sd = 0.0f;
    c->bias_per_step = 0;
    c->gain_left = c->gain_right = 1.0f;
    c->robot_count = 0;
    c->robots = NULL;
}

static int wheels_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX],
                        char msg[SIM_ERR_MAX])
{
    const wheels_config_t *c = config;
    (void)sc;
    int32_t k = per_robot_duplicate(c->robots, c->robot_count, sizeof *c->robots, offsetof(wheels_robot_cal_t, id));
    if (k >= 0) {
        snprintf(path, SCHEMA_PATH_MAX, "wheels.robots.%d.id", (int)k);
        snprintf(msg, SIM_ERR_MAX, "robot id listed twice: one entry per robot");
        return -1;
    }
    return 0;
}

static void wheels_free_config(void *config)
{
    wheels_config_t *c = config;
    free(c->robots);
    c->robots = NULL;
    c->robot_count = 0;
}

/* One robot's motors. */
typedef struct wheels_robot {
    int16_t cmd_left, cmd_right;      /* commanded speeds, steps/s */
    int16_t speed_max;                /* its robot model's top speed under hal.h's, steps/s */
    double steps_left, steps_right;   /* commanded steps so far */
    double bias_left, bias_right;     /* b of eq 3 (this run's, or this step's), steps/s */
    sim_rand_t rand;                  /* f of eq 3 (RAND_WHEELS) */
    sim_rand_t bias_rand;             /* b's draws (RAND_WHEEL_BIAS) */
} wheels_robot_t;

/* Array 1, only when the scenario lists `robots` entries (other runs pay
 * nothing): which entry each robot takes. */
static void wheels_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    const wheels_config_t *c = config;
    (void)sc;
    out->arrays = c->robot_count > 0 ? 2 : 1;
    out->elem_size[0] = sizeof(wheels_robot_t);
    out->elem_size[1] = sizeof(per_robot_cache_t);
}

static wheels_robot_t *robots(const sim_t *sim)
{
    return sim_model_array(sim, SIM_MODEL_wheels, 0);
}

static int wheels_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const wheels_config_t *c = config;
    (void)self;
    (void)err;
    for (uint32_t i = 0; i < sim->n; i++) {
        wheels_robot_t *w = &robots(sim)[i];
        w->speed_max = robot_wheel_speed_max(robot_facts(sim, i));
        sim_rand_seed(&w->rand, sim->seed, i, RAND_WHEELS);
        if (c->robot_count > 0) {
            ((per_robot_cache_t *)sim_model_array(sim, SIM_MODEL_wheels, 1))[i].id = -1;
        }
        if (c->bias_sd > 0.0f) {
            /* Eq 3's bias b, drawn once a run as ARGoS does (its own stream:
             * other streams and golden hashes are unchanged). */
            sim_rand_seed(&w->bias_rand, sim->seed, i, RAND_WHEEL_BIAS);
            const double sd_steps = c->bias_sd / EPUCK_STEP_M;
            w->bias_left = sd_steps * sim_rand_normal(&w->bias_rand);
            w->bias_right = sd_steps * sim_rand_normal(&w->bias_rand);
        }
    }
    return 0;
}

/* pool_fn: robots [begin, end) turn their wheel commands into body
 * velocities (sim->drive), each with its own noise streams, side by side;
 * the core hands them to Box2D in one loop. */
static void drive_range(uint32_t begin, uint32_t end, uint32_t worker, void *ctx)
{
    struct sim *sim = ctx;
    const wheels_config_t *c = sim_model_config(sim, SIM_MODEL_wheels);
    const int bias = c->bias_sd > 0.0f;
    per_robot_cache_t *cal = c->robot_count > 0 ? sim_model_array(sim, SIM_MODEL_wheels, 1) : NULL;
    (void)worker;
    for (uint32_t i = begin; i < end; i++) {
        const sim_robot_t *r = &sim->robots[i];
        wheels_robot_t *wr = &robots(sim)[i];
        const wheels_robot_cal_t *e = NULL;
        if (cal != NULL) {
            e = per_robot_entry(&cal[i], c->robots, c->robot_count, sizeof *c->robots,
                                offsetof(wheels_robot_cal_t, id), r->id);
        }
        const double noise = (e != NULL && !isnan(e->speed_noise_rel)) ? e->speed_noise_rel : c->speed_noise_rel;
        const double gain_l = (e != NULL && !isnan(e->gain_left)) ? e->gain_left : c->gain_left;
        const double gain_r = (e != NULL && !isnan(e->gain_right)) ? e->gain_right : c->gain_right;
        double l = wr->cmd_left, rr = wr->cmd_right;
        if (sim_robot_halted(sim, i)) {
            l = rr = 0.0;       /* a stopped robot's motors are off */
        }
        /* Motor steps are counted as commanded: a blocked stepper still steps. */
        wr->steps_left += l * sim->dt;
        wr->steps_right += rr * sim->dt;
        if (!r->moves) {
            continue;
        }
        if (bias && (l != 0.0 || rr != 0.0)) {
            /* Seed 003's eq 3, read as ARGoS's differential-steering noise
             * (the paper's simulator; its symbols were lost in our copy, but
             * its words "a the actual actuation, f a random factor, w the
             * ideal actuation, b a random bias, both Gaussian" are ARGoS's):
             * a = f (w + b), b drawn once per robot and wheel per run
             * (wheels_create), f every step, and only while the robot is
             * commanded to move: a stopped Robot_Node does not creep.  The
             * motors cannot exceed HAL_WHEEL_SPEED_MAX (1000 steps/s =
             * 12.9 cm/s; speed_max, the robot model's where lower): a bias
             * above that saturates the wheels where the paper's robots (its
             * Figure 17 goes to a 20 cm/s sd) did not. */
            if (c->bias_per_step) {
                /* The other reading of "a random bias drawn from a Gaussian":
                 * a new b every step, which averages out along a path. */
                const double sd_steps = c->bias_sd / EPUCK_STEP_M;
                wr->bias_left = sd_steps * sim_rand_normal(&wr->bias_rand);
                wr->bias_right = sd_steps * sim_rand_normal(&wr->bias_rand);
            }
            l += wr->bias_left;
            rr += wr->bias_right;
            if (noise > 0.0) {
                l *= 1.0 + noise * sim_rand_normal(&wr->rand);
                rr *= 1.0 + noise * sim_rand_normal(&wr->rand);
            }
            l = fmax(-wr->speed_max, fmin(wr->speed_max, l));
            rr = fmax(-wr->speed_max, fmin(wr->speed_max, rr));
        } else if (noise > 0.0) {
            /* Without a bias: the factor f alone, at every step (as before
             * the bias existed: golden hashes unchanged). */
            l *= 1.0 + noise * sim_rand_normal(&wr->rand);
            rr *= 1.0 + noise * sim_rand_normal(&wr->rand);
        }
        /* The steps were counted as commanded; the wheels' true size sets how
         * far they go (x 1 exactly without calibration). */
        l *= gain_l;
        rr *= gain_r;
        faults_wheels(sim, i, &l, &rr);
        double v = 0.5 * (l + rr) * EPUCK_STEP_M;
        double w = (rr - l) * EPUCK_STEP_M / EPUCK_AXLE_M;
        sim->drive[i].v = (b2Vec2){ (float)(v * cos(r->theta)), (float)(v * sin(r->theta)) };
        sim->drive[i].w = (float)w;
    }
}

/* Robots take well under a microsecond each. */
#define DRIVE_CHUNK 256u

static void wheels_drive(sim_t *sim, void *self)
{
    (void)self;
    pool_for(sim->pool, sim->n, DRIVE_CHUNK, drive_range, sim);
}

/* The step counters are part of the state hash (after the pose). */
static uint64_t wheels_hash(const sim_t *sim, const void *self, uint32_t robot, uint64_t h)
{
    const wheels_robot_t *w = &robots(sim)[robot];
    (void)self;
    h = sim_hash_bytes(h, &w->steps_left, sizeof w->steps_left);
    return sim_hash_bytes(h, &w->steps_right, sizeof w->steps_right);
}

static void wheels_platform(const sim_t *sim, const void *self, uint32_t robot, uint64_t since,
                            robot_telemetry_platform_t *p)
{
    const wheels_robot_t *w = &robots(sim)[robot];
    (void)self;
    (void)since;
    p->wheel_left = w->cmd_left;
    p->wheel_right = w->cmd_right;
}

void sim_robot_wheels(const sim_t *sim, uint32_t i, int16_t *left, int16_t *right)
{
    SIM_ASSERT(i < sim->n);
    *left = robots(sim)[i].cmd_left;
    *right = robots(sim)[i].cmd_right;
}

/* ---------------------------------------------------------------- HAL */

static int16_t clamp_speed(int16_t v, int16_t max)
{
    return v > max ? max : (v < -max ? (int16_t)-max : v);
}

void hal_set_wheel_speeds(hal_t *hal, int16_t left_steps_s, int16_t right_steps_s)
{
    wheels_robot_t *w = &robots(hal->sim)[hal->index];
    w->cmd_left = clamp_speed(left_steps_s, w->speed_max);
    w->cmd_right = clamp_speed(right_steps_s, w->speed_max);
}

void hal_wheel_steps(hal_t *hal, int16_t *left, int16_t *right)
{
    const wheels_robot_t *w = &robots(hal->sim)[hal->index];
    /* 16-bit counters wrap as on the robot. */
    *left = (int16_t)(uint16_t)(int64_t)w->steps_left;
    *right = (int16_t)(uint16_t)(int64_t)w->steps_right;
}

static const char *const wheels_hal_calls[] = { "hal_set_wheel_speeds", "hal_wheel_steps", NULL };

#define F(name, unit, doc, type, field) { "wheels." name, unit, doc, type, 0, offsetof(wheels_robot_t, field), 1 }
static const model_field_t wheels_fields[] = {
    F("cmd_left", "steps/s", "commanded speed of the left wheel", SIM_FIELD_I16, cmd_left),
    F("cmd_right", "steps/s", "commanded speed of the right wheel", SIM_FIELD_I16, cmd_right),
    F("speed_max", "steps/s", "the fastest a wheel turns: hal.h's limit, or the robot model's motors' when lower",
      SIM_FIELD_I16, speed_max),
    F("steps_left", "steps", "commanded steps of the left wheel so far", SIM_FIELD_F64, steps_left),
    F("steps_right", "steps", "commanded steps of the right wheel so far", SIM_FIELD_F64, steps_right),
    F("bias_left", "steps/s", "eq 3's bias b of the left wheel", SIM_FIELD_F64, bias_left),
    F("bias_right", "steps/s", "eq 3's bias b of the right wheel", SIM_FIELD_F64, bias_right),
    { NULL, NULL, NULL, SIM_FIELD_U8, 0, 0, 0 }
};
#undef F

const model_def_t wheels_model = {
    .name = "wheels",
    .doc = "the two stepper motors, with seed 003's actuation noise (eq 3)",
    .config_size = sizeof(wheels_config_t),
    .default_config = wheels_defaults,
    .schema = &wheels_schema,
    .check = wheels_check,
    .free_config = wheels_free_config,
    .layout = wheels_layout,
    .create = wheels_create,
    .drive = wheels_drive,
    .hash = wheels_hash,
    .platform = wheels_platform,
    .hal_calls = wheels_hal_calls,
    .fields = wheels_fields,
};
