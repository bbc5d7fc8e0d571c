# platforms/host/platform.mk - the host platform: the simulator, software in
# the loop.  Included by tools/make/firmware.mk for the line `host` of
# platforms/platforms.list.
#
# Its HAL is sim_host/core/sim_hal.c (hal.h for simulated robots: one hal_t
# per robot, sensors computed lazily once per control step from the
# simulated world), bound at link time like every platform's: the Makefile
# links it into libswarm with the controllers (FW_SRC), and the simulator's
# tests are this platform's tests.  Its run loop is the simulator's step
# (sim_host/core/sim.c): each robot's controller runs through its
# controller_def_t, found by name in the registry (tools/make/registry.sh),
# with the robot's own telemetry (firmware/telemetry/robot_telemetry.c)
# when a scenario asks.  Function pointers are fine here: no stack gate
# measures a host build, and one binary runs every controller.
#
# It has no images (a scenario says which controller each robot runs), so
# no images.list and no platform.py.  The HAL and the run loop stay in
# sim_host/ while the simulator's modules are reorganised; they are this
# folder's hal/ and run/ in everything but their place.
HOST_HAL_SRC := sim_host/core/sim_hal.c
