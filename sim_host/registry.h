/*
 * registry.h - the controllers and tasks the simulator can run by name.
 * The core (scenario loading, --help) looks them up here.  The lists are
 * generated from the sources (tools/make/registry.sh): a controller's
 * `const controller_def_t NAME_def = {` in firmware/<folder>/NAME_def.c and
 * a task's `const task_def_t NAME = {` in sim_host/tasks/<task>/ register
 * it; no hand-kept list names one.
 */
#ifndef SIM_REGISTRY_H
#define SIM_REGISTRY_H

#include <stddef.h>

#include "common/controller.h"
#include "swarmsim/task.h"

/** The controller called `name`, or NULL. */
const controller_def_t *registry_controller(const char *name);
/** The i-th registered controller, or NULL past the end. */
const controller_def_t *registry_controller_at(size_t i);

/** The task whose scenario section is `name`, or NULL. */
const task_def_t *registry_task(const char *name);
/** The i-th registered task, or NULL past the end. */
const task_def_t *registry_task_at(size_t i);

/** The task whose `controllers` list `controller` (its world: without it
 *  that controller's robots have nothing to do), or NULL. */
const task_def_t *registry_task_for_controller(const char *controller);

/** Robots that run no firmware: they keep the wheel speeds last set through
 *  their hal_t (tests drive robots so) and are obstacles otherwise. */
extern const controller_def_t idle_def;

#endif
