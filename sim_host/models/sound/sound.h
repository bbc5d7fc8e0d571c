/*
 * sound.h - the sound field: what every robot's microphones hear of the
 * others' speakers, per band, over one control period.  Seed 002's model
 * (section III.A): a robot j emitting in band k is a source that robot i
 * hears as eq 1, A_ij = a0 e^(-alpha d_ij) + ae (d_ij centre to centre, m);
 * robot i's level in band k is eq 2's sum over every other robot j, each
 * pair's term with its own multiplicative noise, eq 4:
 * B_ij = A_ij (1 - N(0, noise^2)).
 *
 * Decisions (docs/notes/i14_sound.md says why):
 *  - silent_robots: ambient (default): a robot silent in band k still adds
 *    its ambient term ae to band k (eq 2 over all j != i, the ambient term
 *    once per robot); none: only the band's emitters are in the sum.
 *  - The three microphones hear the same level (the ~7 cm across the body
 *    are ignored: e^(-alpha 0.07) differs from 1 by < 6 % at alpha 0.726/m,
 *    and the paper's robots carry one omnidirectional microphone).
 *  - self_masking: a robot whose speaker played during the period hears
 *    nothing (hal_mic_level answers HAL_ERR_BUSY); off, every robot hears
 *    the others while it emits (the paper's idealised full duplex).  A
 *    robot never hears itself (eq 2's j != i).
 *  - cutoff > 0: an emitter farther away than cutoff adds only its ambient
 *    term; the error is at most a0 e^(-alpha cutoff) per such emitter
 *    (before noise).  The robots beyond it are one term per band, their m
 *    ambient terms with one noise draw, m ae (1 - noise N / sqrt(m)), the
 *    distribution of m separate draws; so a listener's work grows with the
 *    robots within the cutoff (found on the robot grid), not with the
 *    swarm.  A cutoff beyond every distance gives the all-pairs field
 *    draw for draw (per_term; summed, to the rounding of the sums).  0 (the default): every pair exact, eq 2 as the paper
 *    writes it, work growing with the square of the swarm.
 *  - Levels are counts: round(1000 x the sum), clamped to [0, UINT32_MAX].
 *  - Noise comes from the listener's own stream (RAND_SOUND), one draw per
 *    term in the sum, sources in id order then bands 1..3: the field is a
 *    function of (seed, poses, speakers), whatever the thread count or the
 *    order in which robots step.
 *  - noise_draws: summed (models/noise_draws.h): one draw per listener and
 *    band for its whole sum, sd noise sqrt(sum of the squared terms): eq
 *    4's distribution, three draws a listener instead of three a source;
 *    the near sources are then summed in the grid's order, unsorted
 *    (whose cells follow the largest reach of every model: a level's last
 *    bit may then depend on another model's settings, never on threads).
 * A robot id may have its microphones' gain per band (`robots`: what the
 * calibration kit fits): its levels are the field's times the gain,
 * rounded; the field itself and its draws are unchanged.
 * When: sim_step computes the field once per step, after the tasks'
 * before_control and before the controllers step (with a cutoff, listener
 * by listener on the run's threads; all pairs in one loop), from the poses at
 * that moment and the speakers as they played during the last period (what
 * each robot set in the step before).  Read between steps (tests), the
 * field is the one the next step's controllers will see.
 */
#ifndef SIM_MODELS_SOUND_H
#define SIM_MODELS_SOUND_H

#include <stdint.h>

#include "hal.h"
#include "models/model.h"

/** What a robot silent in a band adds to that band's sum (silent_robots). */
typedef enum sound_silent {
    SOUND_SILENT_AMBIENT = 0,    /**< its ambient term ae (eq 2 over every other robot) */
    SOUND_SILENT_NONE = 1        /**< nothing: only emitters are in the sum */
} sound_silent_t;

/** One robot's microphones as fitted (`sound.robots`, models/per_robot.h):
 *  each band's level times its gain (NaN: 1), the calibration kit's. */
typedef struct sound_robot_cal {
    uint16_t id;                        /**< hal_robot_id */
    float gain[HAL_SOUND_BANDS];        /**< [0] unused; bands 1..3 */
} sound_robot_cal_t;

/** Section `sound` (seed 002's eqs 1-4).  Disabled: hal_mic_level and
 *  hal_speaker_set answer HAL_ERR_UNAVAILABLE and nothing is drawn. */
typedef struct sound_config {
    uint8_t enabled;
    double a0;                 /**< eq 1's level at the source (0 m), units */
    double alpha;              /**< eq 1's attenuation, 1/m (at the scenario's scale) */
    double ae;                 /**< eq 1's ambient term, units, once per source */
    double noise;              /**< eq 4's relative sd per pair (0.06: N100, 0: N0) */
    int silent_robots;         /**< sound_silent_t */
    uint8_t self_masking;      /**< a robot whose speaker played hears nothing (HAL_ERR_BUSY) */
    double cutoff;             /**< m; > 0: sources farther away give only ae (0: exact) */
    int noise_draws;           /**< noise_draws_t: eq 4 drawn per pair, or once per band's sum */
    uint32_t robot_count;      /**< `robots` */
    sound_robot_cal_t *robots; /**< on the heap (free_config) */
} sound_config_t;

MODEL_CONFIG_ACCESSORS(sound, sound_config_t)

/** Eq 1 without noise: what robot j at distance d_m (m) adds to one band of
 *  robot i's sum, in units: a0 e^(-alpha d) + ae when j emits in that band
 *  (only ae beyond a cutoff > 0), ae when it is silent in it and
 *  silent_robots is ambient, else 0. */
double sound_term(const sound_config_t *cfg, double d_m, int emits);

/** Level counts of a sum of units: round(1000 x units), 0 for a sum <= 0
 *  (or NaN), UINT32_MAX above it. */
uint32_t sound_counts(double units);

#endif
