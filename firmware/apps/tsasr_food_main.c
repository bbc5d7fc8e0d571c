/*
 * tsasr_food_main.c - seed 003's TSASR baseline image: the food (target), a fixed robot that broadcasts TSASR FOOD frames.
 * It is chain_main.c (the one source of the chain-baseline images).
 */
#define APP_CHAIN_TSASR 1
#define APP_CHAIN_ROLE PFIAS_ROLE_FOOD
#include "chain_main.c"
