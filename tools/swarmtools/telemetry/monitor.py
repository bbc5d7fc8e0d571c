#!/usr/bin/env python3
"""Live terminal dashboard of a swarm from LCM telemetry.

Shows what is running (RUN_INFO), the swarm and the nest (SWARM_STATE: time,
nest food against F_d, robots by state, k, M_A, OAEs, the nest beacon's own
estimates), one line per robot (ROBOT_STATE: state, task letter, theta,
P_s, S, n, energy, OAEs, deposits, what it carries, sensors, pose), the
latest events (SWARM_EVENT), the run's summary at its end (RUN_SUMMARY) and
the serial bridge's counters (BRIDGE_STATUS).  The same for a simulation
and for real robots behind tools/telemetry/bridge.py.

    .venv/bin/python tools/telemetry/monitor.py                    # LCM's default udpm bus
    .venv/bin/python tools/telemetry/monitor.py --lcm 'udpm://239.255.76.67:7667?ttl=0'
    .venv/bin/python tools/telemetry/monitor.py --log out/run/run_1/telemetry.lcmlog --plain

Keys: q quits; up/down, PgUp/PgDn scroll the robot table.  --plain prints
the dashboard as text every --interval seconds instead (no terminal needed).
"""
import argparse
import collections
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402


def fmt(v, spec="{:.2f}", none="-"):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return none
    return spec.format(v)


def bar(frac, width):
    frac = 0.0 if frac is None or math.isnan(frac) else min(max(frac, 0.0), 1.0)
    full = int(round(frac * width))
    return "[" + "#" * full + "." * (width - full) + "]"


class Model:
    """What the dashboard knows: the latest message of each kind."""

    def __init__(self, run=None, events=12, clock=time.monotonic):
        self.run_filter = run
        self.clock = clock
        self.info = None
        self.swarm = None
        self.summary = None
        self.bridge = None
        self.robots = {}             # robot id -> (robot_state_t, receive time)
        self.events = collections.deque(maxlen=events)
        self.messages = 0
        self.undecodable = 0
        self.run = None
        self.by_channel = collections.Counter()
        self._rate = collections.deque()

    def _follow(self, msg):
        """True if `msg` belongs to the run shown: the one --run chose, or
        the latest whose RUN_INFO or SWARM_STATE came (a new run clears the
        view).  Real robots' messages carry run 0."""
        run = getattr(msg, "run", None)
        if run is None:
            return True
        if self.run_filter is not None:
            return run == self.run_filter
        if self.run is None:
            self.run = run
        elif run != self.run and type(msg).__name__ in ("run_info_t", "swarm_state_t"):
            self.run = run
            self.robots.clear()
            self.events.clear()
            self.summary = self.swarm = self.info = None
        return run == self.run

    def add(self, channel, data):
        now = self.clock()
        self.messages += 1
        self.by_channel[channel] += 1
        self._rate.append(now)
        while self._rate and now - self._rate[0] > 2.0:
            self._rate.popleft()
        msg = common.decode(data)
        if msg is None:
            self.undecodable += 1
            return None
        kind = type(msg).__name__
        if kind == "bridge_status_t":
            self.bridge = msg
            return msg
        if not self._follow(msg):
            return msg
        if kind == "run_info_t":
            self.info = msg
        elif kind == "swarm_state_t":
            self.swarm = msg
        elif kind == "robot_state_t":
            self.robots[msg.robot_id] = (msg, now)
        elif kind == "event_t":
            self.events.append(msg)
        elif kind == "run_summary_t":
            self.summary = msg
        return msg

    def rate(self):
        if len(self._rate) < 2:
            return 0.0
        span = self._rate[-1] - self._rate[0]
        return (len(self._rate) - 1) / span if span > 0 else 0.0

    # ---------------------------------------------------------------- render

    def header(self, source, width):
        lines = [f"swarm monitor  {source}   {self.messages} messages, {self.rate():.0f}/s"]
        i = self.info
        if i is not None:
            pol = f"/{i.policy}" if i.policy else ""
            beacon = " + nest beacon" if i.beacon else ""
            lines.append(f"run {i.scenario} seed {i.run}: {i.controller}{pol}, {i.robots} robots{beacon}, "
                         f"{i.control_period_ms} ms steps, arena {i.arena_width:g} x {i.arena_height:g} m")
        s = self.swarm
        if s is not None:
            total = i.steps if i is not None else 0
            prog = f" of {total} ({100.0 * s.step / total:.0f} %)" if total else ""
            lines.append(f"t = {s.time_s:8.1f} s   step {s.step}{prog}")
            if s.foraging:
                fd = s.food_desired
                lines.append(f"nest food F(t) {fmt(s.food_nest):>7} / F_d {fmt(fd, '{:.1f}')} "
                             f"{bar(s.food_nest / fd if fd else float('nan'), 20)}   collected {s.food_collected}"
                             f"   dropped {s.food_dropped}")
                lines.append(f"robots  waiting {s.waiting:3d}  searching {s.searching:3d}  returning {s.returning:3d}"
                             f"   k {fmt(s.k)} robots/m^2   M_A {fmt(s.mean_oae)}   OAEs {s.oae_total}")
                if s.beacon:
                    lines.append(f"beacon  F {fmt(s.beacon_food)}   N_W {s.beacon_waiting}   M_A {fmt(s.beacon_mean_oae)}")
            else:
                lines.append(f"OAEs {s.oae_total}   contacts {s.robot_contacts} robot, {s.static_contacts} static"
                             f"   distance {s.distance_m:.1f} m")
            states = "  ".join(f"{n} {c}" for n, c in zip(s.state_names, s.state_counts))
            lines.append(f"states  {states}")
        elif not self.robots:
            lines.append("waiting for messages ...")
        return [ln[:width] for ln in lines]

    ROBOT_HEAD = (" id  controller   state    T   theta    P_s      S  n  energy   OAE  dep  item  ir(max) "
                  "ambient blobs      x       y   theta  seen")

    def robot_lines(self, width):
        now = self.clock()
        out = []
        for rid in sorted(self.robots):
            m, t = self.robots[rid]
            item = "-" if m.carried_item == -1 else ("?" if m.carried_item < -1 else str(m.carried_item))
            if m.carrying and item == "-":
                item = "yes"
            ir = f"{m.ir_max}@{m.ir_max_index}" if m.ir_max >= 0 else "-"
            pose = (f"{m.x:7.2f} {m.y:7.2f} {m.theta:7.2f}" if m.pose_known else f"{'-':>7} {'-':>7} {'-':>7}")
            out.append(f"{m.robot_id:3d}  {m.controller[:11]:11s} {m.state[:8]:8s} {common.task_letter(m.task_state) or '-':1s} "
                       f"{fmt(m.threshold):>7} {fmt(m.probability, '{:.3f}'):>6} {fmt(m.stimulus):>6} "
                       f"{m.response_n if m.response_n else '-':>2} {fmt(m.energy):>7} {m.oae_count:5d} {m.deposits:4d} "
                       f"{item:>5} {ir:>8} {m.ambient_min if m.ambient_min >= 0 else '-':>7} "
                       f"{m.blobs if m.blobs >= 0 else '-':>5} {pose} {now - t:4.1f}s"[:width])
        return out

    def footer(self, width):
        lines = []
        if self.events:
            lines.append("events (latest last):")
            for e in self.events:
                kind = common.EVENT_KINDS.get(e.kind, str(e.kind))
                what = {"pickup": f"picked up token {e.value}", "deposit": f"deposited token {e.value}",
                        "oae": f"obstacle avoidance #{e.value}", "failure": f"FAILURE {e.detail}",
                        "state_change": e.detail}.get(kind, f"{kind} {e.detail} {e.value}")
                lines.append(f"  {e.utime / 1e6:9.1f} s  robot {e.robot_id:3d}  {what}")
        if self.summary is not None:
            m = self.summary
            lines.append(f"run finished after {m.steps} steps (state {m.state_hash}):")
            line = " "
            for n, v in zip(m.metric_names, m.metric_values):
                item = f" {n} {v:.6g}"
                if len(line) + len(item) > width and line.strip():
                    lines.append(line)
                    line = " "
                line += item
            lines.append(line)
        if self.bridge is not None:
            for d in self.bridge.devices:
                lines.append(f"bridge {d.device} robot {d.robot_id}: {'up' if d.connected else 'DOWN'}  "
                             f"frames {d.frames}  crc {d.crc_errors}  framing {d.framing_errors}  "
                             f"garbage {d.oversize}  bad payload {d.bad_payload}  lost {d.lost}  "
                             f"reconnects {d.reconnects}")
        if self.undecodable:
            lines.append(f"{self.undecodable} messages of unknown types")
        return [ln[:width] for ln in lines]

    def render(self, source="", width=160, height=None, scroll=0):
        """The dashboard as lines of text, fitted to width x height."""
        head = self.header(source, width)
        foot = self.footer(width)
        robots = self.robot_lines(width)
        table = [self.ROBOT_HEAD[:width]] if robots else []
        if height is None:
            return head + [""] + table + robots + [""] + foot
        # The robot table keeps at least a few lines; the events give way.
        room = max(min(len(robots), 5), height - len(head) - len(foot) - 3)
        foot = foot[:max(0, height - len(head) - 3 - room)]
        scroll = max(0, min(scroll, max(0, len(robots) - room)))
        shown = robots[scroll:scroll + room]
        if len(robots) > room and room > 0:
            table = [f"{self.ROBOT_HEAD[:width - 30]}  ({scroll + 1}-{scroll + len(shown)} of {len(robots)})"[:width]]
        return (head + [""] + table + shown + [""] + foot)[:height]


def open_bus(args):
    lcm = common.lcm_module()
    if args.log:
        path = os.path.abspath(args.log)
        if not os.path.exists(path):
            raise SystemExit(f"monitor: {args.log}: no such file")
        url = f"file://{path}?speed={args.speed:g}"
    else:
        url = args.lcm
    try:
        return lcm.LCM(url), url
    except Exception as e:
        raise SystemExit(f"monitor: cannot open LCM URL {url!r}: {e}") from None


def handle(bus, timeout_ms, args):
    """Handles a message if one comes within the timeout: 1, else 0; None
    at the end of a log file (the log provider then reports an error)."""
    try:
        return bus.handle_timeout(timeout_ms)
    except OSError:
        if args.log:
            return None
        raise


def run_plain(bus, model, source, args):
    last_msg = time.monotonic()
    next_print = time.monotonic() + args.interval
    printed = False
    while True:
        got = handle(bus, 50, args)
        if got is None:
            break
        now = time.monotonic()
        if got > 0:
            last_msg = now
        if now >= next_print and not args.exit_idle:
            print("\n".join(model.render(source)), flush=True)
            print("-" * 40, flush=True)
            next_print = now + args.interval
            printed = True
        if args.exit_idle and now - last_msg >= args.exit_idle:
            break
    if args.exit_idle or not printed:
        print("\n".join(model.render(source)), flush=True)


def run_curses(bus, model, source, args):
    import curses

    ended = []

    def loop(scr):
        curses.curs_set(0)
        scr.nodelay(True)
        scroll = 0
        next_draw = 0.0
        last_msg = time.monotonic()
        while True:
            if ended:
                got = 0
                time.sleep(0.05)
            else:
                got = handle(bus, 30, args)
                if got is None:
                    ended.append(time.monotonic())   # end of the log: keep showing it
            if got:
                last_msg = time.monotonic()
            key = scr.getch()
            if key in (ord("q"), ord("Q"), 27):
                return
            height, width = scr.getmaxyx()
            page = max(1, height - 12)
            scroll = {curses.KEY_DOWN: scroll + 1, curses.KEY_UP: scroll - 1,
                      curses.KEY_NPAGE: scroll + page, curses.KEY_PPAGE: scroll - page}.get(key, scroll)
            scroll = max(0, min(scroll, max(0, len(model.robots) - 1)))
            now = time.monotonic()
            if args.exit_idle and now - last_msg >= args.exit_idle:
                return
            if now < next_draw:
                continue
            next_draw = now + 0.2
            scr.erase()
            for y, line in enumerate(model.render(source, width - 1, height - 1, scroll)):
                try:
                    scr.addnstr(y, 0, line, width - 1)
                except curses.error:
                    pass
            scr.refresh()

    curses.wrapper(loop)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--lcm", default=common.DEFAULT_URL, help="LCM URL to listen on (default %(default)s)")
    src.add_argument("--log", help="read an LCM log file instead (at --speed)")
    ap.add_argument("--speed", type=float, default=1.0,
                    help="with --log: replay speed, 1 = as recorded (simulated time), 0 = as fast as possible")
    ap.add_argument("--run", type=int, help="show only the run with this seed (default: the latest)")
    ap.add_argument("--plain", action="store_true", help="print text instead of a full-screen dashboard")
    ap.add_argument("--interval", type=float, default=2.0, help="--plain: seconds between prints")
    ap.add_argument("--exit-idle", type=float, default=0.0,
                    help="quit after this many seconds without a message (and, with --plain, print once then)")
    ap.add_argument("--events", type=int, default=10, help="events shown")
    args = ap.parse_args(argv)
    common.swarmlcm()   # fail early, with advice, when the types are missing
    bus, url = open_bus(args)
    model = Model(run=args.run, events=args.events)
    bus.subscribe(".*", model.add)
    source = args.log or url
    try:
        if args.plain or not sys.stdout.isatty():
            run_plain(bus, model, source, args)
        else:
            run_curses(bus, model, source, args)
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
