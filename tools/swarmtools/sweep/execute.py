"""Running runs: one simulator process each, several at once, interruptible.

Both backends come here: the local one with every run of the sweep, a slurm
array task with its chunk. A run that finishes (whatever its exit status) is
recorded whole; a run stopped because the sweep was interrupted (SIGINT,
SIGTERM: Ctrl-C, scancel, a job's time limit) is not recorded at all, so a
rerun simply runs it again.
"""

from __future__ import annotations

import json
import math
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from pathlib import Path
from typing import Any

from .plan import Run, file_sha256
from .store import Store

STDERR_TAIL = 2000      # characters of a failed run's stderr kept in its record


class Interrupted(Exception):
    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


class Executor:
    """Runs the given runs with ``jobs`` simulator processes at a time."""

    def __init__(self, store: Store, sim: Path, plan: dict[str, Any], jobs: int,
                 progress: Progress | None = None):
        self.store = store
        self.sim = sim
        self.plan = plan
        self.jobs = max(1, jobs)
        self.progress = progress
        self.sim_sha256 = file_sha256(sim)
        self.host = socket.gethostname()
        self._stop: int | None = None
        self._procs: set[subprocess.Popen] = set()
        self._lock = threading.Lock()

    # ------------------------------------------------------------ signals
    def _on_signal(self, signum: int, _frame: Any) -> None:
        self._stop = signum
        with self._lock:
            for p in self._procs:
                try:
                    p.terminate()
                except OSError:
                    pass

    def run_all(self, runs: list[Run]) -> dict[str, int]:
        """Runs them; returns {"ok", "failed"}; raises Interrupted on a signal."""
        old = {s: signal.signal(s, self._on_signal) for s in (signal.SIGINT, signal.SIGTERM)}
        counts = {"ok": 0, "failed": 0}
        try:
            with ThreadPoolExecutor(max_workers=self.jobs) as pool:
                queue = list(reversed(runs))
                active: set[Future] = set()
                while (queue or active):
                    while queue and len(active) < self.jobs and self._stop is None:
                        active.add(pool.submit(self._one, queue.pop()))
                    if not active:
                        break
                    done, active = wait(active, timeout=0.5, return_when=FIRST_COMPLETED)
                    for f in done:
                        status = f.result()
                        if status is not None:
                            counts[status] += 1
                            if self.progress:
                                self.progress.update(status)
                    if self.progress:
                        self.progress.tick()
        finally:
            for s, h in old.items():
                signal.signal(s, h)
        if self._stop is not None:
            raise Interrupted(self._stop)
        return counts

    # -------------------------------------------------------------- a run
    def command(self, run: Run) -> list[str]:
        cmd = [str(self.sim), run.scenario, "--seed", str(run.seed), "--out",
               str(self.store.run_dir(run)), "--lcm", "off", "--threads", "1", "--quiet"]
        if run.steps is not None:
            cmd += ["--steps", str(run.steps)]
        for k, v in run.overrides:
            cmd += ["--set", f"{k}={v}"]
        return cmd

    def _one(self, run: Run) -> str | None:
        if self._stop is not None:
            return None
        prev = self.store.record(run.run_id)
        attempts = int(prev.get("attempts", 0)) + 1 if prev else 1
        self.store.clear_run(run)
        timeout = float(self.plan.get("run_timeout") or 0) or None
        t0 = time.monotonic()
        try:
            # The simulator holds the folder's lock too (store.py): a sweep
            # killed outright leaves it locked until its simulators end.
            p = subprocess.Popen(self.command(run), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                 text=True, errors="replace", start_new_session=True,
                                 pass_fds=() if self.store.lock_fd is None else (self.store.lock_fd,))
        except OSError as e:                 # the simulator cannot be started: a failed run, not a crash
            self.store.write_record({
                "run_id": run.run_id, "seed": run.seed, "attempts": attempts, "exit_status": None,
                "wall_s": 0.0, "host": self.host, "sim_sha256": self.sim_sha256,
                "code_version": self.plan.get("code_version", ""), "backend": self.plan.get("backend", ""),
                "command": self.command(run), "status": "failed",
                "error": f"cannot start the simulator {self.sim}: {e.strerror or e}"})
            return "failed"
        with self._lock:
            self._procs.add(p)
        timed_out = False
        try:
            _, err = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.kill()
            _, err = p.communicate()
            timed_out = True
        finally:
            with self._lock:
                self._procs.discard(p)
        wall = time.monotonic() - t0
        if self._stop is not None and p.returncode != 0:
            return None                      # stopped by us: not a result
        rec: dict[str, Any] = {
            "run_id": run.run_id, "seed": run.seed, "attempts": attempts,
            "exit_status": p.returncode, "wall_s": round(wall, 3), "host": self.host,
            "sim_sha256": self.sim_sha256, "code_version": self.plan.get("code_version", ""),
            "backend": self.plan.get("backend", ""), "command": self.command(run),
        }
        if p.returncode == 0 and not timed_out:
            summary = self.store.run_dir(run) / f"run_{run.seed}" / "summary.json"
            try:
                doc = json.loads(summary.read_text())
                rec.update(status="ok", steps=doc["steps"], state_hash=doc["state_hash"],
                           metrics={k: (math.nan if v is None else v) for k, v in doc["metrics"].items()})
                control = doc.get("control")
                if isinstance(control, dict) and control.get("touched") is not False:
                    # A run steered by hand (swarmsim --control moved a robot or
                    # set a parameter) is not its scenario's run: never a result.
                    rec.update(status="failed", error=f"touched by hand (swarmsim --control, "
                               f"{control.get('commands', '?')} commands): not a run of this sweep")
            except (OSError, ValueError, KeyError, TypeError) as e:
                rec.update(status="failed", error=f"exit status 0 but no readable summary.json: {e}")
            if not self.plan.get("keep_timeseries", True):
                (summary.parent / "timeseries.csv").unlink(missing_ok=True)
        else:
            why = (f"timed out after {timeout:g} s" if timed_out
                   else f"killed by {signal.Signals(-p.returncode).name}" if p.returncode < 0
                   else f"exit status {p.returncode}")
            rec.update(status="failed", error=f"{why}: {err[-STDERR_TAIL:].strip()}".rstrip(": "))
        self.store.write_record(rec)
        return rec["status"]


class Progress:
    """One line on stderr: runs done, failed, and the time left.

    On a terminal the line is redrawn in place; otherwise (CI, a batch log) a
    line is printed at most every ``every`` seconds and at the end.
    """

    def __init__(self, name: str, total: int, done_before: int, every: float = 10.0,
                 stream: Any = None):
        self.name, self.total = name, total
        self.ok = done_before
        self.failed = 0
        self.new = 0
        self.t0 = time.monotonic()
        self.stream = stream or sys.stderr
        self.tty = hasattr(stream, "isatty") and stream.isatty()
        self.every = 0.5 if self.tty else every
        self.last = 0.0

    def update(self, status: str) -> None:
        self.new += 1
        if status == "ok":
            self.ok += 1
        else:
            self.failed += 1

    def line(self) -> str:
        el = time.monotonic() - self.t0
        left = self.total - self.ok - self.failed
        eta = f"{_hms(el / self.new * left)} left" if self.new and left else "—"
        return (f"sweep {self.name}: {self.ok + self.failed}/{self.total} runs done, "
                f"{self.failed} failed, {_hms(el)} elapsed, {eta}")

    def tick(self, force: bool = False) -> None:
        now = time.monotonic()
        if not force and now - self.last < self.every:
            return
        self.last = now
        if self.tty:
            self.stream.write("\r\033[K" + self.line())
        else:
            self.stream.write(self.line() + "\n")
        self.stream.flush()

    def end(self, note: str = "") -> None:
        self.tick(force=True)
        if self.tty:
            self.stream.write("\n")
        if note:
            self.stream.write(note + "\n")
        self.stream.flush()


def _hms(s: float) -> str:
    s = int(round(s))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


def cpus() -> int:
    n = os.environ.get("SLURM_CPUS_PER_TASK")
    if n and n.isdigit():
        return int(n)
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1
