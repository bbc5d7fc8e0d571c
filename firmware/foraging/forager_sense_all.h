/*
 * forager_sense_all.h - seed 000's forager that also uses every sensor
 * every step: the simulator's full-sensing benchmark (tools/bench/scale.sh,
 * issue 18).  A forager reads only what its state needs (a waiting robot
 * reads its inbox and little else), so a swarm of foragers measures the
 * task's mix, not the cost of sensing.  This one runs the forager
 * unchanged, then reads all eight proximity and ambient sensors, the
 * camera's blobs and the three sound bands, sends an IR frame (its OAE
 * report, which the nest beacon counts anyway and foragers ignore, so the
 * extra frames change nothing but the radio's load) and plays a tone while
 * it is out of the nest.  Not for experiments: its extra reads draw sensor
 * noise that the forager alone would not.
 */
#ifndef FORAGER_SENSE_ALL_H
#define FORAGER_SENSE_ALL_H

#include "foraging/forager.h"

/* The forager first: the foraging task reads a forager_t at the state's
 * address (the gripper's robots, their task states, their OAEs). */
typedef struct forager_sense_all {
    forager_t forager;
    uint32_t sensed;             /**< a sum of every reading: keeps the reads */
} forager_sense_all_t;

typedef forager_params_t forager_sense_all_params_t;

CONTROLLER_API(forager_sense_all);

#define FORAGER_SENSE_ALL_NAME "forager_sense_all"

extern const controller_def_t forager_sense_all_def;

#endif
