/*
 * faults.c - faults injected into robots (faults.h).
 */
#include "faults.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/sim_internal.h"
#include "models/ircom/ircom.h"
#include "registry.h"

#define NEVER UINT64_MAX

/* ---------------------------------------------------------------- keys */

/* The names of fault_kind_t, in its order. */
const char *const faults_kind_names[] = {
    "stop", "wheel_stall", "wheel_drift", "ir_fail", "ir_noise", "camera_fail", "radio_dropout",
    "radio_bursts", "liar", "babble", NULL
};

#define FLT fault_def_t
static const param_desc_t fault_params[] = {
    { .key = "kind", PARAM_ENUM_FIELD(FLT, kind, faults_kind_names),
      .doc = "what goes wrong (docs: models, faults)" },
    { .key = "fraction", PARAM_FIELD(FLT, fraction, float), .min = 0, .max = 1,
      .doc = "of the group's robots, drawn per run (rounded)" },
    { .key = "at", PARAM_ANGLE_FIELD(FLT, at), .min = 0, .max = 1e7,
      .doc = "onset, s, or random (uniform over the run)" },
    { .key = "rate", PARAM_FIELD(FLT, rate, float), .min = 0, .max = 1000,
      .doc = "> 0: onset after an exponential time of this rate, 1/s (instead of at)" },
    { .key = "duration", PARAM_FIELD(FLT, duration, float), .min = 0, .max = 1e7,
      .doc = "s it lasts (0: to the end); radio_bursts: mean burst length, s" },
    { .key = "value", PARAM_FIELD(FLT, value, float), .min = -1e6, .max = 1e6,
      .doc = "wheel_drift: speed factor; ir_noise: sd, counts; radio_bursts: mean gap, s" },
    PARAM_END
};
#undef FLT

static const fault_def_t fault_default = { FAULT_STOP, 1.0f, NAN, 0.0f, 0.0f, 0.0f };

/* A fault's value must mean something for its kind. */
static int check_fault(const loader_t *ld, const ynode_t *item, const char *path, void *elem)
{
    const fault_def_t *f = elem;
    char p[SCHEMA_PATH_MAX];
    if ((f->kind == FAULT_WHEEL_DRIFT && !(f->value >= 0.0f && f->value <= 2.0f))
        || (f->kind == FAULT_IR_NOISE && !(f->value > 0.0f))
        || (f->kind == FAULT_RADIO_BURSTS && !(f->value > 0.0f && f->duration > 0.0f))) {
        schema_join(p, path, "value");
        return schema_fail(ld, schema_node_of(item, "value"), p, "%s needs %s", faults_kind_names[f->kind],
                           f->kind == FAULT_WHEEL_DRIFT ? "a speed factor in [0, 2] (0.8: 20 % slow)"
                           : f->kind == FAULT_IR_NOISE ? "a noise sd > 0, counts (e.g. 200)"
                           : "a mean gap > 0 s (value) and a mean burst > 0 s (duration)");
    }
    if (!isnan(f->at) && f->rate > 0.0f) {
        schema_join(p, path, "rate");
        return schema_fail(ld, schema_node_of(item, "rate"), p, "give `at` or `rate`, not both");
    }
    return 0;
}

static const schema_t fault_schema = { fault_params, NULL, NULL, NULL };
static const seq_desc_t faults_seq = {
    "faults", FAULTS_MAX_PER_GROUP, sizeof(fault_def_t), &fault_default, &fault_schema,
    offsetof(faults_group_config_t, faults), offsetof(faults_group_config_t, fault_count), check_fault, 0, NULL
};
static const child_t group_children[] = {
    { "faults", CHILD_SEQUENCE, NULL, &faults_seq, "faults injected into some of the robots" },
    CHILD_END
};
static const schema_t faults_group_schema = { NULL, group_children, NULL, NULL };
/* No top-level section: a group declares its own faults. */
static const schema_t faults_schema = { NULL, NULL, NULL, NULL };

/* A liar sends what the task of its controller says a lie is. */
static int faults_check(const void *config, const scenario_t *sc, char path[SCHEMA_PATH_MAX], char msg[SIM_ERR_MAX])
{
    (void)config;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        const robot_group_t *grp = &sc->groups[g];
        const faults_group_config_t *fg = faults_of_group(grp);
        const task_def_t *world = registry_task_for_controller(grp->def->name);
        for (uint32_t k = 0; k < fg->fault_count; k++) {
            if (fg->faults[k].kind == FAULT_LIAR && (world == NULL || world->lie == NULL)) {
                snprintf(path, SCHEMA_PATH_MAX, "robots.%u.faults.%u.kind", g, k);
                snprintf(msg, SIM_ERR_MAX, "controller '%s' has no task that defines what a lying robot sends "
                         "(task_def_t.lie); use babble for random messages", grp->def->name);
                return -1;
            }
        }
    }
    return 0;
}

/* Whether any group of the scenario declares a fault (for a robot). */
static int has_faults(const scenario_t *sc)
{
    for (uint32_t g = 0; g < sc->group_count; g++) {
        if (faults_of_group(&sc->groups[g])->fault_count > 0 && sc->groups[g].count > 0) return 1;
    }
    return 0;
}

/* ---------------------------------------------------------------- a run */

/* How many of each kind are active on one robot, and their values. */
typedef struct faults_robot {
    uint8_t on[FAULT_KIND_COUNT];
    uint8_t bursting;              /* in a radio_bursts dropout now */
    float drift;                   /* wheel_drift factor */
    float ir_noise_sd;             /* ir_noise, counts */
    sim_rand_t rand;               /* babble bits, ir_noise, bursts (RAND_FAULTS) */
} faults_robot_t;

typedef struct faults {
    fault_run_t *list;
    uint32_t n, cap;
    uint8_t *hit;                  /* n robots: the summary's count (faulty_robots) */
    uint32_t active;               /* faults active now: with none, what the other
                                      models ask per robot reads no robot's record */
} faults_t;

static faults_robot_t *robots(const sim_t *sim)
{
    return sim_model_array(sim, SIM_MODEL_faults, 0);
}

static int none_active(const sim_t *sim)
{
    const faults_t *fs = sim_model_self(sim, SIM_MODEL_faults);
    return fs->active == 0;
}

static void faults_layout(const void *config, const scenario_t *sc, model_layout_t *out)
{
    (void)config;
    out->arrays = 1;
    out->elem_size[0] = sizeof(faults_robot_t);
    uint32_t n = 0;
    for (uint32_t g = 0; g < sc->group_count; g++) {
        n += faults_of_group(&sc->groups[g])->fault_count * sc->groups[g].count;
    }
    out->run_bytes = sizeof(faults_t) + (size_t)n * sizeof(fault_run_t) + scenario_robot_count(sc);
}

static uint64_t step_of(const struct sim *sim, double t_s)
{
    double s = ceil(t_s / sim->dt - 1e-9);
    return s < 0.0 ? 0 : (s >= 1.8e19 ? NEVER : (uint64_t)s);
}

/* Picks round(fraction x count) of the group's robots (a partial
 * Fisher-Yates shuffle of their indices), each with its own onset. */
static int schedule(struct sim *sim, faults_t *fs, uint32_t g, uint32_t first, uint32_t fi)
{
    const robot_group_t *grp = &sim->sc->groups[g];
    const fault_def_t *f = &faults_of_group(grp)->faults[fi];
    uint32_t pick = (uint32_t)lround((double)f->fraction * grp->count);
    double run_s = sim->sc->duration;
    sim_rand_t rnd;
    uint32_t *idx = malloc((grp->count ? grp->count : 1) * sizeof *idx);
    if (!idx) return -1;
    sim_rand_seed(&rnd, sim->seed, (uint64_t)g * FAULTS_MAX_PER_GROUP + fi, RAND_FAULTS);
    for (uint32_t k = 0; k < grp->count; k++) idx[k] = first + k;
    for (uint32_t k = 0; k < pick; k++) {
        uint32_t j = k + (uint32_t)(sim_rand_uniform(&rnd) * (grp->count - k));
        if (j >= grp->count) j = grp->count - 1;
        uint32_t t = idx[k];
        idx[k] = idx[j];
        idx[j] = t;
        double onset = f->rate > 0.0f ? -log(1.0 - sim_rand_uniform(&rnd)) / f->rate
                       : isnan(f->at) ? sim_rand_uniform(&rnd) * run_s : f->at;
        if (fs->n == fs->cap) {
            uint32_t c = fs->cap ? 2 * fs->cap : 16;
            fault_run_t *grown = realloc(fs->list, c * sizeof *grown);
            if (!grown) {
                free(idx);
                return -1;
            }
            fs->list = grown;
            fs->cap = c;
        }
        fault_run_t *fr = &fs->list[fs->n++];
        memset(fr, 0, sizeof *fr);
        fr->robot = idx[k];
        fr->kind = (uint8_t)f->kind;
        fr->on_step = step_of(sim, onset);
        /* radio_bursts comes and goes inside its fault; it ends with the run */
        fr->off_step = (f->duration > 0.0f && f->kind != FAULT_RADIO_BURSTS)
                       ? fr->on_step + (uint64_t)fmax(1.0, round(f->duration / sim->dt)) : NEVER;
        fr->value = f->value;
        fr->duration = f->duration;
        fr->start_s = fr->end_s = NAN;
    }
    free(idx);
    return 0;
}

/* Who fails and when, drawn per run. */
static int faults_create(sim_t *sim, const void *config, void **self, char err[SIM_ERR_MAX])
{
    const scenario_t *sc = sim->sc;
    uint32_t first = 0;
    faults_t *fs = calloc(1, sizeof *fs);
    (void)config;
    if (!fs) {
        snprintf(err, SIM_ERR_MAX, "out of memory scheduling faults");
        return -1;
    }
    *self = fs;
    if (!(fs->hit = calloc(sim->n ? sim->n : 1, 1))) {
        snprintf(err, SIM_ERR_MAX, "out of memory scheduling faults");
        return -1;
    }
    for (uint32_t g = 0; g < sc->group_count; first += sc->groups[g].count, g++) {
        for (uint32_t fi = 0; fi < faults_of_group(&sc->groups[g])->fault_count; fi++) {
            if (schedule(sim, fs, g, first, fi) != 0) {
                snprintf(err, SIM_ERR_MAX, "out of memory scheduling faults");
                return -1;
            }
        }
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&robots(sim)[i].rand, sim->seed, i, RAND_FAULTS);
    }
    return 0;
}

static void faults_destroy(void *self)
{
    faults_t *fs = self;
    if (fs) {
        free(fs->list);
        free(fs->hit);
        free(fs);
    }
}

uint32_t faults_drawn(const sim_t *sim, const fault_run_t **out)
{
    const faults_t *fs = sim_model_self(sim, SIM_MODEL_faults);
    *out = fs->list;
    return fs->n;
}

/* The summary's start_s / end_s are the times of the fault's events: the
 * telemetry stamps what happened in a step with the time at its end. */
static void set_active(struct sim *sim, faults_t *fs, fault_run_t *fr, int on)
{
    faults_robot_t *r = &robots(sim)[fr->robot];
    double step_end_s = (double)(sim->step + 1) * sim->sc->control_period_ms / 1000.0;
    fr->active = (uint8_t)on;
    fs->active = on ? fs->active + 1 : fs->active - 1;
    if (on) {
        r->on[fr->kind]++;
        if (fr->kind == FAULT_WHEEL_DRIFT) r->drift = fr->value;
        if (fr->kind == FAULT_IR_NOISE) r->ir_noise_sd = fr->value;
        fr->start_s = step_end_s;
    } else {
        r->on[fr->kind]--;
        fr->end_s = step_end_s;
    }
    sim_event(sim, fr->robot, "fault", faults_kind_names[fr->kind], on);
}

/* At the start of a step: faults begin and end (recorded as events),
 * radio bursts come and go. */
static void faults_begin_step(sim_t *sim, void *self)
{
    faults_t *fs = self;
    for (uint32_t k = 0; k < fs->n; k++) {
        fault_run_t *fr = &fs->list[k];
        if (!fr->active && sim->step == fr->on_step) {
            set_active(sim, fs, fr, 1);
        } else if (fr->active && sim->step == fr->off_step) {
            set_active(sim, fs, fr, 0);
        }
        if (fr->active && fr->kind == FAULT_RADIO_BURSTS) {
            /* A two-state channel: in a burst it leaves with probability
             * dt / duration a step, between bursts enters with dt / gap. */
            faults_robot_t *r = &robots(sim)[fr->robot];
            double u = sim_rand_uniform(&r->rand);
            if (fr->bad ? u < sim->dt / fr->duration : u < sim->dt / fr->value) {
                fr->bad = (uint8_t)!fr->bad;
                r->bursting = fr->bad;
            }
        }
    }
}

int faults_stopped(const sim_t *sim, uint32_t i)
{
    return !none_active(sim) && robots(sim)[i].on[FAULT_STOP] != 0;
}

static int faults_halts(const sim_t *sim, const void *self, uint32_t robot)
{
    (void)self;
    return faults_stopped(sim, robot);
}

void faults_wheels(const sim_t *sim, uint32_t i, double *left, double *right)
{
    (void)right;
    if (none_active(sim)) return;
    const faults_robot_t *r = &robots(sim)[i];
    if (r->on[FAULT_WHEEL_DRIFT]) *left *= r->drift;
    if (r->on[FAULT_WHEEL_STALL]) *left = 0.0;
}

void faults_ir(sim_t *sim, uint32_t i, uint16_t ir[HAL_IR_COUNT])
{
    if (none_active(sim)) return;
    faults_robot_t *r = &robots(sim)[i];
    if (r->on[FAULT_IR_FAIL]) {
        memset(ir, 0, HAL_IR_COUNT * sizeof *ir);
    } else if (r->on[FAULT_IR_NOISE]) {
        for (unsigned k = 0; k < HAL_IR_COUNT; k++) {
            double v = ir[k] + r->ir_noise_sd * sim_rand_normal(&r->rand);
            ir[k] = (uint16_t)fmin(fmax(v, 0.0), (double)HAL_RAW_MAX);
        }
    }
}

int faults_camera_blind(const sim_t *sim, uint32_t i)
{
    return !none_active(sim) && robots(sim)[i].on[FAULT_CAMERA_FAIL] != 0;
}

int faults_radio_out(const sim_t *sim, uint32_t i)
{
    if (none_active(sim)) return 0;
    const faults_robot_t *r = &robots(sim)[i];
    return r->on[FAULT_RADIO_DROPOUT] != 0 || (r->on[FAULT_RADIO_BURSTS] && r->bursting);
}

/* Before delivery (this model comes before ircom in the list): liars and
 * babblers put their messages on the air. */
static void faults_transmit(sim_t *sim, void *self)
{
    faults_t *fs = self;
    for (uint32_t k = 0; k < fs->n; k++) {
        const fault_run_t *fr = &fs->list[k];
        faults_robot_t *r = &robots(sim)[fr->robot];
        if (!fr->active || faults_stopped(sim, fr->robot)) continue;   /* a stopped robot is silent */
        if (fr->kind == FAULT_BABBLE) {
            ircom_set_outgoing(sim, fr->robot, (uint16_t)sim_rand_u64(&r->rand));
        } else if (fr->kind == FAULT_LIAR) {
            for (uint32_t t = 0; t < sim->n_tasks; t++) {
                if (sim->tasks[t].def->lie) {
                    ircom_set_outgoing(sim, fr->robot, sim->tasks[t].def->lie(sim->tasks[t].self, sim, fr->robot));
                    break;
                }
            }
        }
    }
}

/* ---------------------------------------------------------------- reports */

static uint32_t started(const faults_t *fs)
{
    uint32_t n = 0;
    for (uint32_t k = 0; k < fs->n; k++) n += !isnan(fs->list[k].start_s);
    return n;
}

static uint32_t faulty_robots(const struct sim *sim, const faults_t *fs)
{
    uint8_t *hit = fs->hit;
    uint32_t n = 0;
    memset(hit, 0, sim->n);
    for (uint32_t k = 0; k < fs->n; k++) {
        const fault_run_t *fr = &fs->list[k];
        if (!isnan(fr->start_s) && !hit[fr->robot]) {
            hit[fr->robot] = 1;
            n++;
        }
    }
    return n;
}

/* Only when the scenario has faults: other summaries keep their keys. */
static void faults_final(const sim_t *sim, const void *self, metric_list_t *out)
{
    const faults_t *fs = self;
    if (has_faults(sim->sc)) {
        metrics_put(out, "faults_started", "", "injected faults that began during the run", (double)started(fs));
        metrics_put(out, "faulty_robots", "robots", "robots with at least one fault begun",
                    (double)faulty_robots(sim, fs));
    }
}

/* The summary's "faults" list: [{robot, kind, start_s, end_s}, ...]. */
static void faults_write_json(const sim_t *sim, const void *self, FILE *f)
{
    const faults_t *fs = self;
    if (!has_faults(sim->sc)) {
        return;
    }
    fputs("  \"faults\": [", f);
    for (uint32_t k = 0, shown = 0; k < fs->n; k++) {
        const fault_run_t *fr = &fs->list[k];
        if (isnan(fr->start_s)) continue;   /* its onset fell after the run */
        fprintf(f, "%s\n    {\"robot\": %u, \"kind\": \"%s\", \"start_s\": %.10g, \"end_s\": ", shown++ ? "," : "",
                fr->robot, faults_kind_names[fr->kind], fr->start_s);
        if (isnan(fr->end_s)) fputs("null}", f);
        else fprintf(f, "%.10g}", fr->end_s);
    }
    fputs("\n  ],\n", f);
}

const model_def_t faults_model = {
    .name = "faults",
    .doc = "faults injected into robots: stops, wheels, sensors, radios, liars (robots[].faults)",
    .schema = &faults_schema,
    .check = faults_check,
    .group_config_size = sizeof(faults_group_config_t),
    .group_schema = &faults_group_schema,
    .layout = faults_layout,
    .create = faults_create,
    .destroy = faults_destroy,
    .begin_step = faults_begin_step,
    .halts = faults_halts,
    .after_control = faults_transmit,
    .final = faults_final,
    .write_json = faults_write_json,
};
