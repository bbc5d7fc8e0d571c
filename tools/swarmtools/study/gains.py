"""Seed 002's gains study (section IV.B, Figures 2a and 2b of the paper),
reduced to fit one machine, and the paper's scoring for the full sweep.

    .venv/bin/python -m swarmtools.study.gains [--out DIR] [--top 20]
        [--n0q1-reps 10] [--backend slurm ...]                 (make study-gains)
    .venv/bin/python -m swarmtools.study.gains --score SWEEP_DIR   (the full sweep's ranking)
    .venv/bin/python -m swarmtools.study.gains --estimate 120      (the full sweep's core-hours)

The paper runs all 900 gain combinations (a_m, r_m in 1, 2, 4, 6, 8, 10;
a_d, r_d in 1, 10, 50, 100, 1000) in its 10 worlds, N0-Q1 and N100-Q40,
30 seeds each (studies/repatt_gains.yaml: 540,000 runs), ranks the
combinations 1..900 per world by mean time, sums the ranks over the worlds
and lets the N100-Q40 sums decide. Here, in the two worlds of Figures 2a
and 2b (One100m, Uniform100m) and N100-Q40, so that noise does not decide:

1. screen (studies/repatt_gains_screen.yaml): all 900, one seed, capped at
   3600 s;
2. confirm: the best 40 by rank sum, and the paper's A4m100d-R1m10d and
   A1m10d-R1m100d and the random walk A1m1d-R1m1d, get seeds 2..6 (the
   same cap); ranks now over the 6 seeds' means;
3. race: the best `--top` of those (and the three named) over 30 fresh
   seeds at the scenarios' own cap (7200 s), N100-Q40, and N0-Q1 over
   `--n0q1-reps` seeds for the points the paper plots beside them. The
   winner is the lowest rank sum over the two worlds of the race's means.

Times are normalised by the random walk's mean (A1m1d-R1m1d in the race,
30 seeds) in the same world, as in the paper's Figure 2. Every stage is a
sweep in OUT/<stage>/ (resumable: rerun the same command).

Exit status: 0 done; 1 a run failed; 2 bad arguments; 130 interrupted.
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from swarmtools.study.common import (
    INTERRUPTED,
    announce,
    boot_ratio,
    narrow,
    quick_out,
    read_rows,
    run_sweep,
    smoke_note,
    write_results,
)
from swarmtools.study.costs import QUICK
from swarmtools.study.repatt import world as repatt_world
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep import plan as sweep_plan
from swarmtools.sweep import spec as sweep_spec
from swarmtools.sweep.spec import Axis, SweepError

REPO_ROOT = Path(__file__).resolve().parents[3]
SCREEN_FILE = REPO_ROOT / "studies" / "repatt_gains_screen.yaml"
FULL_FILE = REPO_ROOT / "studies" / "repatt_gains.yaml"
GAIN_KEYS = tuple(f"robots.0.params.{g}" for g in ("a_m", "a_d", "r_m", "r_d"))
QUEUE, NOISE = "robots.0.params.queue_size", "sound.noise"
TIME = "time_capped_s"
Combo = tuple[int, int, int, int]   # a_m, a_d, r_m, r_d
RW: Combo = (1, 1, 1, 1)
PAPER_BEST: Combo = (4, 100, 1, 10)          # A4m100d-R1m10d, over the 10 worlds
PAPER_UNIFORM_BEST: Combo = (1, 10, 1, 100)  # A1m10d-R1m100d, Uniform100m's best
NAMED = (PAPER_BEST, PAPER_UNIFORM_BEST, RW)
WORLDS = ("One100m", "Uniform100m")
# The paper's Figure 2 as its text gives it: best and worst normalised time.
PAPER_RANGE = {"One100m": (0.30, 1.95), "Uniform100m": (0.74, 1.48)}
CONFIRM_TOP, CONFIRM_SEEDS = 40, list(range(2, 7))
#: --quick: the screen on these gain values only (8 combinations, the
#: paper's two named ones among them), fewer confirmed and raced.
QUICK_GRID = {"a_m": (1, 4), "a_d": (10, 100), "r_m": (1,), "r_d": (10, 100)}
QUICK_CONFIRM_TOP, QUICK_CONFIRM_SEEDS, QUICK_TOP, QUICK_RACE_REPS, QUICK_N0Q1_REPS = 3, [2], 2, 2, 1


def name(c: Combo) -> str:
    """The paper's label: A4m100d-R1m10d."""
    return f"A{c[0]}m{c[1]}d-R{c[2]}m{c[3]}d"


def combo(row: dict[str, str]) -> Combo:
    return tuple(int(float(row[k])) for k in GAIN_KEYS)  # type: ignore[return-value]


def world(row: dict[str, str]) -> str:
    """"One100m" from the row's scenario (repatt_one100.yaml)."""
    dist, size = repatt_world(row)
    return f"{dist.capitalize()}{size}m"


def arm(row: dict[str, str]) -> str:
    return "N100-Q40" if float(row.get(NOISE) or 0) > 0 else "N0-Q1"


def cells(rows: Iterable[dict[str, str]]) -> dict[tuple[str, str, Combo], np.ndarray]:
    """Times of the runs that ran, per (arm, world, combination)."""
    out: dict[tuple[str, str, Combo], list[float]] = {}
    for r in rows:
        if r["status"] == "ok":
            out.setdefault((arm(r), world(r), combo(r)), []).append(float(r[TIME]))
    return {k: np.array(v) for k, v in out.items()}


def with_fixed(rows: list[dict[str, str]], sw: sweep_spec.Sweep) -> list[dict[str, str]]:
    """Rows of a sweep's results.csv with its fixed `set` values filled in:
    the table has columns for the axes only, and a row's arm (its noise)
    may be fixed (the screen's N100-Q40)."""
    for r in rows:
        for k, v in sw.fixed:
            r.setdefault(k, sweep_spec.set_text(v))
    return rows


def rank_sums(times: dict[tuple[str, str, Combo], np.ndarray], arm_name: str) -> list[tuple[int, Combo, dict]]:
    """The paper's score: in each world, the combinations ranked by mean time
    (1 = fastest; ties share the lower rank's order by combination), ranks
    summed over the worlds; only combinations run in every world.  Returns
    (sum, combination, {world: rank}) best first."""
    worlds = sorted({w for (a, w, _) in times if a == arm_name})
    combos = [c for c in {c for (a, _, c) in times if a == arm_name}
              if all((arm_name, w, c) in times for w in worlds)]
    ranks: dict[Combo, dict[str, int]] = {c: {} for c in combos}
    for w in worlds:
        order = sorted(combos, key=lambda c: (float(times[(arm_name, w, c)].mean()), c))
        for i, c in enumerate(order):
            ranks[c][w] = i + 1
    scored = [(sum(ranks[c].values()), c, ranks[c]) for c in combos]
    return sorted(scored, key=lambda s: (s[0], s[1]))


def stage_sweep(base: sweep_spec.Sweep, name_: str, combos: Sequence[Combo], seeds: Sequence[int],
                arms: Sequence[dict[str, Any]] | None = None, uncap: bool = False) -> sweep_spec.Sweep:
    """The screen's sweep narrowed to `combos` and `seeds`; `arms` replaces
    the fixed queue and noise by a list axis; `uncap` drops the screen's
    duration cap (the scenarios' own applies)."""
    sw = sweep_spec.Sweep(path=base.path, name=name_, scenario=base.scenario,
                          fixed=[(k, v) for k, v in base.fixed
                                 if not (uncap and k == "duration") and not (arms and k in (QUEUE, NOISE))],
                          axes=[a for a in base.axes if a.kind != "grid"], seeds=list(seeds),
                          metrics=base.metrics, max_attempts=base.max_attempts, run_timeout=base.run_timeout,
                          keep_timeseries=base.keep_timeseries, key_lines=dict(base.key_lines))
    if arms:
        sw.axes.append(Axis("list", [QUEUE, NOISE], [dict(a) for a in arms], 0))
    sw.axes.append(Axis("list", list(GAIN_KEYS), [dict(zip(GAIN_KEYS, c, strict=True)) for c in combos], 0))
    return sw


def pick_top(scored: Sequence[tuple[int, Combo, dict]], k: int) -> list[Combo]:
    """The best k by rank sum, then the named combinations not among them."""
    top = [c for _, c, _ in scored[:k]]
    return top + [c for c in NAMED if c not in top]


def race_combos(all_rows: dict[str, list[dict[str, str]]], top: int) -> list[Combo]:
    """The confirmed combinations ranked over their 6 seeds (screen and
    confirm pooled), the best `top`, then the named ones."""
    kept = {combo(r) for r in all_rows["confirm"]}
    times = {k: v for k, v in cells(all_rows["screen"] + all_rows["confirm"]).items() if k[2] in kept}
    best = [c for _, c, _ in rank_sums(times, "N100-Q40")][:top]
    return best + [c for c in NAMED if c not in best]


def race_table(times: dict, scored: Sequence[tuple[int, Combo, dict]]) -> tuple[list[dict[str, Any]], list[str]]:
    """The race's rows, best first, normalised by RW's mean in each world."""
    rows, md = [], ["| rank sum | combination | " + " | ".join(
        f"{w} N100-Q40 / RW [95 % CI] | {w} N0-Q1 / RW" for w in WORLDS) + " | seeds (N100-Q40, N0-Q1) |",
        "|---:|---|" + "---:|---:|" * len(WORLDS) + "---|"]
    for s, c, ranks in scored:
        entry: dict[str, Any] = {"combination": name(c), "rank_sum": s, "ranks": ranks}
        cols = []
        for w in WORLDS:
            rw = times.get(("N100-Q40", w, RW), np.array([]))
            m, lo, hi = boot_ratio(times.get(("N100-Q40", w, c), np.array([])), rw)
            q = times.get(("N0-Q1", w, c), np.array([]))
            rw0 = times.get(("N0-Q1", w, RW), rw)
            m0 = float(q.mean() / rw0.mean()) if q.size and rw0.size else math.nan
            entry[w] = {"n100q40": m, "ci_low": lo, "ci_high": hi, "n0q1": m0,
                        "mean_s": float(times[("N100-Q40", w, c)].mean())}
            cols.append(f"{m:.2f} [{lo:.2f}, {hi:.2f}] | {m0:.2f}" if not math.isnan(m0)
                        else f"{m:.2f} [{lo:.2f}, {hi:.2f}] | -")
        n = {a: len(times.get((a, WORLDS[0], c), [])) for a in ("N100-Q40", "N0-Q1")}
        md.append(f"| {s} | {name(c)}{' (paper)' if c == PAPER_BEST else ''} | " + " | ".join(cols)
                  + f" | {n['N100-Q40']}, {n['N0-Q1']} |")
        rows.append(entry)
    return rows, md


def plot(screen: dict, race: dict, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for ax, w in zip(axes, WORLDS, strict=True):
        rw = race.get(("N100-Q40", w, RW))
        if rw is None or rw.size == 0:
            continue
        combos = sorted({c for (a, ww, c) in screen if ww == w}, key=lambda c: screen[("N100-Q40", w, c)].mean())
        y = [screen[("N100-Q40", w, c)].mean() / rw.mean() for c in combos]
        ax.plot(range(1, len(y) + 1), y, ".", ms=2, color="tab:blue", label="N100-Q40, screen (1-6 seeds)")
        lo, hi = PAPER_RANGE[w]
        ax.axhline(lo, color="grey", lw=0.8, ls="--", label=f"paper: best {lo}, worst {hi}")
        ax.axhline(hi, color="grey", lw=0.8, ls="--")
        ax.axhline(1.0, color="black", lw=0.6)
        ax.set_title(f"{w}: the 900 combinations, sorted")
        ax.set_xlabel("combination (sorted by N100-Q40 time)")
        ax.set_ylabel("time to 90 % / random walk")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def score_full(sweep_dir: Path) -> int:
    """The paper's ranking of a full sweep's results.csv (both arms)."""
    rows = read_rows(sweep_dir / "results.csv")
    times = cells(rows)
    for a in ("N100-Q40", "N0-Q1"):
        scored = rank_sums(times, a)
        if not scored:
            continue
        print(f"{a}: {len(scored)} combinations in {len({w for (x, w, _) in times if x == a})} worlds; best 10:")
        for s, c, _ in scored[:10]:
            print(f"  {s:6d}  {name(c)}")
        where = [i for i, (_, c, _) in enumerate(scored) if c == PAPER_BEST]
        if where:
            print(f"  the paper's {name(PAPER_BEST)} is ranked {where[0] + 1}")
    return 0


def cpu_seconds(cmd: list[str]) -> tuple[int, float]:
    """Runs cmd; its exit status and the CPU time (user + system) it used:
    core-seconds, which other load on the machine does not inflate as it
    does wall time."""
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, usage.ru_utime + usage.ru_stime


def estimate(a: argparse.Namespace, sim: Path, out: Path) -> int:
    """The full sweep's cost measured here: `a.estimate` of its 18,000
    configurations (world x arm x gains) drawn uniformly (fixed seed), run
    once each (seed 1) at the scenarios' own cap as the sweep runs them;
    mean CPU time per run x the sweep's 540,000 runs, with a 95 % bootstrap
    interval."""
    full = sweep_spec.load(FULL_FILE, sweep_plan.seed_max(sim))
    configs = [dict(kv for part in parts for kv in part.items())
               for parts in itertools.product(*(ax.combos for ax in full.axes))]
    chosen = sorted(np.random.default_rng(16).choice(len(configs), size=min(a.estimate, len(configs)),
                                                     replace=False))
    runs = []
    with tempfile.TemporaryDirectory(prefix="gains-estimate-") as tmp:
        def one(i: int) -> tuple[int, float]:
            c = dict(configs[i])
            scen = sweep_spec.resolve_scenario(FULL_FILE, str(c.pop("scenario")))
            cmd = [str(sim), str(scen), "--seed", "1", "--out", str(Path(tmp) / str(i)), "--lcm", "off",
                   "--threads", "1", "--quiet"]
            for k, v in [*full.fixed, *c.items()]:
                cmd += ["--set", f"{k}={sweep_spec.set_text(v)}"]
            return cpu_seconds(cmd)
        with ThreadPoolExecutor(max_workers=a.jobs or os.cpu_count() or 1) as pool:
            runs = list(pool.map(one, chosen))
    bad = sum(1 for rc, _ in runs if rc != 0)
    if bad:
        print(f"study_gains: {bad} of {len(runs)} runs failed", file=sys.stderr)
        return 1
    cpu = np.array([t for _, t in runs])
    total = len(configs) * len(full.seeds)
    boot = np.random.default_rng(0).choice(cpu, size=(4000, cpu.size)).mean(axis=1)
    ch = cpu.mean() * total / 3600
    lo, hi = (float(np.percentile(boot, q)) * total / 3600 for q in (2.5, 97.5))
    md = ["# The full gains sweep's cost, measured", "",
          f"{cpu.size} of its {len(configs)} configurations, one run each on this machine: mean {cpu.mean():.2f} "
          f"CPU s a run (median {np.median(cpu):.2f} s, max {cpu.max():.1f} s); x {total} runs = "
          f"**{ch:.0f} core-hours** [95 % CI {lo:.0f}, {hi:.0f}].", ""]
    write_results(out / "estimate", md, {"runs": int(cpu.size), "mean_cpu_s": float(cpu.mean()),
                                          "core_hours": ch, "ci": [lo, hi], "total_runs": total,
                                          "cpu_s": cpu.tolist()}, "study_gains")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="swarmtools.study.gains", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=None, help="default out/study_gains (out/study_gains_quick with --quick)")
    ap.add_argument("--quick", action="store_true",
                    help=f"a smoke run under a minute: {QUICK['gains'].note}, runs cut at {QUICK['gains'].steps} "
                         "steps, into out/study_gains_quick")
    ap.add_argument("--top", type=int, default=None, help="combinations raced over 30 seeds (default 20)")
    ap.add_argument("--race-reps", type=int, default=None, help="seeds of the race (default 30)")
    ap.add_argument("--n0q1-reps", type=int, default=None,
                    help="seeds of N0-Q1 for the raced combinations (0: none; default 10)")
    ap.add_argument("--score", metavar="SWEEP_DIR", help="only rank a full sweep's results (repatt_gains.yaml)")
    ap.add_argument("--estimate", type=int, metavar="N", default=0,
                    help="only measure the full sweep's core-hours from N of its configurations run once")
    ap.add_argument("--sim", default=str(REPO_ROOT / "build" / "swarmsim"))
    ap.add_argument("--jobs", type=int, default=0)
    sweep_cli.add_backend_options(ap)
    a = ap.parse_args(argv)
    if a.score:
        return score_full(Path(a.score))
    command = " ".join(["python -m swarmtools.study.gains", *(argv if argv is not None else sys.argv[1:])])
    t0 = time.monotonic()
    try:
        sweep_cli.check_args(a)
        quick = QUICK["gains"] if a.quick else None
        for k, full, smoke in (("top", 20, QUICK_TOP), ("race_reps", 30, QUICK_RACE_REPS),
                               ("n0q1_reps", 10, QUICK_N0Q1_REPS)):
            if getattr(a, k) is None:
                setattr(a, k, smoke if quick else full)
        confirm_top, confirm_seeds = (QUICK_CONFIRM_TOP, QUICK_CONFIRM_SEEDS) if quick else (CONFIRM_TOP, CONFIRM_SEEDS)
        if a.top < 1 or a.race_reps < 2 or a.n0q1_reps < 0:
            raise SweepError("--top must be at least 1, --race-reps at least 2, --n0q1-reps at least 0")
        sim, out = Path(a.sim), quick_out(a.out, REPO_ROOT / "out" / "study_gains", a.quick)
        if a.estimate:
            return estimate(a, sim, out)
        base = narrow(sweep_spec.load(SCREEN_FILE, sweep_plan.seed_max(sim)), quick)
        if quick:
            grid = next(ax for ax in base.axes if ax.kind == "grid")
            grid.combos = [c for c in grid.combos
                           if all(c[f"robots.0.params.{g}"] in vals for g, vals in QUICK_GRID.items())]
        n_named, n_worlds = len(NAMED), len(WORLDS)
        announce("study_gains", "gains", len(sweep_plan.expand(base))
                 + n_worlds * ((confirm_top + n_named) * len(confirm_seeds)
                               + (a.top + n_named) * (a.race_reps + a.n0q1_reps)), quick, at_most=True)
        md = ["# Seed 002's gains study, reduced (Figures 2a, 2b)", "", *smoke_note(quick), f"Command: `{command}`.", ""]
        all_rows: dict[str, list[dict[str, str]]] = {}

        def stage(st: str, sw: sweep_spec.Sweep) -> int | None:
            if quick:
                sw.steps = quick.steps
            t1 = time.monotonic()
            rc = run_sweep(sw, a, sim, out / st, "study_gains")
            if rc is None or rc == INTERRUPTED:
                return rc if rc is not None else -1
            all_rows[st] = with_fixed(read_rows(out / st / "results.csv"), sw)
            md.append(f"{st}: {len(all_rows[st])} runs, {len(sw.seeds)} seed(s) a cell, "
                      f"{time.monotonic() - t1:.0f} s (sweep `{out / st}`); "
                      f"{sum(float(r.get('wall_s') or 0) for r in all_rows[st]) / 3600:.2f} core-hours of runs.")
            return None

        plans: list[tuple[str, Any]] = [
            ("screen", lambda: base),
            ("confirm", lambda: stage_sweep(base, "study_repatt_gains_confirm",
                                            pick_top(rank_sums(cells(all_rows["screen"]), "N100-Q40"), confirm_top),
                                            confirm_seeds)),
            ("race", lambda: stage_sweep(base, "study_repatt_gains_race", race_combos(all_rows, a.top),
                                         range(1, a.race_reps + 1), [{QUEUE: 40, NOISE: 0.06}], uncap=True)),
        ]
        if a.n0q1_reps:
            plans.append(("race_n0q1", lambda: stage_sweep(base, "study_repatt_gains_race_n0q1",
                                                           race_combos(all_rows, a.top), range(1, a.n0q1_reps + 1),
                                                           [{QUEUE: 1, NOISE: 0}], uncap=True)))
        for st, make in plans:
            rc = stage(st, make())
            if rc == -1:
                print(f"study_gains: {st} submitted; rerun the same command when it has finished", file=sys.stderr)
                return 0
            if rc is not None:
                return rc
        screen_times = cells(all_rows["screen"] + all_rows["confirm"])
        race_times = cells(all_rows["race"] + all_rows.get("race_n0q1", []))
        raced = rank_sums(race_times, "N100-Q40")
        rows, table = race_table(race_times, raced)
        best = raced[0][1]
        md += ["", "## The race: 30 seeds at the scenarios' cap, ranked as the paper ranks", "",
               f"Best by rank sum over One100m and Uniform100m: **{name(best)}**; the paper's best over its 10 "
               f"worlds: {name(PAPER_BEST)} (ranked {[c for _, c, _ in raced].index(PAPER_BEST) + 1} of "
               f"{len(raced)} here); the paper's best in Uniform100m: {name(PAPER_UNIFORM_BEST)}.", ""] + table
        screened = rank_sums(cells(all_rows["screen"]), "N100-Q40")
        summary: dict[str, Any] = {"best": name(best), "paper_best": name(PAPER_BEST), "race": rows,
                                   "screen_rank_of_paper_best":
                                       [c for _, c, _ in screened].index(PAPER_BEST) + 1 if screened else None}
        md += ["", "## Figures 2a, 2b: the range over the 900 combinations (screen, normalised by the race's RW)", "",
               "| world | best / RW (screen) | worst / RW (screen) | capped runs (3600 s) | paper best, worst |",
               "|---|---:|---:|---:|---:|"]
        for w in WORLDS:
            rw = race_times.get(("N100-Q40", w, RW), np.array([]))
            means = [v.mean() for (ar, ww, _), v in screen_times.items() if ww == w and ar == "N100-Q40"]
            capped = sum(1 for r in all_rows["screen"] if world(r) == w and float(r.get("finished") or 0) < 0.5)
            if rw.size and means:
                lo, hi = min(means) / rw.mean(), max(means) / rw.mean()
                summary[w] = {"screen_best": lo, "screen_worst": hi, "capped": capped, "rw_mean_s": float(rw.mean())}
                md.append(f"| {w} | {lo:.2f} | {hi:.2f}{' (a cap: at least)' if capped else ''} | {capped} | "
                          f"{PAPER_RANGE[w][0]}, {PAPER_RANGE[w][1]} |")
        plot(screen_times, race_times, out / "fig2_gains.png")
        md += ["", "![Figures 2a, 2b](fig2_gains.png)", "", f"Wall time: {time.monotonic() - t0:.0f} s."]
        write_results(out, md, summary, "study_gains")
        return 0
    except SweepError as e:
        print(f"study_gains: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
