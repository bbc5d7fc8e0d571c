/*
 * faults.h - faults injected into robots (a group's `faults:`), the core's
 * side: who fails and when (drawn per run from the seed's RAND_FAULTS
 * streams), what each fault does to the robot's HAL, and the record of it
 * (events "fault" with the kind as detail, value 1 at onset and 0 at the
 * end; the summary's fault list and counts).  Internal to the core.
 *
 * Each fault of a group picks round(fraction x count) of its robots at
 * random; each picked robot gets its own onset: `at` s, or uniform over the
 * run (`at: random`), or after an exponential time of `rate` per s.  It
 * lasts `duration` s (0: to the end).  What it does:
 *   stop           the controller is not stepped and the wheels stop
 *   wheel_stall    the left wheel does not turn (its stepper still counts)
 *   wheel_drift    the left wheel turns at `value` x its command
 *   ir_fail        every proximity reading is 0 (nothing seen)
 *   ir_noise       proximity readings get Gaussian noise, sd `value` counts
 *   camera_fail    no blobs
 *   radio_dropout  the robot neither sends nor hears IR messages
 *   radio_bursts   dropouts of mean `duration` s, separated by a mean `value` s
 *   liar           every step it sends the well-formed but false message its
 *                  task defines (task_def_t.lie), instead of its own
 *   babble         every step it sends random bits
 */
#ifndef SIM_FAULTS_H
#define SIM_FAULTS_H

#include <stdint.h>
#include <stdio.h>

#include "hal.h"

struct sim;

/** Draws who fails and when.  Returns 0, or -1 (out of memory, err set). */
int faults_create(struct sim *sim, char err[256]);
void faults_destroy(struct sim *sim);

/** At the start of a step: faults begin and end (recorded as events),
 *  radio bursts come and go. */
void faults_begin_step(struct sim *sim);

/** Robot i's controller does not run and its wheels are stopped. */
int faults_stopped(const struct sim *sim, uint32_t i);
/** The wheel speeds robot i's motors really turn at (a stopped robot's
 *  commands are zeroed before, by the caller: its steppers do not step). */
void faults_wheels(struct sim *sim, uint32_t i, double *left, double *right);
/** Applies sensor faults to robot i's fresh proximity readings. */
void faults_ir(struct sim *sim, uint32_t i, uint16_t ir[HAL_IR_COUNT]);
/** Whether robot i's camera sees nothing. */
int faults_camera_blind(const struct sim *sim, uint32_t i);
/** Whether robot i's radio is out this step (sends and hears nothing). */
int faults_radio_out(const struct sim *sim, uint32_t i);
/** Before delivery: liars and babblers put their messages on the air. */
void faults_transmit(struct sim *sim);

struct scenario;
/** Whether any group of the scenario declares a fault. */
int sim_has_faults(const struct scenario *sc);

/** Summary metrics (only when the scenario has faults): appended by
 *  metrics_final. */
uint32_t faults_started(const struct sim *sim);
uint32_t faults_robots(const struct sim *sim);
/** The summary's "faults" list: [{robot, kind, start_s, end_s}, ...] as
 *  JSON, or nothing when the scenario has no faults. */
void faults_write_json(const struct sim *sim, FILE *f);

#endif
