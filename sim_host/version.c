/*
 * version.c - the build's code version for the shared library
 * (swarmsim/command.h).  Kept out of libswarm.a: the header changes with
 * every commit, and only this file and main.c read it.
 */
#include "version.h"
#include "swarmsim/command.h"

const char *swarmsim_code_version(void) { return SWARMSIM_VERSION; }
