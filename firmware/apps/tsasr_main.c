/*
 * tsasr_main.c - seed 003's TSASR baseline image: the swarm robot (lost / explorer / chain member).
 * It is chain_main.c (the one source of the chain-baseline images).
 */
#define APP_CHAIN_TSASR 1
#define APP_CHAIN_ROLE PFIAS_ROLE_ROBOT
#include "chain_main.c"
