"""A sweep's folder: the plan, one record per finished run, the tidy table.

Layout of ``--out DIR``::

    DIR/.swarmtools-sweep     marker: this folder is a sweep's (never delete
                              or reuse a folder without it)
    DIR/.swarmtools-sweep.lock  held (flock) by the `swarm-sweep run` working
                              in DIR and the simulators it started; it says who
    DIR/sweep.json            the expanded plan: every run, its id, overrides
    DIR/records/<id>.json     one finished run (ok or failed), written whole
    DIR/runs/<id>/run_<seed>/ the simulator's outputs of that run
    DIR/results.csv           the tidy table, one row per recorded run
    DIR/results.parquet       the same table (pandas.read_parquet)
    DIR/slurm/                batch scripts and logs of the slurm backend

Every file is written under a temporary name in its folder and renamed when
complete, so an interrupted sweep never leaves a half-written record or row.

One `swarm-sweep run` works in a folder at a time: it holds an exclusive
flock on the lock file, which its simulators inherit, so a second one is
refused at once with the first one's pid, and the kernel releases the lock
when the last of them ends, however it ends (a crash or `kill -9` leaves no
stale lock; simulators left running by a killed sweep keep the folder
until they finish).
"""

from __future__ import annotations

import datetime as _dt
import fcntl
import json
import math
import os
import shutil
import socket
import sys
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .plan import Run
from .spec import SCENARIO_KEY, SweepError

MARKER = ".swarmtools-sweep"
LOCK = ".swarmtools-sweep.lock"
#: The plan's format: /2 hashes run ids from a canonical encoding (plan.canonical).
FORMAT = "swarmtools-sweep/2"
_HELD: dict[str, int] = {}     # lock file -> the descriptor this process holds it by
FIXED_COLUMNS_BEFORE = ("run", "run_id")
TEXT_COLUMNS = ("run_id", "status", "state_hash", "scenario_sha256", "code_version",
                "sim_sha256", "host", "error", SCENARIO_KEY)


def atomic_write(path: Path, data: bytes | str, check=None, suffix: str = ".tmp") -> None:
    """Writes `path` whole or not at all: a temporary file beside it, renamed
    into place.  `check(tmp)`, if given, is called on the written temporary
    file (named ...`suffix`) before the rename; what it raises leaves no file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode() if isinstance(data, str) else data)
            f.flush()
            os.fsync(f.fileno())
        if check is not None:
            check(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


class Store:
    def __init__(self, root: Path):
        self.root = root
        self.records = root / "records"
        self.runs = root / "runs"
        self.lock_fd: int | None = None    # held while this process works in the folder

    # ------------------------------------------------------------ the folder
    def open_for(self, plan: dict[str, Any]) -> None:
        """Make DIR a sweep folder, or reopen ours; refuse anyone else's."""
        if self.root.exists():
            if not self.root.is_dir():
                raise SweepError(f"{self.root}: exists and is not a folder")
            if any(self.root.iterdir()) and not (self.root / MARKER).exists():
                raise SweepError(f"{self.root}: not empty and not a sweep's folder (no {MARKER}); "
                                 "give a new --out")
        self.root.mkdir(parents=True, exist_ok=True)
        self.lock()
        old = self.root / "sweep.json"
        if old.exists():
            try:
                made = json.loads(old.read_text()).get("format")
            except (OSError, ValueError, AttributeError):
                made = None
            if made != FORMAT:
                raise SweepError(f"{self.root}: made by another version of swarm-sweep (format {made}, this "
                                 f"one writes {FORMAT}: run ids are hashed differently), so its records cannot "
                                 "be resumed; give a new --out")
        (self.root / MARKER).touch()
        self.records.mkdir(exist_ok=True)
        self.runs.mkdir(exist_ok=True)
        atomic_write(self.root / "sweep.json", json.dumps(plan, indent=1) + "\n")

    def lock(self) -> None:
        """Takes the folder's lock for as long as this process (and the
        simulators it starts with lock_fd) live; refuses, naming the holder,
        if another has it."""
        path = self.root / LOCK
        held = _HELD.get(str(path.resolve()))
        if held is not None:             # this process has it (a study's second sweep into one folder)
            self.lock_fd = held
            return
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = os.read(fd, 4096).decode(errors="replace").strip()
            os.close(fd)
            raise SweepError(f"{self.root}: in use by another swarm-sweep: {_holder(holder)}; wait for it to "
                             "end (or stop it), or give another --out") from None
        os.ftruncate(fd, 0)
        since = _dt.datetime.now().astimezone().isoformat(timespec="seconds")
        os.write(fd, f"pid {os.getpid()} on {socket.gethostname()} since {since}: {' '.join(sys.argv)}\n".encode())
        self.lock_fd = _HELD[str(path.resolve())] = fd

    def load_plan(self) -> dict[str, Any]:
        if not (self.root / MARKER).exists():
            raise SweepError(f"{self.root}: not a sweep folder (no {MARKER})")
        try:
            return json.loads((self.root / "sweep.json").read_text())
        except (OSError, json.JSONDecodeError) as e:
            raise SweepError(f"{self.root / 'sweep.json'}: cannot read the plan: {e}") from None

    def run_dir(self, run: Run) -> Path:
        return self.runs / run.run_id

    def clear_run(self, run: Run) -> None:
        """Remove a run's old outputs before it runs again (inside our own folder)."""
        shutil.rmtree(self.run_dir(run), ignore_errors=True)

    # --------------------------------------------------------------- records
    def record(self, run_id: str) -> dict[str, Any] | None:
        try:
            return json.loads((self.records / f"{run_id}.json").read_text())
        except FileNotFoundError:
            return None
        except (OSError, json.JSONDecodeError):
            return None       # unreadable: treated as not run (it runs again)

    def write_record(self, rec: dict[str, Any]) -> None:
        atomic_write(self.records / f"{rec['run_id']}.json", json.dumps(rec, indent=1) + "\n")

    def pending(self, runs: Iterable[Run], max_attempts: int) -> tuple[list[Run], int, int]:
        """Runs still to do: never run, or failed with attempts left.

        Returns (pending, finished ok, failed for good)."""
        todo, ok, dead = [], 0, 0
        for r in runs:
            rec = self.record(r.run_id)
            if rec is None:
                todo.append(r)
            elif rec.get("status") == "ok":
                ok += 1
            elif int(rec.get("attempts", 1)) < max_attempts:
                todo.append(r)
            else:
                dead += 1
        return todo, ok, dead

    # ----------------------------------------------------------------- table
    def write_table(self, runs: list[Run], varied: list[str], metrics: list[str] | None) -> dict[str, int]:
        """results.csv and results.parquet from the records of the plan's runs.

        One row per recorded run, in plan order; runs not yet run are left
        out (the counts say how many). Returns {"rows", "ok", "failed", "runs"}.
        """
        recs = [(r, self.record(r.run_id)) for r in runs]
        recs = [(r, rec) for r, rec in recs if rec is not None]
        if metrics is None:
            metrics = []
            for _, rec in recs:
                for k in rec.get("metrics", {}):
                    if k not in metrics:
                        metrics.append(k)
        header = [*FIXED_COLUMNS_BEFORE, *varied, "seed", "status", "attempts", *metrics,
                  "steps", "state_hash", "scenario_sha256", "code_version", "sim_sha256",
                  "wall_s", "host", "error"]
        rows = []
        for r, rec in recs:
            m = rec.get("metrics", {})
            row = [r.index, r.run_id, *(r.params.get(k, "") for k in varied), r.seed, rec["status"],
                   rec.get("attempts", 1), *(m.get(k) for k in metrics), rec.get("steps"),
                   rec.get("state_hash", ""), r.scenario_sha256, rec.get("code_version", ""),
                   rec.get("sim_sha256", ""), rec.get("wall_s"), rec.get("host", ""),
                   rec.get("error", "")]
            rows.append([_cell(v) for v in row])
        csv_text = _csv(header, rows)
        atomic_write(self.root / "results.csv", csv_text)
        self._write_parquet(header, varied, runs)
        ok = sum(1 for _, rec in recs if rec["status"] == "ok")
        return {"rows": len(recs), "ok": ok, "failed": len(recs) - ok, "runs": len(runs)}

    def _write_parquet(self, header: list[str], varied: list[str], runs: list[Run]) -> None:
        import pandas as pd

        text_cols = [c for c in header if c in TEXT_COLUMNS]
        for k in varied:     # a varied key whose values are all words (or arrays) stays text
            vals = [r.params.get(k) for r in runs]
            if all(isinstance(v, (str, list, tuple)) for v in vals):
                text_cols.append(k)
        df = pd.read_csv(self.root / "results.csv", dtype={c: "string" for c in text_cols},
                         keep_default_na=False, na_values={c: [""] for c in header if c not in text_cols})
        fd, tmp = tempfile.mkstemp(prefix=".results.parquet.", suffix=".tmp", dir=self.root)
        os.close(fd)
        try:
            df.to_parquet(tmp, engine="pyarrow", index=False)
            os.chmod(tmp, 0o644)
            os.replace(tmp, self.root / "results.parquet")
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


def _holder(text: str) -> str:
    """The lock file's "pid N on HOST since T: COMMAND", and whether N still runs."""
    if not text:
        return "a process that has not yet said who it is"
    words = text.split()
    if len(words) > 3 and words[0] == "pid" and words[1].isdigit() and words[3] == socket.gethostname():
        try:
            os.kill(int(words[1]), 0)
        except ProcessLookupError:
            return f"{text} (that process has ended; simulators it started still run and hold the folder)"
        except OSError:
            pass
    return text


def _cell(v: Any) -> str:
    """One CSV field: integers as integers, floats by repr (exact), NaN/None
    empty, an array as "[v0, v1, ...]" (what --set was given)."""
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_cell(x) for x in v) + "]"
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(v)
    return str(v)


def _csv(header: list[str], rows: list[list[str]]) -> str:
    import csv
    import io

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()
