"""A whole run with its outputs, in this process: swarmtools.run.

    out = swarmtools.run("sim_host/scenarios/foraging_base.yaml", seed=3, reps=4,
                         out="out/scan", overrides={"robots.0.count": 30})
    out.summary["metrics"]["food_collected"]     # the aggregate over the 4 runs
    out.runs[0].timeseries                          # run_3/timeseries.csv as a DataFrame
    out.runs[0].log()                               # its telemetry, as DataFrames

It is the swarmsim command line's own work (swarmsim_command, command.h),
called in process with the options the arguments name: the same folders
and files (run_<seed>/summary.json, timeseries.csv, telemetry.lcmlog, the
aggregate summary.json), the same checks and messages, the same results.
Ctrl-C stops it as it stops swarmsim (finished runs are kept) and raises
KeyboardInterrupt.  A failure raises ScenarioError (a bad scenario or
override: file and line) or RunError, with swarmsim's message.
"""

from __future__ import annotations

import ctypes
import json
import os
import signal
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from . import _lib
from .simulation import OverridesLike, ScenarioError, override_texts, parse_loader_error


class RunError(RuntimeError):
    """swarmsim stopped with an error: its exit status and message."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status
        self.message = message


@dataclass
class RunOutput:
    """One repetition's folder, run_<seed>/."""
    seed: int
    dir: Path

    @property
    def summary(self) -> dict:
        """summary.json."""
        return json.loads((self.dir / "summary.json").read_text())

    @property
    def timeseries(self):
        """timeseries.csv as a pandas DataFrame."""
        import pandas as pd
        return pd.read_csv(self.dir / "timeseries.csv")

    @property
    def log_path(self) -> Path:
        return self.dir / "telemetry.lcmlog"

    def log(self, **kwargs):
        """The telemetry log as DataFrames (swarmtools.load_log)."""
        from ..dataframes import load_log
        return load_log(self.log_path, **kwargs)


@dataclass
class Run:
    """What a run() made: the output folder and each repetition's."""
    out: Path
    status: int
    runs: list[RunOutput] = field(default_factory=list)

    @property
    def summary(self) -> dict:
        """The aggregate summary.json when there are several repetitions,
        else the one run's."""
        top = self.out / "summary.json"
        if top.is_file():
            return json.loads(top.read_text())
        return self.runs[0].summary


def _flag(argv: list[str], name: str, value: Any) -> None:
    if value is not None and value is not False:
        argv.append(name)
        if value is not True:
            argv.append(str(value))


def command_line(scenario: str | os.PathLike, *, seed: int | None = None, reps: int = 1, steps: int | None = None,
                 out: str | os.PathLike | None = None, overrides: OverridesLike = None, threads: int | None = None,
                 run_threads: int | None = None, replace: bool = False, resume: bool = False,
                 lcm: str | None = None, telemetry_rate: str | None = None, frames: int | None = None,
                 progress: bool = False, extra: list[str] | None = None) -> list[str]:
    """The swarmsim command line run() runs (argv, "swarmsim" first)."""
    argv = ["swarmsim", os.fspath(scenario)]
    _flag(argv, "--seed", seed)
    if reps != 1:
        _flag(argv, "--reps", reps)
    _flag(argv, "--steps", steps)
    if out is not None:
        _flag(argv, "--out", os.fspath(out))
    for text in override_texts(overrides):
        argv += ["--set", text]
    _flag(argv, "--threads", threads)
    _flag(argv, "--run-threads", run_threads)
    _flag(argv, "--replace", replace)
    _flag(argv, "--resume", resume)
    _flag(argv, "--lcm", lcm)
    _flag(argv, "--telemetry-rate", telemetry_rate)
    _flag(argv, "--frames", frames)
    if not progress:
        argv.append("--quiet")
    return argv + list(extra or [])


class _StderrTee:
    """Fd 2 into a pipe while the C code runs: what it writes still
    reaches this process's stderr (sys.stderr: a notebook's cell, or the
    terminal), and the text is kept for the exception."""

    def __init__(self):
        self.text = bytearray()

    def __enter__(self):
        sys.stderr.flush()
        self.saved = os.dup(2)
        r, w = os.pipe()
        os.dup2(w, 2)
        os.close(w)
        self.reader = threading.Thread(target=self._pump, args=(r,), daemon=True)
        self.reader.start()
        return self

    def _pump(self, r: int) -> None:
        with os.fdopen(r, "rb", buffering=0) as pipe:
            while chunk := pipe.read(65536):
                self.text += chunk
                del self.text[:-65536]
                try:
                    if sys.stderr.fileno() == 2:
                        os.write(self.saved, chunk)
                    else:
                        raise ValueError
                except (ValueError, OSError, AttributeError):   # no real fd behind sys.stderr
                    sys.stderr.write(chunk.decode(errors="replace"))
                    sys.stderr.flush()

    def __exit__(self, *exc):
        os.dup2(self.saved, 2)       # the pipe's last writer goes: the reader sees its end
        self.reader.join()
        os.close(self.saved)

    def last_message(self) -> str:
        lines = [ln for ln in self.text.decode(errors="replace").replace("\r", "\n").split("\n")
                 if ln.startswith("swarmsim: ")]
        return lines[-1][len("swarmsim: "):] if lines else ""


def run(scenario: str | os.PathLike, *, seed: int | None = None, reps: int = 1, steps: int | None = None,
        out: str | os.PathLike | None = None, overrides: OverridesLike = None, threads: int | None = None,
        run_threads: int | None = None, replace: bool = False, resume: bool = False, lcm: str | None = None,
        telemetry_rate: str | None = None, frames: int | None = None, progress: bool = False,
        extra: list[str] | None = None) -> Run:
    """Runs `scenario` as `swarmsim` does, with its outputs.

    seed, reps, steps, out, threads, run_threads, replace, resume, lcm,
    telemetry_rate, frames: swarmsim's --seed, --reps, --steps, --out ...
    (``swarmsim --help``); overrides: its --set, as for Sim; progress: its
    progress bar and summary (off: --quiet); extra: more options as they
    are written on the command line.  Returns a Run (the folders);
    raises ScenarioError, RunError or KeyboardInterrupt."""
    argv = command_line(scenario, seed=seed, reps=reps, steps=steps, out=out, overrides=overrides,
                        threads=threads, run_threads=run_threads, replace=replace, resume=resume, lcm=lcm,
                        telemetry_rate=telemetry_rate, frames=frames, progress=progress, extra=extra)
    lib = _lib.lib()
    words = [a.encode() for a in argv]
    c_argv = (ctypes.c_char_p * (len(words) + 1))(*words, None)
    stop = ctypes.c_int(0)
    status: list[int] = []

    def work():
        status.append(lib.swarmsim_command(len(words), c_argv, lib.swarmsim_code_version(), ctypes.byref(stop)))

    interrupted = False
    with _StderrTee() as tee:
        worker = threading.Thread(target=work, name="swarmsim", daemon=True)
        worker.start()
        while worker.is_alive():
            try:
                worker.join(0.2)
            except KeyboardInterrupt:
                stop.value = int(signal.SIGINT)     # as swarmsim's own handler does
                interrupted = True
    if interrupted:
        raise KeyboardInterrupt(f"swarmtools.run stopped: {tee.last_message()}")
    rc = status[0]
    if rc != 0:
        message = tee.last_message() or f"swarmsim exited with status {rc}"
        if rc == 2:
            err = parse_loader_error(message, os.fspath(scenario), override_texts(overrides))
            if err.file is not None or err.override is not None:
                raise err
        raise RunError(rc, message)
    out_dir = Path(out) if out is not None else None
    if out_dir is None:
        out_dir = _default_out(scenario, overrides)
    first = seed
    runs = []
    for d in sorted(out_dir.glob("run_*")):
        if d.is_dir() and d.name[4:].isdigit():
            runs.append(RunOutput(int(d.name[4:]), d))
    runs.sort(key=lambda r: r.seed)
    if first is not None:
        runs = [r for r in runs if first <= r.seed < first + reps] or runs
    return Run(out_dir, rc, runs)


def _default_out(scenario, overrides) -> Path:
    """out/<scenario name>: swarmsim's folder without --out."""
    from .simulation import Sim
    with Sim(scenario, overrides=overrides) as sim:
        name = sim.summary()["scenario"]
    return Path("out") / name


__all__ = ["Run", "RunError", "RunOutput", "ScenarioError", "command_line", "run"]
