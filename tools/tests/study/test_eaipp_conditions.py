"""Seed 003's comparison sweeps (studies/eaipp_*.yaml with a controller axis:
distance, obstacles) run every controller in the same world: for each
condition, the effective scenario the simulator writes for each controller
(swarmsim --steps 1, its run_<seed>/scenario.yaml, the file with the sweep's
overrides applied) is the same but for the controller itself and its
documented success criterion (swarmtools.study.eaipp.CRITERIA), and the
nest-food distance the paths task measures is the same.  An NNEA entry that
kept nnea_square.yaml's 1.8 m in the 3 m obstacle rows fails here.  About
70 one-step runs (a few seconds), with the real simulator (env SWARMSIM)."""
from __future__ import annotations

import copy
import json
import os
import subprocess
import tempfile
import unittest
from pathlib import Path
from typing import Any

import yaml

from swarmtools.study import eaipp as E
from swarmtools.sweep import plan as sweep_plan
from swarmtools.sweep import spec as sweep_spec
from swarmtools.sweep.spec import SCENARIO_KEY

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM

# What is a controller's own in a scenario, and so may differ between the
# controllers of one condition (every other key must be equal):
GROUP_OWN = ("controller", "policy", "params", "ground_sensors")   # robots[*]: who runs, with what sensors
TOP_OWN = ("name", "areas")      # areas: NNEA's floor discs under the nest and food (docs/studies/nnea.md)
IRCOM_OWN = ("tx_per_period",)   # messages a period: each controller's images' own
PATHS_OWN = ("nodes",)           # the success criterion: checked against CRITERIA instead


def world(effective: dict[str, Any]) -> dict[str, Any]:
    """The effective scenario without what is the controller's own."""
    w = copy.deepcopy(effective)
    for k in TOP_OWN:
        w.pop(k, None)
    for g in w.get("robots", []):
        for k in GROUP_OWN:
            g.pop(k, None)
    for section, own in (("ircom", IRCOM_OWN), ("paths", PATHS_OWN)):
        for k in own:
            w.get(section, {}).pop(k, None)
    return w


def comparison_sweeps() -> list[sweep_spec.Sweep]:
    out = []
    for path in sorted((ROOT / "studies").glob("eaipp_*.yaml")):
        sw = sweep_spec.load(path, 2**53 - 1)
        if any(SCENARIO_KEY in a.keys for a in sw.axes):
            out.append(sw)
    return out


class SameWorldForEveryController(unittest.TestCase):
    def test_the_comparison_sweeps_are_found(self) -> None:
        names = {sw.path.name for sw in comparison_sweeps()}
        self.assertLessEqual({"eaipp_distance.yaml", "eaipp_obstacles.yaml"}, names)

    def test_conditions_identical_but_controller_and_criterion(self) -> None:
        for sw in comparison_sweeps():
            with self.subTest(sweep=sw.path.name), tempfile.TemporaryDirectory() as d:
                axis_keys = {k for a in sw.axes if SCENARIO_KEY in a.keys for k in a.keys}
                sw.seeds = sw.seeds[:1]
                by_condition: dict[tuple, dict[str, tuple[dict, float]]] = {}
                for run in sweep_plan.expand(sw):
                    ctrl = E.controller({}, run.scenario)
                    cond = tuple((k, sweep_spec.set_text(v)) for k, v in run.params.items() if k not in axis_keys)
                    out = Path(d) / f"r{run.index}"
                    cmd = [str(SWARMSIM), run.scenario, "--seed", str(run.seed), "--steps", "1", "--threads", "1",
                           "--lcm", "off", "--out", str(out)]
                    for k, v in run.overrides:
                        cmd += ["--set", f"{k}={v}"]
                    r = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
                    self.assertEqual(r.returncode, 0, r.stderr)
                    effective = yaml.safe_load((out / f"run_{run.seed}" / "scenario.yaml").read_text())
                    summary = json.loads((out / f"run_{run.seed}" / "summary.json").read_text())
                    nodes = (effective.get("paths") or {}).get("nodes", E.DEFAULT_CRITERION)
                    self.assertEqual(nodes, E.criterion(ctrl),
                                     f"{sw.path.name} {dict(cond)}: {ctrl} is scored with nodes: {nodes}, "
                                     f"its documented criterion is {E.criterion(ctrl)}")
                    self.assertNotIn(ctrl, by_condition.setdefault(cond, {}), f"{ctrl} listed twice")
                    by_condition[cond][ctrl] = (world(effective), summary["metrics"]["distance_m"])
                self.assertGreater(len(by_condition), 1)
                controllers = {c for runs in by_condition.values() for c in runs}
                self.assertLessEqual({"EAIPP", "PFIAS", "TSASR", "NNEA"}, controllers)
                for cond, runs in by_condition.items():
                    self.assertEqual(set(runs), controllers, f"{sw.path.name} {dict(cond)}: a controller is missing")
                    (first, (w0, d0)), *rest = sorted(runs.items())
                    for ctrl, (w, dist) in rest:
                        self.assertEqual(dist, d0, f"{sw.path.name} {dict(cond)}: D {dist} m for {ctrl}, "
                                                   f"{d0} m for {first}")
                        self.assertEqual(w, w0, f"{sw.path.name} {dict(cond)}: {ctrl}'s world is not {first}'s")

    def test_the_criterion_names_no_condition(self) -> None:
        # paths.nodes sits on the controller axis, one value per controller:
        # the tables' conditions leave it out (no "(paths.nodes=still)" on every row)
        for sw in comparison_sweeps():
            with self.subTest(sweep=sw.path.name):
                own = E.own_keys(sw)
                self.assertEqual(own["NNEA"], {E.NODES: "any"})
                self.assertEqual(own["EAIPP"], {E.NODES: "still"})
                self.assertNotIn(E.NODES, E.condition_keys(sw))
                self.assertIn(SCENARIO_KEY, E.condition_keys(sw))


if __name__ == "__main__":
    unittest.main()
