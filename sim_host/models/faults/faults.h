/*
 * faults.h - faults injected into robots (a group's `faults:`), the core's
 * side: who fails and when (drawn per run from the seed's RAND_FAULTS
 * streams), what each fault does to the robot's HAL, and the record of it
 * (events "fault" with the kind as detail, value 1 at onset and 0 at the
 * end; the summary's fault list and counts).  Each group declares its own
 * (`robots[].faults`: the model's group keys); the other models ask this
 * one what a fault does to them (faults_ir, faults_radio_out, ...).
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
#ifndef SIM_MODELS_FAULTS_H
#define SIM_MODELS_FAULTS_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"

/** Most faults a group declares. */
#define FAULTS_MAX_PER_GROUP 8

/** What goes wrong with a robot (above). */
typedef enum fault_kind {
    FAULT_STOP = 0,          /**< controller and motors halted */
    FAULT_WHEEL_STALL,       /**< the left wheel does not turn */
    FAULT_WHEEL_DRIFT,       /**< the left wheel turns at `value` times its command */
    FAULT_IR_FAIL,           /**< proximity sensors read 0 */
    FAULT_IR_NOISE,          /**< proximity sensors get Gaussian noise of sd `value` */
    FAULT_CAMERA_FAIL,       /**< the camera sees nothing */
    FAULT_RADIO_DROPOUT,     /**< sends and hears nothing */
    FAULT_RADIO_BURSTS,      /**< dropouts of mean `duration` s, every `value` s on average */
    FAULT_LIAR,              /**< sends, every step, the false message its task defines */
    FAULT_BABBLE,            /**< sends random bits every step */
    FAULT_KIND_COUNT
} fault_kind_t;

/** The names of fault_kind_t (NULL-terminated): the scenario's `kind:` words. */
extern const char *const faults_kind_names[];

/** A fault of some of a group's robots, from an onset time. */
typedef struct fault_def {
    int kind;                   /**< fault_kind_t */
    float fraction;             /**< of the group's robots, rounded (1: all) */
    float at;                   /**< onset, s; NaN ("random"): uniform over the run */
    float rate;                 /**< > 0: onset after an exponential time of this rate, 1/s */
    float duration;             /**< s it lasts (0: to the end); radio_bursts: mean burst */
    float value;                /**< wheel_drift: speed factor; ir_noise: sd, counts;
                                     radio_bursts: mean time between bursts, s */
} fault_def_t;

/** A group's keys (`robots[].faults`). */
typedef struct faults_group_config {
    uint32_t fault_count;
    fault_def_t faults[FAULTS_MAX_PER_GROUP];
} faults_group_config_t;

/** Group g's faults in `sc`. */
static inline const faults_group_config_t *faults_of_group(const robot_group_t *g)
{
    return (const faults_group_config_t *)scenario_group_model_config(g, SIM_MODEL_faults);
}
static inline faults_group_config_t *faults_of_group_mut(robot_group_t *g)
{
    return (faults_group_config_t *)scenario_group_model_config_mut(g, SIM_MODEL_faults);
}

/** One fault of one robot, as drawn for this run. */
typedef struct fault_run {
    uint32_t robot;
    uint8_t kind;                  /**< fault_kind_t */
    uint8_t active, bad;           /**< bad: in a radio burst */
    uint64_t on_step, off_step;    /**< UINT64_MAX: never */
    float value, duration;
    double start_s, end_s;         /**< NaN until it happens */
} fault_run_t;

/** The faults drawn for this run, in group then declaration order: their
 *  count, and the list in *out. */
uint32_t faults_drawn(const sim_t *sim, const fault_run_t **out);

/** Robot i's controller does not run and its wheels are stopped. */
int faults_stopped(const sim_t *sim, uint32_t i);
/** The wheel speeds robot i's motors really turn at (a stopped robot's
 *  commands are zeroed before, by the caller: its steppers do not step). */
void faults_wheels(const sim_t *sim, uint32_t i, double *left, double *right);
/** Applies sensor faults to robot i's fresh proximity readings. */
void faults_ir(sim_t *sim, uint32_t i, uint16_t ir[HAL_IR_COUNT]);
/** Whether robot i's camera sees nothing. */
int faults_camera_blind(const sim_t *sim, uint32_t i);
/** Whether robot i's radio is out this step (sends and hears nothing). */
int faults_radio_out(const sim_t *sim, uint32_t i);

#endif
