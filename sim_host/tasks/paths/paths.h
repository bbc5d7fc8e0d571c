/*
 * paths.h - seed 003's path-formation task: two fixed robots, the nest and
 * the food, too far apart to hear each other, and a swarm that must link
 * them with a chain of robots.  Scenario section `paths:`.
 *
 *   paths:
 *     nest_group: nest     # the robot group(s) that stand for Robot_Nest and
 *     food_group: food     #   Robot_Food (moves: false, at least one robot each)
 *     range: 0.6           # m: R, the communication range a link may span
 *     budget: 1000         # s: the run's allowance (seed 003: 10,000 steps of 100 ms)
 *     hold: 1.0            # s: how long a chain must stand to count (0: one step)
 *     nodes: still         # still: a chain's nodes stand still (EAIPP's Robot_Node);
 *                          #   any: moving robots count too (the paths NNEA's robots make)
 *
 * The task never reads a controller's state: it judges from poses, the
 * commanded wheel speeds and the obstacles, the same for EAIPP, PFIAS and
 * TSASR.  Two criteria, both recorded (docs/notes/i15_paths.md says why):
 *
 *  - merge (section 4.3, the success criterion): "the two networks become
 *    connected and merge to form a network connecting both the Robot_Nest
 *    and the Robot_Food".  A node is a robot of neither source group whose
 *    wheels are commanded (0, 0) this step (Robot_Node "stops moving"; an
 *    explorer's wheel law, Algorithm 3, never stops both wheels).  Two
 *    robots are linked when their centres are at most `range` apart and no
 *    obstacle cuts the segment between them (as IR messages, ircom.c).  The
 *    networks have merged at the end of step k when a chain of links through
 *    nodes joins a nest robot to a food robot at every step from k to
 *    k + hold; the merge time is the end of step k, and the run ends (done)
 *    once the hold is over.
 *  - food perceived (section 5.2): "if the Robot_Food is not perceived
 *    during this time period ... the experiment is considered a failure".
 *    The end of the first step at which a robot of neither source group is
 *    linked to a food robot (within `range`, line of sight clear), whatever
 *    it does.
 *
 * Either counts only within the budget.  A run without a merge is a
 * failure, recorded as the paper records it: merge_time_capped_s is the
 * budget (Figure 11 plots failed runs at 10,000 steps).  The scenario's
 * duration must be at least the budget.
 *
 * Time series: nodes, nest_side, food_side, linked, perceivers.
 * Summary: success, merge_time_s, merge_time_capped_s, merge_steps_capped,
 * food_perceived, food_time_s, food_time_capped_s, chain_nodes, nodes_end,
 * distance_m, budget_s.  Draws the nest and the food with their range
 * rings, the links of the nest's and the food's networks, the chain, and
 * the nodes.
 */
#ifndef TASK_PATHS_H
#define TASK_PATHS_H

#include <stdint.h>

#include "swarmsim/task.h"

#define PATHS_GROUP_NAME_MAX 32

/** The `paths:` section. */
typedef struct paths_config {
    char nest_group[PATHS_GROUP_NAME_MAX];   /**< the group of Robot_Nest */
    char food_group[PATHS_GROUP_NAME_MAX];   /**< the group of Robot_Food */
    float range;               /**< R, m: a link's longest span */
    float budget;              /**< s: merges and perceptions after it do not count */
    float hold;                /**< s: a chain must stand this long past its first step */
    int nodes;                 /**< paths_nodes_t: which robots may be a chain's nodes */
} paths_config_t;

/** `nodes:` which robots of neither source group a chain may pass through. */
typedef enum paths_nodes {
    PATHS_NODES_STILL = 0,     /**< `still` (default): wheels commanded (0, 0) this step, EAIPP's Robot_Node */
    PATHS_NODES_ANY = 1,       /**< `any`: every robot, moving or not (a path of moving robots, Sperati et al.'s) */
} paths_nodes_t;

extern const task_def_t paths_task;

/** The task's ground truth, for tests and tools. */
typedef struct paths_truth {
    uint32_t nodes;            /**< robots standing still now (neither nest nor food) */
    uint32_t nest_side;        /**< nodes linked to a nest robot through nodes now */
    uint32_t food_side;        /**< nodes linked to a food robot through nodes now */
    int linked;                /**< a chain joins nest and food now */
    uint32_t chain_nodes;      /**< nodes on the shortest chain now (0: none) */
    uint32_t perceivers;       /**< robots linked to a food robot now */
    double merge_time_s;       /**< NaN: not (yet) within the budget */
    double food_time_s;        /**< NaN: not (yet) within the budget */
} paths_truth_t;

/** The paths task's truth in `sim`, or 0 when it does not run. */
int paths_truth(const sim_t *sim, paths_truth_t *out);

/** Robot `i`'s place on the current chain, nest side first (0 the nest
 *  robot), or -1 when it is on none. */
int32_t paths_chain_index(const sim_t *sim, uint32_t i);

#endif
