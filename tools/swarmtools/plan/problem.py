"""The planning problem (the package docstring states it), a plan's times and
lengths, and the targets of a scenario as the simulator lays them out.

Node numbering of the distance matrix ``Problem.dist``: 0 is the nest centre,
``k + 1`` is target ``k`` (the task's item index, the value of its "pickup"
event), and the last node ``END = m + 1`` is a phantom at distance 0 from
every node: the end of an open route, so that inserting a target after a
route's last one costs ``d(last, t) + d(t, END) - d(last, END) = d(last, t)``
by the same formula as anywhere else.

The targets come from the simulator itself, never from a copy of its layout
code: ``load_world`` runs ``swarmsim SCENARIO --steps 1`` into a temporary
folder and reads, from what every run writes,

* the items of the first TASK_DRAWING message of ``telemetry.lcmlog`` (sent
  before the first step: every target still there, in the task's order;
  positions as the simulator holds them, float32),
* ``summary.json``: ``robots``, ``targets`` and ``stop_count``,
* the run's ``scenario.yaml`` (the effective scenario): ``targets.nest`` and
  ``targets.pick_time`` (absent keys: the task's defaults, targets.h).
"""

from __future__ import annotations

import json
import math
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

REPO_ROOT = Path(__file__).resolve().parents[3]

#: Seed 002 at e-puck scale (docs/studies/repatt.md).
SPEED_M_S = 0.100
CAPACITY = 5
TIEBREAK = 0.01
#: The targets task's defaults (sim_host/tasks/targets/targets.c) for keys a
#: scenario leaves out.
DEFAULT_NEST = (0.0, 0.0)
DEFAULT_PICK_TIME_S = 5.0


class PlanError(Exception):
    """A problem the planner cannot solve or a world it cannot read; the
    message is for the user."""


@dataclass
class Problem:
    targets: np.ndarray                 # (m, 2) world coordinates, m
    nest: tuple[float, float]
    robots: int
    capacity: int = CAPACITY
    speed: float = SPEED_M_S            # m/s
    pick_time: float = DEFAULT_PICK_TIME_S   # s per target
    tiebreak: float = TIEBREAK          # lambda of the search objective
    dist: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.targets = np.asarray(self.targets, dtype=float).reshape(-1, 2)
        m = len(self.targets)
        if self.robots < 1 or self.capacity < 1:
            raise PlanError(f"need at least one robot of capacity >= 1 (robots {self.robots}, "
                            f"capacity {self.capacity})")
        if self.visits > m:
            raise PlanError(f"{self.robots} robots x capacity {self.capacity} = {self.visits} visits, "
                            f"but there are only {m} targets")
        if not (self.speed > 0 and self.pick_time >= 0 and self.tiebreak >= 0):
            raise PlanError("speed must be > 0, pick_time and tiebreak >= 0")
        pts = np.vstack([np.asarray(self.nest, dtype=float).reshape(1, 2), self.targets])
        d = np.hypot(pts[:, None, 0] - pts[None, :, 0], pts[:, None, 1] - pts[None, :, 1])
        self.dist = np.zeros((m + 2, m + 2))
        self.dist[:m + 1, :m + 1] = d

    @property
    def m(self) -> int:
        return len(self.targets)

    @property
    def end(self) -> int:
        return self.m + 1

    @property
    def visits(self) -> int:
        return self.robots * self.capacity

    # ------------------------------------------------------------ a plan
    def route_length(self, route: list[int]) -> float:
        """Open route from the nest through target nodes `route`, m."""
        nodes = [0, *route]
        return float(sum(self.dist[a, b] for a, b in zip(nodes, nodes[1:], strict=False)))

    def finish_time(self, route: list[int]) -> float:
        return self.route_length(route) / self.speed + self.pick_time * len(route)

    def finish_times(self, routes: list[list[int]]) -> np.ndarray:
        return np.array([self.finish_time(r) for r in routes])

    def search_objective(self, times: np.ndarray) -> float:
        """T + lambda mean(T_i): what the search minimises."""
        return float(times.max() + self.tiebreak * times.mean())

    def check(self, routes: list[list[int]]) -> None:
        """Raises PlanError unless `routes` is a complete plan: n routes of
        exactly `capacity` distinct target nodes, none in two routes."""
        if len(routes) != self.robots:
            raise PlanError(f"{len(routes)} routes for {self.robots} robots")
        seen: set[int] = set()
        for i, r in enumerate(routes):
            if len(r) != self.capacity:
                raise PlanError(f"route {i} has {len(r)} targets, not {self.capacity}")
            for v in r:
                if not 1 <= v <= self.m or v in seen:
                    raise PlanError(f"route {i}: target node {v} is out of range or visited twice")
                seen.add(v)

    def lower_bound(self) -> float:
        """A bound no plan beats: some route visits a target at least as far
        from the nest as the ``n c``-th nearest, so its length is at least that
        distance, and every robot picks ``c`` targets."""
        d = np.sort(self.dist[0, 1:self.m + 1])
        return float(d[self.visits - 1] / self.speed + self.capacity * self.pick_time)

    def describe(self, routes: list[list[int]]) -> dict:
        """The figures of a plan: T (finishing time), lengths, per robot."""
        lengths = [self.route_length(r) for r in routes]
        times = self.finish_times(routes)
        return {"finishing_time_s": float(times.max()), "total_length_m": float(sum(lengths)),
                "max_length_m": float(max(lengths)), "mean_finishing_time_s": float(times.mean()),
                "search_objective": self.search_objective(times)}


# ---------------------------------------------------------------- the world
def default_sim() -> Path:
    return REPO_ROOT / "build" / "swarmsim"


def _first_items(log: Path) -> np.ndarray:
    from swarmtools.telemetry import common, logfile  # needs the LCM types

    for ev in logfile.events(log):
        if ev.channel == "TASK_DRAWING":
            msg = common.decode(ev.data, ev.channel)
            return np.array([(it.x, it.y) for it in msg.items], dtype=float).reshape(-1, 2)
    raise PlanError(f"{log}: no TASK_DRAWING message: the scenario has no task with items")


def load_world(scenario: Path, sim: Path | None = None, sets: list[str] | tuple[str, ...] = ()) -> dict:
    """The targets, nest, robots, stop count and pick time of `scenario`
    (with swarmsim --set overrides `sets`), read from a one-step run."""
    sim = Path(sim) if sim else default_sim()
    if not Path(scenario).is_file():
        raise PlanError(f"{scenario}: no such scenario file")
    if not sim.is_file():
        raise PlanError(f"{sim}: no simulator (build it: make build/swarmsim)")
    with tempfile.TemporaryDirectory(prefix="swarm-plan-") as tmp:
        out = Path(tmp) / "out"
        cmd = [str(sim), str(scenario), "--steps", "1", "--threads", "1", "--quiet", "--telemetry-rate", "0,0",
               "--out", str(out)]
        for s in sets:
            cmd += ["--set", s]
        p = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if p.returncode != 0:
            raise PlanError(f"swarmsim could not load {scenario} (exit {p.returncode}): {p.stderr.strip()}")
        runs = sorted(out.glob("run_*"))
        if len(runs) != 1:
            raise PlanError(f"swarmsim wrote {len(runs)} runs, expected 1")
        run = runs[0]
        summary = json.loads((run / "summary.json").read_text())
        scen = yaml.safe_load((run / "scenario.yaml").read_text()) or {}
        items = _first_items(run / "telemetry.lcmlog")
    metrics = summary.get("metrics", {})
    if "targets" not in summary.get("tasks", []) or "stop_count" not in metrics:
        raise PlanError(f"{scenario}: no `targets:` task (seed 002's world): nothing to plan")
    section = scen.get("targets") or {}
    nest = section.get("nest") or {}
    n_targets = int(metrics["targets"])
    if len(items) != n_targets:
        raise PlanError(f"{scenario}: the drawing has {len(items)} items but the task {n_targets} targets "
                        f"(another task with items?)")
    if not np.all(np.isfinite(items)):
        raise PlanError(f"{scenario}: a target has no position")
    pick = float(section.get("pick_time", DEFAULT_PICK_TIME_S))
    return {"targets": items, "nest": (float(nest.get("x", DEFAULT_NEST[0])), float(nest.get("y", DEFAULT_NEST[1]))),
            "robots": int(metrics["robots"]), "stop_count": int(metrics["stop_count"]), "pick_time": pick,
            "name": summary.get("scenario", Path(scenario).stem), "scenario_hash": summary.get("scenario_hash"),
            "code_version": summary.get("code_version"), "doc": scen}


def problem_of_world(world: dict, capacity: int = CAPACITY, speed: float = SPEED_M_S,
                     tiebreak: float = TIEBREAK) -> Problem:
    """The problem of a world: n c must be the stop count (seed 002: 36 x 5 = 180)."""
    n, sc = world["robots"], world["stop_count"]
    if n * capacity != sc:
        raise PlanError(f"{n} robots x capacity {capacity} = {n * capacity}, but the run stops at {sc} targets: "
                        f"the plan gives every robot exactly `capacity` targets, so these must be equal")
    if not math.isfinite(world["pick_time"]):
        raise PlanError("pick_time is not a number")
    return Problem(world["targets"], world["nest"], n, capacity, speed, world["pick_time"], tiebreak)
