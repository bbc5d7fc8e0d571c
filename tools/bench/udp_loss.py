"""Live UDP telemetry: how many messages a listener misses.

Runs the simulator once into a log (what a run publishes, per channel),
then REPS times publishing the same run to udpm://239.255.76.67:PORT?ttl=0
(a random port, so that no other bus on the machine interferes) at
--realtime X while this process listens, and prints what it missed.

    .venv/bin/python tools/bench/udp_loss.py [--realtime 10] [--steps 12000] [--reps 3]
        [--listener lcm|tools] [--handler count|monitor|dashboard]

--listener lcm listens as any LCM program does by default (a subscription
queue of 30 messages, the kernel's default socket buffer); tools as the
swarm-* tools do (swarmtools.telemetry.bus).  --handler monitor decodes
each message into the monitor's model; dashboard also renders the
dashboard's text every 0.2 s, as swarm-monitor does between messages;
count only counts.  Exit status 0 (the figures are the output).
"""
import argparse
import collections
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from swarmtools.telemetry import bus, common, monitor

ROOT = Path(__file__).resolve().parents[2]


def published(sim, scenario, steps, tmp):
    """Messages per channel of the run, from its log."""
    subprocess.run([sim, scenario, "--steps", str(steps), "--out", str(tmp / "log"), "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    log = common.lcm_module().EventLog(str(tmp / "log" / "run_1" / "telemetry.lcmlog"), "r")
    return collections.Counter(ev.channel for ev in log)


def listen_once(args, tmp):
    """Channel -> messages heard while the simulator publishes the run live."""
    lcm = common.lcm_module()
    sim_url = f"udpm://239.255.76.67:{random.randint(20000, 60000)}?ttl=0"
    heard = collections.Counter()
    model = monitor.Model()
    next_draw = [0.0]

    def handler(channel, data):
        heard[channel] += 1
        if args.handler in ("monitor", "dashboard"):
            model.add(channel, data)
        if args.handler == "dashboard" and time.monotonic() >= next_draw[0]:
            model.render(sim_url, 160, 50)
            next_draw[0] = time.monotonic() + 0.2

    if args.listener == "tools":
        lc, _ = bus.open_listener(sim_url, "udp_loss")
        bus.subscribe(lc, ".*", handler)
    else:
        lc = lcm.LCM(sim_url)
        lc.subscribe(".*", handler)
    p = subprocess.Popen([args.sim, args.scenario, "--steps", str(args.steps), "--lcm", sim_url,
                          "--realtime", str(args.realtime), "--out", str(tmp / "live"), "--quiet"])
    last = time.monotonic()
    while p.poll() is None or time.monotonic() - last < 1.0:
        if lc.handle_timeout(100) > 0:
            last = time.monotonic()
    return heard


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sim", default=str(ROOT / "build" / "swarmsim"))
    ap.add_argument("--scenario", default=str(ROOT / "sim_host" / "scenarios" / "foraging_base.yaml"))
    ap.add_argument("--steps", type=int, default=12000)
    ap.add_argument("--realtime", type=float, default=10.0)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--listener", choices=("lcm", "tools"), default="lcm")
    ap.add_argument("--handler", choices=("count", "monitor", "dashboard"), default="count")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="udp_loss_") as d:
        tmp = Path(d)
        sent = published(args.sim, args.scenario, args.steps, tmp)
        total = sum(sent.values())
        print(f"{Path(args.scenario).name}, {args.steps} steps at --realtime {args.realtime:g}: {total} messages "
              f"({', '.join(f'{ch} {n}' for ch, n in sorted(sent.items()))}); listener {args.listener}, "
              f"handler {args.handler}", flush=True)
        all_lost, summaries_lost = [], 0
        for rep in range(args.reps):
            heard = listen_once(args, tmp)
            lost = {ch: n - heard[ch] for ch, n in sorted(sent.items()) if n != heard[ch]}
            summaries_lost += not heard["RUN_SUMMARY"]
            all_lost.append(sum(lost.values()))
            if args.reps <= 5 or lost:
                summary = "summary heard" if heard["RUN_SUMMARY"] else "SUMMARY LOST"
                print(f"  rep {rep + 1}: lost {all_lost[-1]} of {total} "
                      f"({', '.join(f'{ch} {n}' for ch, n in lost.items()) or 'none'}); {summary}", flush=True)
        print(f"  {args.reps} reps: lost {min(all_lost)} to {max(all_lost)} messages of {total} "
              f"({sum(all_lost)} in all); the summary lost in {summaries_lost} of {args.reps}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
