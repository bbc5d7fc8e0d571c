/*
 * tsasr_nest_main.c - seed 003's TSASR baseline image: the nest, a fixed
 * robot that broadcasts TSASR NEST frames.  It is tsasr_main.c (the one
 * source of the TSASR images) with the role nest.
 */
#define APP_TSASR_ROLE TSASR_ROLE_NEST
#include "tsasr_main.c"
