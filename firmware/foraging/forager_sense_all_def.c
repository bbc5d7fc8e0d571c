/*
 * forager_sense_all_def.c - the full-sensing benchmark's forager as the
 * simulator runs it: the forager's keys, policies and observables.
 */
#include "foraging/forager_sense_all.h"

/* No keys of its own: the forager's defaults, with what the foraging task
 * tells every forager (a benchmark sets no behaviour). */
static const param_desc_t forager_sense_all_params[] = { PARAM_END };

CONTROLLER_ADAPTERS(forager_sense_all)

const controller_def_t forager_sense_all_def = {
    .name = FORAGER_SENSE_ALL_NAME,
    .doc = "benchmark: seed 000's forager that also reads every sensor, sends a frame and plays a tone every step",
    CONTROLLER_FUNCS(forager_sense_all),
    .params = forager_sense_all_params,
    .policies = ta_policy_names,
    .set_policy = forager_set_policy,   /* its params are the forager's */
    .observables = forager_observables,
    .ircom_bits = 16,
};
