"""A parameter scan with the Python API: how long 6 to 24 e-pucks take to
gather under a lamp (the tutorials' phototaxis controller and gather task),
three seeds each, with the swarm's mean distance to the lamp followed step
by step from the robots' arrays.  Writes OUT/scan.csv and OUT/scan.png.

    .venv/bin/python docs/examples/parameter_scan.py out/scan
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")              # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import swarmtools  # noqa: E402

SCENARIO = "sim_host/scenarios/phototaxis_gather.yaml"
LAMP = (0.5, 0.5)                  # the scenario's light, m

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/scan")
out.mkdir(parents=True, exist_ok=True)
rows, curves = [], {}
for count in (6, 12, 18, 24):
    for seed in (1, 2, 3):
        with swarmtools.Sim(SCENARIO, seed=seed, overrides={"robots.0.count": count}) as sim:
            robots = sim.robots                        # views: they follow the run, no copies
            distance = []
            while not sim.done and sim.step_count < sim.duration_steps:
                sim.step(10)
                distance.append(np.hypot(robots.x - LAMP[0], robots.y - LAMP[1]).mean())
            metrics = sim.task_metrics()
            rows.append({"robots": count, "seed": seed, "completion_time_s": metrics["completion_time_s"],
                         "arrivals": metrics["arrivals_total"], "state_hash": sim.state_hash})
            if seed == 1:
                curves[count] = distance

table = pd.DataFrame(rows)
table.to_csv(out / "scan.csv", index=False)
print(table.groupby("robots")["completion_time_s"].agg(["mean", "min", "max"]).round(1).to_string())

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
means = table.groupby("robots")["completion_time_s"]
left.errorbar(means.mean().index, means.mean(), yerr=means.std(), marker="o", capsize=4)
left.set(xlabel="robots", ylabel="time until 3/4 are in the goal, s", title="gathering under a lamp",
         xticks=sorted(curves))
for count, distance in curves.items():
    right.plot(np.arange(1, len(distance) + 1), distance, label=f"{count} robots")
right.set(xlabel="seconds", ylabel="mean distance to the lamp, m", title="seed 1")
right.legend()
fig.tight_layout()
fig.savefig(out / "scan.png", dpi=100)
print(f"wrote {out / 'scan.csv'} and {out / 'scan.png'}")
