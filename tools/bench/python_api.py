#!/usr/bin/env python3
"""python_api.py - what stepping the simulator from Python costs over the
C loop: the same world, seed and steps through swarmtools.Sim (the public
C API in build/libswarmsim.so, through ctypes) and through a C program
that calls sim_step in a loop (tools/bench/api_loop.c, linked with the
same objects), each run in turn, medians over --runs.  Times are the
process's CPU time over the steps alone (the world's loading excluded),
which a machine shared with other work disturbs less than wall time.

Python is measured three ways per world: step(K) for K steps a call
(default 100), the same reading the robots' poses and states after each
call (what a script that watches the swarm does), and step(1), one call a
step.  Every way must end in the C loop's state hash.

    make bench-api                    # 20, 200 and 2,000 robots
    .venv/bin/python tools/bench/python_api.py --c-loop build/api_loop --robots 200 --runs 5

Prints a Markdown table (docs/development/benchmarks.md has its figures).
"""
import argparse
import math
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "tools" / "bench" / "bench_random_walk.yaml"
DENSITY = 1.25        # robots per m^2, as bench.sh


def world(n):
    side = f"{math.sqrt(n / DENSITY):.3f}"
    return [f"robots.0.count={n}", f"arena.width={side}", f"arena.height={side}"]


def c_loop(binary, n, steps, seed):
    out = subprocess.run([binary, str(SCENARIO), str(steps), str(seed), *world(n)], check=True,
                         capture_output=True, text=True).stdout.split()
    return float(out[3]), out[5]


def python_loop(n, steps, seed, per_call, read):
    import swarmtools
    with swarmtools.Sim(SCENARIO, seed=seed, overrides=world(n)) as sim:
        robots = sim.robots
        t0 = time.process_time()
        done = 0
        while done < steps:
            done += sim.step(min(per_call, steps - done))
            if read:
                _ = robots.x.sum() + robots.y.sum()
                _ = robots.state_codes()
        t1 = time.process_time()
        return t1 - t0, sim.state_hash


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--c-loop", default=str(ROOT / "build" / "api_loop"), help="the C loop program")
    ap.add_argument("--robots", type=int, action="append", help="robot counts (default 20, 200, 2000)")
    ap.add_argument("--steps", type=int, help="steps per run (default: 40,000 robot-steps x 30 / robots)")
    ap.add_argument("--per-call", type=int, default=100, help="steps per step() call (default %(default)s)")
    ap.add_argument("--runs", type=int, default=5, help="runs of each way, in turn (default %(default)s)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    counts = args.robots or [20, 200, 2000]
    ways = [("C loop", None), (f"step({args.per_call})", (args.per_call, False)),
            (f"step({args.per_call}) + poses, states", (args.per_call, True)), ("step(1)", (1, False))]
    print(f"| robots | steps | {' | '.join(w for w, _ in ways)} | overhead of step({args.per_call}) | "
          f"with poses, states | step(1) |")
    print("|---|---|" + "---|" * (len(ways) + 3))
    for n in counts:
        steps = args.steps or max(100, 1_200_000 // n)
        times = {w: [] for w, _ in ways}
        want = None
        for _ in range(args.runs):
            for w, spec in ways:
                if spec is None:
                    t, h = c_loop(args.c_loop, n, steps, args.seed)
                else:
                    t, h = python_loop(n, steps, args.seed, *spec)
                if want is None:
                    want = h
                if h != want:
                    sys.exit(f"python_api.py: {w} at {n} robots ended in state hash {h}, the C loop in {want}")
                times[w].append(t)
        med = {w: statistics.median(v) for w, v in times.items()}
        c = med["C loop"]
        cells = [f"{med[w] / steps * 1e6:.1f} us/step" for w, _ in ways]
        over = [f"{100 * (med[w] - c) / c:+.1f} %" for w, _ in ways[1:]]
        print(f"| {n:,} | {steps:,} | {' | '.join(cells)} | {' | '.join(over)} |", flush=True)
    print(f"\nmachine: {platform.processor() or platform.machine()}, {cpu_name()}, Python {platform.python_version()}; "
          f"medians of {args.runs} runs, each way in turn; every run ended in the C loop's state hash")


def cpu_name():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


if __name__ == "__main__":
    main()
