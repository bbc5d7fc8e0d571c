"""The slurm backend: a sweep as sbatch job arrays and a dependent merge job.

The pending runs are cut into chunks of ``--chunk-size``; array task i runs
chunk i (``swarm-sweep worker``) with ``--cpus-per-task`` runs at a time. A
cluster caps array indices (MaxArraySize, 1001 by default), so a sweep with
more chunks is submitted as several arrays. One merge job, dependent on all of
them finishing whatever their state (``afterany``), writes the tidy table.
Unless ``--no-wait``, the command then follows the jobs with ``squeue`` and
the records as they arrive, and reports like the local backend.

The sweep folder must be on a filesystem the compute nodes share (the home or
a project folder), and so must the simulator and the Python environment.
"""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from .execute import Progress
from .plan import Run
from .spec import SweepError
from .store import Store, atomic_write


@dataclass
class SlurmOptions:
    chunk_size: int = 10
    cpus_per_task: int = 1
    mem: str | None = None             # per node, as sbatch --mem takes it
    time: str | None = None            # per array task, e.g. 01:00:00
    partition: str | None = None
    account: str | None = None
    max_parallel: int | None = None    # array throttle %N
    extra: list[str] = field(default_factory=list)   # more sbatch options
    wait: bool = True
    poll_s: float = 2.0


def check_options(options: list[tuple[str, str | None]]) -> None:
    """Each goes into a batch script's `#SBATCH` line: one line of printable
    text (a newline would end the line and start a command)."""
    for flag, value in options:
        if value is not None and not re.fullmatch(r"[^\x00-\x1f\x7f]*", value):
            raise SweepError(f"{flag} {value!r}: a control character or line break cannot go into "
                             "an #SBATCH line")


def _sbatch(args: list[str]) -> str:
    try:
        p = subprocess.run(["sbatch", "--parsable", *args], capture_output=True, text=True,
                           timeout=120, check=False)
    except FileNotFoundError:
        raise SweepError("sbatch: not found; the slurm backend runs on a cluster's login node "
                         "(docs: how-to, run on a cluster)") from None
    if p.returncode != 0:
        raise SweepError(f"sbatch {' '.join(args)} failed: {p.stderr.strip() or p.returncode}")
    return p.stdout.strip().split(";")[0]


def max_array_size() -> int:
    try:
        p = subprocess.run(["scontrol", "show", "config"], capture_output=True, text=True,
                           timeout=60, check=False)
        m = re.search(r"^MaxArraySize\s*=\s*(\d+)", p.stdout, re.MULTILINE)
        if m:
            return int(m.group(1))
    except (OSError, subprocess.SubprocessError):
        pass
    return 1001   # slurm's default


def _directives(opt: SlurmOptions, name: str, log: str) -> list[str]:
    d = [f"--job-name={name}", f"--cpus-per-task={opt.cpus_per_task}", "--ntasks=1",
         f"--output={log}"]
    if opt.mem:
        d.append(f"--mem={opt.mem}")
    if opt.time:
        d.append(f"--time={opt.time}")
    if opt.partition:
        d.append(f"--partition={opt.partition}")
    if opt.account:
        d.append(f"--account={opt.account}")
    return d + list(opt.extra)


def submit(store: Store, pending: list[Run], opt: SlurmOptions, sim: Path) -> tuple[list[str], str]:
    """Writes the chunks and scripts, submits the arrays and the merge job.

    Returns (array job ids, merge job id)."""
    check_options([("--out", str(store.root.resolve()))])
    earlier = still_queued(store)
    if earlier:
        raise SweepError(f"{store.root}: jobs of an earlier submission are still queued "
                         f"({', '.join(earlier)}): they run the same runs; wait for them (swarm-sweep status "
                         f"{store.root}) or scancel them, then rerun")
    stamp = time.strftime("%Y%m%d-%H%M%S")
    sub = store.root.resolve() / "slurm" / stamp
    n = 1
    while sub.exists():
        n += 1
        sub = store.root.resolve() / "slurm" / f"{stamp}-{n}"
    (sub / "logs").mkdir(parents=True)
    chunks = [[r.run_id for r in pending[i:i + opt.chunk_size]]
              for i in range(0, len(pending), opt.chunk_size)]
    atomic_write(sub / "chunks.json", json.dumps(chunks) + "\n")
    root = shlex.quote(str(store.root.resolve()))
    py = shlex.quote(sys.executable)
    worker = (f"{py} -m swarmtools.sweep worker {root} --chunks {shlex.quote(str(sub / 'chunks.json'))}"
              f" --sim {shlex.quote(str(sim.resolve()))}")
    name = f"sweep-{store.load_plan()['name']}"
    per_array = max(1, max_array_size() - 1)
    arrays = []
    for a, first in enumerate(range(0, len(chunks), per_array)):
        count = min(per_array, len(chunks) - first)
        throttle = f"%{opt.max_parallel}" if opt.max_parallel else ""
        script = sub / f"array_{a}.sh"
        lines = ["#!/bin/bash",
                 *(f"#SBATCH {d}" for d in _directives(opt, name, str(sub / "logs" / "%A_%a.out"))),
                 f"#SBATCH --array=0-{count - 1}{throttle}",
                 "# swarm-sweep: array task i runs chunk i + OFFSET of chunks.json",
                 "set -eu",
                 f"exec {worker} --index $((SLURM_ARRAY_TASK_ID + {first}))", ""]
        atomic_write(script, "\n".join(lines))
        arrays.append(_sbatch([str(script)]))
    py_merge = f"{py} -m swarmtools.sweep merge {root}"
    merge = _sbatch([*_directives(SlurmOptions(partition=opt.partition, account=opt.account,
                                               time=opt.time, extra=opt.extra),
                                  f"{name}-merge", str(sub / "logs" / "merge_%j.out")),
                     f"--dependency=afterany:{':'.join(arrays)}", f"--wrap={py_merge}"])
    atomic_write(sub / "jobs.json", json.dumps({"arrays": arrays, "merge": merge,
                                                "chunks": len(chunks)}) + "\n")
    return arrays, merge


def still_queued(store: Store) -> list[str]:
    """The jobs of this folder's earlier submissions (slurm/*/jobs.json)
    that squeue still lists."""
    ids = []
    for f in sorted((store.root / "slurm").glob("*/jobs.json")):
        try:
            doc = json.loads(f.read_text())
            ids += [*doc["arrays"], doc["merge"]]
        except (OSError, ValueError, KeyError, TypeError):
            continue
    return [j for j in ids if queued([j])] if ids else []


def queued(job_ids: list[str]) -> dict[str, int]:
    """Tasks of these jobs still in the queue, by state (squeue)."""
    try:
        p = subprocess.run(["squeue", "-h", "-r", "-j", ",".join(job_ids), "-o", "%T"],
                           capture_output=True, text=True, timeout=60, check=False)
    except (OSError, subprocess.SubprocessError) as e:
        raise SweepError(f"squeue: {e}") from None
    if p.returncode != 0:
        # squeue fails on ids that have left the queue altogether
        if "Invalid job id" in p.stderr:
            return {}
        raise SweepError(f"squeue failed: {p.stderr.strip()}")
    states: dict[str, int] = {}
    for s in p.stdout.split():
        states[s] = states.get(s, 0) + 1
    return states


def follow(store: Store, runs: list[Run], arrays: list[str], merge: str, progress: Progress,
           max_attempts: int, poll_s: float) -> None:
    """Waits until every job has left the queue, printing progress."""
    jobs = [*arrays, merge]
    before = progress.ok
    while True:
        states = queued(jobs)
        _, ok, dead = store.pending(runs, max_attempts)
        failed_now = sum(1 for r in runs if (rec := store.record(r.run_id)) and rec.get("status") != "ok")
        progress.ok, progress.failed = ok, failed_now
        progress.new = max(0, ok + failed_now - before)
        q = ", ".join(f"{v} {k.lower()}" for k, v in sorted(states.items())) or "none queued"
        progress.stream.write(f"{progress.line()}; slurm tasks: {q}\n")
        progress.stream.flush()
        if not states:
            return
        time.sleep(poll_s)


