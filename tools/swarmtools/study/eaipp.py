"""Seed 003's simulation study (EAIPP path formation, section 5 of the paper):
Figures 10-17 run through the sweep engine, beside the paper's numbers.

    .venv/bin/python -m swarmtools.study.eaipp [--figures maze,distance,...]
        [--quick] [--reps N] [--steps N] [--controllers NNEA,...] [--out DIR] [--sim PATH]
        [--backend slurm ...]                        (make study-eaipp STUDY_ARGS=...)

    .venv/bin/python -m swarmtools.study.eaipp --picture [--picture-seed auto|S]
        [--picture-px 420] [--picture-out docs/figures/eaipp_square_frames.png]
                                                     (make study-eaipp STUDY_ARGS=--picture)

The sweeps (studies/eaipp_*.yaml; `--figures` picks among them, default all):

- maze (Figure 10): the half-scale maze, N = 40 .. 70.  Paper: success 54,
  57, 64, 68, 77, 81, 88 %.
- distance (Figures 11-12): the square arena, D = 1.0 .. 3.0 m, per
  controller.  The text gives no numbers.
- obstacles (Figures 13-14): 0 .. 30 random cylinders at D = 3 m, per
  controller.  Paper: EAIPP above 90 % in every case (no other number).
- bearing (Figure 15): the bearing-noise vector's sd.  No numbers in the text.
- loss (Figure 16): packet loss.  Paper: 92, 86, 83, 89, 91 %, and 0 % at
  100 % loss.
- bias (Figure 17): the wheels' bias sd.  Paper: 92, 87, 78, 63, 45 %.
- bias_step (Figure 17 again): the bias drawn anew every step (eq 3's
  other reading).

Per figure, per controller and condition, results.md has the success rate
(a run succeeds when the nest's and the food's networks merge within the
budget; sim_host/tasks/paths) with its 95 % Wilson score interval (scipy's
binomtest), the paper's rate beside it where the text gives one (and whether
it falls inside our interval), the completion time over the successes
(median and quartiles of merge_time_s), the paper's convention (Figure 11:
every failure counted at the 1000 s budget, merge_time_capped_s: median and
quartiles over every run), how many runs perceived the food and the median
chain length.  A PNG per figure: box plots of the capped completion time by
condition and controller (the paper's figures; 1 s = 10 steps), and the
success rates with their intervals and the paper's.  results.json holds
every run, every cell and the wall times.

Controllers: a sweep's `scenario` axis lists them, one scenario file each
(eaipp_square.yaml, pfias_square.yaml, ...); a controller is named by its
file name's prefix before the first `_`, upper-cased (tsasr_square.yaml ->
TSASR), so a scenario added to the sweep files is picked up as it is.
CONTROLLERS below orders and colours the known ones as the paper's figures
do (EAIPP red, TSASR green, PFIAS blue, NNEA purple).  NNEA (the evolved
controller, firmware/nnea, docs/studies/nnea.md) is its scenario
nnea_square.yaml in the `scenario:` lists of studies/eaipp_distance.yaml
and eaipp_obstacles.yaml; nothing here names it but its colour and its
success criterion (CRITERIA: `paths.nodes: any`, set beside its scenario in
those lists; the tables leave such per-controller settings out of the
conditions and results.md names them).
`--controllers NNEA` runs one controller's rows alone (the scenario axes
narrowed to its file), e.g. after a new genome, without rerunning the
others'.

Cost (2 cores, this machine, EAIPP failing so every run goes the full
1000 s): a square-arena run about 0.5 s, a maze run (40-70 robots) about 9 s;
the full study (5,900 runs, 700 of them in the maze) about 9,000 CPU-s, some
75 minutes on 2 cores (measured since: docs/studies/index.md); `--quick`,
a smoke run, under a minute (swarmtools.study.costs.QUICK).

Each sweep lives in OUT/<figure>/ with its frozen simulator copy and is
resumable: rerun the same command.  `--quick` takes 1 seed a cell and cuts
the runs (into OUT_quick, its results.md marked as a smoke run), `--reps
N` N seeds, `--steps N` cuts every run at N steps (a smoke test: a failure
is then still recorded at the 1000 s budget, and results.md says the runs
were cut).  `--studies DIR` reads the sweep files from DIR (tests).

The picture: `--picture` runs no sweep.  It runs the square arena's base
condition (eaipp_square.yaml: N = 15, D = 3 m) for seeds 1..20 (summaries
only), takes the first seed whose run merges (seed 1 if none does:
the caption says so), reruns it with frames and tiles 4 of them, from the
start to the run's end, into docs/figures/eaipp_square_frames.png (the
working folders in OUT/picture/).  `--picture-seed S` takes seed S,
`--picture-scenario` another scenario (e.g. sim_host/scenarios/eaipp_maze.yaml).

Exit status: 0 done; 1 a run failed; 2 bad arguments; 130 interrupted.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from swarmtools.study.common import (
    INTERRUPTED,
    announce,
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
from swarmtools.sweep.spec import SCENARIO_KEY, SweepError

REPO_ROOT = Path(__file__).resolve().parents[3]
STUDIES = REPO_ROOT / "studies"
SCENARIOS = REPO_ROOT / "sim_host" / "scenarios"
BUDGET_S = 1000.0       # the paper's 10,000 steps (paths.budget in every eaipp scenario)
STEPS_PER_S = 10        # control_period_ms: 100 in every eaipp scenario
METRICS = ("success", "merge_time_s", "merge_time_capped_s", "food_perceived", "food_time_s",
           "chain_nodes", "nodes_end", "distance_m")

# The controllers the paper compares, in its figures' order and colours
# (Figure 11: "the red box [EAIPP] is generally at the lowest position ...
# green [TSASR] ... blue [PFIAS]"; NNEA's boxes are purple).  A controller
# is the upper-cased prefix of its scenario file's name.  NNEA's scenario
# (nnea_square.yaml) is in the sweep files' `scenario:` lists.  Any other
# prefix is drawn after these in matplotlib's colours.
CONTROLLERS = {"EAIPP": "tab:red", "TSASR": "tab:green", "PFIAS": "tab:blue", "NNEA": "tab:purple"}

# Each controller's success criterion (the paths task's `nodes:`), as the
# sweep files' controller axes set it: a chain of still robots (EAIPP's
# Robot_Node) for all but NNEA, whose robots make paths by travelling and
# never stop (docs/studies/nnea.md); any other controller: still.  The one
# documented difference between the controllers' worlds (tested in
# tools/tests/study/test_eaipp_conditions.py).
NODES = "paths.nodes"
CRITERIA = {"NNEA": "any"}
DEFAULT_CRITERION = "still"


def criterion(ctrl: str) -> str:
    """The `paths.nodes` a controller is scored with."""
    return CRITERIA.get(ctrl, DEFAULT_CRITERION)

# The override keys the sweep files vary (one place: the files and this script agree).
COUNT = "robots.2.count"
NEST_X = "robots.0.placement.poses.0.x"
FOOD_X = "robots.1.placement.poses.0.x"
CYLINDERS = "random_cylinders.count"
BEARING = "ircom.bearing_noise_vec"
LOSS = "ircom.loss"
BIAS = "wheels.bias_sd"
# Figure 17's levels are a marXbot's (axle about 140 mm, ref [36]); the e-puck's is 53 mm.
MARXBOT_AXLE_M = 0.140
EPUCK_AXLE_M = 0.053
AXLE_RATIO = EPUCK_AXLE_M / MARXBOT_AXLE_M
PAPER_SPEED_M_S = 0.05   # Table 2
EPUCK_MAX_M_S = 0.1288   # 1000 steps/s of 0.1288 mm


def distance(row: dict[str, str]) -> float:
    """D (m) from the nest's and the food's x (the sweep's zip axis)."""
    return round(float(row[FOOD_X]) - float(row[NEST_X]), 3)


@dataclass
class Figure:
    name: str                      # --figures name, OUT/<name>/
    file: str                      # studies/<file>
    figs: str                      # the paper's figure numbers
    title: str
    axis: str                      # the condition's name (table column, x label)
    keys: tuple[str, ...]          # the varied keys that make the condition
    value: Callable[[dict[str, str]], float]
    show: Callable[[float], str]
    paper: dict[float, float] = field(default_factory=dict)   # EAIPP's success rate by condition
    paper_min: float | None = None  # "above this in every case" (EAIPP)
    note: str = ""                 # what the paper's text says


FIGURES: dict[str, Figure] = {f.name: f for f in (
    Figure("maze", "eaipp_maze.yaml", "10", "the maze at half scale, against the swarm size", "N",
           (COUNT,), lambda r: float(r[COUNT]), lambda v: f"{v:.0f}",
           paper={40: 0.54, 45: 0.57, 50: 0.64, 55: 0.68, 60: 0.77, 65: 0.81, 70: 0.88},
           note="Paper (section 5.1): success 54, 57, 64, 68, 77, 81, 88 % for N = 40 .. 70; its completion "
                "times only in the figure. Our maze is a reconstruction and its budget (1000 s) our choice."),
    Figure("distance", "eaipp_distance.yaml", "11-12", "the square arena, against the nest-food distance",
           "D (m)", (NEST_X, FOOD_X), distance, lambda v: f"{v:.1f}",
           note="Paper (section 5.2.1): no numbers in the text (Figures 11-12 only): EAIPP the most "
                "efficient, slower than TSASR for D in [1.0, 1.8] m, the highest success rate, most of "
                "all at long distances; PFIAS's success too low at D = 2.4 .. 3.0 m for boxes."),
    Figure("obstacles", "eaipp_obstacles.yaml", "13-14", "the square arena, D = 3 m, against random cylinders",
           "obstacles", (CYLINDERS,), lambda r: float(r[CYLINDERS]), lambda v: f"{v:.0f}",
           paper_min=0.90,
           note="Paper (section 5.2.2): EAIPP's success rate above 90 % in every case; PFIAS's and "
                "TSASR's drop dramatically (no numbers). Levels 0, 5, .., 30 are our reading."),
    Figure("bearing", "eaipp_bearing.yaml", "15", "direction noise (bearing-noise vector)",
           "noise vector sd (m)", (BEARING,), lambda r: float(r[BEARING]), lambda v: f"{v:.2f}",
           note="Paper (section 5.3): \"stable performance\"; no numbers in the text. Levels are our reading."),
    Figure("loss", "eaipp_loss.yaml", "16", "packet loss", "loss", (LOSS,), lambda r: float(r[LOSS]),
           lambda v: f"{100 * v:.0f} %",
           paper={0.0: 0.92, 0.2: 0.86, 0.4: 0.83, 0.6: 0.89, 0.8: 0.91, 1.0: 0.0},
           note="Paper (section 5.3): 92, 86, 83, 89, 91 % \"from left to right\" over five levels the "
                "text does not give (0 .. 80 % is our reading), and 0 % at 100 % loss."),
    Figure("bias", "eaipp_bias.yaml", "17", "wheel bias noise", "bias sd (cm/s)", (BIAS,),
           lambda r: float(r[BIAS]), lambda v: f"{100 * v:.0f}",
           paper={0.0: 0.92, 0.05: 0.87, 0.10: 0.78, 0.15: 0.63, 0.20: 0.45},
           note="Paper (section 5.3): 92, 87, 78, 63, 45 % for 0 .. 20 cm/s. The e-puck's wheels top out at "
                "12.9 cm/s: our high levels saturate them (an upper bound, docs/notes/i15_paths.md)."),
    Figure("bias_scaled", "eaipp_bias_scaled.yaml", "17", "wheel bias noise scaled by the axle ratio",
           "marXbot bias sd (cm/s)", (BIAS,), lambda r: round(float(r[BIAS]) / AXLE_RATIO, 2),
           lambda v: f"{100 * v:.0f}",
           paper={0.0: 0.92, 0.05: 0.87, 0.10: 0.78, 0.15: 0.63, 0.20: 0.45},
           note="The paper's levels are a marXbot's (axle about 140 mm): the e-puck (53 mm) runs each times "
                "53/140, the same heading drift and turning radius at 5 cm/s; drawn once a run per wheel."),
    Figure("bias_step", "eaipp_bias_step.yaml", "17", "wheel bias noise, drawn anew every step",
           "bias sd (cm/s)", (BIAS,), lambda r: float(r[BIAS]), lambda v: f"{100 * v:.0f}",
           paper={0.0: 0.92, 0.05: 0.87, 0.10: 0.78, 0.15: 0.63, 0.20: 0.45},
           note="Eq 3's other reading (wheels.bias_per_step): b redrawn every control step, not once a run "
                "as ARGoS draws it; with a once-a-run bias an open-loop Robot_Lost drives in circles."),
)}


# ------------------------------------------------------------------ turning radii
def turning_radii(sd: float, axle: float, v: float = PAPER_SPEED_M_S, vmax: float | None = None,
                  n: int = 100_000, seed: int = 17) -> np.ndarray:
    """|R| (m) of n robots whose wheels carry a once-a-run bias N(0, sd^2) each
    (ARGoS's, m/s) at commanded speed v: R = (L/2)(v_l + v_r)/(v_r - v_l);
    with vmax the wheels saturate at +-vmax (the e-puck's).  Infinite when
    the bias is 0."""
    rng = np.random.default_rng(seed)
    b = rng.normal(0.0, sd, size=(n, 2)) if sd > 0 else np.zeros((n, 2))
    vl, vr = v + b[:, 0], v + b[:, 1]
    if vmax is not None:
        vl, vr = np.clip(vl, -vmax, vmax), np.clip(vr, -vmax, vmax)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.abs(axle / 2.0 * (vl + vr) / (vr - vl))
    return np.where(np.isnan(r), np.inf, r)


def render_radii(paper: dict[float, float]) -> list[str]:
    """Figure 17's levels as turning radii: a marXbot at the paper's levels,
    an e-puck at the same levels and at the levels x 53/140 (median and
    quartiles of |R|, the share circling within 0.3 m, half the range R)."""
    lines = ["### Figure 17's bias as turning radii", "",
             f"|R| = (L/2)|v_l + v_r|/|v_r - v_l| at {100 * PAPER_SPEED_M_S:.0f} cm/s with a once-a-run bias "
             "N(0, sd^2) per wheel (100,000 draws; the e-puck's wheels saturate at 12.9 cm/s): median "
             "[quartiles] in m, and the share with |R| < 0.3 m (half the range R = 0.6 m).", "",
             "| paper's sd (cm/s) | paper's success | marXbot (L 140 mm) | e-puck, same sd | "
             "e-puck, sd x 53/140 |", "|---:|---:|---|---|---|"]

    def cell(r: np.ndarray) -> str:
        if np.all(np.isinf(r)):
            return "straight"
        q1, q2, q3 = np.quantile(r, [0.25, 0.5, 0.75])
        return f"{q2:.2f} [{q1:.2f}, {q3:.2f}], {100 * np.mean(r < 0.3):.0f} % < 0.3 m"

    for sd, ok in paper.items():
        lines.append(f"| {100 * sd:.0f} | {100 * ok:.0f} % | {cell(turning_radii(sd, MARXBOT_AXLE_M))} | "
                     f"{cell(turning_radii(sd, EPUCK_AXLE_M, vmax=EPUCK_MAX_M_S))} | "
                     f"{cell(turning_radii(sd * AXLE_RATIO, EPUCK_AXLE_M, vmax=EPUCK_MAX_M_S))} |")
    return lines + [""]


# ------------------------------------------------------------------ statistics
def wilson(k: int, n: int) -> tuple[float, float, float]:
    """k / n and its 95 % Wilson score interval (scipy); NaNs when n = 0."""
    if n <= 0:
        return math.nan, math.nan, math.nan
    from scipy.stats import binomtest
    ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
    return k / n, float(ci.low), float(ci.high)


def quartiles(values: Sequence[float]) -> tuple[float, float, float]:
    """(Q1, median, Q3) by numpy's linear interpolation; NaNs when empty."""
    v = np.asarray([x for x in values if not math.isnan(x)], dtype=float)
    if v.size == 0:
        return math.nan, math.nan, math.nan
    q1, med, q3 = np.percentile(v, [25, 50, 75])
    return float(q1), float(med), float(q3)


def num(row: dict[str, str], key: str) -> float:
    v = row.get(key)
    return float(v) if v not in (None, "") else math.nan


def controller(row: dict[str, str], default_scenario: str | Path = "") -> str:
    """EAIPP, PFIAS, TSASR ...: the row's scenario file name's prefix, upper-cased."""
    scenario = row.get(SCENARIO_KEY) or str(default_scenario)
    return Path(scenario).stem.split("_")[0].upper()


def controller_order(names: Sequence[str]) -> list[str]:
    known = [c for c in CONTROLLERS if c in names]
    return known + sorted(set(names) - set(known))


def own_keys(sw: sweep_spec.Sweep) -> dict[str, dict[str, str]]:
    """The controllers' own settings: keys of the controller (scenario) axis
    with one value per controller (its success criterion), {controller:
    {key: value}}.  They name no condition, so the tables leave them out; a
    key with two values for one controller stays a condition (its cells apart)."""
    own: dict[str, dict[str, str]] = {}
    for axis in (a for a in sw.axes if SCENARIO_KEY in a.keys):
        for key in (k for k in axis.keys if k != SCENARIO_KEY):
            values: dict[str, set[str]] = {}
            for c in axis.combos:
                values.setdefault(controller({SCENARIO_KEY: str(c[SCENARIO_KEY])}), set()).add(
                    sweep_spec.set_text(c[key]))
            if all(len(v) == 1 for v in values.values()):
                for ctrl, v in values.items():
                    own.setdefault(ctrl, {})[key] = next(iter(v))
    return own


def condition_keys(sw: sweep_spec.Sweep, own: dict[str, dict[str, str]] | None = None) -> list[str]:
    """The varied keys that make a condition (the controllers' own settings,
    own_keys(sw) unless given, left out)."""
    left_out = {k for settings in (own_keys(sw) if own is None else own).values() for k in settings}
    return [k for k in sw.varied_keys if k not in left_out]


def extra(row: dict[str, str], fig: Figure, varied: Sequence[str]) -> str:
    """Any other varied key (a sweep file extended with another axis): its cells stay apart."""
    return ", ".join(f"{k}={row.get(k, '')}" for k in varied if k != SCENARIO_KEY and k not in fig.keys)


def cells(rows: Sequence[dict[str, str]], fig: Figure, varied: Sequence[str] = (),
          default_scenario: str | Path = "") -> list[dict[str, Any]]:
    """One entry per controller and condition, in the table's order."""
    by: dict[tuple[str, float, str], list[dict[str, str]]] = {}
    for r in rows:
        by.setdefault((controller(r, default_scenario), fig.value(r), extra(r, fig, varied)), []).append(r)
    order = controller_order([k[0] for k in by])
    out = []
    for key in sorted(by, key=lambda k: (order.index(k[0]), k[2], k[1])):
        ctrl, value, ex = key
        cell = by[key]
        ok = [r for r in cell if r.get("status") == "ok"]
        wins = [r for r in ok if num(r, "success") >= 0.5]
        p, lo, hi = wilson(len(wins), len(ok))
        t = quartiles([num(r, "merge_time_s") for r in wins])
        capped = quartiles([num(r, "merge_time_capped_s") for r in ok])
        paper = fig.paper.get(round(value, 3)) if ctrl == "EAIPP" else None
        paper_min = fig.paper_min if ctrl == "EAIPP" else None
        if paper is not None:
            inside: bool | None = bool(lo <= paper <= hi) if ok else None
        elif paper_min is not None:
            inside = bool(hi > paper_min) if ok else None
        else:
            inside = None
        out.append({
            "figure": fig.name, "controller": ctrl, "condition": value, "label": fig.show(value), "extra": ex,
            "runs": len(cell), "ok": len(ok), "failed_runs": len(cell) - len(ok), "successes": len(wins),
            "success_rate": p, "ci_low": lo, "ci_high": hi,
            "time_q1_s": t[0], "time_median_s": t[1], "time_q3_s": t[2],
            "capped_q1_s": capped[0], "capped_median_s": capped[1], "capped_q3_s": capped[2],
            "capped_mean_s": float(np.mean([num(r, "merge_time_capped_s") for r in ok])) if ok else math.nan,
            "food_perceived": sum(1 for r in ok if num(r, "food_perceived") >= 0.5),
            "chain_nodes_median": quartiles([num(r, "chain_nodes") for r in wins])[1],
            "paper_success": paper, "paper_min": paper_min, "paper_within_ci": inside})
    return out


# ------------------------------------------------------------------ rendering
def fmt(x: float | None, d: int = 0) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{d}f}"


def pct(x: float | None) -> str:
    return "-" if x is None or math.isnan(x) else f"{100 * x:.0f}"


def iqr(c: dict[str, Any], prefix: str) -> str:
    if math.isnan(c[f"{prefix}_median_s"]):
        return "-"
    return f"{fmt(c[f'{prefix}_median_s'])} [{fmt(c[f'{prefix}_q1_s'])}, {fmt(c[f'{prefix}_q3_s'])}]"


def paper_cell(c: dict[str, Any]) -> tuple[str, str]:
    if c["paper_success"] is not None:
        p = pct(c["paper_success"])
    elif c["paper_min"] is not None:
        p = f"> {pct(c['paper_min'])}"
    else:
        return "-", "-"
    inside = c["paper_within_ci"]
    return p, "-" if inside is None else ("yes" if inside else "no")


def render(fig: Figure, cs: Sequence[dict[str, Any]]) -> list[str]:
    """The figure's section of results.md."""
    lines = [f"## Figure{'s' if '-' in fig.figs else ''} {fig.figs} ({fig.name}): {fig.title}", "",
             fig.note, "",
             "Success: the nest's and the food's networks merged within the budget; rate in % with its 95 % "
             "Wilson interval over the runs that ran. Time to merge over the successes, and the paper's "
             f"convention (every failure counted at the {BUDGET_S:.0f} s budget, x {STEPS_PER_S} for steps): "
             "median [Q1, Q3] in s. Paper within CI: the paper's rate inside our interval (for \"> 90\": our "
             "interval reaches above 90).", "",
             f"| controller | {fig.axis} | runs | success % [95 % CI] | paper % | paper within CI "
             "| time to merge, successes (s) | time, failures at budget (s) | food perceived | chain nodes |",
             "|---|---:|---:|---:|---:|---|---:|---:|---:|---:|"]
    for c in cs:
        p, inside = paper_cell(c)
        cond = c["label"] + (f" ({c['extra']})" if c["extra"] else "")
        runs = f"{c['ok']}" + (f" (+{c['failed_runs']} failed)" if c["failed_runs"] else "")
        lines.append(
            f"| {c['controller']} | {cond} | {runs} | {pct(c['success_rate'])} [{pct(c['ci_low'])}, "
            f"{pct(c['ci_high'])}] | {p} | {inside} | {iqr(c, 'time')} | {iqr(c, 'capped')} "
            f"| {c['food_perceived']} | {fmt(c['chain_nodes_median'])} |")
    return lines + [""]


def plot(fig: Figure, rows: Sequence[dict[str, str]], cs: Sequence[dict[str, Any]], path: Path,
         default_scenario: str | Path = "") -> None:
    """Box plots of the capped completion time (the paper's figures) and the
    success rates with their intervals and the paper's, against the condition."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    values = sorted({c["condition"] for c in cs})
    ctrls = controller_order([c["controller"] for c in cs])
    others = iter(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    colour = {k: CONTROLLERS.get(k) or next(others) for k in ctrls}
    width = 0.8 / max(1, len(ctrls))
    fig_, (top, bottom) = plt.subplots(2, 1, figsize=(min(14.0, max(7.0, 0.45 * len(values) * max(1, len(ctrls)) + 3)), 6.5),
                                       sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for i, ctrl in enumerate(ctrls):
        off = (i - (len(ctrls) - 1) / 2) * width
        data, pos = [], []
        for j, v in enumerate(values):
            t = [num(r, "merge_time_capped_s") for r in rows if r.get("status") == "ok"
                 and controller(r, default_scenario) == ctrl and fig.value(r) == v]
            t = [x for x in t if not math.isnan(x)]
            if t:
                data.append(t)
                pos.append(j + off)
        if data:
            bp = top.boxplot(data, positions=pos, widths=width * 0.85, patch_artist=True, manage_ticks=False,
                             flierprops={"markersize": 2})
            for b in bp["boxes"]:
                b.set(facecolor=colour[ctrl], alpha=0.55)
            for m in bp["medians"]:
                m.set(color="black")
        pts = [(values.index(c["condition"]) + off, c) for c in cs if c["controller"] == ctrl
               and not math.isnan(c["success_rate"])]
        if pts:
            x = [p[0] for p in pts]
            y = np.array([100 * p[1]["success_rate"] for p in pts])
            lo = y - np.array([100 * p[1]["ci_low"] for p in pts])
            hi = np.array([100 * p[1]["ci_high"] for p in pts]) - y
            bottom.errorbar(x, y, yerr=[lo, hi], fmt="o", ms=4, capsize=3, color=colour[ctrl], label=ctrl)
        top.plot([], [], "s", color=colour[ctrl], alpha=0.55, label=ctrl)
    shift = ((ctrls.index("EAIPP") - (len(ctrls) - 1) / 2) * width) if "EAIPP" in ctrls else 0.0
    paper = [(values.index(v) + shift, 100 * p) for v, p in ((v, fig.paper.get(round(v, 3))) for v in values)
             if p is not None]
    if paper:
        bottom.plot([p[0] for p in paper], [p[1] for p in paper], "kx", ms=8, label="paper (EAIPP)")
    if fig.paper_min is not None:
        bottom.axhline(100 * fig.paper_min, color="k", ls="--", lw=0.8, label=f"paper: EAIPP > {pct(fig.paper_min)} %")
    top.axhline(BUDGET_S, color="grey", ls=":", lw=0.8)
    top.set_ylim(0, BUDGET_S * 1.05)
    top.set_ylabel("completion time (s)\nfailures at the budget")
    sec = top.secondary_yaxis("right", functions=(lambda s: s * STEPS_PER_S, lambda k: k / STEPS_PER_S))
    sec.set_ylabel("steps")
    top.legend(fontsize=8, loc="upper left")
    top.set_title(f"Seed 003, Figure{'s' if '-' in fig.figs else ''} {fig.figs}: {fig.title}", fontsize=10)
    bottom.set_ylim(-5, 105)
    bottom.set_ylabel("success (%), 95 % CI")
    bottom.set_xticks(range(len(values)), [fig.show(v) for v in values])
    bottom.set_xlabel(fig.axis)
    bottom.legend(fontsize=8, loc="best")
    fig_.tight_layout()
    fig_.savefig(path, dpi=100)
    plt.close(fig_)


def run_entry(fig: Figure, row: dict[str, str], varied: Sequence[str], default_scenario: str | Path) -> dict[str, Any]:
    """One run for results.json."""
    e: dict[str, Any] = {"figure": fig.name, "controller": controller(row, default_scenario),
                         "condition": fig.value(row), "extra": extra(row, fig, varied), "seed": int(row["seed"]),
                         "status": row["status"], "run_id": row["run_id"]}
    for m in METRICS:
        if m in row:
            v = num(row, m)
            e[m] = None if math.isnan(v) else v
    e.update({"state_hash": row.get("state_hash", ""), "code_version": row.get("code_version", "")})
    return e


# ------------------------------------------------------------------ the picture
def picture(sim: Path, out_png: Path, work: Path, scenario: Path, seed: str = "auto", px: int = 420,
            frames: int = 4, search: int = 20) -> str:
    """Frames of one run tiled into out_png; returns the caption."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    def sim_run(out: Path, *args: str) -> None:
        cmd = [str(sim), str(scenario), "--lcm", "off", "--quiet", "--replace", "--out", str(out), *args]
        p = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if p.returncode != 0:
            raise SweepError(f"picture: {' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")

    work.mkdir(parents=True, exist_ok=True)
    note = ""
    if seed == "auto":
        sim_run(work / "search", "--seed", "1", "--reps", str(search), "--threads", "2")
        chosen = None
        for s in range(1, search + 1):
            m = json.loads((work / "search" / f"run_{s}" / "summary.json").read_text())["metrics"]
            if (m.get("success") or 0) >= 0.5:
                chosen = s
                break
        if chosen is None:
            chosen, note = 1, f" (none of seeds 1-{search} merged)"
    else:
        chosen = int(seed)
    sim_run(work / "probe", "--seed", str(chosen), "--threads", "1")
    summary = json.loads((work / "probe" / f"run_{chosen}" / "summary.json").read_text())
    steps = int(summary["steps"])
    every = max(1, math.ceil(steps / max(1, frames - 1)))
    sim_run(work / "frames", "--seed", str(chosen), "--threads", "1", "--frames", str(every), "--frame-px", str(px))
    files = sorted((work / "frames" / f"run_{chosen}" / "frames").glob("frame_*.png"))
    if not files:
        raise SweepError("picture: the simulator wrote no frames")
    idx = sorted({round(i * (len(files) - 1) / max(1, frames - 1)) for i in range(frames)})
    pick = [files[i] for i in idx]
    m = summary["metrics"]
    period = float(summary.get("control_period_ms", 1000 / STEPS_PER_S)) / 1000
    if (m.get("success") or 0) >= 0.5:
        outcome = f"merged at {m['merge_time_s']:.1f} s, chain of {m.get('chain_nodes')} nodes"
    else:
        outcome = f"no merge within {m.get('budget_s', BUDGET_S):.0f} s"
    caption = (f"{summary.get('scenario', scenario.stem)}, seed {chosen}{note}: {outcome} "
               f"(code {summary.get('code_version', '?')})")
    fig, axes = plt.subplots(1, len(pick), figsize=(3.2 * len(pick), 3.6), squeeze=False)
    for ax, f in zip(axes[0], pick, strict=True):
        ax.imshow(mpimg.imread(f))
        ax.set_axis_off()
        step = int(f.stem.split("_")[1])
        ax.set_title(f"t = {step * period:.0f} s (step {step})", fontsize=9)
    fig.suptitle(caption, fontsize=9)
    fig.tight_layout()
    out_png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out_png, dpi=130)
    plt.close(fig)
    return caption


# ------------------------------------------------------------------ driver
def only_controllers(sw: sweep_spec.Sweep, wanted: set[str]) -> sweep_spec.Sweep | None:
    """The sweep with only the scenarios of the `wanted` controllers (EAIPP, NNEA, ...) on its scenario
    axis: one controller's rows without rerunning the others'; None when it runs none of them."""
    found: set[str] = set()
    axes = [a for a in sw.axes if SCENARIO_KEY in a.keys]
    for axis in axes:
        names = [controller({SCENARIO_KEY: str(c[SCENARIO_KEY])}) for c in axis.combos]
        found |= set(names)
        axis.combos = [c for c, n in zip(axis.combos, names, strict=True) if n in wanted]
    if not axes:
        found = {controller({}, sw.scenario)}
    return sw if found & wanted else None


def load_sweep(fig: Figure, studies: Path, sim: Path, reps: int | None, quick: bool,
               steps: int | None, controllers: set[str] | None = None) -> sweep_spec.Sweep | None:
    """The figure's sweep as this invocation runs it (None: it runs none of `controllers`)."""
    sw = narrow(sweep_spec.load(studies / fig.file, sweep_plan.seed_max(sim)), QUICK["eaipp"] if quick else None)
    if controllers:
        narrowed = only_controllers(sw, controllers)
        if narrowed is None:
            return None
        sw = narrowed
    if reps is not None:
        sw.seeds = list(range(1, reps + 1))
    if steps is not None:
        sw.steps = steps
    return sw


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="swarmtools.study.eaipp", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--figures", default=",".join(FIGURES),
                    help="which sweeps to run, comma-separated: " + ", ".join(
                        f"{f.name} (Fig {f.figs})" for f in FIGURES.values()))
    ap.add_argument("--quick", action="store_true",
                    help=f"a smoke run under a minute: {QUICK['eaipp'].seeds} seed a cell, runs cut at "
                         f"{QUICK['eaipp'].steps} steps, into out/study_eaipp_quick")
    ap.add_argument("--reps", type=int, default=None, help="seeds per cell (default the files' 100)")
    ap.add_argument("--controllers", default=None,
                    help="run only these controllers' rows, comma-separated (e.g. NNEA): the scenario axis "
                         "of each sweep narrowed to their scenario files")
    ap.add_argument("--steps", type=int, default=None,
                    help="cut every run at N steps (a smoke test; default the scenarios' 10,000)")
    ap.add_argument("--out", default=None, help="default out/study_eaipp (out/study_eaipp_quick with --quick)")
    ap.add_argument("--sim", default=str(REPO_ROOT / "build" / "swarmsim"))
    ap.add_argument("--jobs", type=int, default=0, help="runs at a time (default: the CPUs)")
    ap.add_argument("--studies", default=str(STUDIES), help="folder of the eaipp_*.yaml sweep files")
    p = ap.add_argument_group("the picture (runs no sweep)")
    p.add_argument("--picture", action="store_true", help="render frames of one run into --picture-out")
    p.add_argument("--picture-out", default=str(REPO_ROOT / "docs" / "figures" / "eaipp_square_frames.png"))
    p.add_argument("--picture-seed", default="auto", help="a seed, or auto: the first of 1..20 that merges")
    p.add_argument("--picture-px", type=int, default=420, help="each frame's width in pixels")
    p.add_argument("--picture-frames", type=int, default=4)
    p.add_argument("--picture-scenario", default=str(SCENARIOS / "eaipp_square.yaml"))
    sweep_cli.add_backend_options(ap)
    a = ap.parse_args(argv)
    command = " ".join(["python -m swarmtools.study.eaipp", *(argv if argv is not None else sys.argv[1:])])
    t0 = time.monotonic()
    try:
        sweep_cli.check_args(a)
        sim, out = Path(a.sim), quick_out(a.out, REPO_ROOT / "out" / "study_eaipp", a.quick)
        if not sim.is_file():
            raise SweepError(f"--sim {sim}: no such simulator (make build/swarmsim)")
        if a.picture:
            if a.picture_seed != "auto" and not a.picture_seed.isdigit():
                raise SweepError("--picture-seed: a seed or auto")
            caption = picture(sim, Path(a.picture_out), out / "picture", Path(a.picture_scenario),
                              a.picture_seed, a.picture_px, max(1, a.picture_frames))
            print(f"study_eaipp: wrote {a.picture_out}: {caption}")
            return 0
        figs = pick(a.figures, FIGURES)
        if a.reps is not None and a.reps < 1:
            raise SweepError("--reps must be at least 1")
        if a.steps is not None and a.steps < 1:
            raise SweepError("--steps must be at least 1")
        wanted = {c.strip().upper() for c in a.controllers.split(",") if c.strip()} if a.controllers else None
        loaded = {name: load_sweep(FIGURES[name], Path(a.studies), sim, a.reps, a.quick, a.steps, wanted)
                  for name in figs}
        sweeps = {name: sw for name, sw in loaded.items() if sw is not None}
        if wanted and not sweeps:
            raise SweepError(f"--controllers {a.controllers}: none of the sweeps ({', '.join(figs)}) runs "
                             f"{'it' if len(wanted) == 1 else 'them'} (the paper's controllers: "
                             f"{', '.join(CONTROLLERS)})")
        quick = QUICK["eaipp"] if a.quick else None
        announce("study_eaipp", "eaipp", sum(len(sweep_plan.expand(sw)) for sw in sweeps.values()), quick)
        rc_all = 0
        md = ["# Seed 003 (EAIPP path formation): the simulation study", "", *smoke_note(quick),
              f"Command: `{command}`.", ""]
        if a.steps is not None:
            md += [f"**Every run was cut at {a.steps} steps** (`--steps`): a smoke test, not the study; a run "
                   f"that did not merge is still recorded at the {BUDGET_S:.0f} s budget.", ""]
        results: dict[str, Any] = {"command": command, "steps_override": a.steps or (quick.steps if quick else None), "sweeps": {}, "cells": {},
                                   "runs": []}
        sections: list[str] = []
        for name, sw in sweeps.items():
            fig = FIGURES[name]
            sweep_dir = out / name
            t1 = time.monotonic()
            rc = run_sweep(sw, a, sim, sweep_dir, "study_eaipp")
            if rc == INTERRUPTED:
                return rc
            if rc is None:
                continue
            rc_all = rc_all or rc
            wall = time.monotonic() - t1
            rows = read_rows(sweep_dir / "results.csv")
            own = own_keys(sw)
            varied = condition_keys(sw, own)
            cs = cells(rows, fig, varied, sw.scenario)
            builds = sorted({r.get("code_version", "") for r in rows})
            ctrls = controller_order([c["controller"] for c in cs])
            settings = "; ".join(f"{c} " + ", ".join(f"{k}={v}" for k, v in own[c].items()) for c in ctrls if own.get(c))
            md.append(f"- {name} (Fig {fig.figs}): {len(rows)} runs ({', '.join(ctrls)}; {len(sw.seeds)} seeds a "
                      f"cell), {wall:.0f} s in this invocation, sweep `{sweep_dir}`, simulator build(s) "
                      f"{', '.join(builds)}" + (f"; each controller's own settings: {settings}" if settings else "")
                      + ".")
            results["sweeps"][name] = {"file": str(sw.path), "runs": len(rows), "seeds": len(sw.seeds),
                                       "controllers": ctrls, "wall_s": wall, "sweep_dir": str(sweep_dir),
                                       "code_versions": builds}
            results["cells"][name] = cs
            results["runs"] += [run_entry(fig, r, varied, sw.scenario) for r in rows]
            png = f"fig{fig.figs.replace('-', '_')}_{name}.png"
            plot(fig, rows, cs, out / png, sw.scenario)
            sections += render(fig, cs) + [f"![Figure {fig.figs}]({png})", ""]
            if name == "bias_scaled":
                sections += render_radii(fig.paper)
        wall_all = time.monotonic() - t0
        results["wall_time_s"] = wall_all
        md += ["", *sections, f"Wall time of this invocation: {wall_all:.0f} s (runs already done in a resumed "
               "sweep are not rerun and not counted)."]
        write_results(out, md, results, "study_eaipp")
        return 0 if rc_all == 0 else 1
    except SweepError as e:
        print(f"study_eaipp: {e}", file=sys.stderr)
        return e.exit_code


if __name__ == "__main__":
    sys.exit(main())
