/*
 * main.c - the swarmsim command line: swarmsim_command (command.c, the
 * same function the Python binding's run() calls) with the signals that
 * stop it.
 *
 * Exit codes: 0 success, 1 a run failed (I/O), 2 bad command line or
 * scenario, robots that cannot be placed, an LCM URL no provider takes, an
 * output folder it may not use (nothing is written), 130 / 143 stopped by
 * SIGINT / SIGTERM (finished runs kept; --resume continues).
 */
#include <signal.h>
#include <string.h>

#include "version.h"
#include "swarmsim/command.h"

/* The signal that asked to stop (0: none); the runner polls it. */
static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int sig)
{
    stop_signal = sig;
}

static void catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

int main(int argc, char **argv)
{
    catch_stop_signals();
    return swarmsim_command(argc, argv, SWARMSIM_VERSION, &stop_signal);
}
