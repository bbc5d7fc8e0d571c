/*
 * gather.h - the example task of the README's "Write your own task": how
 * many robots are inside a goal circle, and a run that ends when enough of
 * them are.  Scenario section `gather:`.
 *
 *   gather:
 *     goal: { x: 0, y: 0, radius: 0.4 }   # m: a robot is in when its centre is
 *     stop_fraction: 0.8                  # end the run when this share is in (0: never)
 *
 * Time series: in_goal (robots).  Summary: max_in_goal, mean_in_goal; with
 * a stop_fraction, the core adds completed and completion_time_s.  Draws
 * the goal as a ring on the floor and the robots inside it in green.
 */
#ifndef TASK_GATHER_H
#define TASK_GATHER_H

#include "swarmsim/task.h"

typedef struct gather_config {
    struct {
        float x, y;        /**< m */
        float radius;      /**< m */
    } goal;
    float stop_fraction;   /**< 0..1; 0: the run goes on */
} gather_config_t;

extern const task_def_t gather_task;

#endif
