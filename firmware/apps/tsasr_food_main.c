/*
 * tsasr_food_main.c - seed 003's TSASR baseline image: the food (target), a
 * fixed robot that broadcasts TSASR FOOD frames.  It is tsasr_main.c (the
 * one source of the TSASR images) with the role food.
 */
#define APP_TSASR_ROLE TSASR_ROLE_FOOD
#include "tsasr_main.c"
