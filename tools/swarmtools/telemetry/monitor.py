"""Live terminal dashboard of a swarm from LCM telemetry.

Shows what is running (RUN_INFO: scenario, groups, tasks), the swarm
(SWARM_STATE: time, step, every value the swarm schema names, robots by
state), one table per controller with a line per robot (ROBOT_STATE: group,
state, wheels, sensors, pose, and the values the controller's schema names,
whatever the controller), the events of the run by kind and the latest of
them (SWARM_EVENT), the run's summary at its end (RUN_SUMMARY) and the
serial bridge's counters (BRIDGE_STATUS).  The same for a simulation and
for real robots behind the bridge (swarm-bridge); --prefix shows channels
published with a prefix instead (the bridge's --prefix; FW_ for the robots'
own telemetry in a simulation with robot_telemetry.enabled).

    swarm-monitor                                             # LCM's default udpm bus
    swarm-monitor --lcm 'udpm://239.255.76.67:7667?ttl=0'
    swarm-monitor --log out/run/run_1/telemetry.lcmlog --plain
    (or .venv/bin/python -m swarmtools.telemetry.monitor ...)

Keys: q quits; up/down, PgUp/PgDn scroll the robot tables.  --plain prints
the dashboard as text every --interval seconds instead (no terminal needed).
Listening live, the monitor asks for a 4 MiB socket buffer and a long LCM
queue (swarmtools.telemetry.bus) so that it keeps up with the simulator's
bursts.  Exit status: 0 (q, the end of a log, --exit-idle), 1 an error,
130 / 143 Ctrl-C / SIGTERM (the terminal restored, one line on stderr).
"""
import argparse
import collections
import os
import shlex
import shutil
import sys
import time

from swarmtools.telemetry import bus, common, stop

PROG = "swarm-monitor"
fmt = common.fmt_number


def wrap(items, width, indent="  ", first=""):
    """`first`, then `items` three spaces apart, in lines of at most
    `width` (None: one line); further lines start with `indent`."""
    lines, line, empty = [], first, True
    for item in items:
        if not empty and width is not None and len(line) + 3 + len(item) > width:
            lines.append(line)
            line, empty = indent, True
        line += item if empty else "   " + item
        empty = False
    if not empty:
        lines.append(line)
    return lines


def fit(lines, width):
    return lines if width is None else [ln[:width] for ln in lines]


class Model:
    """What the dashboard knows: the latest message of each kind, the
    schemas, the events of the run."""

    def __init__(self, run=None, events=12, clock=time.monotonic, prefix=""):
        self.run_filter = run
        self.prefix = prefix
        self.clock = clock
        self.info = None
        self.swarm = None
        self.summary = None
        self.bridge = None
        self.robots = {}             # robot id -> (robot_state_t, receive time)
        self.events = collections.deque(maxlen=events)
        self.event_counts = collections.Counter()
        self.schemas = common.Schemas()
        self.messages = 0
        self.undecodable = 0
        self.elsewhere = collections.Counter()   # channel -> messages not shown (another prefix, not ours)
        self.run = None
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
            self.event_counts.clear()
            self.summary = self.swarm = self.info = None
        return run == self.run

    def add(self, channel, data):
        """Takes one message (an LCM handler).  Raises
        common.IncompatibleMessage for one of another toolkit version."""
        now = self.clock()
        self.messages += 1
        self._rate.append(now)
        while self._rate and now - self._rate[0] > 2.0:
            self._rate.popleft()
        msg = common.decode(data, channel)
        if msg is None:
            self.undecodable += 1
            return None
        ours = common.split_channel(channel)
        if ours is None or ours[0] != self.prefix:
            self.elsewhere[channel] += 1
            return msg
        kind = type(msg).__name__
        if kind == "bridge_status_t":
            self.bridge = msg
            return msg
        if kind == "schema_t":
            self.schemas.add(msg)     # every run's: kept by run
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
            self.event_counts[msg.kind] += 1
        elif kind == "run_summary_t":
            self.summary = msg
        return msg

    def rate(self):
        if len(self._rate) < 2:
            return 0.0
        span = self._rate[-1] - self._rate[0]
        return (len(self._rate) - 1) / span if span > 0 else 0.0

    def states(self):
        """(state, robots) of the run: SWARM_STATE's, or counted from the
        robots' latest states when there is none (real robots)."""
        if self.swarm is not None:
            return list(zip(self.swarm.state_names, self.swarm.state_counts, strict=True))
        return list(collections.Counter(m.state for m, _ in self.robots.values()).items())

    # ---------------------------------------------------------------- render

    def header(self, source, width):
        lines = [f"swarm monitor  {source}   {self.messages} messages, {self.rate():.0f}/s"]
        i = self.info
        if i is not None:
            tasks = ", ".join(i.tasks) if i.tasks else "none"
            lines.append(f"run {i.scenario} seed {i.run}: {i.robots} robots, {i.control_period_ms} ms steps, "
                         f"arena {i.arena_width:g} x {i.arena_height:g} m, tasks: {tasks}")
            groups = [f"{n}: {c} x {ctrl}{'/' + pol if pol else ''}"
                      for n, ctrl, pol, c in zip(i.group_names, i.group_controllers, i.group_policies,
                                                 i.group_counts, strict=True)]
            lines += wrap(groups, width, indent="        ", first="groups  ")
        s = self.swarm
        if s is not None:
            total = i.steps if i is not None else 0
            prog = f" of {total} ({100.0 * s.step / total:.0f} %)" if total else ""
            lines.append(f"t = {s.utime / 1e6:8.1f} s   step {s.step}{prog}   {s.robots} robots")
            schema = self.schemas.of(s)
            items = []
            for k, v in enumerate(s.values):
                e = schema.entry(k)
                if e.name in common.TIME_VALUES:
                    continue
                items.append(f"{e.name} {fmt(v, e.counter)}{' ' + e.unit if e.unit else ''}")
            lines += wrap(items, width, indent="        ", first="swarm   ")
        elif self.robots:
            newest = max(m.utime for m, _ in self.robots.values())
            lines.append(f"t = {newest / 1e6:8.1f} s (robot clock)   {len(self.robots)} robots heard")
        else:
            lines.append("waiting for messages ...")
        states = self.states()
        if states:
            lines += wrap([f"{n} {c}" for n, c in states], width, indent="        ", first="states  ")
        return fit(lines, width)

    ROBOT_HEAD = (f"{'id':>3} {'group':11} {'state':10} {'wheels':>11} {'ir(max)':>8} {'amb':>5} {'blobs':>5} "
                  f"{'x':>6} {'y':>6} {'theta':>6} {'seen':>5}")

    def robot_line_count(self):
        """How many lines robot_lines gives, without building them: per
        controller a title, the column heads and a line per robot, and a
        blank line between tables."""
        if not self.robots:
            return 0
        controllers = {m.controller for m, _ in self.robots.values()}
        return len(self.robots) + 3 * len(controllers) - 1

    def robot_lines(self, width):
        """One table per controller (in order of their first robot): a
        title, the column heads, a line per robot."""
        now = self.clock()
        by_ctrl = {}
        for rid in sorted(self.robots):
            m, t = self.robots[rid]
            by_ctrl.setdefault(m.controller, []).append((m, t))
        out = []
        for ctrl, robots in by_ctrl.items():
            schema = self.schemas.of(robots[0][0])
            n = max(len(m.values) for m, _ in robots)
            entries = [schema.entry(k) for k in range(n)]
            widths = [max(6, min(len(e.name), 18)) for e in entries]
            if out:
                out.append("")
            out.append(f"{ctrl or '(no controller)'}: {len(robots)} robot{'s' if len(robots) != 1 else ''}"
                       + ("" if schema.complete and schema.total else "   (schema incomplete: value<k> not named yet)"
                          if n else ""))
            out.append(self.ROBOT_HEAD + "".join(f" {e.name[:w]:>{w}}" for e, w in zip(entries, widths, strict=True)))
            for m, t in robots:
                ir = f"{m.ir_max}@{m.ir_max_index}" if m.ir_max >= 0 else "-"
                pose = (f"{m.x:6.2f} {m.y:6.2f} {m.theta:6.2f}" if m.pose_known else f"{'-':>6} {'-':>6} {'-':>6}")
                line = (f"{m.robot_id:3d} {(m.group or '-')[:11]:11s} {m.state[:10]:10s} "
                        f"{m.wheel_left:>5}/{m.wheel_right:<5} {ir:>8} "
                        f"{m.ambient_min if m.ambient_min >= 0 else '-':>5} {m.blobs if m.blobs >= 0 else '-':>5} "
                        f"{pose} {now - t:4.1f}s")
                for k, w in enumerate(widths):
                    v = m.values[k] if k < len(m.values) else None
                    line += f" {fmt(v, entries[k].counter, '{:.4g}'):>{w}}"
                out.append(line)
        return fit(out, width)

    def event_text(self, e):
        words = [e.kind]
        if e.value:
            words.append(str(e.value))
        if e.detail:
            words.append(e.detail)
        return " ".join(words)

    def footer(self, width):
        lines = []
        if self.event_counts:
            lines += wrap([f"{k} {n}" for k, n in self.event_counts.most_common()], width, indent="        ",
                          first="events  ")
            lines.append("latest events (last at the bottom):")
            for e in self.events:
                lines.append(f"  {e.utime / 1e6:9.1f} s  robot {e.robot_id:3d}  {self.event_text(e)}")
        if self.summary is not None:
            m = self.summary
            lines.append(f"run finished after {m.steps} steps (state {m.state_hash}):")
            lines += wrap([f"{n} {v:.6g}" for n, v in zip(m.metric_names, m.metric_values, strict=True)], width, indent="  ",
                          first="  ")
        if self.bridge is not None:
            for d in self.bridge.devices:
                lines.append(f"bridge {d.device} robot {d.robot_id}: {'up' if d.connected else 'DOWN'}  "
                             f"frames {d.frames}  crc {d.crc_errors}  framing {d.framing_errors}  "
                             f"garbage {d.oversize}  bad payload {d.bad_payload}  lost {d.lost}  "
                             f"reconnects {d.reconnects}")
        if self.elsewhere:
            prefixes = sorted({common.split_channel(ch)[0] for ch in self.elsewhere if common.split_channel(ch)}
                              - {self.prefix})
            lines += wrap([f"{ch} {n}" for ch, n in sorted(self.elsewhere.items())], width, indent="           ",
                          first="not shown  ")
            if prefixes:
                lines.append(f"           (see them with {' or '.join(f'--prefix {shlex.quote(p)}' for p in prefixes)})")
        if self.undecodable:
            lines.append(f"{self.undecodable} messages of unknown types")
        return fit(lines, width)

    def render(self, source="", width=160, height=None, scroll=0):
        """The dashboard as lines of text, fitted to width x height (None:
        no limit)."""
        head = self.header(source, width)
        foot = self.footer(width)
        table = self.robot_lines(width)
        if height is None:
            return head + [""] + table + [""] + foot
        # The robot tables keep at least a few lines; the events give way.
        room = max(min(len(table), 6), height - len(head) - len(foot) - 2)
        foot = foot[:max(0, height - len(head) - 2 - room)]
        scroll = max(0, min(scroll, max(0, len(table) - room)))
        shown = table[scroll:scroll + room]
        if len(table) > room and room > 1:
            note = f"robot tables: lines {scroll + 1}-{scroll + len(shown) - 1} of {len(table)} (up/down scroll)"
            shown = fit([note], width) + shown[:-1]
        return (head + [""] + shown + [""] + foot)[:height]


def check_log(lcm, name, path):
    """Reads the whole log with the checked reader (logfile.py) before LCM's
    file provider, whose C reader trusts every length field, replays it: a
    corrupt log is refused with the byte offset, never handed over."""
    from . import logfile
    del lcm
    n = 0
    try:
        for _ in logfile.events(path):
            n += 1
    except logfile.LogError as e:
        raise SystemExit(f"{PROG}: {name}: not an LCM log ({e})" if n == 0 else f"{PROG}: {e}") from None
    except OSError as e:
        raise SystemExit(f"{PROG}: {name}: cannot read: {e.strerror}") from None
    if n == 0:
        what = "empty (no events)" if os.path.getsize(path) == 0 else "not an LCM log (no events in it)"
        raise SystemExit(f"{PROG}: {name}: {what}")


def open_bus(args):
    if not args.log:
        return bus.open_listener(args.lcm, PROG)
    lcm = common.lcm_module()
    path = os.path.abspath(args.log)
    if not os.path.isfile(path):
        raise SystemExit(f"{PROG}: {args.log}: no such file")
    check_log(lcm, args.log, path)
    url = f"file://{path}?speed={args.speed:g}"
    try:
        return lcm.LCM(url), url
    except Exception as e:
        raise SystemExit(f"{PROG}: cannot open LCM URL {url!r}: {e}") from None


def handle(lc, timeout_ms, args, signals):
    """Handles a message if one comes within the timeout: 1, else 0; None
    when reading should end: at the end of a log file, or after a signal.
    LCM reports both as an error of handle_timeout (its log provider at
    the end; its wait interrupted by the signal), and the signal handler
    has run by the time `signals` is asked."""
    try:
        return lc.handle_timeout(timeout_ms)
    except OSError as e:
        if signals or args.log:
            return None
        raise SystemExit(f"{PROG}: {args.lcm}: listening failed ({e})") from None


def run_plain(lc, model, source, args, signals):
    width = shutil.get_terminal_size().columns if sys.stdout.isatty() else None
    last_msg = time.monotonic()
    next_print = time.monotonic() + args.interval
    printed = False
    while not signals:
        got = handle(lc, 50, args, signals)
        if got is None:
            break
        now = time.monotonic()
        if got > 0:
            last_msg = now
        if now >= next_print and not args.exit_idle:
            print("\n".join(model.render(source, width)), flush=True)
            print("-" * 40, flush=True)
            next_print = now + args.interval
            printed = True
        if args.exit_idle and now - last_msg >= args.exit_idle:
            break
    if signals:
        return                       # stopped: the caller says so, nothing more is printed
    if args.exit_idle or not printed:
        print("\n".join(model.render(source, width)), flush=True)


def run_curses(lc, model, source, args, signals):
    import curses

    ended = []

    def loop(scr):
        curses.curs_set(0)
        scr.nodelay(True)
        scroll = 0
        next_draw = 0.0
        last_msg = time.monotonic()
        while not signals:          # Ctrl-C: return, and curses.wrapper restores the terminal
            if ended:
                got = 0
                time.sleep(0.05)
            else:
                got = handle(lc, 30, args, signals)
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
            scroll = max(0, min(scroll, max(0, model.robot_line_count() - 1)))
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
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
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
    ap.add_argument("--events", type=int, default=10, help="latest events shown")
    ap.add_argument("--prefix", default="",
                    help="show the channels with this prefix (FW_: the robots' own telemetry in a simulation)")
    args = ap.parse_args(argv)
    try:
        with stop.Signals() as signals:
            lc, _ = open_bus(args)
            model = Model(run=args.run, events=args.events, prefix=args.prefix)
            bus.subscribe(lc, ".*", model.add)
            source = args.log or args.lcm      # as the user gave it (the bus adds its buffer size)
            try:
                if args.plain or not sys.stdout.isatty():
                    run_plain(lc, model, source, args, signals)
                else:
                    run_curses(lc, model, source, args, signals)
            except common.IncompatibleMessage as e:
                raise SystemExit(f"{PROG}: {e.explain(source, log=bool(args.log))}") from None
    except BrokenPipeError:          # `swarm-monitor --plain | head`
        return stop.stdout_closed()
    except KeyboardInterrupt:        # before the handlers were set, or after
        return stop.interrupted(PROG)
    if signals:
        return signals.exit_status(PROG)
    return 0

if __name__ == "__main__":
    sys.exit(main())
