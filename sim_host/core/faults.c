/*
 * faults.c - faults injected into robots (faults.h).
 */
#include "faults.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sim_internal.h"

#define NEVER UINT64_MAX

static uint64_t step_of(const struct sim *sim, double t_s)
{
    double s = ceil(t_s / sim->dt - 1e-9);
    return s < 0.0 ? 0 : (s >= 1.8e19 ? NEVER : (uint64_t)s);
}

/* Picks round(fraction x count) of the group's robots (a partial
 * Fisher-Yates shuffle of their indices), each with its own onset. */
static int schedule(struct sim *sim, uint32_t g, uint32_t first, uint32_t fi, fault_run_t **out, uint32_t *n,
                    uint32_t *cap)
{
    const robot_group_t *grp = &sim->sc->groups[g];
    const fault_def_t *f = &grp->faults[fi];
    uint32_t pick = (uint32_t)lround((double)f->fraction * grp->count);
    double run_s = sim->sc->duration;
    sim_rand_t rnd;
    uint32_t *idx = malloc((grp->count ? grp->count : 1) * sizeof *idx);
    if (!idx) return -1;
    sim_rand_seed(&rnd, sim->seed, (uint64_t)g * SCENARIO_MAX_FAULTS + fi, RAND_FAULTS);
    for (uint32_t k = 0; k < grp->count; k++) idx[k] = first + k;
    for (uint32_t k = 0; k < pick; k++) {
        uint32_t j = k + (uint32_t)(sim_rand_uniform(&rnd) * (grp->count - k));
        if (j >= grp->count) j = grp->count - 1;
        uint32_t t = idx[k];
        idx[k] = idx[j];
        idx[j] = t;
        double onset = f->rate > 0.0f ? -log(1.0 - sim_rand_uniform(&rnd)) / f->rate
                       : isnan(f->at) ? sim_rand_uniform(&rnd) * run_s : f->at;
        if (*n == *cap) {
            uint32_t c = *cap ? 2 * *cap : 16;
            fault_run_t *grown = realloc(*out, c * sizeof *grown);
            if (!grown) {
                free(idx);
                return -1;
            }
            *out = grown;
            *cap = c;
        }
        fault_run_t *fr = &(*out)[(*n)++];
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

int faults_create(struct sim *sim, char err[256])
{
    const scenario_t *sc = sim->sc;
    uint32_t cap = 0, first = 0;
    sim->faults = NULL;
    sim->n_faults = 0;
    for (uint32_t g = 0; g < sc->group_count; first += sc->groups[g].count, g++) {
        for (uint32_t fi = 0; fi < sc->groups[g].fault_count; fi++) {
            if (schedule(sim, g, first, fi, &sim->faults, &sim->n_faults, &cap) != 0) {
                snprintf(err, 256, "out of memory scheduling faults");
                return -1;
            }
        }
    }
    for (uint32_t i = 0; i < sim->n; i++) {
        sim_rand_seed(&sim->robots[i].fault_rand, sim->seed, i, RAND_FAULTS);
    }
    return 0;
}

void faults_destroy(struct sim *sim)
{
    free(sim->faults);
    sim->faults = NULL;
    sim->n_faults = 0;
}

/* The summary's start_s / end_s are the times of the fault's events: the
 * telemetry stamps what happened in a step with the time at its end. */
static void set_active(struct sim *sim, fault_run_t *fr, int on)
{
    sim_robot_t *r = &sim->robots[fr->robot];
    double step_end_s = (double)(sim->step + 1) * sim->sc->control_period_ms / 1000.0;
    fr->active = (uint8_t)on;
    if (on) {
        r->fault_on[fr->kind]++;
        if (fr->kind == FAULT_WHEEL_DRIFT) r->drift = fr->value;
        if (fr->kind == FAULT_IR_NOISE) r->ir_noise_sd = fr->value;
        fr->start_s = step_end_s;
    } else {
        r->fault_on[fr->kind]--;
        fr->end_s = step_end_s;
    }
    sim_event(sim, fr->robot, "fault", scenario_fault_names[fr->kind], on);
}

void faults_begin_step(struct sim *sim)
{
    for (uint32_t k = 0; k < sim->n_faults; k++) {
        fault_run_t *fr = &sim->faults[k];
        if (!fr->active && sim->step == fr->on_step) {
            set_active(sim, fr, 1);
        } else if (fr->active && sim->step == fr->off_step) {
            set_active(sim, fr, 0);
        }
        if (fr->active && fr->kind == FAULT_RADIO_BURSTS) {
            /* A two-state channel: in a burst it leaves with probability
             * dt / duration a step, between bursts enters with dt / gap. */
            sim_robot_t *r = &sim->robots[fr->robot];
            double u = sim_rand_uniform(&r->fault_rand);
            if (fr->bad ? u < sim->dt / fr->duration : u < sim->dt / fr->value) {
                fr->bad = (uint8_t)!fr->bad;
                r->radio_bursting = fr->bad;
            }
        }
    }
}

int faults_stopped(const struct sim *sim, uint32_t i)
{
    return sim->robots[i].fault_on[FAULT_STOP] != 0;
}

void faults_wheels(struct sim *sim, uint32_t i, double *left, double *right)
{
    const sim_robot_t *r = &sim->robots[i];
    (void)right;
    if (r->fault_on[FAULT_WHEEL_DRIFT]) *left *= r->drift;
    if (r->fault_on[FAULT_WHEEL_STALL]) *left = 0.0;
}

void faults_ir(struct sim *sim, uint32_t i, uint16_t ir[HAL_IR_COUNT])
{
    sim_robot_t *r = &sim->robots[i];
    if (r->fault_on[FAULT_IR_FAIL]) {
        memset(ir, 0, HAL_IR_COUNT * sizeof *ir);
    } else if (r->fault_on[FAULT_IR_NOISE]) {
        for (unsigned k = 0; k < HAL_IR_COUNT; k++) {
            double v = ir[k] + r->ir_noise_sd * sim_rand_normal(&r->fault_rand);
            ir[k] = (uint16_t)fmin(fmax(v, 0.0), (double)HAL_RAW_MAX);
        }
    }
}

int faults_camera_blind(const struct sim *sim, uint32_t i)
{
    return sim->robots[i].fault_on[FAULT_CAMERA_FAIL] != 0;
}

int faults_radio_out(const struct sim *sim, uint32_t i)
{
    const sim_robot_t *r = &sim->robots[i];
    return r->fault_on[FAULT_RADIO_DROPOUT] != 0 || (r->fault_on[FAULT_RADIO_BURSTS] && r->radio_bursting);
}

void faults_transmit(struct sim *sim)
{
    uint16_t mask = (uint16_t)((1u << sim->sc->ircom.payload_bits) - 1u);
    for (uint32_t k = 0; k < sim->n_faults; k++) {
        const fault_run_t *fr = &sim->faults[k];
        sim_robot_t *r = &sim->robots[fr->robot];
        if (!fr->active || faults_stopped(sim, fr->robot)) continue;   /* a stopped robot is silent */
        if (fr->kind == FAULT_BABBLE) {
            r->ircom_tx[0] = (uint16_t)((uint16_t)sim_rand_u64(&r->fault_rand) & mask);
            r->ircom_tx_n = 1;
        } else if (fr->kind == FAULT_LIAR) {
            for (uint32_t t = 0; t < sim->n_tasks; t++) {
                if (sim->tasks[t].def->lie) {
                    r->ircom_tx[0] = (uint16_t)(sim->tasks[t].def->lie(sim->tasks[t].self, sim, fr->robot) & mask);
                    r->ircom_tx_n = 1;
                    break;
                }
            }
        }
    }
}

int sim_has_faults(const scenario_t *sc)
{
    for (uint32_t g = 0; g < sc->group_count; g++) {
        if (sc->groups[g].fault_count > 0 && sc->groups[g].count > 0) return 1;
    }
    return 0;
}

uint32_t faults_started(const struct sim *sim)
{
    uint32_t n = 0;
    for (uint32_t k = 0; k < sim->n_faults; k++) n += !isnan(sim->faults[k].start_s);
    return n;
}

uint32_t faults_robots(const struct sim *sim)
{
    uint8_t *hit = calloc(sim->n ? sim->n : 1, 1);
    uint32_t n = 0;
    if (!hit) return 0;
    for (uint32_t k = 0; k < sim->n_faults; k++) {
        const fault_run_t *fr = &sim->faults[k];
        if (!isnan(fr->start_s) && !hit[fr->robot]) {
            hit[fr->robot] = 1;
            n++;
        }
    }
    free(hit);
    return n;
}

void faults_write_json(const struct sim *sim, FILE *f)
{
    fputs("  \"faults\": [", f);
    for (uint32_t k = 0, shown = 0; k < sim->n_faults; k++) {
        const fault_run_t *fr = &sim->faults[k];
        if (isnan(fr->start_s)) continue;   /* its onset fell after the run */
        fprintf(f, "%s\n    {\"robot\": %u, \"kind\": \"%s\", \"start_s\": %.10g, \"end_s\": ", shown++ ? "," : "",
                fr->robot, scenario_fault_names[fr->kind], fr->start_s);
        if (isnan(fr->end_s)) fputs("null}", f);
        else fprintf(f, "%.10g}", fr->end_s);
    }
    fputs("\n  ],\n", f);
}
