"""swarmtools: the host tools of the e-puck swarm toolkit.

The simulator from Python (the public C API in build/libswarmsim.so):

    Sim(scenario, seed=..., overrides={...})   one run, stepped in this process
    run(scenario, ...)                          a whole run with its outputs, as swarmsim makes it
    load_log(path), load_run(folder)            telemetry and a run's outputs as pandas DataFrames

The command-line tools (swarm-bridge, swarm-monitor, ...) are the
subpackages; importing swarmtools loads none of the above until used.
"""
from typing import TYPE_CHECKING

_EXPORTS = {
    "Sim": "sim", "SimError": "sim", "ScenarioError": "sim", "run": "sim", "Run": "sim", "RunError": "sim",
    "load_log": "dataframes", "load_run": "dataframes", "iter_log": "dataframes", "LogData": "dataframes",
    "RunData": "dataframes",
}

__all__ = ["LogData", "Run", "RunData", "RunError", "ScenarioError", "Sim", "SimError", "iter_log", "load_log",
           "load_run", "run"]
assert sorted(__all__) == sorted(_EXPORTS)

if TYPE_CHECKING:
    from .dataframes import LogData, RunData, iter_log, load_log, load_run
    from .sim import Run, RunError, ScenarioError, Sim, SimError, run


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'swarmtools' has no attribute {name!r}")
    import importlib
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value
