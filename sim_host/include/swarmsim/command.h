/*
 * command.h - a whole run with its outputs, as the swarmsim command line
 * makes it: the options of `swarmsim --help` (one table, cli.c), the
 * scenario's checks, the runs on their threads, run_<seed>/summary.json,
 * timeseries.csv, telemetry.lcmlog and the aggregate, the messages on
 * stderr and the exit status.  main.c is this function and the signals
 * that stop it; the Python binding's swarmtools.run() calls it in process.
 */
#ifndef SIM_COMMAND_H
#define SIM_COMMAND_H

#include <signal.h>

/**
 * Does what `swarmsim ARGS...` does, argv[0] being the program's name as
 * the summaries' provenance records it ("swarmsim"), and returns its exit
 * status (0 done, 1 a run failed, 2 a bad option or scenario, nothing
 * written; 128 + the signal when stopped).  `code_version` goes into every
 * summary's provenance.  It installs no signal handler: setting *stop
 * (NULL: never) to SIGINT or SIGTERM, from a handler or another thread,
 * stops the runs as that signal stops the command line (finished runs
 * kept).  Messages and the progress bar go to stderr.
 */
int swarmsim_command(int argc, char **argv, const char *code_version, volatile sig_atomic_t *stop);

/** The code version of the build (`git describe`, as summaries record
 *  it).  Defined by the shared library (libswarmsim.so, sim_host/version.c),
 *  not by libswarm.a: a program that links the static library passes its
 *  own version to swarmsim_command (main.c: the generated version.h). */
const char *swarmsim_code_version(void);

#endif
