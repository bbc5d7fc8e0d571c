/*
 * nnea_evolved.h - the genome NNEA runs by default (nnea_default_params):
 * written by `swarm-evolve` (tools/swarmtools/evolve) as its best
 * genome's C initialisers.  Replace it with a run's best_params.h.
 *
 * Placeholder: the zero genome (every output 1/2: the robot stands still).
 */
#ifndef FW_NNEA_EVOLVED_H
#define FW_NNEA_EVOLVED_H

#define NNEA_EVOLVED_W_IN { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, \
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 }
#define NNEA_EVOLVED_W_REC { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 }
#define NNEA_EVOLVED_B_HIDDEN { 0, 0, 0, 0 }
#define NNEA_EVOLVED_TAU { 0, 0, 0, 0 }
#define NNEA_EVOLVED_W_OUT { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 }
#define NNEA_EVOLVED_B_OUT { 0, 0, 0 }

#endif
