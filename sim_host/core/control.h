/*
 * control.h - a running simulation controlled over LCM (swarmsim --control):
 * pause, resume, step N control periods, set the real-time factor, move a
 * robot, and inspect one robot's latest readings.
 *
 * Channels, on the control bus (CONTROL_DEFAULT_URL unless --control-lcm
 * names another):
 *   SWARM_CONTROL         control_t         commands, to the run
 *   SWARM_CONTROL_STATUS  control_status_t  from the run: at the start, the
 *                                           answer to each command, and about
 *                                           twice a second meanwhile
 *   ROBOT_DETAIL          robot_detail_t    the selected robot's readings,
 *                                           every control step
 * The default bus is LCM's multicast with ttl 0: what the run sends never
 * leaves this machine.  Its status carries a key drawn from the system's
 * random source when the run starts, and a command counts only with that
 * key, so a sender elsewhere on the network, which cannot hear the
 * status, cannot steer the run even though multicast reaches it.
 *
 * Every command but `select` is recorded: a SWARM_EVENT of kind "control"
 * in the telemetry (robot -1 for the run's own, the moved robot's id for a
 * move) and a line of summary.json's "control" (control_json).  Pause,
 * resume, step and realtime only decide when steps run, never what they
 * compute: a run paused and resumed ends with the state hash of one that
 * was not (tests/cli/control.sh).  A move changes the run: it is
 * "touched", and tools that pool runs (studies) refuse it.
 *
 * Everything happens on the run's own thread, between two steps: the
 * handlers change the sim only there.
 */
#ifndef SIM_CONTROL_H
#define SIM_CONTROL_H

#include <signal.h>
#include <stdint.h>

#include "swarmsim/sim.h"
#include "telemetry.h"

#define CONTROL_CHANNEL "SWARM_CONTROL"
#define CONTROL_CHANNEL_STATUS "SWARM_CONTROL_STATUS"
#define CONTROL_CHANNEL_DETAIL "ROBOT_DETAIL"
/** The loopback-only bus: LCM's default group, ttl 0. */
#define CONTROL_DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0"
/** Most steps one `step` command asks for. */
#define CONTROL_STEPS_MAX 1000000000LL

typedef struct control control_t;

/** Subscribes to the commands on `url` for the run of `sim` (of `steps`
 *  steps), whose
 *  telemetry `tel` records them and paces it; with `paused` the run waits
 *  for a command before its first step.  Returns 0, or -1 with a message
 *  in `err`. */
int control_open(const char *url, int paused, sim_t *sim, uint64_t steps, telemetry_t *tel, control_t **out,
                 char err[SIM_ERR_MAX]);

/** Before each step: takes the commands that came and, while paused,
 *  waits for one that lets the next step run.  Returns 0 when it may run,
 *  -1 when *stop was set meanwhile.  NULL c: 0 at once. */
int control_before_step(control_t *c, const volatile sig_atomic_t *stop);

/** After each step: the selected robot's details, the status when due. */
void control_after_step(control_t *c);

/** Non-zero once a command changed what the run computes (move). */
int control_touched(const control_t *c);

/** The run's "control" object for summary.json (its commands, whether it
 *  was touched), malloc'd, without a trailing comma; NULL c: NULL. */
char *control_json(const control_t *c);

/** Unsubscribes and frees. */
void control_close(control_t *c);

#endif
