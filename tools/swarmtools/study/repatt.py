"""Seed 002's simulation study (RepAtt): Figures 3, 2c and 4 of the paper,
run through the sweep engine, at e-puck scale (docs/studies/repatt.md).

    .venv/bin/python -m swarmtools.study.repatt [--figures fig3,queue,scale]
        [--quick] [--reps N] [--out DIR] [--backend slurm ...]   (make study-repatt)

- worlds (studies/repatt_worlds.yaml): the 10 worlds with random walk
  (RW), N0-Q1 and N100 with queues 1, 8, 20, 40, 80, 120, all with the
  paper's best gains (A4m100d-R1m10d).  Figure 3: time to pick up 90 % of
  the targets for RW, N0-Q1 and N100-Q40, normalised by RW's mean in each
  world, beside the paper's improvements over RW; Figure 2c: the queue
  sizes under N100, normalised the same way.
- slotted (studies/repatt_slotted.yaml): N100-Q40 as a real e-puck can run
  it (a robot's own tone masks its microphones; slotted listening), in the
  10 worlds, normalised by the worlds sweep's RW: a column beside Figure 3.
- scale (studies/repatt_scale.yaml): Figure 4, relative efficiency E_r
  (eqs 7-8, tp = 180) for 1..100 robots in One100m and Uniform100m.
- half (studies/repatt_half.yaml, not in the default set): Half50m and
  Half100m under both readings of Figure 1d (targets.half_shape cluster
  and strip) with RW, N0-Q1 and N100-Q40, each normalised by its own RW;
  half_slotted (studies/repatt_half_slotted.yaml) adds the slotted arm.

Each figure's sweep lives in OUT/<figure>/ (resumable: rerun the same
command); results.md, results.json and PNG figures are written to OUT.
Normalised times and E_r carry 95 % confidence intervals from a bootstrap
of both samples (percentile, 4,000 resamples, fixed seed), as the paper's
error bars are 95 % intervals.  A run that did not reach 90 % within its
scenario's duration is counted as unfinished and enters the means at that
duration (a lower bound), and results.md says how many there were.

Exit status: 0 done; 1 a run failed; 2 bad arguments; 130 interrupted.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from swarmtools.study import alns_bars
from swarmtools.study.common import (
    INTERRUPTED,
    announce,
    boot_ratio,
    narrow,
    pick,
    quick_out,
    read_rows,
    run_sweep,
    smoke_note,
    write_results,
)
from swarmtools.study.costs import QUICK
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep import plan as sweep_plan
from swarmtools.sweep import spec as sweep_spec
from swarmtools.sweep.spec import SweepError

REPO_ROOT = Path(__file__).resolve().parents[3]
STUDIES = REPO_ROOT / "studies"
FIGURES = {"worlds": "repatt_worlds.yaml", "slotted": "repatt_slotted.yaml", "scale": "repatt_scale.yaml",
           "half": "repatt_half.yaml", "half_slotted": "repatt_half_slotted.yaml"}
TIME = "time_capped_s"  # the time to 90 %, or the run's length when it did not finish
FINISHED = "finished"
# The override keys the sweep files vary (one place: the files and this script agree).
POLICY = "robots.0.policy"
QUEUE = "robots.0.params.queue_size"
NOISE = "sound.noise"
COUNT = "robots.0.count"
LISTEN = "robots.0.params.listening"
HALF_SHAPE = "targets.half_shape"
SLOTTED = "N100-Q40 slotted"  # the arm a real e-puck can run: own tone masks its microphones
DISTS = ("one", "two", "four", "half", "uniform")
WORLD_NAMES = {d: d.capitalize() for d in DISTS}
TP = 180  # targets picked up: the paper's tp (90 % of 200)

# The paper's text, section IV.D: improvement of RepAtt over RW, which we
# read as N0-Q1 (1 - normalised time); only these are given in numbers.
PAPER_N0Q1 = {("one", 50): 0.23, ("uniform", 50): 0.67, ("one", 100): 0.17, ("two", 100): 0.37,
              ("four", 100): 0.63, ("half", 100): 0.29, ("uniform", 100): 0.68}
PAPER_N100Q40 = "0.30 to 0.77 of RW's time over the 10 worlds"
PAPER_SCALE = "E_r up to 5.82 for N0-Q1; N100-Q40 always above 2; RW at best about 1, degrading"


def arm(row: dict[str, str]) -> str:
    """RW, N0-Q1, N100-Q40 ... from a row's policy, noise and queue."""
    if row.get(POLICY) == "random_walk":
        return "RW"
    noise = float(row.get(NOISE) or 0.0)
    level = round(noise / 0.06 * 100)
    name = f"N{level}-Q{int(float(row.get(QUEUE) or 1))}"
    return f"{name} slotted" if row.get(LISTEN) == "slotted" else name


def world(row: dict[str, str]) -> tuple[str, int]:
    """("one", 50) from the row's scenario file name repatt_one50.yaml."""
    stem = Path(row["scenario"]).stem.removeprefix("repatt_")
    size = 100 if stem.endswith("100") else 50
    return stem.removesuffix(str(size)), size


def times(rows: Sequence[dict[str, str]]) -> tuple[np.ndarray, int]:
    """Times to 90 % of the runs that ran, and how many did not finish."""
    ok = [r for r in rows if r["status"] == "ok"]
    t = np.array([float(r[TIME]) for r in ok], dtype=float)
    unfinished = sum(1 for r in ok if float(r.get(FINISHED) or 0) < 0.5)
    return t, unfinished


def group(rows: Sequence[dict[str, str]], key) -> dict[Any, list[dict[str, str]]]:
    out: dict[Any, list[dict[str, str]]] = {}
    for r in rows:
        out.setdefault(key(r), []).append(r)
    return out


def fmt(x: float, d: int = 2) -> str:
    return "-" if x is None or math.isnan(x) else f"{x:.{d}f}"


def normalised(rows: Sequence[dict[str, str]], arms: Sequence[str]) -> dict[str, Any]:
    """Per world and arm: mean time, normalised time with CI, unfinished runs."""
    out: dict[str, Any] = {}
    by = group(rows, lambda r: (world(r), arm(r)))
    for (dist, size) in [(d, s) for s in (50, 100) for d in DISTS]:
        rw, _ = times(by.get(((dist, size), "RW"), []))
        for a in arms:
            cell = by.get(((dist, size), a), [])
            if not cell:
                continue
            t, unfinished = times(cell)
            m, lo, hi = boot_ratio(t, rw) if a != "RW" or rw.size else (math.nan,) * 3
            out[f"{WORLD_NAMES[dist]}{size}m/{a}"] = {
                "world": f"{WORLD_NAMES[dist]}{size}m", "arm": a, "runs": len(cell), "ok": int(t.size),
                "unfinished": unfinished, "mean_s": float(t.mean()) if t.size else math.nan,
                "sd_s": float(t.std(ddof=1)) if t.size > 1 else math.nan,
                "normalised": m, "ci_low": lo, "ci_high": hi}
    return out


def render_fig3(res: dict[str, Any]) -> list[str]:
    lines = ["## Figure 3: time to 90 % of the targets, normalised by RW", "",
             "Mean time (s) over the seeds, and the mean normalised by RW's mean in the same world "
             "with its 95 % bootstrap interval. Paper: its text's improvements over RW read as "
             f"N0-Q1 (1 - improvement); N100-Q40: {PAPER_N100Q40}.", "",
             "| world | RW time (s) | N0-Q1 time (s) | N100-Q40 time (s) | N0-Q1 / RW [95 % CI] | paper N0-Q1 / RW "
             f"| N100-Q40 / RW [95 % CI] | {SLOTTED} / RW [95 % CI] | unfinished (RW, N0-Q1, N100-Q40) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for size in (50, 100):
        for d in DISTS:
            w = f"{WORLD_NAMES[d]}{size}m"
            c = {a: res.get(f"{w}/{a}") for a in ("RW", "N0-Q1", "N100-Q40", SLOTTED)}
            if not any(c.values()):
                continue

            def t(a: str, c: dict = c) -> str:
                x = c[a]
                return "-" if not x else f"{fmt(x['mean_s'], 0)} +- {fmt(x['sd_s'], 0)}"

            def n(a: str, c: dict = c) -> str:
                x = c[a]
                return "-" if not x else f"{fmt(x['normalised'])} [{fmt(x['ci_low'])}, {fmt(x['ci_high'])}]"

            paper = PAPER_N0Q1.get((d, size))
            unf = ", ".join(str(c[a]["unfinished"]) if c[a] else "-" for a in ("RW", "N0-Q1", "N100-Q40"))
            lines.append(f"| {w} | {t('RW')} | {t('N0-Q1')} | {t('N100-Q40')} | {n('N0-Q1')} | "
                         f"{fmt(paper) if paper is not None else '(not given)'} | {n('N100-Q40')} | {n(SLOTTED)} | {unf} |")
    return lines + [""]


def render_queue(res: dict[str, Any], queues: Sequence[int]) -> list[str]:
    arms = [f"N100-Q{q}" for q in queues]
    lines = ["## Figure 2c: queue size under N100 (normalised by RW)", "",
             "Paper: N100-Q1 comparable to RW; queues 8-120 better; Q40 best over the 10 worlds; 80 and "
             "120 worse than 40.", "",
             "| world | " + " | ".join(arms) + " |", "|---|" + "---:|" * len(arms)]
    for size in (50, 100):
        for d in DISTS:
            w = f"{WORLD_NAMES[d]}{size}m"
            cells = [res.get(f"{w}/{a}") for a in arms]
            if not any(cells):
                continue
            lines.append(f"| {w} | " + " | ".join(
                "-" if not x else f"{fmt(x['normalised'])} [{fmt(x['ci_low'])}, {fmt(x['ci_high'])}]"
                for x in cells) + " |")
    means = []
    for a in arms:
        v = [res[k]["normalised"] for k in res if k.endswith("/" + a) and not math.isnan(res[k]["normalised"])]
        means.append(fmt(float(np.mean(v))) if v else "-")
    lines.append("| mean over worlds | " + " | ".join(means) + " |")
    return lines + [""]


def efficiency(rows: Sequence[dict[str, str]]) -> dict[str, Any]:
    """E_r = E_n / E_1 = t_1 / (n t_n) per world and arm (eqs 7-8, tp fixed)."""
    out: dict[str, Any] = {}
    by = group(rows, lambda r: (world(r), arm(r), int(float(r[COUNT]))))
    keys = sorted({(w, a) for (w, a, _) in by})
    for (w, a) in keys:
        t1, _ = times(by.get((w, a, 1), []))
        for n in sorted({k[2] for k in by if k[0] == w and k[1] == a}):
            tn, unfinished = times(by[(w, a, n)])
            m, lo, hi = boot_ratio(t1, tn, scale=n)
            name = f"{WORLD_NAMES[w[0]]}{w[1]}m"
            out[f"{name}/{a}/{n}"] = {"world": name, "arm": a, "robots": n, "ok": int(tn.size),
                                      "unfinished": unfinished, "mean_s": float(tn.mean()) if tn.size else math.nan,
                                      "E_r": m, "ci_low": lo, "ci_high": hi}
            if a != "RW":
                # E_r(arm) / E_r(RW) = [t1(arm) / t1(RW)] x tn(RW) / tn(arm); a lone robot hears no one,
                # so its runs are the random walk's and the first factor is 1 (checked, not assumed)
                t1_rw, _ = times(by.get((w, "RW", 1), []))
                tn_rw, _ = times(by.get((w, "RW", n), []))
                same_e1 = t1.size > 0 and t1.size == t1_rw.size and bool(np.array_equal(np.sort(t1), np.sort(t1_rw)))
                e1 = t1.mean() / t1_rw.mean() if t1.size and t1_rw.size else math.nan
                # at n = 1 the two samples are the same runs: the ratio is 1 exactly, not an interval
                g, glo, ghi = (1.0, 1.0, 1.0) if n == 1 and same_e1 else boot_ratio(tn_rw, tn)
                out[f"{name}/{a}/{n}"] |= {"vs_rw": g * e1, "vs_rw_low": glo * e1, "vs_rw_high": ghi * e1,
                                           "same_e1": same_e1}
    return out


def half_table(rows: Sequence[dict[str, str]]) -> dict[str, Any]:
    """The Half sweep: per world size and half_shape, each arm's mean time and
    its time over the same shape's RW (95 % bootstrap interval)."""
    out: dict[str, Any] = {}
    by = group(rows, lambda r: (world(r)[1], r.get(HALF_SHAPE, ""), arm(r)))
    for (size, shape) in sorted({(k[0], k[1]) for k in by}):
        rw, _ = times(by.get((size, shape, "RW"), []))
        for a in ("RW", "N0-Q1", "N100-Q40", SLOTTED):
            t, unfinished = times(by.get((size, shape, a), []))
            if not t.size:
                continue
            m, lo, hi = boot_ratio(t, rw) if rw.size else (math.nan,) * 3
            out[f"Half{size}m/{shape}/{a}"] = {"world": f"Half{size}m", "half_shape": shape, "arm": a,
                                               "ok": int(t.size), "unfinished": unfinished,
                                               "mean_s": float(t.mean()), "normalised": m, "ci_low": lo, "ci_high": hi}
    return out


def render_half(res: dict[str, Any]) -> list[str]:
    lines = ["## Half, two readings of Figure 1d", "",
             "`half_shape` cluster: 100 targets in One's disc, 100 uniform over the square; strip: all 200 "
             "uniform over the half x >= 0. Time to 90 %, mean; normalised by the same shape's RW "
             "[95 % bootstrap CI]. Paper (N0-Q1, Half100m): 0.29.", "",
             "| world | half_shape | runs | RW (s) | N0-Q1 / RW | N100-Q40 / RW | N100-Q40 slotted / RW | unfinished |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    for (w, shape) in sorted({(x["world"], x["half_shape"]) for x in res.values()}, key=lambda k: (len(k[0]), k)):
        def cell(a: str, w: str = w, shape: str = shape) -> str:
            x = res.get(f"{w}/{shape}/{a}")
            return "-" if x is None else f"{fmt(x['normalised'])} [{fmt(x['ci_low'])}, {fmt(x['ci_high'])}]"
        rw = res.get(f"{w}/{shape}/RW", {})
        runs = sum(x["ok"] for x in res.values() if x["world"] == w and x["half_shape"] == shape)
        unf = sum(x["unfinished"] for x in res.values() if x["world"] == w and x["half_shape"] == shape)
        lines.append(f"| {w} | {shape} | {runs} | {fmt(rw.get('mean_s', math.nan), 0)} | {cell('N0-Q1')} | "
                     f"{cell('N100-Q40')} | {cell(SLOTTED)} | {unf} |")
    return lines + [""]


def render_scale(res: dict[str, Any]) -> list[str]:
    lines = ["## Figure 4: relative efficiency E_r against swarm size", "",
             f"E_r = E_n / E_1 with E_n = tp / (n t_tp), tp = {TP} (eqs 7-8). Paper: {PAPER_SCALE}.", "",
             "| world | arm | robots | time to 90 % (s) | E_r [95 % CI] | unfinished |", "|---|---|---:|---:|---:|---:|"]
    for k in sorted(res, key=lambda k: (res[k]["world"], res[k]["arm"], res[k]["robots"])):
        x = res[k]
        lines.append(f"| {x['world']} | {x['arm']} | {x['robots']} | {fmt(x['mean_s'], 0)} | "
                     f"{fmt(x['E_r'])} [{fmt(x['ci_low'])}, {fmt(x['ci_high'])}] | {x['unfinished']} |")
    gains = [x for x in res.values() if "vs_rw" in x]
    if gains:
        lines += ["", "RepAtt's gain over the random walk at each size, E_r(arm) / E_r(RW) [95 % bootstrap CI]: "
                  "a lone robot hears no one, so its runs are the random walk's (same E_1: "
                  + ("yes, in every arm" if all(x["same_e1"] for x in gains) else "NO, not in every arm")
                  + ") and the ratio is RW's time over the arm's at that size, 1 at n = 1 by construction.", "",
                  "| world | arm | robots | E_r(arm) / E_r(RW) [95 % CI] |", "|---|---|---:|---:|"]
        for x in sorted(gains, key=lambda x: (x["world"], x["arm"], x["robots"])):
            lines.append(f"| {x['world']} | {x['arm']} | {x['robots']} | "
                         f"{fmt(x['vs_rw'])} [{fmt(x['vs_rw_low'])}, {fmt(x['vs_rw_high'])}] |")
    return lines + [""]


def plot_bars(res: dict[str, Any], arms: Sequence[str], path: Path, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), sharey=True)
    for ax, size in zip(axes, (50, 100), strict=True):
        worlds = [f"{WORLD_NAMES[d]}{size}m" for d in DISTS]
        width = 0.8 / len(arms)
        for i, a in enumerate(arms):
            xs, ys, lo, hi = [], [], [], []
            for j, w in enumerate(worlds):
                x = res.get(f"{w}/{a}")
                if x and not math.isnan(x["normalised"]):
                    xs.append(j + (i - (len(arms) - 1) / 2) * width)
                    ys.append(x["normalised"])
                    lo.append(x["normalised"] - x["ci_low"])
                    hi.append(x["ci_high"] - x["normalised"])
            if xs:
                ax.bar(xs, ys, width, yerr=[lo, hi], capsize=2, label=a)
        ax.axhline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_xticks(range(len(worlds)), [w.removesuffix(f"{size}m") for w in worlds])
        ax.set_title(f"{size} m worlds (paper scale)")
    axes[0].set_ylabel("time to 90 % / RW's")
    axes[1].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_scale(res: dict[str, Any], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    worlds = sorted({x["world"] for x in res.values()})
    fig, axes = plt.subplots(1, max(1, len(worlds)), figsize=(10, 3.8), squeeze=False)
    for ax, w in zip(axes[0], worlds, strict=False):
        for a in sorted({x["arm"] for x in res.values() if x["world"] == w}):
            pts = sorted((x["robots"], x["E_r"], x["ci_low"], x["ci_high"]) for x in res.values()
                         if x["world"] == w and x["arm"] == a)
            n = [p[0] for p in pts]
            e = np.array([p[1] for p in pts])
            ax.errorbar(n, e, yerr=[e - np.array([p[2] for p in pts]), np.array([p[3] for p in pts]) - e],
                        marker="o", ms=3, capsize=2, label=a)
        ax.axhline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_xlabel("robots")
        ax.set_title(w)
    axes[0][0].set_ylabel("E_r")
    axes[0][-1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def load_sweep(name: str, sim: Path, reps: int | None, quick: bool) -> sweep_spec.Sweep:
    sw = sweep_spec.load(STUDIES / FIGURES[name], sweep_plan.seed_max(sim))
    narrow(sw, QUICK["repatt"] if quick else None)
    if reps is not None:
        sw.seeds = list(range(1, reps + 1))
    return sw


def run_entry(row: dict[str, str]) -> dict[str, Any]:
    """One run for results.json: its world, arm, swarm, seed and outcome."""
    def num(k: str) -> float | None:
        v = row.get(k, "")
        return float(v) if v not in ("", None) else None
    dist, size = world(row)
    return {"world": f"{WORLD_NAMES[dist]}{size}m", "arm": arm(row), "robots": int(num(COUNT) or 36),
            "seed": int(row["seed"]), "status": row["status"], "run_id": row["run_id"],
            "time_to_stop_s": num("time_to_stop_s"), "time_capped_s": num(TIME),
            "finished": num(FINISHED), "picked": num("picked"), "state_hash": row.get("state_hash", "")}


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="swarmtools.study.repatt", description=__doc__.split("\n\n")[0])
    ap.add_argument("--figures", default="worlds,slotted,scale",
                    help="which sweeps to run: worlds (Figures 3 and 2c), slotted (the e-puck's listening "
                         "schedule, beside Figure 3), scale (Figure 4), half (Half's two layouts), half_slotted (their slotted arm; needs half), alns (Figure 3's ALNS bars: plans, then "
                         "the routes followed; needs worlds); comma-separated")
    ap.add_argument("--quick", action="store_true",
                    help=f"a smoke run under a minute: {QUICK['repatt'].seeds} seed a cell, runs cut at "
                         f"{QUICK['repatt'].steps} steps, into out/study_repatt_quick")
    ap.add_argument("--reps", type=int, default=None, help="seeds per cell (default the files' 30)")
    ap.add_argument("--out", default=None, help="default out/study_repatt (out/study_repatt_quick with --quick)")
    ap.add_argument("--sim", default=str(REPO_ROOT / "build" / "swarmsim"))
    ap.add_argument("--jobs", type=int, default=0)
    ap.add_argument("--alns-iterations", type=int, default=None,
                    help="ALNS iterations per plan (default the paper's 25,000; 500 with --quick)")
    ap.add_argument("--alns-q", type=int, default=50, help="visits ALNS removes per iteration (the paper: 50 or 100)")
    sweep_cli.add_backend_options(ap)
    a = ap.parse_args(argv)
    command = " ".join(["python -m swarmtools.study.repatt", *(argv if argv is not None else sys.argv[1:])])
    t0 = time.monotonic()
    try:
        sweep_cli.check_args(a)
        figs = pick(a.figures, [*FIGURES, "alns"])
        if "alns" in figs and "worlds" not in figs:
            raise SweepError("--figures alns needs worlds too (ALNS is normalised by its random walk): "
                             "--figures worlds,alns (a finished worlds sweep resumes at once)")
        if "half_slotted" in figs and "half" not in figs:
            raise SweepError("--figures half_slotted needs half too (normalised by its random walk): "
                             "--figures half,half_slotted")
        if a.reps is not None and a.reps < 1:
            raise SweepError("--reps must be at least 1")
        sim, out = Path(a.sim), quick_out(a.out, REPO_ROOT / "out" / "study_repatt", a.quick)
        if a.alns_iterations is None:
            a.alns_iterations = 500 if a.quick else 25000
        quick = QUICK["repatt"] if a.quick else None
        sweeps = {name: load_sweep(name, sim, a.reps, a.quick) for name in figs if name != "alns"}
        announce("study_repatt", "repatt", sum(len(sweep_plan.expand(sw)) for sw in sweeps.values()), quick)
        rc_all, results, md = 0, {}, ["# Seed 002 (RepAtt) at e-puck scale", "", *smoke_note(quick),
                                       f"Command: `{command}`.", ""]
        tables: dict[str, list[dict[str, str]]] = {}
        for name in figs:
            if name == "alns":
                continue
            sw = sweeps[name]
            sweep_dir = out / name
            t1 = time.monotonic()
            rc = run_sweep(sw, a, sim, sweep_dir, "study_repatt")
            if rc == INTERRUPTED:
                return rc
            if rc is None:
                continue
            rc_all = rc_all or rc
            rows = tables[name] = read_rows(sweep_dir / "results.csv")
            builds = sorted({r.get("code_version", "") for r in rows})
            md.append(f"{name}: {len(rows)} runs, {len(sw.seeds)} seeds a cell, {time.monotonic() - t1:.0f} s "
                      f"(sweep `{sweep_dir}`), made by {len({r.get('sim_sha256') for r in rows})} simulator "
                      f"build(s): {', '.join(builds)}.")
            results[f"{name}_runs"] = [run_entry(r) for r in rows]
        md.append("")
        alns_res: dict[str, Any] = {}
        if "alns" in figs:
            t1 = time.monotonic()
            plans = alns_bars.plan_layouts(out / "alns", sim, a.alns_iterations, a.alns_q, 1, 2000)
            seeds = list(range(1, (a.reps or (quick.seeds if quick else 30)) + 1))
            sw = narrow(sweep_spec.load(alns_bars.sweep_file(out / "alns", seeds), sweep_plan.seed_max(sim)), quick)
            rc = run_sweep(sw, a, sim, out / "alns" / "sweep", "study_repatt")
            if rc == INTERRUPTED:
                return rc
            if rc is not None:
                rc_all = rc_all or rc
                arows = read_rows(out / "alns" / "sweep" / "results.csv")
                rw = {world(r): times(rr)[0] for r, rr in
                      ((g[0], g) for g in group(tables["worlds"], lambda r: (world(r), arm(r))).values())
                      if arm(r) == "RW"}
                alns_res = alns_bars.bars(arows, rw)
                md.append(f"alns: 5 plans ({a.alns_iterations} iterations, q {a.alns_q}) and {len(arows)} runs, "
                          f"{time.monotonic() - t1:.0f} s (`{out / 'alns'}`).")
                md.append("")
                md += alns_bars.render(alns_res, rw, plans)
                results["alns"] = alns_res
                results["alns_plans"] = {d: {k: p.get(k) for k in ("finishing_time_s", "lower_bound_s",
                                                                     "total_length_m", "pyvrp", "iterations", "q")}
                                         for d, p in plans.items()}
        if "worlds" in tables:
            # the slotted arm (its own sweep) is normalised by the worlds sweep's RW
            rows = tables["worlds"] + tables.get("slotted", [])
            res = normalised(rows, ("RW", "N0-Q1", "N100-Q40", SLOTTED)) | alns_res
            md += render_fig3(res)
            plot_bars(res, ("N0-Q1", "N100-Q40", "ALNS") if alns_res else ("N0-Q1", "N100-Q40"),
                      out / "fig3_normalised.png",
                      "time to 90 % of the targets, normalised by random walk")
            md.append("![Figure 3](fig3_normalised.png)\n")
            queues = sorted({int(float(r[QUEUE])) for r in rows if r.get(POLICY) != "random_walk"
                             and float(r.get(NOISE) or 0) > 0 and r.get(LISTEN) != "slotted"})
            qres = normalised(rows, [f"N100-Q{q}" for q in queues])
            md += render_queue(qres, queues)
            plot_bars(qres, [f"N100-Q{q}" for q in queues], out / "fig2c_queue.png",
                      "queue size under N100, normalised by random walk")
            md.append("![Figure 2c](fig2c_queue.png)\n")
            results["fig3"], results["fig2c"] = res, qres
        if "half" in tables:
            # the slotted arm (its own sweep) is normalised by the half sweep's RW
            res = half_table(tables["half"] + tables.get("half_slotted", []))
            md += render_half(res)
            results["half"] = res
        if "scale" in tables:
            res = efficiency(tables["scale"])
            md += render_scale(res)
            plot_scale(res, out / "fig4_efficiency.png")
            md.append("![Figure 4](fig4_efficiency.png)\n")
            results["fig4"] = res
        md.append(f"Wall time: {time.monotonic() - t0:.0f} s.")
        write_results(out, md, results, "study_repatt")
        return 0 if rc_all == 0 else 1
    except SweepError as e:
        print(f"study_repatt: {e}", file=sys.stderr)
        return e.exit_code


if __name__ == "__main__":
    sys.exit(main())
