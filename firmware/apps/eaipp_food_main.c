/*
 * eaipp_food_main.c - seed 003's EAIPP image: Robot_Food, the fixed
 * gradient source at the food.  It is eaipp_main.c (the one source of the
 * EAIPP images) with the role food.
 */
#define APP_EAIPP_ROLE EAIPP_ROLE_FOOD
#include "eaipp_main.c"
