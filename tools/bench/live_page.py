#!/usr/bin/env python3
"""live_page.py - the live view's cost with many robots: a run of --robots
random walkers (a 20 x 20 m arena, every robot's state 10 times a simulated
second) replayed by swarm-live at 1x to --pages headless Chromium pages
(Debian's, as make live-tests drives it); for --seconds each page counts
its animation frames (requestAnimationFrame: the browser's own frame
timing) and times its arena drawing, while the server's CPU time is read
from /proc.

    .venv/bin/python tools/bench/live_page.py --robots 2000 --pages 1
    .venv/bin/python tools/bench/live_page.py --robots 2000 --pages 2

Prints one Markdown row: robots, pages, frames per second (median over the
pages of each page's frames / seconds, and the slowest page's 95th-percentile
frame interval), the page's drawing time per frame (median, 95th
percentile), and the server's CPU seconds per wall second, in all and per
page.  docs/development/benchmarks.md has its figures.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from tools.tests.live.browser import Browser  # noqa: E402  the tests' headless Chromium
from tools.tests.live.serve import Server, wait_for  # noqa: E402

# Counts animation frames and times Arena.draw from now on.
MEASURE_JS = """
window.benchFrames = [];
window.benchDraws = [];
const draw = Arena.draw;
Arena.draw = function (...args) {
  const t0 = performance.now();
  const out = draw.apply(this, args);
  window.benchDraws.push(performance.now() - t0);
  return out;
};
const tick = (t) => { window.benchFrames.push(t); requestAnimationFrame(tick); };
requestAnimationFrame(tick);
"""


def cpu_s(pid):
    """User + system CPU seconds of a process so far (/proc/PID/stat)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def pct(values, q):
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))] if v else float("nan")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--robots", type=int, default=2000)
    ap.add_argument("--pages", type=int, default=1)
    ap.add_argument("--seconds", type=float, default=10.0, help="measured window (default %(default)s)")
    o = ap.parse_args(argv)
    steps = int(10 * (o.seconds + 10))          # the window, and time to load the pages
    with tempfile.TemporaryDirectory(prefix="live_bench.") as tmp:
        sim = ROOT / "build" / "swarmsim"
        subprocess.run([str(sim), str(ROOT / "sim_host/scenarios/random_walk.yaml"),
                        "--set", f"robots.0.count={o.robots}", "--set", "arena.width=20", "--set", "arena.height=20",
                        "--steps", str(steps), "--telemetry-rate", "10", "--out", tmp + "/run", "--quiet"],
                       check=True, cwd=ROOT)
        log = Path(tmp) / "run" / "run_1" / "telemetry.lcmlog"
        srv = Server("--log", log, "--speed", "1", "--paused", timeout=600)
        browsers = [Browser() for _ in range(o.pages)]
        try:
            for b in browsers:
                b.driver.get(srv.url)
                wait_for(lambda b=b: (s := b.driver.execute_script("return window.liveState")) and s["frames"] > 0,
                         "the page", timeout=600)
            for b in browsers:
                b.driver.execute_script("document.getElementById('play').click();")
            time.sleep(2.0)                      # playing: every page drawing all robots
            for b in browsers:
                b.driver.execute_script(MEASURE_JS)
            c0, t0 = cpu_s(srv.proc.pid), time.monotonic()
            time.sleep(o.seconds)
            cpu = (cpu_s(srv.proc.pid) - c0) / (time.monotonic() - t0)
            fps, slow, draws = [], [], []
            for b in browsers:
                frames = b.driver.execute_script("return window.benchFrames")
                draws += b.driver.execute_script("return window.benchDraws")
                gaps = [y - x for x, y in zip(frames, frames[1:], strict=False)]
                fps.append(1000 * len(gaps) / (frames[-1] - frames[0]) if len(frames) > 1 else 0.0)
                slow.append(pct(gaps, 0.95))
                placed = len(b.driver.execute_script("return window.liveState.placed"))
            print("| robots drawn | pages | frames/s (median page) | slowest page's p95 frame interval, ms "
                  "| draw ms per frame (median, p95) | server CPU s/s (per page) |")
            print("|---|---|---|---|---|---|")
            print(f"| {placed:,} | {o.pages} | {statistics.median(fps):.1f} | {max(slow):.1f} | "
                  f"{statistics.median(draws):.1f}, {pct(draws, 0.95):.1f} | {cpu:.2f} ({cpu / o.pages:.2f}) |")
        finally:
            for b in browsers:
                b.quit()
            srv.stop()


if __name__ == "__main__":
    sys.exit(main())
