/*
 * areas.h - the nest and food areas of Sperati, Trianni and Nolfi's path
 * formation (seed 003's NNEA baseline): a disc on the floor under each
 * robot of the nest group and of the food group, that the robots' ground
 * sensors see, and the trips robots make between them.  Section `areas:`.
 *
 *   areas:
 *     nest_group: nest        # the groups whose robots stand on the areas
 *     food_group: food
 *     radius: 0.2             # m, each disc
 *     nest_reflectance: 0.0   # black (ground sensor about 0 counts)
 *     food_reflectance: 0.5   # grey (about 500 counts; the bare floor is white)
 *
 * The discs are placed where the source robots stand when the run starts,
 * so a sweep that moves the nest and the food (seed 003's distance axis)
 * moves their areas with them.  A trip (ground truth, from poses): a robot
 * of neither group whose centre enters the area other than the one it was
 * last in (the paper's fitness counts robots going from one area to the
 * other).
 *
 * Time series: trips.  Summary: trips_total, trips_per_robot, visited_both
 * (robots that have been in both areas).
 */
#ifndef TASK_AREAS_H
#define TASK_AREAS_H

#include "swarmsim/task.h"

#define AREAS_GROUP_NAME_MAX 32

typedef struct areas_config {
    char nest_group[AREAS_GROUP_NAME_MAX];
    char food_group[AREAS_GROUP_NAME_MAX];
    float radius;             /**< m */
    float nest_reflectance;   /**< 0 black .. 1 white */
    float food_reflectance;
} areas_config_t;

extern const task_def_t areas_task;

#endif
