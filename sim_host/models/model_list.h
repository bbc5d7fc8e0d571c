/*
 * model_list.h - the simulator's models (model.h), one line each, in the
 * order their sections appear in --help and their hooks run within each
 * phase of a step.  Adding a model: its folder under sim_host/models/ and
 * one line here.
 *
 * The order matters where two models meet in one phase: faults put the
 * faulty robots' messages on the air before ircom delivers the step's
 * messages (after_control).
 */
SIM_MODEL(robot)
SIM_MODEL(faults)
SIM_MODEL(ir)
SIM_MODEL(camera)
SIM_MODEL(tracker)
SIM_MODEL(host)
SIM_MODEL(uart)
SIM_MODEL(sound)
SIM_MODEL(ircom)
SIM_MODEL(wheels)
SIM_MODEL(ground)
SIM_MODEL(pil)
