"""swarm-sweep: run a sweep file here or on a SLURM cluster.

    swarm-sweep run SWEEP.yaml [--out DIR] [--backend local|slurm] [--jobs N] ...
    swarm-sweep plan SWEEP.yaml            expand and check it; run nothing
    swarm-sweep status DIR                 how many runs are done, failed, left
    swarm-sweep merge DIR                  (re)write DIR/results.csv and .parquet
    swarm-sweep plot DIR --x KEY --y METRIC [--by KEY]   a figure from the table
    swarm-sweep worker DIR --chunks F --index I   one slurm array task (internal)

``run`` checks every combination with the simulator first, then runs what is
not yet done into DIR (default out/sweeps/<name>): rerunning the same command
skips finished runs and retries failed ones up to the sweep's max_attempts.

Exit status: 0 every run ok; 1 some runs failed (their records and the
table's ``error`` column say why); 2 a bad sweep file or argument; 130 or 143
interrupted (SIGINT, SIGTERM): finished runs are kept, rerun to resume.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import shutil
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from . import plan as planmod
from . import slurm
from .execute import Executor, Interrupted, Progress, cpus
from .plan import Run
from .spec import MAX_RUNS, Sweep, SweepError, load
from .store import FORMAT, Store

REPO_ROOT = Path(__file__).resolve().parents[3]


def code_version() -> str:
    """The checkout's code version, as swarmsim's summaries give it
    (tools/make/code_version.sh: git describe, and the diff's hash when the
    tree is dirty; "unknown" outside git)."""
    try:
        p = subprocess.run(["bash", str(REPO_ROOT / "tools" / "make" / "code_version.sh")],
                           capture_output=True, text=True, timeout=30, check=False)
        if p.returncode == 0 and p.stdout.strip():
            return p.stdout.strip()
    except OSError:
        pass
    return "unknown"


def default_sim() -> Path:
    return REPO_ROOT / "build" / "swarmsim"


def make_plan(sw: Sweep, runs: list[Run], backend: str) -> dict[str, Any]:
    return {
        "format": FORMAT, "name": sw.name, "sweep_file": str(sw.path),
        "sweep_sha256": planmod.file_sha256(sw.path) if sw.path.is_file() else "",
        "code_version": code_version(),
        "written": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "backend": backend, "varied": sw.varied_keys, "metrics": sw.metrics,
        "max_attempts": sw.max_attempts, "run_timeout": sw.run_timeout,
        "keep_timeseries": sw.keep_timeseries, "runs": [r.to_json() for r in runs],
    }


def plan_runs(plan: dict[str, Any]) -> list[Run]:
    return [Run.from_json(r) for r in plan["runs"]]


def prepare(sw: Sweep, out: Path, sim: Path, backend: str, jobs: int) -> tuple[Store, dict, list[Run]]:
    """Expand, check with the simulator, and open the sweep's folder."""
    runs = planmod.expand(sw)
    planmod.check_runs(sw, runs, sim, jobs)
    plan = make_plan(sw, runs, backend)
    store = Store(out)
    store.open_for(plan)
    return store, plan, runs


def merge(store: Store, plan: dict[str, Any]) -> dict[str, int]:
    return store.write_table(plan_runs(plan), plan["varied"], plan["metrics"])


def report(store: Store, counts: dict[str, int], quiet: bool) -> int:
    left = counts["runs"] - counts["rows"]
    if not quiet or counts["failed"]:
        print(f"swarm-sweep: {counts['ok']} of {counts['runs']} runs ok, {counts['failed']} failed"
              + (f", {left} not run" if left else "")
              + f"; table: {store.root / 'results.csv'} (and results.parquet)", file=sys.stderr)
    if counts["failed"]:
        print("swarm-sweep: the failed runs' errors are in the table's `error` column and in "
              f"{store.records}/", file=sys.stderr)
    return 1 if counts["failed"] or left else 0


# ------------------------------------------------------------------ commands
def cmd_run(a: argparse.Namespace) -> int:
    sim = Path(a.sim) if a.sim else default_sim()
    sw = load(a.sweep, planmod.seed_max(sim), a.max_runs)
    return run_sweep(sw, a, sim)


def freeze_simulator(store: Store, sim: Path) -> Path:
    """The sweep's own copy of the simulator, DIR/bin/swarmsim-<sha256 prefix>,
    which every run of this invocation uses: rebuilding build/swarmsim while
    a sweep runs (a `make` after a commit) then changes nothing under it, and
    every record's sim_sha256 names the binary that made it."""
    sha = planmod.file_sha256(sim)
    frozen = store.root / "bin" / f"swarmsim-{sha[:16]}"
    if not frozen.is_file() or planmod.file_sha256(frozen) != sha:
        frozen.parent.mkdir(parents=True, exist_ok=True)
        tmp = frozen.with_name(frozen.name + ".tmp")
        shutil.copy2(sim, tmp)
        tmp.chmod(0o755)
        tmp.replace(frozen)
    return frozen


def warn_other_simulator(store: Store, runs: list[Run], sim: Path) -> None:
    """Says when finished runs were made by another swarmsim binary: a resumed
    sweep then mixes two versions (a rebuild after any commit changes the
    binary, so this warns rather than refuses; the table's sim_sha256 and
    code_version columns tell the rows apart)."""
    if not sim.is_file():
        return
    current = planmod.file_sha256(sim)
    other = {}
    for r in runs:
        rec = store.record(r.run_id)
        if rec and rec.get("status") == "ok" and rec.get("sim_sha256") not in (None, "", current):
            other[rec.get("code_version", "?")] = other.get(rec.get("code_version", "?"), 0) + 1
    if other:
        which = ", ".join(f"{n} by {v}" for v, n in sorted(other.items()))
        print(f"swarm-sweep: warning: {sum(other.values())} finished runs in {store.root} were made by "
              f"another swarmsim ({which}); they are kept, not rerun. If the simulation changed, "
              "start again in a new --out.", file=sys.stderr)


def run_sweep(sw: Sweep, a: argparse.Namespace, sim: Path) -> int:
    """The body of `run`, also called by the studies with a sweep they built."""
    out = Path(a.out) if a.out else REPO_ROOT / "out" / "sweeps" / sw.name
    jobs = a.jobs or cpus()
    store, plan, runs = prepare(sw, out, sim, a.backend, jobs)
    sim = freeze_simulator(store, sim)
    todo, ok, dead = store.pending(runs, sw.max_attempts)
    warn_other_simulator(store, runs, sim)
    if not a.quiet:
        print(f"swarm-sweep: {sw.name}: {len(runs)} runs, {ok} already done, {dead} failed "
              f"for good, {len(todo)} to run ({a.backend}) in {out}", file=sys.stderr)
    progress = Progress(sw.name, len(runs), ok + dead) if not a.quiet else None
    if a.backend == "local":
        try:
            Executor(store, sim, plan, jobs, progress).run_all(todo)
        except Interrupted as e:
            counts = merge(store, plan)
            if progress:
                progress.end()
            print(f"swarm-sweep: interrupted by {e}: {counts['rows']} of {counts['runs']} runs "
                  f"recorded and tabled; rerun the same command to resume", file=sys.stderr)
            return 128 + e.signum
        if progress:
            progress.end()
        return report(store, merge(store, plan), a.quiet)
    opt = slurm.SlurmOptions(chunk_size=a.chunk_size, cpus_per_task=a.cpus_per_task, mem=a.mem,
                             time=a.time, partition=a.partition, account=a.account,
                             max_parallel=a.max_parallel, extra=a.sbatch_arg or [],
                             wait=not a.no_wait, poll_s=a.poll)
    if not todo:
        return report(store, merge(store, plan), a.quiet)
    arrays, merge_job = slurm.submit(store, todo, opt, sim)
    print(f"swarm-sweep: submitted array job(s) {', '.join(arrays)} ({-(-len(todo) // opt.chunk_size)} "
          f"tasks of up to {opt.chunk_size} runs) and merge job {merge_job}", file=sys.stderr)
    if not opt.wait:
        print(f"swarm-sweep: follow with `swarm-sweep status {out}`; rerun this command to resume",
              file=sys.stderr)
        return 0
    try:
        slurm.follow(store, runs, arrays, merge_job, progress or Progress(sw.name, len(runs), ok + dead),
                     sw.max_attempts, opt.poll_s)
    except KeyboardInterrupt:
        print(f"\nswarm-sweep: stopped following; the jobs go on (scancel {' '.join(arrays)} "
              f"{merge_job} stops them); `swarm-sweep status {out}` counts, rerunning this "
              "command resumes", file=sys.stderr)
        return 130
    return report(store, merge(store, plan), a.quiet)


def cmd_plan(a: argparse.Namespace) -> int:
    sim = Path(a.sim) if a.sim else default_sim()
    sw = load(a.sweep, planmod.seed_max(sim), a.max_runs)
    runs = planmod.expand(sw)
    planmod.check_runs(sw, runs, sim, a.jobs or cpus())
    cells = len(runs) // len(sw.seeds)
    print(f"{sw.name}: {cells} combinations x {len(sw.seeds)} seeds = {len(runs)} runs; all check")
    for r in runs[: a.show]:
        params = " ".join(f"{k}={v}" for k, v in r.params.items())
        print(f"  {r.index:>6} {r.run_id} seed {r.seed} {params}")
    if len(runs) > a.show:
        print(f"  ... {len(runs) - a.show} more")
    return 0


def cmd_status(a: argparse.Namespace) -> int:
    store = Store(Path(a.dir))
    plan = store.load_plan()
    runs = plan_runs(plan)
    todo, ok, dead = store.pending(runs, plan["max_attempts"])
    retry = sum(1 for r in todo if store.record(r.run_id))
    print(f"{plan['name']}: {len(runs)} runs: {ok} ok, {dead} failed for good, "
          f"{retry} failed to retry, {len(todo) - retry} not run")
    return 0


def cmd_merge(a: argparse.Namespace) -> int:
    store = Store(Path(a.dir))
    plan = store.load_plan()
    return report(store, merge(store, plan), a.quiet)


def cmd_plot(a: argparse.Namespace) -> int:
    from .figure import plot_metric
    store = Store(Path(a.dir))
    plan = store.load_plan()
    out = Path(a.out) if a.out else store.root / f"{a.y}_by_{a.x}.png"
    frozen = sorted((store.root / "bin").glob("swarmsim-*"))   # the sweep's own simulator documents its keys
    plot_metric(store.root / "results.parquet", a.x, a.y, a.by, out, title=plan["name"],
                sim=frozen[-1] if frozen else default_sim())
    print(f"swarm-sweep: wrote {out}")
    return 0


def cmd_worker(a: argparse.Namespace) -> int:
    store = Store(Path(a.dir))
    plan = store.load_plan()
    chunks = json.loads(Path(a.chunks).read_text())
    if not 0 <= a.index < len(chunks):
        raise SweepError(f"{a.chunks}: no chunk {a.index} (it has {len(chunks)})")
    by_id = {r.run_id: r for r in plan_runs(plan)}
    runs = [by_id[i] for i in chunks[a.index]]
    sim = Path(a.sim) if a.sim else default_sim()
    try:
        counts = Executor(store, sim, plan, a.jobs or cpus()).run_all(runs)
    except Interrupted as e:
        print(f"swarm-sweep worker: interrupted by {e}; unfinished runs are left for a rerun",
              file=sys.stderr)
        return 128 + e.signum
    print(f"swarm-sweep worker: chunk {a.index}: {counts['ok']} ok, {counts['failed']} failed")
    return 0


# --------------------------------------------------------------------- main
def add_run_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", help="sweep folder (default out/sweeps/<name>)")
    p.add_argument("--jobs", type=int, default=0, help="local: runs at a time (default: the CPUs)")
    p.add_argument("--sim", help="simulator binary (default build/swarmsim)")
    p.add_argument("--quiet", action="store_true")
    add_max_runs(p)
    add_backend_options(p)


def add_max_runs(p: argparse.ArgumentParser) -> None:
    p.add_argument("--max-runs", type=int, default=MAX_RUNS,
                   help="refuse a sweep of more runs than this (default %(default)s), counted before expanding it")


def add_backend_options(p: argparse.ArgumentParser) -> None:
    """--backend and the slurm backend's options (the studies take them too)."""
    p.add_argument("--backend", choices=("local", "slurm"), default="local")
    s = p.add_argument_group("slurm backend")
    s.add_argument("--chunk-size", type=int, default=10, help="runs per array task (default 10)")
    s.add_argument("--cpus-per-task", type=int, default=1, help="CPUs per array task; runs at a time")
    s.add_argument("--mem", help="memory per array task, as sbatch --mem takes it (e.g. 2G)")
    s.add_argument("--time", help="time limit per array task, as sbatch --time takes it (e.g. 01:00:00)")
    s.add_argument("--partition", help="sbatch --partition")
    s.add_argument("--account", help="sbatch --account")
    s.add_argument("--max-parallel", type=int, help="at most this many array tasks at once (%%N)")
    s.add_argument("--sbatch-arg", action="append", metavar="OPT",
                   help="another sbatch option, e.g. --sbatch-arg=--qos=short (repeatable)")
    s.add_argument("--no-wait", action="store_true", help="submit and return; do not follow the jobs")
    s.add_argument("--poll", type=float, default=5.0, help="seconds between squeue polls (default 5)")


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="swarm-sweep", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("run", help="run a sweep (resumes one started in the same --out)")
    p.add_argument("sweep")
    add_run_options(p)
    p = sub.add_parser("plan", help="expand and check a sweep; run nothing")
    p.add_argument("sweep")
    p.add_argument("--sim")
    p.add_argument("--jobs", type=int, default=0)
    p.add_argument("--show", type=int, default=10, help="runs to list (default 10)")
    add_max_runs(p)
    p = sub.add_parser("status", help="runs done, failed and left in a sweep folder")
    p.add_argument("dir")
    p = sub.add_parser("merge", help="write the table of a sweep folder")
    p.add_argument("dir")
    p.add_argument("--quiet", action="store_true")
    p = sub.add_parser("plot", help="a metric's mean and 95%% CI against a varied key")
    p.add_argument("dir")
    p.add_argument("--x", required=True, help="a varied key (the x axis)")
    p.add_argument("--y", required=True, help="a metric")
    p.add_argument("--by", help="another varied key: one line per value")
    p.add_argument("--out", help="PNG file (default DIR/<y>_by_<x>.png)")
    p = sub.add_parser("worker", help="run one chunk (a slurm array task)")
    p.add_argument("dir")
    p.add_argument("--chunks", required=True)
    p.add_argument("--index", type=int, required=True)
    p.add_argument("--sim")
    p.add_argument("--jobs", type=int, default=0)
    return ap


def check_args(a: argparse.Namespace) -> None:
    for name in ("jobs", "chunk_size", "cpus_per_task", "max_parallel", "max_runs"):
        v = getattr(a, name, None)
        if v is not None and v < (0 if name == "jobs" else 1):
            raise SweepError(f"--{name.replace('_', '-')} must be at least {0 if name == 'jobs' else 1}")
    slurm.check_options([(f"--{n.replace('_', '-')}", getattr(a, n, None))
                         for n in ("mem", "time", "partition", "account")]
                        + [("--sbatch-arg", v) for v in getattr(a, "sbatch_arg", None) or []])


def main(argv: Sequence[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        check_args(a)
        return {"run": cmd_run, "plan": cmd_plan, "status": cmd_status, "merge": cmd_merge,
                "plot": cmd_plot, "worker": cmd_worker}[a.cmd](a)
    except SweepError as e:
        print(f"swarm-sweep: {e}", file=sys.stderr)
        return e.exit_code
    except KeyboardInterrupt:
        print("swarm-sweep: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
