/*
 * pfias_main.c - seed 003's PFIAS baseline image: the swarm robot (lost / explorer / chain member).
 * It is chain_main.c (the one source of the chain-baseline images).
 */
#define APP_CHAIN_TSASR 0
#define APP_CHAIN_ROLE PFIAS_ROLE_ROBOT
#include "chain_main.c"
