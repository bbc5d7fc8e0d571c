"""The cross-check: the planner's instance solved by PyVRP, a vehicle-routing
solver whose objective is total distance.

The model: one depot at the nest; ``n`` vehicles of capacity ``c``; every
target a client with a delivery of 1, optional (``required=False``) with a
prize far above any route length, so that the solver visits as many targets
as the vehicles can carry (``n c``: every vehicle full) and chooses which
``m - n c`` to leave out by distance; open routes: every edge into the depot
has distance 0.  PyVRP's distances are integers: millimetres, rounded.  The
routes PyVRP returns are measured again with the planner's own distances, and
reported with their total length and their finishing time T (the planner's
objective), beside the ALNS plan's.  Deterministic for a seed (PyVRP's
``MaxIterations`` stop, never a time limit).
"""

from __future__ import annotations

import time

import numpy as np
from pyvrp import Model
from pyvrp.stop import MaxIterations

from swarmtools.plan.problem import Problem

MM = 1000.0


def _is_client(activity) -> bool:
    flag = activity.is_client
    return bool(flag() if callable(flag) else flag)


def pyvrp_plan(problem: Problem, iterations: int, seed: int) -> dict:
    """PyVRP's plan of `problem`: its routes (target nodes), their total
    length and T, whether every vehicle is full."""
    m = problem.m
    # Above any detour a target can cost (two edges), so visiting is always worth it.
    prize = int(np.ceil(2 * MM * problem.dist.max())) + 1
    model = Model()
    locs = [model.add_location(float(problem.nest[0]), float(problem.nest[1]))]
    locs += [model.add_location(float(x), float(y)) for x, y in problem.targets]
    depot = model.add_depot(locs[0])
    for k in range(m):
        model.add_client(locs[k + 1], delivery=[1], prize=prize, required=False)
    model.add_vehicle_type(num_available=problem.robots, capacity=[problem.capacity], start_depot=depot,
                           end_depot=depot)
    D = np.rint(problem.dist[:m + 1, :m + 1] * MM).astype(np.int64)
    for a in range(m + 1):
        for b in range(m + 1):
            if a != b:
                model.add_edge(locs[a], locs[b], distance=int(D[a, b]) if b != 0 else 0)
    t0 = time.perf_counter()
    res = model.solve(MaxIterations(iterations), seed=seed, display=False)
    wall = time.perf_counter() - t0
    # A route's client activity idx k is client k, location k + 1 (the depot
    # is location 0): the planner's node numbering.
    routes = [[int(a.idx) + 1 for a in r if _is_client(a)] for r in res.best.routes()]
    lengths = [problem.route_length(r) for r in routes]
    visited = sum(len(r) for r in routes)
    times = problem.finish_times(routes) if routes else np.array([np.nan])
    full = len(routes) == problem.robots and all(len(r) == problem.capacity for r in routes)
    return {"total_length_m": float(sum(lengths)), "finishing_time_s": float(times.max()),
            "visited": visited, "routes_used": len(routes), "all_full": bool(full),
            "feasible": bool(res.best.is_feasible()), "cost_mm": int(res.best.distance()),
            "iterations": iterations, "seed": seed, "wall_s": wall,
            "routes": [[v - 1 for v in r] for r in routes]}
