"""A tour of the Python API (docs/reference/python-api.md runs it): a run
stepped from Python, its robots' arrays, a loader error, two simulations
side by side, a whole run with its outputs, and its log as DataFrames.
Each claim is checked, so the page cannot drift from the code.

    .venv/bin/python docs/examples/api_tour.py out/tour
"""
import sys
from pathlib import Path

import numpy as np

import swarmtools

FORAGING = "sim_host/scenarios/foraging_base.yaml"
out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/tour")

# One run, stepped from Python: the arrays are views, they follow the run.
with swarmtools.Sim(FORAGING, seed=3, overrides={"robots.0.count": 12}) as sim:
    robots = sim.robots
    sim.step(300)                                   # 30 s of a 0.1 s control period
    print(f"t = {sim.time:.1f} s, {sim.robot_count} robots, first at ({robots.x[0]:.3f}, {robots.y[0]:.3f}) m")
    codes, names = robots.state_codes()
    print("robots by state:", {names[c]: int(n) for c, n in zip(*np.unique(codes[codes >= 0], return_counts=True),
                                                                  strict=True)})
    print("threshold of the first 4 robots:", robots.observable("threshold")[:4].round(3))
    print("food collected so far:", sim.task_metrics()["food_collected"])
    table = robots.to_frame()                       # a pandas snapshot, one row per robot
    assert len(table) == sim.robot_count
    hash_after_300 = sim.state_hash

# The same seed again gives the same run, bit for bit.
with swarmtools.Sim(FORAGING, seed=3, overrides={"robots.0.count": 12}) as again:
    again.step(300)
    assert again.state_hash == hash_after_300

# A mistake in a scenario is an exception that says where.
bad = out / "bad.yaml"
bad.parent.mkdir(parents=True, exist_ok=True)
bad.write_text("duration: 60\nrobots:\n  - controller: forager\n    count: -5\n")
try:
    swarmtools.Sim(bad)
except swarmtools.ScenarioError as e:
    print(f"ScenarioError: file {Path(e.file).name}, line {e.line}, key {e.key}: {e.reason}")
    assert (Path(e.file).name, e.line) == ("bad.yaml", 4)

# Several simulations in one process, stepped in turn (or from threads).
a = swarmtools.Sim("sim_host/scenarios/random_walk.yaml", seed=1)
b = swarmtools.Sim("sim_host/scenarios/random_walk.yaml", seed=2)
for _ in range(5):
    a.step(20)
    b.step(20)
print(f"two runs at t = {a.time:.1f} s: hashes {a.state_hash} and {b.state_hash}")
assert a.state_hash != b.state_hash
a.close()
b.close()

# A whole run with the command line's outputs, and the same hash from Sim.
run = swarmtools.run(FORAGING, seed=3, steps=300, out=out / "run", overrides={"robots.0.count": 12},
                     replace=True)
summary = run.runs[0].summary
assert summary["state_hash"] == hash_after_300, "swarmsim's run and Sim's are the same run"
print(f"swarmtools.run: {summary['command']}")

# Its telemetry log and its folder as pandas DataFrames.
log = swarmtools.load_log(run.runs[0].dir / "telemetry.lcmlog")
print(f"log: {len(log.swarm)} swarm states, {len(log.robots)} robot states, {len(log.events)} events")
foragers = log.robots[log.robots["controller"] == "forager"]
print(foragers.groupby("state", observed=True)["threshold"].mean().round(3).to_string())
folder = swarmtools.load_run(run.runs[0].dir)
assert folder.summary["state_hash"] == hash_after_300
print(f"timeseries.csv: {len(folder.timeseries)} rows, columns {list(folder.timeseries.columns)[:5]} ...")
