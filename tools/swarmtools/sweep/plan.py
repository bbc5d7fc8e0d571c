"""Expanding a sweep into runs with stable ids, and checking them first.

A run is one simulator process: a scenario file, its overrides (the sweep's
``set`` then the axes' values, in file order), one seed and the step count.
Its id is a hash of exactly those inputs (the scenario by its bytes) in one
unambiguous encoding (canonical()), so the same run has the same id in every
expansion, on every machine, a rerun of a sweep finds the runs it already
has, and two different runs never share an id.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import re
import subprocess
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

from .spec import SCENARIO_KEY, Sweep, SweepError, Value, resolve_scenario, set_text


@dataclass(frozen=True)
class Run:
    index: int                      # position in the expansion (table order)
    run_id: str
    scenario: str                   # path of the scenario file
    params: dict[str, Value]        # the varied keys' values (table columns; arrays as lists)
    overrides: list[tuple[str, str]]  # every --set, in order
    seed: int
    steps: int | None
    scenario_sha256: str            # the scenario's bytes and its overrides

    def to_json(self) -> dict:
        return asdict(self)

    @staticmethod
    def from_json(d: dict) -> Run:
        d = dict(d)
        d["overrides"] = [tuple(o) for o in d["overrides"]]
        return Run(**d)


def file_sha256(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def canonical(value: object) -> bytes:
    """One unambiguous encoding of plain data (JSON: every string quoted and
    escaped, lists bracketed), so that two different inputs never hash alike:
    a value holding a newline and `--set ...` is not a second override."""
    return json.dumps(value, ensure_ascii=True, separators=(",", ":"), sort_keys=True,
                      allow_nan=False).encode()


def scenario_hash(scenario_bytes_sha: str, overrides: Iterable[tuple[str, str]]) -> str:
    """The effective scenario's identity: its file's hash and its overrides."""
    text = canonical({"scenario_sha256": scenario_bytes_sha, "overrides": [[k, v] for k, v in overrides]})
    return hashlib.sha256(text).hexdigest()[:16]


def run_id(shash: str, seed: int, steps: int | None) -> str:
    """A run's id: its effective scenario, seed and step count."""
    return hashlib.sha256(canonical({"scenario": shash, "seed": seed, "steps": steps})).hexdigest()[:16]


def expand(sw: Sweep) -> list[Run]:
    """Every run: the axes' Cartesian product (first axis outermost), seeds innermost."""
    file_sha: dict[str, str] = {}
    runs: list[Run] = []
    seen: dict[str, int] = {}
    fixed = [(k, set_text(v)) for k, v in sw.fixed]
    for parts in itertools.product(*(a.combos for a in sw.axes)) if sw.axes else [()]:
        params: dict[str, Value] = {}
        for p in parts:
            params.update(p)
        scenario = str(resolve_scenario(sw.path, str(params[SCENARIO_KEY]))
                       if SCENARIO_KEY in params else sw.scenario)
        overrides = fixed + [(k, set_text(v)) for k, v in params.items() if k != SCENARIO_KEY]
        if scenario not in file_sha:
            file_sha[scenario] = file_sha256(scenario)
        shash = scenario_hash(file_sha[scenario], overrides)
        for seed in sw.seeds:
            rid = run_id(shash, seed, sw.steps)
            if rid in seen:
                other = ", ".join(f"{k}={set_text(v)}" for k, v in runs[seen[rid]].params.items())
                mine = ", ".join(f"{k}={set_text(v)}" for k, v in params.items())
                raise SweepError(f"{sw.path}: the runs with {other} and with {mine} are the same run "
                                 "(same scenario content, overrides and seed); list it once")
            seen[rid] = len(runs)
            runs.append(Run(len(runs), rid, scenario, dict(params), overrides, seed, sw.steps, shash))
    return runs


def seed_max(sim: Path) -> int:
    """The simulator's seed range's upper end, read from its --help key table."""
    out = _sim_help(sim)
    m = re.search(r"^\s+seed\s+int\s+\S+\s+\[0, (\d+)\]", out, re.MULTILINE)
    if not m:
        raise SweepError(f"{sim}: --help does not give the seed range (an older simulator?)")
    return int(m.group(1))


def _sim_help(sim: Path) -> str:
    try:
        p = subprocess.run([str(sim), "--help"], capture_output=True, text=True, timeout=30, check=False)
    except OSError as e:
        raise SweepError(f"{sim}: cannot run the simulator: {e.strerror} (build it with `make`)") from None
    if p.returncode != 0:
        raise SweepError(f"{sim} --help exited with status {p.returncode}")
    return p.stdout


def check_runs(sw: Sweep, runs: list[Run], sim: Path, jobs: int) -> None:
    """Loads every distinct (scenario, overrides) with `swarmsim --check`.

    A bad value is reported with the sweep file's line of its key and the
    simulator's own message, before anything runs.
    """
    distinct: dict[str, Run] = {}
    for r in runs:
        distinct.setdefault(r.scenario_sha256, r)

    def check(r: Run) -> tuple[Run, subprocess.CompletedProcess]:
        cmd = [str(sim), r.scenario, "--check", "--quiet"]
        for k, v in r.overrides:
            cmd += ["--set", f"{k}={v}"]
        return r, subprocess.run(cmd, capture_output=True, text=True, timeout=60, check=False)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        for r, p in pool.map(check, distinct.values()):
            if p.returncode == 0:
                continue
            msg = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else f"exit status {p.returncode}"
            m = re.search(r"--set ([^=\s]+)=", msg)
            key = m.group(1) if m else None
            line = sw.key_lines.get(key) if key else None
            where = f"{sw.path}:{line}" if line else f"{sw.path}"
            combo = ", ".join(f"{k}={set_text(v)}" for k, v in r.params.items()) or "the base scenario"
            raise SweepError(f"{where}: the simulator rejects the run with {combo}: {msg}")
