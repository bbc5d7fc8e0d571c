/*
 * pfias_nest_main.c - seed 003's PFIAS baseline image: the nest, a fixed robot that broadcasts PFIAS NEST frames.
 * It is chain_main.c (the one source of the chain-baseline images).
 */
#define APP_CHAIN_TSASR 0
#define APP_CHAIN_ROLE PFIAS_ROLE_NEST
#include "chain_main.c"
