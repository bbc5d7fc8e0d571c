"""Figure 3's ALNS bars (seed 002, issue 16): the planned routes run in the
simulator by waypoint followers, normalised by the random walk.

For each of the five layouts one plan serves both world sizes (the 100 m
worlds keep the 50 m worlds' targets and nest: checked, not assumed):
``swarmtools.plan.alns`` plans it from the 50 m world into
OUT/alns/plans/<layout>/, and each world's run scenario (its robots
following the routes, swarmtools.plan.routes) is written to
OUT/alns/scenarios/repatt_<layout><size>.yaml.  A sweep of the 10 run
scenarios x the seeds (the robots' start headings, sensor and wheel noise;
the plan is the same) goes to OUT/alns/sweep/, and each world's mean time
to 180 targets is divided by the random walk's in the worlds sweep."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from swarmtools.plan import alns as planner
from swarmtools.plan.problem import load_world
from swarmtools.plan.routes import run_scenario
from swarmtools.study.common import boot_ratio
from swarmtools.sweep.store import atomic_write

REPO_ROOT = Path(__file__).resolve().parents[3]
SCENARIOS = REPO_ROOT / "sim_host" / "scenarios"
DISTS = ("one", "two", "four", "half", "uniform")
# The paper's text (section IV.D): ALNS's improvement over RW.
PAPER_BETTER = {("one", 100): 0.94, ("two", 100): 0.88, ("four", 100): 0.79, ("half", 100): 0.90,
                ("uniform", 100): 0.70, ("one", 50): 0.90}


def plan_layouts(out: Path, sim: Path, iterations: int, q: int, seed: int, pyvrp_iterations: int) -> dict[str, dict]:
    """Plans each layout once (kept: a rerun reuses OUT/alns/plans/<layout>
    when its iterations, q and seed match) and writes the 10 run scenarios."""
    plans: dict[str, dict] = {}
    for d in DISTS:
        pdir = out / "plans" / d
        summary = pdir / "summary.json"
        old = json.loads(summary.read_text()) if summary.is_file() else None
        if not old or (old.get("iterations"), old.get("q"), old.get("seed")) != (iterations, q, seed):
            rc = planner.main(["--scenario", str(SCENARIOS / f"repatt_{d}50.yaml"), "--iterations", str(iterations),
                               "--q", str(q), "--seed", str(seed), "--pyvrp-iterations", str(pyvrp_iterations),
                               "--sim", str(sim), "--out", str(pdir), "--replace"])
            if rc != 0:
                raise RuntimeError(f"planning {d} failed (exit {rc})")
        plans[d] = json.loads(summary.read_text())
        ref = None
        for size in (50, 100):
            world = load_world(SCENARIOS / f"repatt_{d}{size}.yaml", sim)
            if ref is None:
                ref = world
            elif not (np.array_equal(world["targets"], ref["targets"]) and world["nest"] == ref["nest"]):
                raise RuntimeError(f"repatt_{d}{size}.yaml's targets differ from the 50 m world's: plan it on its own")
            routes = [[(float(world["targets"][k][0]), float(world["targets"][k][1])) for k in r]
                      for r in plans[d]["routes"]]
            doc = run_scenario(world["doc"], routes, world["nest"], f"repatt_{d}{size}_alns")
            path = out / "scenarios" / f"repatt_{d}{size}.yaml"
            path.parent.mkdir(parents=True, exist_ok=True)
            atomic_write(path, planner.RUN_SCENARIO_HEADER + yaml.safe_dump(doc, sort_keys=False))
    return plans


def sweep_file(out: Path, seeds: Sequence[int]) -> Path:
    """The sweep of the 10 run scenarios (relative paths: the folder moves whole)."""
    names = [f"scenarios/repatt_{d}{s}.yaml" for s in (50, 100) for d in DISTS]
    text = "\n".join([
        "# Written by swarmtools.study.repatt (figure alns): the ALNS plans run in the 10 worlds.",
        "name: study_repatt_alns", f"scenario: {names[0]}", "axes:", "  - list:",
        *[f"      - {{scenario: {n}}}" for n in names],
        f"seeds: [{', '.join(str(s) for s in seeds)}]",
        "metrics: [time_capped_s, time_to_stop_s, finished, picked]", "keep_timeseries: false", ""])
    path = out / "sweep.yaml"
    atomic_write(path, text)
    return path


def bars(alns_rows: Sequence[dict[str, str]], rw: dict[tuple[str, int], np.ndarray]) -> dict[str, Any]:
    """Per world: ALNS's mean time, its ratio to RW's with a 95 % interval."""
    res: dict[str, Any] = {}
    for d in DISTS:
        for size in (50, 100):
            rows = [r for r in alns_rows if Path(r["scenario"]).stem == f"repatt_{d}{size}" and r["status"] == "ok"]
            t = np.array([float(r["time_capped_s"]) for r in rows])
            w = f"{d.capitalize()}{size}m"
            base = rw.get((d, size), np.array([]))
            m, lo, hi = boot_ratio(t, base) if t.size and base.size else (math.nan,) * 3
            res[f"{w}/ALNS"] = {"world": w, "arm": "ALNS", "runs": len(rows), "ok": int(t.size),
                                "unfinished": sum(1 for r in rows if float(r.get("finished") or 0) < 0.5),
                                "mean_s": float(t.mean()) if t.size else math.nan,
                                "sd_s": float(t.std(ddof=1)) if t.size > 1 else math.nan,
                                "normalised": m, "ci_low": lo, "ci_high": hi,
                                "paper_better": PAPER_BETTER.get((d, size))}
    return res


def render(res: dict[str, Any], rw: dict[tuple[str, int], np.ndarray], plans: dict[str, dict]) -> list[str]:
    lines = ["## Figure 3: ALNS, the planned routes followed in the simulator", "",
             "ALNS's mean time to 180 targets (s) over the seeds, and that mean divided by RW's in the same world, "
             "with its 95 % bootstrap interval; 'better' = 1 - ratio, the paper's way of putting it. The plan's own "
             "estimate T (straight lines at 0.1 m/s, 5 s a target, every robot from the nest centre) and its bound "
             "are the same in both sizes (one plan per layout).", "",
             "| world | RW time (s) | ALNS time (s) | ALNS / RW [95 % CI] | better than RW | paper | plan T (s) "
             "| bound (s) | plan length (m) | PyVRP length (m) | unfinished |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for size in (50, 100):
        for d in DISTS:
            w = f"{d.capitalize()}{size}m"
            x, p = res.get(f"{w}/ALNS"), plans.get(d, {})
            if not x:
                continue
            base = rw.get((d, size), np.array([]))
            paper = f"{x['paper_better'] * 100:.0f} %" if x["paper_better"] else "-"
            py = (p.get("pyvrp") or {}).get("total_length_m")
            lines.append(
                f"| {w} | {base.mean():.0f} | {x['mean_s']:.1f} +- {x['sd_s']:.1f} | {x['normalised']:.3f} "
                f"[{x['ci_low']:.3f}, {x['ci_high']:.3f}] | {(1 - x['normalised']) * 100:.0f} % | {paper} | "
                f"{p.get('finishing_time_s', math.nan):.1f} | {p.get('lower_bound_s', math.nan):.1f} | "
                f"{p.get('total_length_m', math.nan):.1f} | {py if py is None else f'{py:.1f}'} | {x['unfinished']} |")
    return lines + [""]
