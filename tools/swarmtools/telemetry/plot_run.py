"""PNG figures of a run from its LCM log, whatever its controllers and tasks.

    swarm-plot out/run/run_1/telemetry.lcmlog -o out/run/run_1/plots
    (or .venv/bin/python -m swarmtools.telemetry.plot_run ...)

writes
  robots_by_state.png      robots in each controller state over time (SWARM_STATE;
                           from the robots' own states when there is none)
  swarm_values.png         every value of the swarm schema (but step and time_s,
                           the time axis) over time, one panel each
                           (swarm_values_2.png, ... past 12 panels)
  events.png               cumulative events of each kind (SWARM_EVENT; log scale)
  controller_<name>.png    per controller: the mean over its robots of each of
                           its values over time, with their range (ROBOT_STATE)
  bridge.png               the serial bridge's counters per device over time:
                           frames, bytes, each kind of error, reconnects, link
                           up or down (BRIDGE_STATUS)
named by the schemas on TELEMETRY_SCHEMA: any log with them (a
simulation's, or lcm-logger's of real robots behind the bridge).  A log
without the simulation's RUN_INFO and SWARM_STATE is of real robots, whose
clocks start at their own power-on: their states and events, and the
bridge's status, are then drawn on the log's clock (when the logger got
them).  --prefix
plots channels published with a prefix instead (the bridge's --prefix; FW_
for the robots' own telemetry in a simulation with robot_telemetry.enabled).
"""
import argparse
import collections
import math
import os
import re
import sys
from dataclasses import dataclass, field

from swarmtools.telemetry import common

PROG = "swarm-plot"
PANELS_PER_FIGURE = 12


@dataclass
class Figure:
    """A PNG written: its path, title and the names of what its panels
    (or series) show."""
    path: str
    title: str
    series: list = field(default_factory=list)


@dataclass
class Run:
    """What the plots need from a log (one run)."""
    info: object = None
    summary: object = None
    swarm: list = field(default_factory=list)           # swarm_state_t
    events: list = field(default_factory=list)          # event_t
    robots: dict = field(default_factory=dict)          # controller -> [robot_state_t]
    bridge: list = field(default_factory=list)          # (s since the log began, bridge_status_t)
    schemas: common.Schemas = field(default_factory=common.Schemas)
    run: int = None
    time_label: str = "time (s)"


#: The x axis of the robots' figures when they are put on the log's clock.
LOG_CLOCK = "time since the log began (s, the logger's clock)"


def read_log(path, run=None, prefix=""):
    """The messages of one run on the channels with `prefix` of a log (the
    run --run chose; the only one there is, else an error).

    Without the simulation's RUN_INFO and SWARM_STATE the robots are real:
    each stamps its messages with its own clock, from its own power-on, so
    their states and events are put on the log's clock instead (when the
    logger received them, from the log's first message), as the bridge's
    status is."""
    r = Run()
    runs = []
    first = None
    received = {}                # id(message) -> us since the log began
    for ev, msg in common.read_log(path, PROG):
        if first is None:
            first = ev.timestamp     # the log began (whatever its first message)
        ours = common.split_channel(ev.channel)
        if msg is None or ours is None or ours[0] != prefix:
            continue
        kind = type(msg).__name__
        if kind == "schema_t":
            r.schemas.add(msg)
            continue
        if kind == "bridge_status_t":
            r.bridge.append(((ev.timestamp - first) / 1e6, msg))     # the bridge's, not a run's
            continue
        mrun = getattr(msg, "run", None)
        if run is not None and mrun != run:
            continue
        if mrun not in runs:
            runs.append(mrun)
        if kind == "swarm_state_t":
            r.swarm.append(msg)
        elif kind == "event_t":
            r.events.append(msg)
            received[id(msg)] = ev.timestamp - first
        elif kind == "robot_state_t":
            r.robots.setdefault(msg.controller, []).append(msg)
            received[id(msg)] = ev.timestamp - first
        elif kind == "run_info_t" and r.info is None:
            r.info = msg
        elif kind == "run_summary_t":
            r.summary = msg
    if len(runs) > 1:
        raise SystemExit(f"{PROG}: {path} holds several runs ({', '.join(map(str, runs))}): choose one with --run")
    r.run = runs[0] if runs else run
    if r.info is None and not r.swarm and received:
        for m in r.events + [m for ms in r.robots.values() for m in ms]:
            m.utime = received[id(m)]
        r.time_label = LOG_CLOCK
    return r


def title(info, what):
    if info is None:
        return what
    return f"{what}: {info.scenario}, seed {info.run}, {info.robots} robots"


def label(entry):
    return f"{entry.name} ({entry.unit})" if entry.unit else entry.name


def filename(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text) or "_"


def robot_bins(robots, bin_s):
    """Per time bin (robot clock, `bin_s` wide): each robot's latest state
    in it.  Returns [(bin time s, [robot_state_t])]."""
    bins = collections.OrderedDict()
    for m in sorted(robots, key=lambda m: m.utime):
        b = math.floor(m.utime / 1e6 / bin_s + 1e-9)
        bins.setdefault(b, {})[m.robot_id] = m
    return [(b * bin_s, list(ms.values())) for b, ms in bins.items()]


def robot_bin_s(info):
    hz = info.robot_state_hz if info is not None else 0.0
    return 1.0 / hz if hz > 0 else 1.0


def plot(path, out_dir, run=None, dpi=110, prefix=""):
    """Writes the figures; returns them (Figure)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    r = read_log(path, run, prefix)
    if not r.swarm and not r.events and not r.robots and not r.bridge:
        raise SystemExit(f"{PROG}: {path}: no {prefix}SWARM_STATE, {prefix}SWARM_EVENT, {prefix}ROBOT_STATE or "
                         f"{prefix}BRIDGE_STATUS messages" + (f" of run {run}" if run is not None else ""))
    os.makedirs(out_dir, exist_ok=True)
    written = []

    def save(fig, name, what, series):
        p = os.path.join(out_dir, name)
        fig.tight_layout()
        fig.savefig(p, dpi=dpi)
        plt.close(fig)
        written.append(Figure(p, what, list(series)))

    def grids(name, what, panels, draw, time_label=None):
        """Figures of up to PANELS_PER_FIGURE panels, three a row; panels
        are (name, label, data), draw(ax, data)."""
        for f0 in range(0, len(panels), PANELS_PER_FIGURE):
            part = panels[f0:f0 + PANELS_PER_FIGURE]
            cols = min(3, len(part))
            rows = math.ceil(len(part) / cols)
            fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 2.6 * rows + 0.6), squeeze=False,
                                     sharex=True)
            for ax, (_, lab, data) in zip(axes.flat, part, strict=False):
                draw(ax, data)
                ax.set_title(lab, fontsize="medium")
                ax.grid(alpha=0.3)
            for ax in axes.flat[len(part):]:
                ax.set_visible(False)
            for ax in axes[-1]:
                ax.set_xlabel(r.time_label if time_label is None else time_label)
            fig.suptitle(title(r.info, what))
            suffix = "" if f0 == 0 else f"_{f0 // PANELS_PER_FIGURE + 1}"
            save(fig, f"{name}{suffix}.png", what, [n for n, _, _ in part])

    # Robots by state.
    if r.swarm:
        t = [m.utime / 1e6 for m in r.swarm]
        names = []
        for m in r.swarm:
            names += [n for n in m.state_names if n not in names]
        counts = [dict(zip(m.state_names, m.state_counts, strict=True)) for m in r.swarm]
        total = max(m.robots for m in r.swarm)
    else:
        bins = robot_bins([m for ms in r.robots.values() for m in ms], robot_bin_s(r.info))
        t = [b for b, _ in bins]
        names = []
        for _, ms in bins:
            names += [n for n in dict.fromkeys(m.state for m in ms) if n not in names]   # robots in one state: once
        counts = [collections.Counter(m.state for m in ms) for _, ms in bins]
        total = max((len(ms) for _, ms in bins), default=1)
    if t and names:
        fig, ax = plt.subplots(figsize=(8, 4))
        ax.stackplot(t, *[[c.get(n, 0) for c in counts] for n in names], labels=names, alpha=0.85)
        ax.set_xlabel(r.time_label)
        ax.set_ylabel("robots")
        ax.set_title(title(r.info, "Robots by state"))
        ax.set_ylim(0, max(1, total))
        ax.legend(loc="upper right", fontsize="small", ncol=max(1, len(names) // 8))
        save(fig, "robots_by_state.png", "Robots by state", names)

    # Every swarm value.
    if r.swarm:
        t = [m.utime / 1e6 for m in r.swarm]
        schema = r.schemas.of(r.swarm[-1])
        n = max(len(m.values) for m in r.swarm)
        panels = []
        for k in range(n):
            e = schema.entry(k)
            if e.name in common.TIME_VALUES:
                continue
            ys = [m.values[k] if k < len(m.values) else math.nan for m in r.swarm]
            panels.append((e.name, label(e), (t, ys)))
        if panels:
            grids("swarm_values", "Swarm", panels, lambda ax, d: ax.plot(*d, color="tab:blue", linewidth=1))

    # Cumulative events by kind.
    if r.events:
        times = collections.OrderedDict()
        for e in sorted(r.events, key=lambda e: e.utime):
            times.setdefault(e.kind, []).append(e.utime / 1e6)
        end = max([e.utime / 1e6 for e in r.events] + [m.utime / 1e6 for m in r.swarm[-1:]])
        fig, ax = plt.subplots(figsize=(8, 4.5))
        for kind, ts in times.items():
            ax.step([0.0] + ts + [end], [0] + list(range(1, len(ts) + 1)) + [len(ts)], where="post",
                    label=f"{kind} ({len(ts)})")
        ax.set_xlabel(r.time_label)
        ax.set_ylabel("events so far")
        ax.set_yscale("symlog", linthresh=10)
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", fontsize="small", ncol=2)
        ax.set_title(title(r.info, "Events by kind"))
        save(fig, "events.png", "Events by kind", list(times))

    # Each controller's values: the mean over its robots, and their range.
    for ctrl, robots in r.robots.items():
        schema = r.schemas.of(robots[-1])
        n = max(len(m.values) for m in robots)
        if n == 0:
            continue
        bins = robot_bins(robots, robot_bin_s(r.info))
        t = [b for b, _ in bins]
        panels = []
        for k in range(n):
            mean, low, high = [], [], []
            for _, ms in bins:
                vs = [m.values[k] for m in ms if k < len(m.values) and not math.isnan(m.values[k])]
                mean.append(sum(vs) / len(vs) if vs else math.nan)
                low.append(min(vs) if vs else math.nan)
                high.append(max(vs) if vs else math.nan)
            e = schema.entry(k)
            panels.append((e.name, label(e), (t, mean, low, high)))

        def draw(ax, d):
            t, mean, low, high = d
            ax.fill_between(t, low, high, color="tab:blue", alpha=0.15, linewidth=0)
            ax.plot(t, mean, color="tab:blue", linewidth=1)

        count = len({m.robot_id for m in robots})
        grids(f"controller_{filename(ctrl)}", f"{ctrl or '(no controller)'}: mean of {count} robots (band: range)",
              panels, draw)

    # The bridge's counters: a panel per counter, a line per device.
    if r.bridge:
        panels = bridge_panels(r.bridge)

        def draw_devices(ax, lines):
            for name, (t, ys) in lines.items():
                ax.step(t, ys, where="post", linewidth=1, label=name)
            ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
            ax.set_ylim(bottom=0, top=max(1, max(max(ys) for _, ys in lines.values()) * 1.05))
            spec = ax.get_subplotspec()
            if spec.is_first_row() and spec.is_first_col():     # one legend: the devices are the same everywhere
                ax.legend(loc="upper left", fontsize="x-small")

        grids("bridge", "Serial bridge", panels, draw_devices, LOG_CLOCK)
    return written


#: bridge_device_t's counters, as the panels of bridge.png call them.
BRIDGE_COUNTERS = (("frames", "frames republished"), ("bytes", "bytes read"), ("crc_errors", "CRC errors"),
                   ("framing_errors", "framing errors"), ("oversize", "garbage runs"),
                   ("bad_payload", "bad payloads"), ("unknown_channel", "unknown channels"),
                   ("lost", "frames lost (sequence gaps)"), ("reconnects", "reconnects"),
                   ("connected", "link up (1) or down (0)"))


def bridge_panels(statuses):
    """(name, label, {device label: (t, values)}) for each counter of the
    devices in (t, bridge_status_t) pairs.  A device is labelled with the
    robot id it last had."""
    statuses = sorted(statuses, key=lambda p: p[0])
    names = {}
    for _, m in statuses:
        for d in m.devices:
            names[d.device] = d.device + (f" (robot {d.robot_id})" if d.robot_id >= 0 else "")
    panels = []
    for key, lab in BRIDGE_COUNTERS:
        series = {}
        for t, m in statuses:
            for d in m.devices:
                ts, ys = series.setdefault(d.device, ([], []))
                ts.append(t)
                ys.append(int(getattr(d, key)))
        panels.append((key, lab, {names[dev]: data for dev, data in series.items()}))
    return panels

def main(argv=None):
    ap = argparse.ArgumentParser(prog="swarm-plot", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    ap.add_argument("log", help="an LCM log (a run's telemetry.lcmlog, or lcm-logger's)")
    ap.add_argument("-o", "--out", help="folder for the PNGs (default: plots/ beside the log)")
    ap.add_argument("--run", type=int, help="only the run with this seed (a log of several runs)")
    ap.add_argument("--dpi", type=int, default=110)
    ap.add_argument("--prefix", default="",
                    help="plot the channels with this prefix (FW_: the robots' own telemetry in a simulation)")
    args = ap.parse_args(argv)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise SystemExit(f"{PROG}: matplotlib is missing: run with .venv/bin/python (`make deps`)") from None
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.log)), "plots")
    for f in plot(args.log, out, args.run, args.dpi, args.prefix):
        print(f.path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
