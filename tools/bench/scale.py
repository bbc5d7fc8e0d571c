"""Cost per robot-step from 20 to 100,000 robots, on 1 and 2 threads (issue 18).

Two worlds at constant density (1.25 robots per m^2, the default
scenario's; the arena's side sqrt(n / 1.25) m, 282.8 m at 100,000):

  rw  tools/bench/bench_random_walk.yaml: random walk, IR only, --lcm off
      (the reference the full-sensing target is a multiple of);
  fs  tools/bench/bench_full_sensing.yaml: seed 000's foraging world where
      every robot reads every sensor every step (forager_sense_all), with
      1.25 food tokens per m^2, --lcm off;
  fs+tel  the same with telemetry at its default (an LCM log: SWARM_STATE
      at the control rate, 10 Hz, every robot's ROBOT_STATE at 1 Hz).

Each world runs on each of --run-threads (swarmsim --run-threads: that
many threads inside the one run; 1 and 2 by default).  Each run is a
separate process.  The rates divide robot-steps by the
simulation's own span (creating the world to the last output, as
swarmsim's last line reports it) in wall time and in CPU time (user +
system, every thread): on a loaded machine the wall rate drops with the
load, the CPU rate much less.  Peak memory is the process's max RSS
(os.wait4); bytes per robot is that over the robot count.  Medians of
--runs runs (--runs-big at 100,000), the worlds taken in turn.

    python3 tools/bench/scale.py [--sim build/swarmsim] [--runs 5] [--runs-big 1]
        [--counts 20:3000,200:1500,2000:500,10000:300,100000:100] [--modes rw,fs,fs+tel]
        [--run-threads 1,2]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DENSITY = 1.25   # robots (and food tokens) per m^2
LINE = re.compile(r"in ([0-9.]+) s wall .*; ([0-9.]+) s CPU")
WORLDS = {
    "rw": ("tools/bench/bench_random_walk.yaml", False, False),
    "fs": ("tools/bench/bench_full_sensing.yaml", True, False),
    "fs+tel": ("tools/bench/bench_full_sensing.yaml", True, True),
}


def one_run(sim, mode, n, steps, threads, out):
    """(wall s, CPU s, max RSS bytes) of one run on `threads` threads."""
    scenario, tokens, telemetry = WORLDS[mode]
    side = f"{(n / DENSITY) ** 0.5:.3f}"
    cmd = [sim, str(ROOT / scenario), "--threads", "1", "--run-threads", str(threads), "--steps", str(steps),
           "--out", out, "--replace",
           "--set", f"robots.0.count={n}", "--set", f"arena.width={side}", "--set", f"arena.height={side}"]
    if tokens:
        cmd += ["--set", f"foraging.food_count={n}"]
    if not telemetry:
        cmd += ["--lcm", "off"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    m = LINE.search(err)
    if proc.returncode != 0 or not m:
        sys.exit(f"scale.py: {' '.join(cmd)} failed ({proc.returncode}):\n{err}")
    return float(m.group(1)), float(m.group(2)), usage.ru_maxrss * 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sim", default=str(ROOT / "build" / "swarmsim"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--runs-big", type=int, default=1, help="runs at 100,000 robots and more")
    ap.add_argument("--counts", default="20:3000,200:1500,2000:500,10000:300,100000:100",
                    help="robots:steps,...")
    ap.add_argument("--modes", default="rw,fs,fs+tel")
    ap.add_argument("--run-threads", default="1,2", help="threads inside a run, each in turn")
    a = ap.parse_args()
    modes = [(m, int(t)) for m in a.modes.split(",") for t in a.run_threads.split(",")]
    print(f"{'robots':>7} {'arena_m':>8} {'steps':>6} {'world':>7} {'thr':>3} {'runs':>4} {'wall_s':>8} {'cpu_s':>8} "
          f"{'Mrs/s_wall':>10} {'Mrs/s_cpu':>9} {'us/rs_cpu':>9} {'rtf_cpu':>8} {'maxrss_MB':>9} {'B/robot':>8}",
          flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for spec in a.counts.split(","):
            n, steps = (int(v) for v in spec.split(":"))
            runs = a.runs_big if n >= 100000 else a.runs
            got = {m: [] for m in modes}
            for r in range(runs):
                for m in modes:   # in turn: a load change hits every world alike
                    got[m].append(one_run(a.sim, m[0], n, steps, m[1], os.path.join(tmp, f"{m[0]}_{m[1]}_{n}_{r}")))
            for m in modes:
                wall = statistics.median(g[0] for g in got[m])
                cpu = statistics.median(g[1] for g in got[m])
                rss = statistics.median(g[2] for g in got[m])
                rs = n * steps
                print(f"{n:>7} {(n / DENSITY) ** 0.5:>8.1f} {steps:>6} {m[0]:>7} {m[1]:>3} {runs:>4} {wall:>8.3f} "
                      f"{cpu:>8.3f} "
                      f"{rs / wall / 1e6:>10.3f} {rs / cpu / 1e6:>9.3f} {cpu / rs * 1e6:>9.3f} "
                      f"{steps * 0.1 / cpu:>8.1f} {rss / 2**20:>9.1f} {rss / n:>8.0f}", flush=True)
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
