"""The simulator in this process (swarmtools.Sim) and whole runs with their
outputs (swarmtools.run), over the simulator's public C API
(sim_host/include/swarmsim/) in build/libswarmsim.so."""
from .run import Run, RunError, run
from .simulation import Event, FieldInfo, Group, Observable, Robots, ScenarioError, Sim, SimError

__all__ = ["Event", "FieldInfo", "Group", "Observable", "Robots", "Run", "RunError", "ScenarioError", "Sim",
           "SimError", "run"]
