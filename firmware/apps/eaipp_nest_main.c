/*
 * eaipp_nest_main.c - seed 003's EAIPP image: Robot_Nest, the fixed
 * gradient source at the nest.  It is eaipp_main.c (the one source of the
 * EAIPP images) with the role nest.
 */
#define APP_EAIPP_ROLE EAIPP_ROLE_NEST
#include "eaipp_main.c"
