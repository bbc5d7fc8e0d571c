#!/usr/bin/env python3
"""Reproduce the simulation study of seed 000 (DRTM task allocation).

Seed 000 compares its dynamical response threshold model (DRTM) with the
adaptive response threshold model (ARTM) in a swarm-foraging task: section 3.1
(the base condition, Figures 5-6, Table 2) and section 4 (four variations of
it, Figures 10-17, Table 4; Table 3 numbers them 5.1-5.4). This driver runs
the same study on our simulator (``build/swarmsim``), adds a third policy, the
fixed response threshold model (FRTM), and sets our numbers beside the paper's.

Study design
------------
* 5 conditions, one scenario file each in ``sim_host/scenarios/``:

  ========  ===================  ===========================================
  name      scenario file        paper
  ========  ===================  ===========================================
  base      foraging_base.yaml   3.1: N_f=20, E_a=10, N_r=20, L=4 m, d=1.5 m
  nf25      foraging_nf25.yaml   4.1 (Table 4 row 5.1): N_f = 25
  ea20      foraging_ea20.yaml   4.2 (row 5.2): E_a = 20 per OAE
  nr30      foraging_nr30.yaml   4.3 (row 5.3): N_r = 30 robots
  l3        foraging_l3.yaml     4.4 (row 5.4): L = 3 m, d = 1 m
  ========  ===================  ===========================================

* x 3 policies (``--set robots.0.policy=drtm|artm|frtm``: the foragers are the first group)
* x 50 repetitions, seeds 1..50 for every policy (``--reps``, ``--seed``)
* x 12,000 steps of 100 ms = 1200 s (the scenarios' ``duration``; ``--steps``).

One ``swarmsim`` process runs each (condition, policy) cell with ``--reps N
--threads T``; the simulator spreads the repetitions over its threads, and a
run's result depends on its seed only, never on the thread count. Every exit
status is checked; on failure the simulator's stderr is printed and the study
stops with a non-zero status.

Statistics
----------
Like the paper (sample size 50 per model, df = 98), DRTM is compared with
ARTM, and here also with FRTM, by Student's two-sample t-test with pooled
variance, two-tailed, alpha = 0.05, on the net food in the nest at the end,
F_t = F(T) (metric ``food_net``), and on the total number of obstacle-avoidance
events, M_T. The same seeds are used for every policy, but the runs diverge
after the first task-allocation decision, so, as in the paper, the samples
are treated as independent (a paired test is not used).

Sign convention (the paper's): t > 0 means DRTM is better, i.e. t is computed
as (DRTM - other) for F_t (more net food is better) and as (other - DRTM) for
M_T (fewer OAEs are better).

Metrics are the simulator's (seed 000's eqs 8-10): V_f, the average deviation
|F_d - F(t)| of the net food from the desired level; E_e = E_n / E_T, the
energy efficiency (a fraction in summary.json, printed here in percent, as
the paper does); ``food_collected``, the tokens delivered to the nest;
``food_net`` = F(T); ``oae_total``, the total OAEs (the paper's M_T);
``oae_per_robot`` = M_T / N_r (its M_v).

Outputs (in ``--out``, default ``out/study_drtm``)
--------------------------------------------------
``results.md``
    (1) per condition, a table of V_f, E_e (%), food collected, net food F(T),
    M_T and M_v: mean +- sd over the repetitions for DRTM, ARTM and FRTM, with
    the paper's DRTM and ARTM figures beside them (transcribed from the text
    of sections 3.1 and 4.1-4.4; the paper gives means only);
    (2) t-test tables, DRTM vs ARTM with the paper's t and p beside them
    (Tables 2 and 4), and DRTM vs FRTM;
    (3) the command line, the number of runs, the wall time and the machine.
``results.json``
    every run's metrics, and per (condition, policy) the mean and sd time
    series behind the figures, so that ``--from-json`` can re-render
    ``results.md`` and the figures without running anything.
``food_<condition>.png``
    net food in the nest F(t) (mean line, light band: the mean's 95 %
    confidence interval) per policy, and the desired level F_d dashed (paper
    Figures 5, 10, 12, 14, 16).
``oae_<condition>.png``
    cumulative OAEs (the same way) per policy (Figures 6, 11, 13, 15, 17).
``active_<condition>.png``
    number of active robots, searching + returning, per policy.
``runs/<condition>/<policy>/run_<seed>/``
    the simulator's own outputs (summary.json, timeseries.csv); each cell's
    folder is emptied before it is run.

Every output file is written under a temporary name and renamed when
complete; ``results.md`` is written last, so a failed study never leaves a
half-written one (a previous complete one is left as it was).

Command line
------------
::

    .venv/bin/python -m swarmtools.study.drtm                 # the full study
    .venv/bin/python -m swarmtools.study.drtm --quick         # smoke run
    .venv/bin/python -m swarmtools.study.drtm --conditions base,l3 --policies drtm,artm
    .venv/bin/python -m swarmtools.study.drtm --from-json out/study_drtm/results.json

``--reps N``         repetitions per (condition, policy), default 50
``--seed S``         first seed, default 1 (runs use S .. S+N-1)
``--steps N``        steps per run, default the scenario's (12,000)
``--threads T``      simulator threads, default os.cpu_count()
``--out DIR``        output folder, default out/study_drtm (out/study_drtm_quick
                     with --quick)
``--conditions L``   comma-separated subset of base,nf25,ea20,nr30,l3 (the
                     ``foraging_`` prefix is optional)
``--policies L``     comma-separated subset of drtm,artm,frtm
``--sim PATH``       simulator binary, default build/swarmsim
``--scenario-dir D`` default sim_host/scenarios
``--quick``          a smoke run under a minute (swarmtools.study.costs.QUICK:
                     2 repetitions x 1000 steps unless --reps/--steps are given);
                     results.md then says it is a smoke run
``--from-json PATH`` re-render results.md and the figures from a results.json
                     (into --out if given, else beside the json); runs nothing
``--no-figures``     skip the PNGs

Default paths are relative to the repository root (two folders above this
file); paths given on the command line are relative to the current folder.

Exit status: 0 done; 1 a simulator run failed, or its outputs are missing or
garbled; 2 bad arguments, or a missing simulator binary or scenario file;
130 interrupted.

Requirements: Python 3.11 with the pinned wheels of
``tools/requirements-study.txt`` (numpy, scipy, matplotlib). Tests:
tools/tests/study/test_drtm.py (part of ``make test``).
"""

from __future__ import annotations

import argparse
import csv
import datetime as _dt
import json
import math
import os
import platform
import re
import shlex
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from swarmtools.study.common import announce, json_safe
from swarmtools.study.costs import QUICK
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep import plan as sweep_plan
from swarmtools.sweep import spec as sweep_spec
from swarmtools.sweep.spec import Sweep, SweepError

REPO_ROOT = Path(__file__).resolve().parents[3]
FORMAT = "study_drtm/1"
SWEEP_FILE = REPO_ROOT / "studies" / "drtm.yaml"
SPEED_SWEEP_FILE = REPO_ROOT / "studies" / "drtm_speed.yaml"
SPEED_KEY = "foraging.robot_speed"
SPEED_ROWS: tuple[tuple[str, str, float, int], ...] = (
    ("V_f", "V_f", 1.0, 2), ("E_e", "E_e %", 100.0, 2), ("food_collected", "collected", 1.0, 1),
    ("food_net", "F(T)", 1.0, 2), ("oae_total", "M_T", 1.0, 0), ("tau_s", "tau (s)", 1.0, 1),
    ("active_mean", "robots foraging", 1.0, 2))
POLICY_KEY = "robots.0.policy"     # the foragers are the scenarios' first group
ALPHA = 0.05

THETA_KEY = "robots.0.params.drtm_theta"
# The study's arms: a policy, and for DRTM how theta0 and the bounds enter
# eq 6 (docs/studies/drtm.md: "offset" is our reading, "clip" the other one).
POLICIES: tuple[str, ...] = ("drtm", "drtm_clip", "artm", "frtm")
ARM_OF = {("drtm", "offset"): "drtm", ("drtm", "clip"): "drtm_clip", ("artm", "offset"): "artm",
          ("frtm", "offset"): "frtm"}
POLICY_LABEL = {"drtm": "DRTM", "drtm_clip": "DRTM-clip", "artm": "ARTM", "frtm": "FRTM"}
POLICY_COLOUR = {"drtm": "tab:blue", "drtm_clip": "tab:purple", "artm": "tab:red", "frtm": "tab:green"}
# FRTM dotted, drawn last: it can coincide with ARTM (same start threshold).
POLICY_STYLE = {"drtm": "-", "drtm_clip": "-.", "artm": "--", "frtm": ":"}

# name -> scenario file stem, label, where in the paper, row of Table 2 or 4
CONDITIONS: dict[str, dict[str, str]] = {
    "base": {
        "scenario": "foraging_base",
        "label": "N_f = 20, E_a = 10, N_r = 20, L = 4 m, d = 1.5 m",
        "paper": "section 3.1, Figures 5-6, Table 2",
        "table_row": "Table 2",
    },
    "nf25": {
        "scenario": "foraging_nf25",
        "label": "N_f = 25 food tokens (otherwise base)",
        "paper": "section 4.1, Figures 10-11, Table 4 row 5.1",
        "table_row": "Table 4, 5.1",
    },
    "ea20": {
        "scenario": "foraging_ea20",
        "label": "E_a = 20 energy units per OAE (otherwise base)",
        "paper": "section 4.2, Figures 12-13, Table 4 row 5.2",
        "table_row": "Table 4, 5.2",
    },
    "nr30": {
        "scenario": "foraging_nr30",
        "label": "N_r = 30 robots (otherwise base)",
        "paper": "section 4.3, Figures 14-15, Table 4 row 5.3",
        "table_row": "Table 4, 5.3",
    },
    "l3": {
        "scenario": "foraging_l3",
        "label": "L = 3 m arena, d = 1 m nest (otherwise base)",
        "paper": "section 4.4, Figures 16-17, Table 4 row 5.4",
        "table_row": "Table 4, 5.4",
    },
}

# Rows of the per-condition table: (key, label, scale from summary.json, decimals)
METRIC_ROWS: tuple[tuple[str, str, float, int], ...] = (
    ("V_f", "V_f, average deviation from F_d (tokens)", 1.0, 2),
    ("E_e", "E_e, energy efficiency (%)", 100.0, 2),
    ("food_collected", "food collected (tokens)", 1.0, 2),
    ("food_net", "net food F(T) (tokens)", 1.0, 2),
    ("oae_total", "M_T, total OAEs (oae_total)", 1.0, 2),
    ("oae_per_robot", "M_v = M_T / N_r, OAEs per robot (oae_per_robot)", 1.0, 2),
    ("tau_s", "tau, robot-seconds of foraging per delivered token (tau_s)", 1.0, 1),
    ("active_mean", "mean robots foraging, in S_S or S_R (active_mean)", 1.0, 2),
    ("oae_at_nest", "OAEs within 0.1 m of the nest or in it (oae_at_nest)", 1.0, 0),
    ("wait_radius_m", "mean distance of the waiting robots from the nest centre, m", 1.0, 2),
)
REQUIRED_METRICS: tuple[str, ...] = tuple(k for k, *_ in METRIC_ROWS)

# The paper's means, from the text of sections 3.1 and 4.1-4.4 (E_e in %).
PAPER_MEANS: dict[str, dict[str, dict[str, float]]] = {
    "base": {
        "drtm": {"V_f": 2.55, "E_e": 11.99, "food_collected": 173.76,
                 "food_net": 20.84, "oae_total": 925.96, "oae_per_robot": 46.30},
        "artm": {"V_f": 4.74, "E_e": 9.99, "food_collected": 183.46,
                 "food_net": 18.34, "oae_total": 1148.44, "oae_per_robot": 57.42},
    },
    "nf25": {
        "drtm": {"V_f": 2.90, "E_e": 13.31, "food_collected": 156.90,
                 "food_net": 20.88, "oae_total": 760.22, "oae_per_robot": 38.01},
        "artm": {"V_f": 2.92, "E_e": 11.06, "food_collected": 150.44,
                 "food_net": 16.63, "oae_total": 1053.20, "oae_per_robot": 52.66},
    },
    "ea20": {
        "drtm": {"V_f": 3.06, "E_e": 10.78, "food_collected": 189.14,
                 "food_net": 20.39, "oae_total": 912.06, "oae_per_robot": 45.60},
        "artm": {"V_f": 5.18, "E_e": 8.45, "food_collected": 189.32,
                 "food_net": 15.99, "oae_total": 1152.26, "oae_per_robot": 57.61},
    },
    "nr30": {
        "drtm": {"V_f": 3.17, "E_e": 8.72, "food_collected": 229.44,
                 "food_net": 19.99, "oae_total": 1203.32, "oae_per_robot": 40.11},
        "artm": {"V_f": 4.94, "E_e": 6.67, "food_collected": 236.40,
                 "food_net": 15.77, "oae_total": 1612.26, "oae_per_robot": 53.74},
    },
    "l3": {
        "drtm": {"V_f": 2.35, "E_e": 10.74, "food_collected": 165.32,
                 "food_net": 17.75, "oae_total": 1423.08, "oae_per_robot": 71.15},
        "artm": {"V_f": 4.61, "E_e": 8.91, "food_collected": 170.90,
                 "food_net": 15.22, "oae_total": 1882.32, "oae_per_robot": 94.12},
    },
}

# The paper's trip economics, solved from its printed means with its energy
# balance (section 2.3): F(T) = F(0) + collected - C T - (1 unit x robot-steps
# foraging + E_a M_T) / 1500, with F(0) = 5, C = 2 tokens/min, T = 20 min.
PAPER_F0, PAPER_C_PER_MIN, PAPER_MINUTES, PAPER_TOKEN_UNITS = 5.0, 2.0, 20.0, 1500.0
PAPER_E_A = {"base": 10.0, "nf25": 10.0, "ea20": 20.0, "nr30": 10.0, "l3": 10.0}
PAPER_STEP_S = 0.1


def paper_trip_economics(means: dict[str, float], e_a: float) -> dict[str, float]:
    """tau_s and active_mean that the paper's F(T), collected and M_T imply."""
    collected = means["food_collected"]
    energy = PAPER_TOKEN_UNITS * (PAPER_F0 + collected - PAPER_C_PER_MIN * PAPER_MINUTES
                                  - means["food_net"])
    robot_steps = energy - e_a * means["oae_total"]
    steps = PAPER_MINUTES * 60.0 / PAPER_STEP_S
    return {"tau_s": robot_steps * PAPER_STEP_S / collected, "active_mean": robot_steps / steps}


for _cond, _arms in PAPER_MEANS.items():
    for _means in _arms.values():
        _means.update(paper_trip_economics(_means, PAPER_E_A[_cond]))

# The t-tests compared: (metric key, name in the paper, +1 if larger is better)
TESTS: tuple[tuple[str, str, int], ...] = (
    ("food_net", "F_t", +1),
    ("oae_total", "M_T", -1),
)

# Tables 2 and 4, DRTM vs ARTM: (t, two-tailed p, p as printed); all
# "YES" (significant) in the paper.
PAPER_TTESTS: dict[str, dict[str, tuple[float, float, str]]] = {
    "base": {"food_net": (3.1918, 0.0019, "0.0019"),
             "oae_total": (2.2899, 0.0242, "0.0242")},
    "nf25": {"food_net": (4.9663, 2.89e-6, "2.89e-06"),
             "oae_total": (2.7761, 6.59e-3, "6.59e-03")},
    "ea20": {"food_net": (3.2744, 1.46e-3, "1.46e-03"),
             "oae_total": (2.3803, 0.0192, "0.0192")},
    "nr30": {"food_net": (4.7869, 6.00e-6, "6.00e-06"),
             "oae_total": (3.9267, 1.60e-4, "1.60e-04")},
    "l3": {"food_net": (2.1899, 0.0310, "0.0310"),
           "oae_total": (2.6984, 8.21e-3, "8.21e-03")},
}
PAPER_REPS = 50
PAPER_STEPS = 12000

# Time series columns the figures need (read by name: the header says the rest).
SERIES_KEYS: tuple[str, ...] = ("food_nest", "oae_total", "active")


class StudyError(Exception):
    """A failure the study reports in one clear message (exit status 1)."""

    exit_code = 1


class SetupError(StudyError):
    """Bad arguments or a missing binary or scenario (exit status 2)."""

    exit_code = 2


class Interrupted(StudyError):
    """SIGINT or SIGTERM during the runs: finished runs are kept (exit 130)."""

    exit_code = 130


class Submitted(StudyError):
    """--backend slurm --no-wait: the jobs are queued, nothing to render yet."""

    exit_code = 0


# --------------------------------------------------------------- statistics


def pooled_t_test(a: Sequence[float], b: Sequence[float]) -> dict[str, float]:
    """Student's two-sample t-test with pooled variance, two-tailed.

    t = (mean(a) - mean(b)) / sqrt(s_p^2 (1/n_a + 1/n_b)), with
    s_p^2 = ((n_a - 1) s_a^2 + (n_b - 1) s_b^2) / (n_a + n_b - 2) and
    df = n_a + n_b - 2; p = 2 P(T_df > |t|). NaN values are dropped. Returns
    t, p, df and the two means; t and p are NaN when df < 1 or when both
    samples are constant and equal, t is +-inf and p 0 when both are constant
    and differ. Equals scipy.stats.ttest_ind(a, b, equal_var=True).
    """
    from scipy import stats

    x = np.asarray(a, dtype=float)
    y = np.asarray(b, dtype=float)
    x = x[~np.isnan(x)]
    y = y[~np.isnan(y)]
    na, nb = x.size, y.size
    df = na + nb - 2
    out = {"t": math.nan, "p": math.nan, "df": float(df),
           "n_a": float(na), "n_b": float(nb),
           "mean_a": float(x.mean()) if na else math.nan,
           "mean_b": float(y.mean()) if nb else math.nan}
    if na < 1 or nb < 1 or df < 1:
        return out
    ss = float(((x - x.mean()) ** 2).sum() + ((y - y.mean()) ** 2).sum())
    sp2 = ss / df
    se = math.sqrt(sp2 * (1.0 / na + 1.0 / nb))
    diff = out["mean_a"] - out["mean_b"]
    if se == 0.0:
        if diff != 0.0:
            out["t"] = math.copysign(math.inf, diff)
            out["p"] = 0.0
        return out
    t = diff / se
    out["t"] = t
    out["p"] = float(2.0 * stats.t.sf(abs(t), df))
    return out


def compare_policies(drtm: Sequence[float], other: Sequence[float],
                     better: int) -> dict[str, float]:
    """The t-test in the paper's sign convention: t > 0 when DRTM is better.

    ``better`` is +1 when a larger value is better (net food), -1 when a
    smaller one is (OAEs): t = t(DRTM - other) or t(other - DRTM).
    """
    res = pooled_t_test(drtm, other) if better > 0 else pooled_t_test(other, drtm)
    res["significant"] = bool(res["p"] < ALPHA) if not math.isnan(res["p"]) else False
    return res


def mean_sd(values: Sequence[float]) -> tuple[float, float, int]:
    """Mean, sample sd (ddof = 1) and count of the non-NaN values."""
    v = np.asarray(values, dtype=float)
    v = v[~np.isnan(v)]
    n = int(v.size)
    if n == 0:
        return math.nan, math.nan, 0
    sd = float(v.std(ddof=1)) if n > 1 else math.nan
    return float(v.mean()), sd, n


# ------------------------------------------------------------------ readers


def _number(value: Any, what: str, path: Path) -> float:
    if value is None:
        return math.nan
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise StudyError(f"{path}: {what} is not a number: {value!r}")
    return float(value)


def read_summary(path: Path, expect_seed: int | None = None) -> dict[str, Any]:
    """Read one run's summary.json; check its shape and the metrics we use.

    Returns {"seed", "steps", "robots", "state_hash", "metrics": {...}} with
    "robots" the foragers (N_r: the robots of the groups running the forager,
    not the nest beacon), and
    every metric as a float (JSON null becomes NaN). Raises StudyError naming
    the file when it is missing, not JSON, or lacks a field.
    """
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise StudyError(f"{path}: missing (the simulator did not write this run's summary)") from None
    except OSError as e:
        raise StudyError(f"{path}: cannot read: {e.strerror}") from None
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise StudyError(f"{path}: garbled JSON: {e}") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("metrics"), dict):
        raise StudyError(f"{path}: garbled summary: no \"metrics\" object")
    control = doc.get("control")
    if isinstance(control, dict) and control.get("touched") is not False:
        # A run steered by hand (swarmsim --control moved a robot) is not
        # the scenario's: never pooled with the others.
        raise StudyError(f"{path}: this run was touched by hand (swarmsim --control: "
                         f"{control.get('commands', '?')} commands, a robot moved): not part of a study")
    metrics_in = doc["metrics"]
    missing = [k for k in REQUIRED_METRICS if k not in metrics_in]
    if missing:
        raise StudyError(f"{path}: garbled summary: metrics lack {', '.join(missing)}")
    metrics = {k: _number(metrics_in[k], f"metrics.{k}", path) for k in REQUIRED_METRICS}
    for k, v in metrics_in.items():     # the others, as far as they are numbers
        if k not in metrics and (v is None or (isinstance(v, (int, float)) and not isinstance(v, bool))):
            metrics[k] = math.nan if v is None else float(v)
    for key in ("seed", "steps"):
        if not isinstance(doc.get(key), int) or isinstance(doc.get(key), bool):
            raise StudyError(f"{path}: garbled summary: \"{key}\" is not an integer")
    if expect_seed is not None and doc["seed"] != expect_seed:
        raise StudyError(f"{path}: seed {doc['seed']}, expected {expect_seed}")
    groups = doc.get("groups")
    robots = None
    if isinstance(groups, list):
        robots = sum(g.get("count", 0) for g in groups
                     if isinstance(g, dict) and g.get("controller") == "forager")
    return {
        "seed": doc["seed"],
        "steps": doc["steps"],
        "robots": robots if isinstance(robots, int) else None,
        "state_hash": str(doc.get("state_hash", "")),
        "metrics": metrics,
    }


def read_timeseries(path: Path, columns: Iterable[str] = SERIES_KEYS) -> dict[str, np.ndarray]:
    """Read one run's timeseries.csv; return step, time_s and ``columns``.

    Checks the header has the columns needed, every row has as many fields as
    the header, the values are numbers and the steps increase. Raises
    StudyError naming the file and line otherwise.
    """
    want = ["step", "time_s", *columns]
    try:
        fh = path.open(newline="", encoding="utf-8")
    except FileNotFoundError:
        raise StudyError(f"{path}: missing (the simulator did not write this run's time series)") from None
    with fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        if not header:
            raise StudyError(f"{path}: empty time series")
        header = [h.strip() for h in header]
        missing = [c for c in want if c not in header]
        if missing:
            raise StudyError(f"{path}: garbled time series: header lacks {', '.join(missing)}")
        idx = [header.index(c) for c in want]
        rows: list[list[float]] = []
        for lineno, row in enumerate(reader, start=2):
            if not row:
                continue
            if len(row) != len(header):
                raise StudyError(f"{path}:{lineno}: garbled time series: "
                                 f"{len(row)} fields, header has {len(header)}")
            try:
                rows.append([float(row[i]) for i in idx])
            except ValueError:
                raise StudyError(f"{path}:{lineno}: garbled time series: not a number") from None
    if not rows:
        raise StudyError(f"{path}: time series has no rows")
    data = np.asarray(rows, dtype=float)
    d = np.diff(data[:, 0])
    if np.any(d < 0) or np.any((d == 0) & np.any(data[1:] != data[:-1], axis=1)):
        raise StudyError(f"{path}: garbled time series: steps do not increase")
    if np.any(d == 0):      # an identical row repeated (e.g. the final row): keep one
        data = data[np.concatenate(([True], d != 0))]
    return {c: data[:, j] for j, c in enumerate(want)}


def aggregate_series(series: Sequence[dict[str, np.ndarray]],
                     columns: Iterable[str] = SERIES_KEYS) -> dict[str, Any]:
    """Mean and sd (ddof = 1; 0 for a single run) over runs, step by step.

    Runs are aligned on the steps they all have (normally every one).
    """
    if not series:
        return {"step": [], "time_s": [], "n": 0}
    common = series[0]["step"]
    for s in series[1:]:
        common = np.intersect1d(common, s["step"])
    out: dict[str, Any] = {"n": len(series), "step": common}
    rows = [np.searchsorted(s["step"], common) for s in series]
    out["time_s"] = series[0]["time_s"][rows[0]]
    for c in columns:
        m = np.vstack([s[c][r] for s, r in zip(series, rows, strict=True)])
        out[c] = {"mean": m.mean(axis=0),
                  "sd": m.std(axis=0, ddof=1) if len(series) > 1 else np.zeros(m.shape[1])}
    return out


def read_runs(run_dirs: Sequence[tuple[Path, int]],
              expect_steps: int | None = None) -> tuple[list[dict[str, Any]], dict[str, Any]]:
    """Read the run folders given as (run_<seed>/ folder, seed).

    Returns the per-run summaries (see read_summary) and the aggregated time
    series (see aggregate_series).
    """
    runs = []
    series = []
    for run_dir, seed in run_dirs:
        s = read_summary(run_dir / "summary.json", expect_seed=seed)
        if expect_steps is not None and s["steps"] != expect_steps:
            raise StudyError(f"{run_dir / 'summary.json'}: {s['steps']} steps, expected {expect_steps}")
        runs.append(s)
        series.append(read_timeseries(run_dir / "timeseries.csv"))
    steps = {r["steps"] for r in runs}
    if len(steps) > 1:
        raise StudyError(f"{run_dirs[0][0].parent}: runs differ in length: {sorted(steps)} steps")
    return runs, aggregate_series(series)


def read_desired_food(scenario: Path) -> float | None:
    """F_d (foraging.desired_food) from a scenario file, None if not found.

    A light reading (no YAML library): the first `desired_food: <number>`.
    """
    try:
        text = scenario.read_text(encoding="utf-8")
    except OSError:
        return None
    m = re.search(r"^[^#\n]*\bdesired_food\s*:\s*([-+0-9.eE]+)", text, re.MULTILINE)
    if not m:
        return None
    try:
        return float(m.group(1))
    except ValueError:
        return None


# --------------------------------------------------------------- rendering


def _fmt(x: float, decimals: int = 2) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    return f"{x:.{decimals}f}"


def fmt_mean_sd(values: Sequence[float], scale: float = 1.0, decimals: int = 2) -> str:
    m, sd, n = mean_sd([v * scale for v in values])
    if n == 0:
        return "—"
    if math.isnan(sd):
        return _fmt(m, decimals)
    return f"{m:.{decimals}f} ± {sd:.{decimals}f}"


def fmt_t(t: float) -> str:
    if t is None or math.isnan(t):
        return "—"
    if math.isinf(t):
        return "+inf" if t > 0 else "-inf"
    return f"{t:.4f}"


def fmt_p(p: float) -> str:
    if p is None or math.isnan(p):
        return "—"
    if p == 0.0:
        return "0"
    if p < 1e-3:
        return f"{p:.2e}"
    return f"{p:.4f}"


def _metric_values(results: dict[str, Any], cond: str, policy: str, key: str) -> list[float]:
    runs = results["conditions"][cond]["policies"][policy]["runs"]
    return [float("nan") if r["metrics"].get(key) is None else float(r["metrics"][key])
            for r in runs]


def _policies_run(results: dict[str, Any], cond: str) -> list[str]:
    have = results["conditions"][cond]["policies"]
    return [p for p in POLICIES if p in have]


def render_condition_table(results: dict[str, Any], cond: str) -> list[str]:
    """The Table-2-like metrics table of one condition (markdown lines)."""
    info = CONDITIONS[cond]
    c = results["conditions"][cond]
    pols = _policies_run(results, cond)
    ns = {p: len(c["policies"][p]["runs"]) for p in pols}
    lines = [f"### {cond}: {info['label']}", "",
             f"Paper: {info['paper']}. Scenario `{c.get('scenario_file', info['scenario'] + '.yaml')}`"
             + (f", F_d = {c['desired_food']:g}" if c.get("desired_food") is not None else "")
             + (f", N_r = {c['robots']}" if c.get("robots") else "")
             + "; runs per policy: " + ", ".join(f"{POLICY_LABEL[p]} {ns[p]}" for p in pols) + ".",
             ""]
    paper = PAPER_MEANS.get(cond, {})
    head = ["metric"] + [f"{POLICY_LABEL[p]} (ours)" for p in pols]
    head += [f"{POLICY_LABEL[p]} (paper)" for p in ("drtm", "artm")]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "---|" + "---:|" * (len(head) - 1))
    for key, label, scale, dec in METRIC_ROWS:
        cells = [label]
        cells += [fmt_mean_sd(_metric_values(results, cond, p, key), scale, dec) for p in pols]
        cells += [_fmt(paper.get(p, {}).get(key, math.nan), dec) for p in ("drtm", "artm")]
        lines.append("| " + " | ".join(cells) + " |")
        if key == "V_f":   # the paper computes V_f from its Figure 5 curve: both, labelled
            cells = ["V_f of the mean curve, mean over t of abs(F_d - mean F(t)) (tokens)"]
            cells += [_fmt(vf_of_mean_curve(c, p), 2) for p in pols]
            cells += ["—", "—"]
            lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def vf_of_mean_curve(cond_results: dict[str, Any], policy: str) -> float:
    """V_f computed as the paper does from a figure: the time mean of
    abs(F_d - F(t)) of the mean curve F(t) over the runs (the per-run V_f's
    mean is larger: runs above and below F_d cancel in the mean curve)."""
    fd = cond_results.get("desired_food")
    ser = (cond_results["policies"][policy].get("series") or {}).get("food_nest")
    if fd is None or not ser:
        return math.nan
    m = np.asarray(ser["mean"], dtype=float)
    return float(np.mean(np.abs(fd - m))) if m.size else math.nan


def compute_ttests(results: dict[str, Any], other: str, drtm: str = "drtm") -> list[dict[str, Any]]:
    """``drtm`` (an arm of DRTM) vs ``other`` on F_t and M_T for every
    condition that ran both."""
    rows = []
    for cond in results["conditions"]:
        pols = _policies_run(results, cond)
        if drtm not in pols or other not in pols:
            continue
        for key, name, better in TESTS:
            res = compare_policies(_metric_values(results, cond, drtm, key),
                                   _metric_values(results, cond, other, key), better)
            res.update({"condition": cond, "metric": key, "name": name, "other": other})
            if other == "artm":
                paper = PAPER_TTESTS.get(cond, {}).get(key)
                if paper:
                    res["paper_t"], res["paper_p"], res["paper_p_text"] = paper
            rows.append(res)
    return rows


def render_ttest_table(rows: list[dict[str, Any]], with_paper: bool) -> list[str]:
    if not rows:
        return ["(not run: needs DRTM and the other policy in the same condition)", ""]
    head = ["condition"] + (["paper"] if with_paper else [])
    head += ["compare", "t", "two-tailed p", "df", "significant (p < 0.05)"]
    if with_paper:
        head += ["paper t", "paper p", "paper significant", "same verdict as paper"]
    n_text = 3 if with_paper else 2          # condition, [paper,] compare
    lines = ["| " + " | ".join(head) + " |",
             "|" + "---|" * n_text + "---:|" * 3 + "---|" * (len(head) - n_text - 3)]
    for r in rows:
        cells = [r["condition"]] + ([CONDITIONS[r["condition"]]["table_row"]] if with_paper else [])
        cells += [r["name"], fmt_t(r["t"]), fmt_p(r["p"]),
                  f"{r['df']:.0f}" if r["df"] >= 1 else "—",
                  "YES" if r["significant"] else "NO"]
        if with_paper:
            pt = r.get("paper_t")
            if pt is None:
                cells += ["—", "—", "—", "—"]
            else:
                # The paper's verdict is "DRTM significantly better" (t > 0, p < 0.05).
                ours = r["significant"] and r["t"] > 0
                cells += [f"{pt:.4f}", r["paper_p_text"], "YES", "yes" if ours else "no"]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def render_markdown(results: dict[str, Any], figures: dict[str, list[str]] | None = None,
                    rerender_command: str | None = None) -> str:
    """The whole results.md as a string."""
    s = results["settings"]
    conds = list(results["conditions"])
    n_runs = sum(len(p["runs"]) for c in results["conditions"].values()
                 for p in c["policies"].values())
    steps = sorted({r["steps"] for c in results["conditions"].values()
                    for p in c["policies"].values() for r in p["runs"]})
    reps = sorted({len(p["runs"]) for c in results["conditions"].values()
                   for p in c["policies"].values()})
    out = ["# Seed 000 simulation study: DRTM vs ARTM vs FRTM", ""]
    out.append(f"Generated {results['generated_utc']} by `swarmtools.study.drtm` "
               f"(format {results['format']}).")
    if rerender_command:
        out.append(f"Re-rendered from results.json by `{rerender_command}`.")
    out.append("")
    if s.get("quick") or steps != [PAPER_STEPS] or reps != [PAPER_REPS]:
        out += [f"> **Not the paper's design**: {', '.join(map(str, reps))} repetitions x "
                f"{', '.join(map(str, steps))} steps per (condition, policy)"
                + (" (a --quick smoke run)" if s.get("quick") else "")
                + f"; the paper used {PAPER_REPS} x {PAPER_STEPS:,}. "
                "Do not compare these numbers with the paper's.", ""]

    out += ["## Run", "",
            f"- command: `{results['command']}` (in `{results['cwd']}`)",
            f"- runs: {n_runs} = {len(conds)} condition(s) x policies "
            f"{{{', '.join(POLICY_LABEL[p] for p in s['policies'])}}} x {s['reps']} repetitions "
            f"(seeds {s['first_seed']}..{s['first_seed'] + s['reps'] - 1} for every policy), "
            f"{', '.join(f'{x:,}' for x in steps)} steps of {s.get('control_period_ms', 100)} ms each",
            f"- wall time: {results['wall_time_s']:.1f} s ({_hms(results['wall_time_s'])}) "
            f"for the runs and reading their outputs, simulator threads: {s['threads']}",
            f"- machine: {results['machine']['cores']} cores, {results['machine']['cpu']}, "
            f"{results['machine']['platform']}, Python {results['machine']['python']}",
            f"- source: {results.get('source', 'unknown')}; simulator `{s['sim']}`",
            ""]

    out += ["## Metrics per condition", "",
            "Mean ± sd over the repetitions (sample sd). The paper gives means only, "
            "transcribed from the text of its sections 3.1 and 4.1-4.4. "
            "V_f: mean |F_d - F(t)| over the run (eq 8); E_e = E_n / E_T (eq 9), in percent; "
            "food collected: tokens delivered to the nest; net food F(T): tokens in the nest "
            "at the end (collected minus consumed); M_T: total obstacle-avoidance events "
            "(the summary's oae_total); M_v = M_T / N_r (eq 10, oae_per_robot). "
            "tau: robot-seconds spent foraging (S_S or S_R) per token delivered, and the mean "
            "number of robots foraging; the paper's are solved from its printed F(T), "
            "collected and M_T with its energy balance (F(0) = 5, 2 tokens/min, 20 min, "
            "1 unit per foraging robot per step, E_a per OAE, 1500 units per token). "
            "OAEs at the nest and the waiting robots' distance from its centre show where "
            "the nest's traffic is (not in the paper).", ""]
    for cond in conds:
        out += render_condition_table(results, cond)

    out += ["## t-tests", "",
            "Student's two-sample t-test with pooled variance (equal variances), two-tailed, "
            "alpha = 0.05, df = n_DRTM + n_other - 2 (98 for 50 + 50), on the net food at the "
            "end F_t = F(T) and on the total number of OAEs M_T, as in the paper's Tables 2 "
            "and 4 (Table 4's rows 5.1-5.4 are the conditions of sections 4.1-4.4).", "",
            "**Sign convention (the paper's): t > 0 means DRTM is better**, i.e. "
            "t = t(DRTM - other) for F_t (more net food is better) and "
            "t = t(other - DRTM) for M_T (fewer OAEs are better). "
            "The paper reports DRTM significantly better in every row (t > 0, p < 0.05); "
            "\"same verdict\" says whether our run agrees.", ""]
    out += ["### DRTM vs ARTM (paper's Tables 2 and 4)", ""]
    out += render_ttest_table(compute_ttests(results, "artm"), with_paper=True)
    out += ["### DRTM-clip vs ARTM (DRTM with eq 6 clipped to [1, 10], the other reading)", ""]
    out += render_ttest_table(compute_ttests(results, "artm", "drtm_clip"), with_paper=True)
    out += ["### DRTM vs FRTM (not in the paper)", ""]
    out += render_ttest_table(compute_ttests(results, "frtm"), with_paper=False)

    out += render_speed_table(results)

    if figures:
        out += ["## Figures", "",
                "Mean over the repetitions (a line per arm) over a light band, the mean's 95 % "
                "confidence interval; the dashed line in the food figures is the desired level F_d.",
                ""]
        for cond in conds:
            files = figures.get(cond, [])
            if files:
                out.append(f"- {cond}: " + ", ".join(f"[{f}]({f})" for f in files))
        out.append("")
    return "\n".join(out)


def _hms(seconds: float) -> str:
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def _umask_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def _atomic_write_text(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, _umask_mode())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def render_figures(results: dict[str, Any], out_dir: Path) -> dict[str, list[str]]:
    """food_/oae_/active_<condition>.png (Agg, 150 dpi); returns the names per condition."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from scipy import stats

    specs = (
        ("food", "food_nest", "net food in the nest F(t) (tokens)", "Net food in the nest F(t)"),
        ("oae", "oae_total", "cumulative OAEs (events)", "Cumulative obstacle-avoidance events"),
        ("active", "active", "active robots (searching + returning)", "Active robots"),
    )
    made: dict[str, list[str]] = {}
    for cond, c in results["conditions"].items():
        pols = _policies_run(results, cond)
        made[cond] = []
        for prefix, key, ylabel, title in specs:
            fig, ax = plt.subplots(figsize=(7.0, 4.6))
            reps = set()
            for p in pols:
                ser = c["policies"][p].get("series") or {}
                if not ser.get("time_s") or key not in ser:
                    continue
                t = np.asarray(ser["time_s"], dtype=float)
                m = np.asarray(ser[key]["mean"], dtype=float)
                sd = np.asarray(ser[key]["sd"], dtype=float)
                n = int(ser.get("n", len(c["policies"][p]["runs"])))
                reps.add(n)
                # A light band of the mean's 95 % confidence interval under a
                # strong mean line: three policies stay apart where bands
                # overlap (an sd band hid them).
                half = sd / np.sqrt(n) * float(stats.t.ppf(0.975, n - 1)) if n > 1 else np.zeros_like(sd)
                lo = m - half if key != "active" else np.maximum(m - half, 0.0)   # counts: not below 0
                ax.fill_between(t, lo, m + half, color=POLICY_COLOUR[p], alpha=0.12, lw=0)
                ax.plot(t, m, color=POLICY_COLOUR[p], ls=POLICY_STYLE[p],
                        lw=2.0 if p == "frtm" else 1.6, label=POLICY_LABEL[p])
            if prefix == "food" and c.get("desired_food") is not None:
                fd = c["desired_food"]
                ax.axhline(fd, color="black", ls="--", lw=1.0, label=f"F_d = {fd:g}")
                lo, hi = ax.get_ylim()          # room above F_d for the legend
                ax.set_ylim(lo, max(hi, fd + 0.25 * (max(hi, fd) - lo)))
            n_txt = "/".join(str(n) for n in sorted(reps)) or "0"
            ax.set_title(f"{title}\n{cond}: {CONDITIONS[cond]['label']}\n"
                         f"mean and 95 % CI of the mean, {n_txt} reps per policy", fontsize=10)
            ax.set_xlabel("time (s)")
            ax.set_ylabel(ylabel)
            ax.grid(True, alpha=0.3)
            ax.legend(loc="best", fontsize=9)
            fig.tight_layout()
            name = f"{prefix}_{cond}.png"
            fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=out_dir)
            os.close(fd)
            try:
                fig.savefig(tmp, dpi=150, format="png")
                os.chmod(tmp, _umask_mode())
                os.replace(tmp, out_dir / name)
            finally:
                plt.close(fig)
                if os.path.exists(tmp):
                    os.unlink(tmp)
            made[cond].append(name)
    return made


# ------------------------------------------------------------------ running


def machine_info() -> dict[str, Any]:
    cpu = platform.processor() or "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.lower().startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cores": os.cpu_count(), "cpu": cpu, "platform": platform.platform(),
            "python": platform.python_version()}


def source_info() -> str:
    try:
        head = subprocess.run(["git", "-C", str(REPO_ROOT), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, timeout=10)
        if head.returncode != 0:
            return "not a git checkout"
        dirty = subprocess.run(["git", "-C", str(REPO_ROOT), "status", "--porcelain",
                                "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10)
        return f"git {head.stdout.strip()}" + (" with local changes" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown (git not available)"


def _series_to_json(agg: dict[str, Any]) -> dict[str, Any]:
    def r(a: np.ndarray) -> list[float]:
        return [float(f"{x:.6g}") for x in np.asarray(a, dtype=float)]
    out: dict[str, Any] = {"n": agg["n"], "step": [int(x) for x in agg["step"]],
                           "time_s": r(agg["time_s"])}
    for k in SERIES_KEYS:
        if k in agg:
            out[k] = {"mean": r(agg[k]["mean"]), "sd": r(agg[k]["sd"])}
    return out


def parse_list(text: str | None, allowed: Sequence[str], what: str,
               strip_prefix: str = "") -> list[str]:
    if text is None:
        return list(allowed)
    items = []
    for raw in text.split(","):
        name = raw.strip().lower()
        if strip_prefix and name.startswith(strip_prefix):
            name = name[len(strip_prefix):]
        if name.endswith(".yaml"):
            name = name[:-5]
            if strip_prefix and name.startswith(strip_prefix):
                name = name[len(strip_prefix):]
        if not name:
            continue
        if name not in allowed:
            raise SetupError(f"unknown {what} '{raw.strip()}' (choose from {', '.join(allowed)})")
        if name not in items:
            items.append(name)
    if not items:
        raise SetupError(f"no {what} given")
    # keep the canonical order, whatever order they were given in
    return [a for a in allowed if a in items]


def study_sweep(args: argparse.Namespace, sim: Path) -> Sweep:
    """studies/drtm.yaml, narrowed to the conditions, policies, seeds and steps asked for."""
    try:
        sw = sweep_spec.load(args.sweep_file, sweep_plan.seed_max(sim))
    except SweepError as e:
        raise SetupError(str(e)) from None
    conds, pols = sw.axes[0], sw.axes[1]
    if conds.keys != [sweep_spec.SCENARIO_KEY] or pols.keys != [POLICY_KEY, THETA_KEY]:
        raise SetupError(f"{sw.path}: expected a list of scenarios, then a list of {POLICY_KEY} "
                         f"and {THETA_KEY}")
    scen_dir = Path(args.scenario_dir) if args.scenario_dir else None
    combos = []
    for cond in args.conditions:
        name = f"{CONDITIONS[cond]['scenario']}.yaml"
        given = [c for c in conds.combos if Path(str(c[sweep_spec.SCENARIO_KEY])).name == name]
        if not given:
            raise SetupError(f"{sw.path}: condition {cond} ({name}) is not among its scenarios")
        value = str(scen_dir.resolve() / name) if scen_dir else str(given[0][sweep_spec.SCENARIO_KEY])
        if not sweep_spec.resolve_scenario(sw.path, value).is_file():
            raise SetupError(f"scenario file {sweep_spec.resolve_scenario(sw.path, value)} not found")
        combos.append({sweep_spec.SCENARIO_KEY: value})
    conds.combos = combos
    arms = {ARM_OF.get((c[POLICY_KEY], c[THETA_KEY])): c for c in pols.combos}
    missing = [a for a in args.policies if a not in arms]
    if missing:
        raise SetupError(f"{sw.path}: no arm for {', '.join(missing)}")
    pols.combos = [arms[a] for a in args.policies]
    sw.seeds = list(range(args.seed, args.seed + args.reps))
    sw.steps = args.steps
    sw.name = "study_drtm_quick" if args.quick else "study_drtm"
    return sw


def arm_of(row: dict[str, str]) -> str:
    """The study arm of a table row (its policy and DRTM threshold mode)."""
    return ARM_OF.get((row[POLICY_KEY], row.get(THETA_KEY, "offset")), row[POLICY_KEY])


def condition_of(scenario: str) -> str:
    stem = Path(scenario).stem
    for cond, c in CONDITIONS.items():
        if c["scenario"] == stem:
            return cond
    raise StudyError(f"run of an unknown scenario {scenario}")


def run_study(args: argparse.Namespace, command: str) -> dict[str, Any]:
    """Runs the study's sweep (resuming one begun), then reads its table."""
    sim = Path(args.sim)
    if not sim.is_file():
        raise SetupError(f"simulator binary {sim} not found: run `make` first")
    if not os.access(sim, os.X_OK):
        raise SetupError(f"simulator binary {sim} is not executable: run `make` first")
    sw = study_sweep(args, sim)
    out_dir = Path(args.out)
    sweep_dir = out_dir / "sweep"
    nc, npol = len(args.conditions), len(args.policies)
    speed = speed_sweep(args, sim) if not args.no_speed and "base" in args.conditions else None
    announce("study_drtm", "drtm", len(sweep_plan.expand(sw)) + (len(sweep_plan.expand(speed)) if speed else 0),
             QUICK["drtm"] if args.quick else None)
    print(f"study_drtm: {nc} condition{'s' if nc != 1 else ''} x {npol} "
          f"polic{'ies' if npol != 1 else 'y'} x {args.reps} reps"
          f" x {args.steps if args.steps is not None else 'scenario'} steps as sweep "
          f"{sweep_dir} ({args.backend}, {args.threads} at a time)", flush=True)
    t_start = time.monotonic()
    run_args = argparse.Namespace(**{**vars(args), "out": str(sweep_dir), "jobs": args.threads,
                                     "quiet": False})
    try:
        rc = sweep_cli.run_sweep(sw, run_args, sim)
    except SweepError as e:
        raise SetupError(str(e)) from None
    if rc in (130, 143):
        raise Interrupted(f"sweep {sweep_dir} interrupted; finished runs are kept: "
                          "rerun the same command to resume")
    table = sweep_dir / "results.csv"
    rows = read_table(table) if table.exists() or not args.no_wait else []
    if args.backend == "slurm" and args.no_wait and len(rows) < len(sw.seeds) * nc * npol:
        raise Submitted("jobs submitted; rerun the same command when they are done to render "
                        "the tables and figures")
    failed = [r for r in rows if r["status"] != "ok"]
    if rc != 0 or failed or len(rows) != len(sw.seeds) * nc * npol:
        lines = [f"{len(failed)} of {len(rows)} runs failed ({table}):"]
        lines += [f"  {r['scenario']} {arm_of(r)} seed {r['seed']}: {r['error']}" for r in failed[:5]]
        raise StudyError("\n".join(lines) if failed else f"sweep ended with status {rc}; see {table}")
    results = results_from_table(rows, sweep_dir, args, command, time.monotonic() - t_start)
    if speed is not None:
        results["speed"] = run_speed(args, sim, speed, out_dir / "sweep_speed")
    results["wall_time_s"] = time.monotonic() - t_start
    return results


def speed_sweep(args: argparse.Namespace, sim: Path) -> Sweep:
    """studies/drtm_speed.yaml (the base condition at 0.06, 0.07 and 0.10 m/s),
    narrowed like the main sweep."""
    try:
        sw = sweep_spec.load(SPEED_SWEEP_FILE, sweep_plan.seed_max(sim))
    except SweepError as e:
        raise SetupError(str(e)) from None
    arms = sw.axes[1]
    arms.combos = [c for c in arms.combos if ARM_OF.get((c[POLICY_KEY], c[THETA_KEY])) in args.policies]
    sw.seeds = list(range(args.seed, args.seed + args.reps))
    sw.steps = args.steps
    if args.quick:
        sw.name += "_quick"
    return sw


def run_speed(args: argparse.Namespace, sim: Path, sw: Sweep, sweep_dir: Path) -> dict[str, Any]:
    """The robot-speed sweep (speed_sweep); per speed and arm, every run's metrics."""
    arms = sw.axes[1]
    print(f"study_drtm: robot-speed sensitivity, {len(sw.axes[0].combos)} speeds x {len(arms.combos)} arms "
          f"x {args.reps} reps as sweep {sweep_dir}", flush=True)
    run_args = argparse.Namespace(**{**vars(args), "out": str(sweep_dir), "jobs": args.threads, "quiet": False})
    try:
        rc = sweep_cli.run_sweep(sw, run_args, sim)
    except SweepError as e:
        raise SetupError(str(e)) from None
    if rc in (130, 143):
        raise Interrupted(f"sweep {sweep_dir} interrupted; rerun the same command to resume")
    rows = read_table(sweep_dir / "results.csv")
    failed = [r for r in rows if r["status"] != "ok"]
    if rc != 0 or failed:
        raise StudyError(f"{len(failed)} speed runs failed ({sweep_dir / 'results.csv'})")
    out: dict[str, Any] = {}
    for r in rows:
        cell = out.setdefault(r[SPEED_KEY], {}).setdefault(arm_of(r), {})
        for key, *_ in SPEED_ROWS:
            cell.setdefault(key, []).append(float(r[key]) if r[key] != "" else math.nan)
    return out


def render_speed_table(results: dict[str, Any]) -> list[str]:
    """Sensitivity to the robot's speed: the base condition at 0.05 m/s (the
    main table) and the other speeds, mean +- sd per arm."""
    speed = results.get("speed")
    if not speed or "base" not in results["conditions"]:
        return []
    arms = [p for p in POLICIES if p in results["conditions"]["base"]["policies"]]
    lines = ["## Sensitivity to the robot's speed (base condition)", "",
             "Seed 000's simulation speed is not given; 0.05 m/s is its real robots'. "
             "`foraging.robot_speed` sets the foragers' wheel speed and the beacon's "
             "T2 = L / (2 v) together (studies/drtm_speed.yaml).", "",
             "| v (m/s) | arm | " + " | ".join(h for _, h, _, _ in SPEED_ROWS) + " |",
             "|---:|---|" + "---:|" * len(SPEED_ROWS)]
    base = {a: {k: _metric_values(results, "base", a, k) for k, *_ in SPEED_ROWS} for a in arms}
    for v, cells in [("0.05", base)] + sorted(speed.items(), key=lambda kv: float(kv[0])):
        for a in arms:
            if a not in cells:
                continue
            vals = [fmt_mean_sd(cells[a][k], sc, d) for k, _, sc, d in SPEED_ROWS]
            lines.append(f"| {v} | {POLICY_LABEL[a]} | " + " | ".join(vals) + " |")
    lines.append("")
    return lines


def read_table(path: Path) -> list[dict[str, str]]:
    try:
        with path.open(newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise StudyError(f"{path}: cannot read the sweep's table: {e.strerror}") from None


def results_from_table(rows: list[dict[str, str]], sweep_dir: Path, args: argparse.Namespace,
                       command: str, wall: float) -> dict[str, Any]:
    """The study's results (per condition and policy: runs and mean series)
    from the sweep's tidy table and its runs' time series."""
    results: dict[str, Any] = {
        "format": FORMAT, "command": command, "cwd": os.getcwd(),
        "settings": {"reps": args.reps, "first_seed": args.seed, "steps": args.steps,
                     "threads": args.threads, "backend": args.backend, "quick": args.quick,
                     "sim": str(args.sim), "conditions": args.conditions, "policies": args.policies,
                     "control_period_ms": None, "sweep": str(sweep_dir)},
        "machine": machine_info(), "source": source_info(), "conditions": {},
    }
    for cond in args.conditions:
        for policy in args.policies:
            cell = [r for r in rows if condition_of(r["scenario"]) == cond and arm_of(r) == policy]
            cell.sort(key=lambda r: int(r["seed"]))
            dirs = [(sweep_dir / "runs" / r["run_id"] / f"run_{r['seed']}", int(r["seed"])) for r in cell]
            runs, agg = read_runs(dirs, args.steps)
            for run, row in zip(runs, cell, strict=True):   # the table's values
                for k in run["metrics"]:
                    if row.get(k, "") != "":
                        run["metrics"][k] = float(row[k])
            scen = sweep_spec.resolve_scenario(Path(args.sweep_file), cell[0]["scenario"]) \
                if not Path(cell[0]["scenario"]).is_absolute() else Path(cell[0]["scenario"])
            try:
                period = json.loads((dirs[0][0] / "summary.json").read_text()).get("control_period_ms")
                if isinstance(period, int):
                    results["settings"]["control_period_ms"] = period
            except (OSError, ValueError):
                pass
            c = results["conditions"].setdefault(cond, {
                "scenario_file": os.path.relpath(scen, REPO_ROOT)
                if scen.resolve().is_relative_to(REPO_ROOT) else str(scen),
                "desired_food": read_desired_food(scen),
                "robots": runs[0]["robots"],
                "policies": {},
            })
            c["policies"][policy] = {"wall_s": round(sum(float(r["wall_s"] or 0) for r in cell), 3),
                                     "runs": runs, "series": _series_to_json(agg)}
            fn = [r["metrics"]["food_net"] for r in runs]
            mt = [r["metrics"]["oae_total"] for r in runs]
            print(f"  {cond:5s} {policy}: F(T) {fmt_mean_sd(fn)}, M_T {fmt_mean_sd(mt, decimals=0)}",
                  flush=True)
    results["wall_time_s"] = wall
    results["generated_utc"] = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M:%S UTC")
    return results


def write_outputs(results: dict[str, Any], out_dir: Path, figures: bool,
                  rerender_command: str | None = None) -> Path:
    """results.json (unless re-rendering), the figures, then results.md last."""
    out_dir.mkdir(parents=True, exist_ok=True)
    if rerender_command is None:
        _atomic_write_text(out_dir / "results.json",
                           json.dumps(json_safe(results), indent=1, allow_nan=False) + "\n")
    if figures:
        made = render_figures(results, out_dir)
    else:   # list the figures already there, if any
        made = {c: [f"{k}_{c}.png" for k in ("food", "oae", "active")
                    if (out_dir / f"{k}_{c}.png").is_file()] for c in results["conditions"]}
    md = render_markdown(results, made, rerender_command)
    _atomic_write_text(out_dir / "results.md", md)
    return out_dir / "results.md"


def load_results(path: Path) -> dict[str, Any]:
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise SetupError(f"{path}: not found") from None
    except json.JSONDecodeError as e:
        raise StudyError(f"{path}: garbled JSON: {e}") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise StudyError(f"{path}: not a {FORMAT} results file")
    for cond, c in doc.get("conditions", {}).items():
        if cond not in CONDITIONS:
            raise StudyError(f"{path}: unknown condition {cond!r}")
        for p, cell in c.get("policies", {}).items():
            if p not in POLICIES:
                raise StudyError(f"{path}: unknown policy {p!r} in {cond}")
            for r in cell.get("runs", []):
                r["metrics"] = {k: (math.nan if v is None else float(v))
                                for k, v in r["metrics"].items()}
    return doc


# --------------------------------------------------------------------- main


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="swarm-study-drtm",
        description="Reproduce seed 000's DRTM simulation study (sections 3.1 and 4) with "
                    "build/swarmsim: 5 conditions x {DRTM, ARTM, FRTM} x N repetitions; "
                    "writes results.md, results.json and figures.",
        epilog="Exit status: 0 done, 1 a run failed or its outputs are bad, 2 bad arguments "
               "or missing binary/scenario.")
    ap.add_argument("--reps", type=int, default=None,
                    help=f"repetitions per cell (default 50; {QUICK['drtm'].seeds} with --quick)")
    ap.add_argument("--seed", type=int, default=1, help="first seed (default 1)")
    ap.add_argument("--steps", type=int, default=None,
                    help=f"steps per run (default: the scenario's, 12000; {QUICK['drtm'].steps} with --quick)")
    ap.add_argument("--threads", "--jobs", type=int, default=os.cpu_count() or 1,
                    help="local backend: runs at a time (default: os.cpu_count() = %(default)s)")
    ap.add_argument("--out", default=None, help="output folder (default out/study_drtm)")
    ap.add_argument("--conditions", default=None,
                    help="comma-separated subset of " + ",".join(CONDITIONS))
    ap.add_argument("--policies", default=None, help="comma-separated subset of drtm,artm,frtm")
    ap.add_argument("--sim", default=None, help="simulator binary (default build/swarmsim)")
    ap.add_argument("--scenario-dir", default=None,
                    help="take the conditions' scenario files from here (default: the sweep file's)")
    ap.add_argument("--sweep-file", default=None, help="default studies/drtm.yaml")
    ap.add_argument("--quick", action="store_true",
                    help=f"a smoke run under a minute: {QUICK['drtm'].seeds} reps x {QUICK['drtm'].steps} steps, "
                         "into out/study_drtm_quick")
    ap.add_argument("--from-json", metavar="PATH", default=None,
                    help="re-render results.md and figures from a results.json; runs nothing")
    ap.add_argument("--no-figures", action="store_true", help="do not draw the PNGs")
    ap.add_argument("--no-speed", action="store_true",
                    help="skip the robot-speed sensitivity sweep (studies/drtm_speed.yaml)")
    sweep_cli.add_backend_options(ap)
    return ap


def invocation(argv: Sequence[str]) -> str:
    """This run's command line as typed: the interpreter relative to the current
    folder when it lies inside it (e.g. .venv/bin/python), then the script and
    its arguments."""
    exe = sys.executable or "python3"
    try:
        rel = os.path.relpath(exe)
        if not rel.startswith(".."):
            exe = rel
    except ValueError:
        pass
    return shlex.join([exe, "-m", "swarmtools.study.drtm", *argv])


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    ap = build_parser()
    args = ap.parse_args(argv)
    command = invocation(argv)
    t0 = time.monotonic()
    try:
        if args.from_json:
            src = Path(args.from_json)
            results = load_results(src)
            out_dir = Path(args.out) if args.out else src.parent
            md = write_outputs(results, out_dir, figures=not args.no_figures,
                               rerender_command=command)
            print(f"study_drtm: re-rendered {md} from {src} in {time.monotonic() - t0:.1f} s")
            return 0

        if args.reps is None:
            args.reps = QUICK["drtm"].seeds if args.quick else PAPER_REPS
        if args.steps is None and args.quick:
            args.steps = QUICK["drtm"].steps
        if args.reps < 1:
            raise SetupError("--reps must be at least 1")
        if args.steps is not None and args.steps < 1:
            raise SetupError("--steps must be at least 1")
        if args.threads < 1:
            raise SetupError("--threads must be at least 1")
        if args.seed < 0:
            raise SetupError("--seed must not be negative")
        args.conditions = parse_list(args.conditions, list(CONDITIONS), "condition", "foraging_")
        args.policies = parse_list(args.policies, list(POLICIES), "policy")
        args.sim = args.sim or str(REPO_ROOT / "build" / "swarmsim")
        args.sweep_file = args.sweep_file or str(SWEEP_FILE)
        sweep_cli.check_args(args)
        args.out = args.out or str(REPO_ROOT / "out" / ("study_drtm_quick" if args.quick else "study_drtm"))

        results = run_study(args, command)
        md = write_outputs(results, Path(args.out), figures=not args.no_figures)
        n_runs = len(args.conditions) * len(args.policies) * args.reps
        print(f"study_drtm: {n_runs} runs; wrote {md}, results.json"
              + ("" if args.no_figures else " and figures")
              + f"; total wall time {time.monotonic() - t0:.1f} s ({_hms(time.monotonic() - t0)})")
        return 0
    except Submitted as e:
        print(f"study_drtm: {e}")
        return 0
    except Interrupted as e:
        print(f"study_drtm: {e}", file=sys.stderr)
        return e.exit_code
    except SweepError as e:
        print(f"study_drtm: error: {e}", file=sys.stderr)
        return e.exit_code
    except StudyError as e:
        print(f"study_drtm: error: {e}", file=sys.stderr)
        print(f"study_drtm: stopped after {time.monotonic() - t0:.1f} s; results.md not written",
              file=sys.stderr)
        return e.exit_code
    except KeyboardInterrupt:
        print("\nstudy_drtm: interrupted; results.md not written", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
