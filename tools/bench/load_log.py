#!/usr/bin/env python3
"""load_log.py - how fast a telemetry log reaches pandas: swarmtools.load_log
against the CSV way (swarm-export of the robots' channel, then
pandas.read_csv), on a log the simulator writes for the purpose (random
walkers, tools/bench/bench_random_walk.yaml, grown to about --mb
megabytes).  Each way runs in a process of its own, --runs times in turn;
the table gives the median wall time, the log's megabytes and robot rows
per second, and the process's peak memory (max RSS) against the log's size.

    make bench-load-log
    .venv/bin/python tools/bench/load_log.py --mb 100 --runs 3

Prints a Markdown table (docs/development/benchmarks.md has its figures).
"""
import argparse
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from python_api import cpu_name  # this folder: the machine line both benchmarks print

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "tools" / "bench" / "bench_random_walk.yaml"
BYTES_PER_ROBOT_STEP = 19.4        # what the scenario's log takes, measured: to size the run

# Each way prints its robot rows and its peak memory (its own or a child's, kB).
PEAK = ("import resource; print(max(resource.getrusage(w).ru_maxrss for w in "
        "(resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)))")
LOAD = "import sys, swarmtools; d = swarmtools.load_log(sys.argv[1]); print(len(d.robots)); " + PEAK
CSV = ("import sys, subprocess, pandas; subprocess.run([sys.argv[2], sys.argv[1], '--channel', 'ROBOT_STATE', "
       "'-o', sys.argv[3]], check=True); print(len(pandas.read_csv(sys.argv[3]))); " + PEAK)


def make_log(swarmsim, out, mb, robots):
    steps = max(100, int(mb * 1e6 / (BYTES_PER_ROBOT_STEP * robots)))
    side = f"{math.sqrt(robots / 1.25):.3f}"
    subprocess.run([swarmsim, str(SCENARIO), "--steps", str(steps), "--threads", "1", "--out", str(out),
                    "--set", f"robots.0.count={robots}", "--set", f"arena.width={side}",
                    "--set", f"arena.height={side}"], check=True, capture_output=True)
    return out / "run_1" / "telemetry.lcmlog"


def timed(code, *args):
    """(wall s, robot rows, peak memory in bytes) of python -c code."""
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code, *args], check=True, capture_output=True, text=True).stdout
    t = time.perf_counter() - t0
    rows, peak_kb = out.split()[-2:]
    return t, rows, int(peak_kb) * 1024      # ru_maxrss: kB on Linux


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--swarmsim", default=str(ROOT / "build" / "swarmsim"))
    ap.add_argument("--export", default=str(Path(sys.executable).parent / "swarm-export"))
    ap.add_argument("--mb", type=float, default=100.0, help="the log's size, MB (default %(default)s)")
    ap.add_argument("--robots", type=int, default=200, help="robots in the run (default %(default)s)")
    ap.add_argument("--runs", type=int, default=3, help="runs of each way (default %(default)s)")
    ap.add_argument("--no-csv", action="store_true", help="load_log alone")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        log = make_log(args.swarmsim, Path(tmp) / "out", args.mb, args.robots)
        size = os.path.getsize(log)
        ways = [("load_log", LOAD, (str(log),))]
        if not args.no_csv:
            ways.append(("swarm-export + read_csv", CSV, (str(log), args.export, str(Path(tmp) / "r.csv"))))
        print("| way | log, MB | robot rows | wall, s | MB/s | rows/s | peak memory / log size |")
        print("|---|---|---|---|---|---|---|")
        for name, code, extra in ways:
            walls, rss = [], 0
            rows = None
            for _ in range(args.runs):
                t, rows, peak = timed(code, *extra)
                walls.append(t)
                rss = max(rss, peak)
            wall = statistics.median(walls)
            print(f"| {name} | {size / 1e6:.1f} | {int(rows):,} | {wall:.1f} | {size / 1e6 / wall:.1f} | "
                  f"{int(rows) / wall:,.0f} | {rss / size:.2f} |", flush=True)
    print(f"\nmachine: {os.cpu_count()} cores, {cpu_name()}, Python {platform.python_version()}; medians of "
          f"{args.runs} runs; wall time of the whole process (Python's start and imports included); peak "
          f"memory: the way's largest process's max RSS")


if __name__ == "__main__":
    main()
