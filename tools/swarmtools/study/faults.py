"""Seed 000 under faults: runs studies/faults_drtm.yaml through the sweep
engine and writes out/study_faults/results.md.

Per condition (healthy; 10 % or 30 % of the foragers stopping at a uniformly
random time; one lying forager for the whole run or from 100 s to 400 s):
runs that finished, mean +- sd over the seeds of the food collected, the net
food F(T), V_f, M_T and the robots that failed, and the beacon's ledger:
its largest belief max F_beacon(t) (the broadcast saturates at 128 tokens),
and how far it is from the truth at the end, |F_beacon(T) - F(T)|, and 100 s
after a lie stops.

    .venv/bin/python -m swarmtools.study.faults [--quick] [--reps N] [--steps N] [--out DIR]
        [--backend slurm ...]        (make study-faults)

`--quick` is a smoke run (swarmtools.study.costs.QUICK) into
out/study_faults_quick/, its results.md marked as such.

Exit status: 0 done; 1 a run failed; 2 bad arguments; 130 interrupted.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from swarmtools.study.common import announce, narrow, quick_out, smoke_note
from swarmtools.study.costs import QUICK, Quick
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep import plan as sweep_plan
from swarmtools.sweep import spec as sweep_spec
from swarmtools.sweep.spec import SweepError

REPO_ROOT = Path(__file__).resolve().parents[3]
SWEEP_FILE = REPO_ROOT / "studies" / "faults_drtm.yaml"
FAULT_KEY = "robots.0.faults"
LABELS = {
    "[]": "healthy",
    "[{kind: stop, fraction: 0.1, at: random}]": "10 % stop",
    "[{kind: stop, fraction: 0.3, at: random}]": "30 % stop",
    "[{kind: liar, fraction: 0.05, at: 0}]": "1 liar, whole run",
    "[{kind: liar, fraction: 0.05, at: 100, duration: 300}]": "1 liar, 100-400 s",
}
METRICS = (("food_collected", "collected"), ("food_net", "F(T)"), ("V_f", "V_f"), ("M_T", "M_T"),
           ("faulty_robots", "failed robots"))


def ms(values: Sequence[float], decimals: int = 2) -> str:
    v = np.asarray([x for x in values if not math.isnan(x)], dtype=float)
    if v.size == 0:
        return "-"
    sd = v.std(ddof=1) if v.size > 1 else 0.0
    return f"{v.mean():.{decimals}f} +- {sd:.{decimals}f}"


def beacon_figures(ts: Path, end_of_lie_s: float | None) -> dict[str, float]:
    """From a run's time series: max F_beacon, |F_beacon - F| at the end and
    100 s after a lie stopped."""
    with ts.open(newline="") as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["time_s"]) for r in rows])
    fb = np.array([float(r["food_beacon"]) for r in rows])
    fn = np.array([float(r["food_nest"]) for r in rows])
    out = {"max_beacon": float(np.nanmax(fb)), "end_error": float(abs(fb[-1] - fn[-1])),
           "after_lie_error": math.nan}
    if end_of_lie_s is not None:
        k = int(np.searchsorted(t, end_of_lie_s + 100.0))
        if k < len(t):
            out["after_lie_error"] = float(abs(fb[k] - fn[k]))
    return out


def render(rows: list[dict[str, str]], sweep_dir: Path, command: str, wall: float, quick: Quick | None = None) -> str:
    conds: dict[str, list[dict[str, str]]] = {}
    for r in rows:
        conds.setdefault(r[FAULT_KEY], []).append(r)
    lines = ["# Seed 000 under faults (base condition, DRTM)", "", *smoke_note(quick),
             f"Command: `{command}`; {len(rows)} runs in {wall:.0f} s; sweep `{sweep_dir}`.", "",
             "Mean +- sd over the seeds. The beacon: max F_beacon is the largest F(t) its ledger "
             "held (the broadcast carries at most 128 tokens); error = |F_beacon - F|, the "
             "distance of its belief from the true nest food, at the end and 100 s after a "
             "lie stopped.", "",
             "| condition | runs ok | " + " | ".join(h for _, h in METRICS)
             + " | max F_beacon | error at end | error 100 s after the lie |",
             "|---|---:|" + "---:|" * (len(METRICS) + 3)]
    for key, label in LABELS.items():
        cell = conds.get(key, [])
        if not cell:
            continue
        ok = [r for r in cell if r["status"] == "ok"]
        end_of_lie = 400.0 if "duration: 300" in key else None
        beacon = [beacon_figures(sweep_dir / "runs" / r["run_id"] / f"run_{r['seed']}" / "timeseries.csv",
                                 end_of_lie) for r in ok]
        vals = [ms([float(r[m] or "nan") for r in ok]) for m, _ in METRICS]
        lines.append(f"| {label} | {len(ok)} of {len(cell)} | " + " | ".join(vals)
                     + f" | {ms([b['max_beacon'] for b in beacon])} | {ms([b['end_error'] for b in beacon])}"
                     + f" | {ms([b['after_lie_error'] for b in beacon])} |")
    return "\n".join(lines) + "\n"


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="swarmtools.study.faults", description=__doc__.split("\n\n")[0])
    ap.add_argument("--reps", type=int, default=None, help="seeds per condition (default the file's, 20)")
    ap.add_argument("--steps", type=int, default=None, help="steps per run (default the scenario's)")
    ap.add_argument("--quick", action="store_true",
                    help=f"a smoke run under a minute: {QUICK['faults'].seeds} seeds a condition, runs cut at "
                         f"{QUICK['faults'].steps} steps, into out/study_faults_quick")
    ap.add_argument("--out", default=None, help="default out/study_faults (out/study_faults_quick with --quick)")
    ap.add_argument("--sim", default=str(REPO_ROOT / "build" / "swarmsim"))
    ap.add_argument("--jobs", type=int, default=0)
    sweep_cli.add_backend_options(ap)
    a = ap.parse_args(argv)
    command = " ".join(["python -m swarmtools.study.faults", *(argv if argv is not None else sys.argv[1:])])
    t0 = time.monotonic()
    try:
        sweep_cli.check_args(a)
        sim = Path(a.sim)
        quick = QUICK["faults"] if a.quick else None
        sw = narrow(sweep_spec.load(SWEEP_FILE, sweep_plan.seed_max(sim)), quick)
        if a.reps is not None:
            if a.reps < 1:
                raise SweepError("--reps must be at least 1")
            sw.seeds = list(range(1, a.reps + 1))
        if a.steps is not None:
            sw.steps = a.steps
        out = quick_out(a.out, REPO_ROOT / "out" / "study_faults", a.quick)
        announce("study_faults", "faults", len(sweep_plan.expand(sw)), quick)
        sweep_dir = out / "sweep"
        rc = sweep_cli.run_sweep(sw, argparse.Namespace(**{**vars(a), "out": str(sweep_dir), "quiet": False}), sim)
        if rc in (130, 143):
            print("study_faults: interrupted; rerun the same command to resume", file=sys.stderr)
            return 130
        if a.backend == "slurm" and a.no_wait:
            return 0
        with (sweep_dir / "results.csv").open(newline="") as f:
            rows = list(csv.DictReader(f))
        md = render(rows, sweep_dir, command, time.monotonic() - t0, quick)
        from swarmtools.sweep.store import atomic_write
        atomic_write(out / "results.md", md)
        print(md)
        print(f"study_faults: wrote {out / 'results.md'}")
        return 0 if rc == 0 else 1
    except SweepError as e:
        print(f"study_faults: {e}", file=sys.stderr)
        return e.exit_code


if __name__ == "__main__":
    sys.exit(main())
