"""What the seed studies share: picking their sweeps, running each through
the sweep engine into OUT/<name>/, a --quick smoke run's narrowing, its
folder and its note, saying what the full study costs before it starts, and
writing results.md / results.json whole (atomic writes).  A study module
keeps only its figures and tables."""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from swarmtools.study.costs import COSTS, Quick
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep.spec import Sweep, SweepError
from swarmtools.sweep.store import atomic_write

INTERRUPTED = 130


def pick(arg: str, known: Iterable[str], option: str = "--figures") -> list[str]:
    """The comma-separated names of `arg`, each one of `known`."""
    known = list(known)
    names = [f.strip() for f in arg.split(",") if f.strip()]
    bad = [f for f in names if f not in known]
    if bad or not names:
        raise SweepError(f"{option}: unknown {', '.join(bad) or '(none)'}; choose from {', '.join(known)}")
    return names


def run_sweep(sw: Sweep, args: argparse.Namespace, sim: Path, sweep_dir: Path, tag: str) -> int | None:
    """Runs (or resumes) one sweep into sweep_dir with the study's backend
    options.  Returns its exit status; None when the jobs were only submitted
    (slurm --no-wait); INTERRUPTED after saying how to resume."""
    rc = sweep_cli.run_sweep(sw, argparse.Namespace(**{**vars(args), "out": str(sweep_dir), "quiet": False}), sim)
    if rc in (130, 143):
        print(f"{tag}: interrupted; rerun the same command to resume", file=sys.stderr)
        return INTERRUPTED
    if args.backend == "slurm" and args.no_wait:
        return None
    return rc


def boot_ratio(num: np.ndarray, den: np.ndarray, scale: float = 1.0, n: int = 4000) -> tuple[float, float, float]:
    """mean(num) / mean(den) / scale and its 95 % bootstrap interval."""
    if num.size == 0 or den.size == 0:
        return math.nan, math.nan, math.nan
    rng = np.random.default_rng(0)
    a = rng.choice(num, size=(n, num.size)).mean(axis=1)
    b = rng.choice(den, size=(n, den.size)).mean(axis=1)
    r = a / b / scale
    return float(num.mean() / den.mean() / scale), float(np.percentile(r, 2.5)), float(np.percentile(r, 97.5))


def read_rows(path: Path) -> list[dict[str, str]]:
    """A sweep's results.csv as rows of strings."""
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def json_safe(o: Any) -> Any:
    """NaN and infinities as null (JSON has neither), recursively."""
    if isinstance(o, float) and not math.isfinite(o):
        return None
    if isinstance(o, dict):
        return {k: json_safe(v) for k, v in o.items()}
    if isinstance(o, list):
        return [json_safe(v) for v in o]
    return o


def write_results(out: Path, md: Sequence[str], results: dict[str, Any], tag: str) -> None:
    """results.md and results.json into out, each written whole; the tables
    echoed to stdout."""
    out.mkdir(parents=True, exist_ok=True)
    atomic_write(out / "results.md", "\n".join(md) + "\n")
    atomic_write(out / "results.json", json.dumps(json_safe(results), indent=1) + "\n")
    print("\n".join(md))
    print(f"{tag}: wrote {out / 'results.md'}")


def quick_out(out: str | None, default: Path, quick: bool) -> Path:
    """The output folder: --out if given, else the study's own, with
    _quick after its name for a --quick run (out/study_repatt_quick), so a
    smoke run never mixes with the full study's runs."""
    if out:
        return Path(out)
    return default.with_name(default.name + "_quick") if quick else default


def narrow(sw: Sweep, quick: Quick | None) -> Sweep:
    """The sweep as a --quick run makes it: its first seeds, every run cut."""
    if quick is not None:
        sw.seeds = sw.seeds[:quick.seeds]
        sw.steps = min(sw.steps, quick.steps) if sw.steps else quick.steps
    return sw


def quick_words(quick: Quick) -> str:
    return (f"--quick: {quick.seeds} seed{'s' if quick.seeds != 1 else ''} a cell, every run cut at "
            f"{quick.steps:,} control steps" + (f", {quick.note}" if quick.note else ""))


def announce(tag: str, study: str, runs_now: int, quick: Quick | None, at_most: bool = False) -> None:
    """Says what the full study costs, and what this invocation runs, before it starts."""
    c = COSTS[study]
    print(f"{tag}: the full study is {c.runs:,} runs, {c.core_hours:g} core-hours, {c.wall} on 2 cores "
          f"(measured{'; ' + c.note if c.note else ''}); this invocation: {'at most ' if at_most else ''}"
          f"{runs_now:,} runs"
          + (f" ({quick_words(quick)}: a smoke run)" if quick else ""), flush=True)


def smoke_note(quick: Quick | None) -> list[str]:
    """The line results.md starts with in a smoke run."""
    if quick is None:
        return []
    return [f"> **A smoke run** ({quick_words(quick)}): it shows that the study runs end to end. "
            "Its numbers are not the study's: do not compare them with the paper's.", ""]
