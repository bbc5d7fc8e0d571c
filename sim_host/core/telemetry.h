/*
 * telemetry.h - LCM telemetry of a simulation run.
 *
 * Publishes the message types of lcm_types/ (package swarmlcm) on these
 * channels:
 *   RUN_INFO     run_info_t      at step 0, then every 10 s of simulated time
 *   TELEMETRY_SCHEMA schema_t    with every RUN_INFO: the names, units and kinds of
 *                                each controller's values and of the swarm's
 *   SWARM_STATE  swarm_state_t   every 1/swarm_hz simulated seconds (and the last step)
 *   ROBOT_STATE  robot_state_t   every robot every 1/robot_hz simulated seconds (and the last step)
 *   SWARM_EVENT  event_t         as they happen: counters going up, state
 *                                changes, escapes, and the tasks' own events
 *   RUN_SUMMARY  run_summary_t   once, at the end (the metrics of summary.json)
 *   SCENE, TASK_DRAWING          the arena and the tasks' drawing, for views that
 *                                draw the run (telemetry_scene.h)
 * to an LCM provider URL (udpm://, tcpq://, memq://, file://, ...) or, by
 * default, to an LCM log file in the run folder (LCM's log format, byte for
 * byte what lcm_eventlog writes) whose event timestamps are the SIMULATED
 * time in microseconds: the file is a pure function of the run's seed
 * (bit-identical for any --threads), and lcm-logplayer replays it at the
 * pace of the simulated run.  (A file:// URL goes through LCM's own log
 * provider instead, which stamps events with the wall clock.)
 *
 * Telemetry only reads: a run's results are the same with and without it
 * (sensor summaries come from the readings the controllers already made).
 * One telemetry_t per run; different runs' telemetry_t are independent (one
 * lcm_t each), so runs publish from their own threads.
 */
#ifndef SIM_TELEMETRY_H
#define SIM_TELEMETRY_H

#include <stdint.h>

#include "swarmsim/metrics.h"
#include "swarmsim/sim.h"

#define TELEMETRY_CHANNEL_RUN_INFO "RUN_INFO"
#define TELEMETRY_CHANNEL_SWARM_STATE "SWARM_STATE"
#define TELEMETRY_CHANNEL_ROBOT_STATE "ROBOT_STATE"
#define TELEMETRY_CHANNEL_EVENT "SWARM_EVENT"
#define TELEMETRY_CHANNEL_RUN_SUMMARY "RUN_SUMMARY"
#define TELEMETRY_CHANNEL_SCHEMA "TELEMETRY_SCHEMA"

/** Default rates, per simulated second: 1 state per robot (20 robots: 20
 *  messages/s), and the swarm state at the 10 Hz control rate. */
#define TELEMETRY_DEFAULT_ROBOT_HZ 1.0
#define TELEMETRY_DEFAULT_SWARM_HZ 10.0
/** The default sink: this file in the run folder. */
#define TELEMETRY_LOG_NAME "telemetry.lcmlog"

typedef struct telemetry_options {
    int enabled;        /**< 0: no telemetry at all (--lcm off) */
    const char *url;    /**< LCM provider URL; NULL: the run folder's log file */
    double robot_hz;    /**< robot states per robot per simulated second (0: none) */
    double swarm_hz;    /**< swarm states per simulated second (0: none) */
    double realtime;    /**< > 0: run no faster than this many times real time */
} telemetry_options_t;

/** Enabled, log file, default rates, as fast as possible. */
void telemetry_default_options(telemetry_options_t *opt);

/** Parses "ROBOT_HZ[,SWARM_HZ]" (non-negative numbers, at most 1000) into
 *  `opt`.  Returns 0, or -1 if the text is not that. */
int telemetry_parse_rate(const char *text, telemetry_options_t *opt);

/** Whether an LCM provider takes `url` (opened and closed at once), given
 *  by the command-line `option` the message names ("--lcm").
 *  Returns 0, or -1 with a message in `err`. */
int telemetry_check_url(const char *option, const char *url, char err[SIM_ERR_MAX]);

typedef struct telemetry telemetry_t;

/** Opens the telemetry of the run of `sim`: the URL of `opt`, or when it is
 *  NULL an LCM log at `log_path` (written as log_path.tmp and renamed by
 *  telemetry_close).  *out is NULL when opt->enabled is 0.  Returns 0, or
 *  -1 with a message in `err`. */
int telemetry_open(const telemetry_options_t *opt, const sim_t *sim, const char *log_path,
                   telemetry_t **out, char err[SIM_ERR_MAX]);

/** Before the first step of a run of `steps` steps: RUN_INFO and the
 *  states at step 0. */
void telemetry_begin(telemetry_t *t, const sim_t *sim, uint64_t steps);

/** After each sim_step: the step's events, the states that are due, and
 *  the pacing of opt->realtime.  NULL t: nothing. */
void telemetry_step(telemetry_t *t, const sim_t *sim);

/** After the last step: the final states (when not just sent) and
 *  RUN_SUMMARY with `final` (summary.json's metrics) and the state hash. */
void telemetry_end(telemetry_t *t, const sim_t *sim, const metric_list_t *final, uint64_t state_hash);

/** Closes the sink and frees `t`.  With `keep` the log file is renamed into
 *  place, otherwise removed.  Returns 0, or -1 with a message in `err` if
 *  writing failed (publishing to a URL never fails a run: messages that
 *  could not be sent are counted and reported on stderr). */
int telemetry_close(telemetry_t *t, int keep, char err[SIM_ERR_MAX]);

/** One event of `kind` now (SWARM_EVENT), of robot `robot` (its pose) or,
 *  with robot -1, of the run as a whole (pose_known 0): what a command of
 *  control.h did.  NULL t: nothing. */
void telemetry_event(telemetry_t *t, const sim_t *sim, int32_t robot, const char *kind, const char *detail,
                     int32_t value);

/** From now on, run no faster than `factor` (> 0) times real time, counted
 *  from the simulated time now: a run that was paused does not rush to
 *  catch up.  NULL t: nothing. */
void telemetry_set_realtime(telemetry_t *t, const sim_t *sim, double factor);

/** The real-time factor now (0: as fast as it goes). */
double telemetry_realtime(const telemetry_t *t);

/** Messages published so far. */
uint64_t telemetry_message_count(const telemetry_t *t);

/** The lcm_t of a URL sink (NULL for the log file): tests subscribe to a
 *  memq:// sink through it. */
struct _lcm_t *telemetry_lcm(telemetry_t *t);

#endif
