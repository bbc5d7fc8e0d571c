/*
 * targets.h - seed 002's world (RepAtt): 200 red targets in one of the five
 * layouts of its Figure 1, a central nest, and the pick-up rule; the run
 * ends when 90 % of the targets are picked up.  Scenario section `targets:`.
 *
 *   targets:
 *     distribution: one       # one | two | four | half | uniform (Fig 1 a-e)
 *     count: 200              # targets
 *     layout_side: 8.264      # m: the square the layout is drawn in (the 50 m
 *                             #   world's, kept when the world doubles)
 *     cluster_radius: 0.826   # m: one/two/four, targets uniform in discs
 *     cluster_offset: 2.479   # m: each cluster centre's |dx| and |dy| from the nest
 *     half_shape: cluster     # half: cluster (half in One's disc, half uniform)
 *                             #   or strip (all uniform over the half x >= 0)
 *     layout_seed: 1          # the layout's own seed (not the run's)
 *     target_radius: 0.010    # m
 *     target_height: 0.020    # m
 *     nest: { x: 0, y: 0, radius: 0.331 }   # m: a floor region, not an obstacle
 *     pick_time: 5            # s stationary per target
 *     pick_reach: 0.010       # m beyond body + target radius
 *     stop_fraction: 0.9      # end when ceil(0.9 x count) are picked up (0: never)
 *
 * The layouts (a reconstruction of Figure 1 from its caption and the text:
 * the figure's exact coordinates are not published; docs/notes/i14_targets.md
 * says what is read and what is chosen), all centred on the nest, inside the
 * layout square, outside the nest disc, no two targets overlapping:
 *   one      all targets uniform in one disc centred at (+o, +o);
 *   two      half in a disc at (+o, +o), half at (-o, -o);
 *   four     a quarter in each of the discs at (+-o, +-o);
 *   half     half_shape cluster: the even-numbered targets in One's disc at
 *            (+o, +o), the odd-numbered uniform over the layout square (the
 *            text groups Half with One and Two as "cluster distributions");
 *            half_shape strip: all uniform over the square's half x >= nest.x;
 *   uniform  uniform over the layout square;
 * (o = cluster_offset, target k goes to cluster k mod clusters).  The
 * positions are a pure function of the section (layout_seed included), never
 * of the run seed or the arena: the 100 m world's layout is the 50 m world's.
 *
 * Pick-up (i14 plan): a robot picks up a target when it has commanded wheel
 * speeds (0, 0) for pick_time (rounded to whole control periods) consecutive
 * control steps with that same target within reach at the start of each of
 * those steps: centre distance <= EPUCK_BODY_RADIUS_M + target_radius +
 * pick_reach.  Then the target leaves the world (NaN position; event
 * "pickup", value = its index).  Robots are checked in id order each step,
 * so of two robots waiting at one target the first to complete its wait
 * takes it (the lower id on the same step); the other's wait restarts on
 * another target within reach, if any.  Any robot can pick up; the task
 * reads only poses and commanded wheel speeds, never a controller's state.
 *
 * Time series: picked, in_nest.  Summary: time_to_stop_s, finished,
 * time_capped_s, picked, targets, stop_count, robots, efficiency (eq 7).
 * Draws the nest, a halo at every target left (1 cm targets vanish in a
 * picture of a 16 m world) and robots waiting on a target.
 */
#ifndef TASK_TARGETS_H
#define TASK_TARGETS_H

#include <stdint.h>

#include "swarmsim/task.h"

/** What `half` means (the paper's Figure 1d is not in its text). */
typedef enum targets_half_shape {
    TARGETS_HALF_CLUSTER = 0,  /**< half the targets in One's disc, half uniform over the square */
    TARGETS_HALF_STRIP = 1     /**< all uniform over the half x >= nest.x */
} targets_half_shape_t;

typedef enum targets_distribution {
    TARGETS_ONE = 0,
    TARGETS_TWO = 1,
    TARGETS_FOUR = 2,
    TARGETS_HALF = 3,
    TARGETS_UNIFORM = 4
} targets_distribution_t;

/** The `targets:` section. */
typedef struct targets_config {
    int distribution;          /**< targets_distribution_t */
    uint32_t count;            /**< targets */
    float layout_side;         /**< m: side of the square the layout is drawn in */
    float cluster_radius;      /**< m: one/two/four */
    float cluster_offset;      /**< m: |dx| = |dy| of each cluster centre from the nest */
    int half_shape;            /**< targets_half_shape_t (distribution half) */
    uint64_t layout_seed;      /**< the layout's seed (independent of the run seed) */
    float target_radius;       /**< m */
    float target_height;       /**< m (the camera's rows, pictures) */
    struct {
        float x, y;            /**< centre, m */
        float radius;          /**< m */
    } nest;
    float pick_time;           /**< s stationary per target */
    float pick_reach;          /**< m, tolerance beyond touching */
    float stop_fraction;       /**< 0..1; 0: the run goes on */
} targets_config_t;

extern const task_def_t targets_task;

/** The layout of `c`: count positions into x, y (m).  Returns 0, or -1 with
 *  a message when the targets do not fit. */
int targets_layout(const targets_config_t *c, float *x, float *y, char err[SIM_ERR_MAX]);

/** Targets that must be picked up to end the run: ceil(stop_fraction x
 *  count), 0 when stop_fraction is 0. */
uint32_t targets_stop_count(const targets_config_t *c);

/** The task's ground truth, for tests and tools. */
typedef struct targets_truth {
    uint32_t count;            /**< targets at the start */
    uint32_t picked;           /**< picked up so far */
    uint32_t in_nest;          /**< robots whose centre is in the nest now */
    double stop_time_s;        /**< when the stop count was reached; NaN: not yet */
} targets_truth_t;

/** The targets task's truth in `sim`, or 0 when it does not run. */
int targets_truth(const sim_t *sim, targets_truth_t *out);

/** Target `k` now: its item (NaN position once picked up), or NULL. */
const sim_item_t *targets_item(const sim_t *sim, uint32_t k);

#endif
