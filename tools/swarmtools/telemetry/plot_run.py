#!/usr/bin/env python3
"""PNG figures of a run from its LCM log.

    plot_run.py out/run/run_1/telemetry.lcmlog -o out/run/run_1/plots

writes
  food_level.png       nest food F(t) with F_d, and the nest beacon's own F(t)
                       when there is one (foraging runs)
  robots_by_state.png  robots waiting / searching / returning over time
                       (foraging), or by controller state (any controller)
  oae.png              obstacle-avoidance events: the total, and per 10 s
  events.png           pick-ups, deposits and failures over time (when any)
from SWARM_STATE and SWARM_EVENT (any log with them: a simulation's, or
lcm-logger's of real robots behind the bridge).  Needs matplotlib
(`make telemetry-deps`).
"""
import argparse
import collections
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

EVENT_WINDOW_S = 10.0


def read_log(path, run=None):
    """SWARM_STATE rows, events, the run info and summary of a log."""
    lcm = common.lcm_module()
    common.swarmlcm()
    try:
        log = lcm.EventLog(path, "r")
    except (IOError, OSError) as e:
        raise SystemExit(f"plot_run: {path}: {e}") from None
    swarm, events, info, summary = [], [], None, None
    for ev in log:
        msg = common.decode(ev.data)
        if msg is None:
            continue
        if run is not None and getattr(msg, "run", run) != run:
            continue
        kind = type(msg).__name__
        if kind == "swarm_state_t":
            swarm.append(msg)
        elif kind == "event_t":
            events.append(msg)
        elif kind == "run_info_t" and info is None:
            info = msg
        elif kind == "run_summary_t":
            summary = msg
    log.close()
    return swarm, events, info, summary


def title(info, what):
    if info is None:
        return what
    pol = f" {info.policy.upper()}" if info.policy else ""
    return f"{what}: {info.scenario}, seed {info.run},{pol} {info.robots} robots"


def plot(path, out_dir, run=None, dpi=110):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    swarm, events, info, summary = read_log(path, run)
    if not swarm and not events:
        raise SystemExit(f"plot_run: {path}: no SWARM_STATE or SWARM_EVENT messages")
    os.makedirs(out_dir, exist_ok=True)
    written = []

    def save(fig, name):
        p = os.path.join(out_dir, name)
        fig.tight_layout()
        fig.savefig(p, dpi=dpi)
        plt.close(fig)
        written.append(p)

    t = [m.time_s for m in swarm]
    foraging = bool(swarm) and swarm[-1].foraging

    if foraging:
        fig, ax = plt.subplots(figsize=(8, 4))
        ax.plot(t, [m.food_nest for m in swarm], label="F(t), nest food (ground truth)", color="tab:green")
        ax.axhline(swarm[-1].food_desired, color="tab:red", linestyle="--", label="F_d, desired")
        if swarm[-1].beacon:
            ax.plot(t, [m.beacon_food for m in swarm], label="the nest beacon's F(t)", color="tab:olive",
                    linewidth=0.8, alpha=0.8)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("food in the nest (tokens)")
        ax.set_title(title(info, "Nest food"))
        ax.legend(loc="best", fontsize="small")
        ax.grid(alpha=0.3)
        save(fig, "food_level.png")

    if swarm:
        fig, ax = plt.subplots(figsize=(8, 4))
        if foraging:
            series = [("waiting (S_W)", [m.waiting for m in swarm]),
                      ("searching (S_S)", [m.searching for m in swarm]),
                      ("returning (S_R)", [m.returning for m in swarm])]
        else:
            names = []
            for m in swarm:
                for n in m.state_names:
                    if n not in names:
                        names.append(n)
            series = []
            for n in names:
                series.append((n, [dict(zip(m.state_names, m.state_counts)).get(n, 0) for m in swarm]))
        ax.stackplot(t, *[s for _, s in series], labels=[n for n, _ in series], alpha=0.85)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("robots")
        ax.set_title(title(info, "Robots by state"))
        ax.set_ylim(0, max(1, swarm[-1].robots))
        ax.legend(loc="upper right", fontsize="small")
        save(fig, "robots_by_state.png")

        fig, ax = plt.subplots(figsize=(8, 4))
        ax.plot(t, [m.oae_total for m in swarm], color="tab:purple", label="total OAEs (M_T so far)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("obstacle-avoidance events")
        ax.grid(alpha=0.3)
        oae_t = [e.utime / 1e6 for e in events if e.kind == 3]
        if oae_t:
            ax2 = ax.twinx()
            end = max(t[-1], oae_t[-1])
            bins = max(1, int(math.ceil(end / EVENT_WINDOW_S)))
            ax2.hist(oae_t, bins=bins, range=(0, bins * EVENT_WINDOW_S), color="tab:orange", alpha=0.35,
                     label=f"OAEs per {EVENT_WINDOW_S:g} s")
            ax2.set_ylabel(f"OAEs per {EVENT_WINDOW_S:g} s")
            ax.set_zorder(ax2.get_zorder() + 1)    # the total over the bars
            ax.patch.set_visible(False)
            h1, l1 = ax.get_legend_handles_labels()
            h2, l2 = ax2.get_legend_handles_labels()
            ax.legend(h1 + h2, l1 + l2, loc="upper left", fontsize="small")
        else:
            ax.legend(loc="upper left", fontsize="small")
        ax.set_title(title(info, "Obstacle avoidance"))
        save(fig, "oae.png")

    counts = collections.Counter(e.kind for e in events if e.kind in (1, 2, 4))
    if counts:
        fig, ax = plt.subplots(figsize=(8, 3.5))
        rows = [(1, "pick-ups", "tab:blue"), (2, "deposits", "tab:green"), (4, "failures", "tab:red")]
        for y, (kind, label, colour) in enumerate(rows):
            xs = [e.utime / 1e6 for e in events if e.kind == kind]
            ax.scatter(xs, [y] * len(xs), marker="|", s=200, color=colour, label=f"{label} ({len(xs)})")
        ax.set_yticks(range(len(rows)), [r[1] for r in rows])
        ax.set_ylim(-0.6, len(rows) - 0.4)
        ax.set_xlabel("time (s)")
        ax.set_title(title(info, "Events"))
        ax.legend(loc="upper left", fontsize="small", ncol=3)
        ax.grid(axis="x", alpha=0.3)
        save(fig, "events.png")
    return written


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("log", help="an LCM log (a run's telemetry.lcmlog, or lcm-logger's)")
    ap.add_argument("-o", "--out", help="folder for the PNGs (default: plots/ beside the log)")
    ap.add_argument("--run", type=int, help="only the run with this seed (a log of several runs)")
    ap.add_argument("--dpi", type=int, default=110)
    args = ap.parse_args(argv)
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.log)), "plots")
    for p in plot(args.log, out, args.run, args.dpi):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
