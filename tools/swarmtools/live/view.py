"""What the page shows, built from decoded telemetry messages, and what
each page still needs of it.

A View keeps the latest of each kind of message, the robots' latest
states, the latest events and the swarm's time series.  Messages become JSON
(convert.py) only when a page is sent them, once: a seek through a long log
converts nothing it passes.  Each change gets a revision number; a page's `sync` remembers the revision (and
series length) it has, so a frame carries only what changed since (and
everything after a reset: a new run, or a seek backwards in a log).

The time series are named by the schemas, never by this code: a
simulation's are the swarm schema's values (`swarm.<name>`, the run's
timeseries.csv without step and time_s) and its robots by state
(`state.<name>`), at the simulated time of each SWARM_STATE.  Real robots
send no SWARM_STATE: theirs are the robots by state and, per controller,
the mean over its robots of each value its schema names
(`<controller>.<value>`), at the feed's time of each ROBOT_STATE (at most
two points a second).
"""
import collections

from swarmtools.live import convert, limits
from swarmtools.telemetry import common

#: Latest events kept for the page.
EVENTS = 12
#: Points a time series keeps: beyond, every other one is dropped.
SERIES_MAX = 2000
#: Seconds between two points of the series derived from robot states.
ROBOT_SERIES_DT = 0.5


class Series:
    """Time series on one time axis: t, and one column a name, None where a
    column had no value (it appeared later)."""

    def __init__(self, min_dt=0.0, max_points=SERIES_MAX, max_cols=limits.MAX_SERIES):
        self.t = []
        self.cols = {}
        self.units = {}
        self.min_dt = min_dt
        self.max_points = max_points
        self.max_cols = max_cols
        self.dropped = set()     # names of columns past max_cols, not kept
        self.epoch = 0           # bumps when points were dropped: pages take it whole again

    def add(self, t, values, units):
        """Adds a point unless it comes sooner than min_dt after the last."""
        if self.t and t - self.t[-1] < self.min_dt:
            return False
        n = len(self.t)
        for name in values:
            if name not in self.cols:
                if len(self.cols) >= self.max_cols:
                    self.dropped.add(name)
                    continue
                self.cols[name] = [None] * n
                self.units[name] = units.get(name, "")
        self.t.append(t)
        for name, col in self.cols.items():
            col.append(values.get(name))
        if len(self.t) > self.max_points:
            # Every other point, and no denser from now on: the page's
            # charts are a few hundred pixels wide.
            self.t = self.t[::2]
            self.cols = {k: v[::2] for k, v in self.cols.items()}
            self.min_dt = max(self.min_dt, (self.t[-1] - self.t[0]) / (self.max_points / 2))
            self.epoch += 1
        return True

    def since(self, n):
        return {"t": self.t[n:], "cols": {k: v[n:] for k, v in self.cols.items()}, "units": self.units}


class View:
    def __init__(self, prefix=""):
        self.prefix = prefix
        self.rev = 0
        self.epoch = 0
        self.time = 0.0          # the feed's time, s (a log's from its first event; live: since start)
        self.cuts = collections.Counter()   # what the limits cut (limits.py) -> how many times
        self.reset()

    def reset(self):
        """Forgets everything (a seek backwards replays from the start)."""
        self.schemas = common.Schemas()
        self._new_run(None)

    def _new_run(self, run):
        self.epoch += 1
        self.run = run
        self.parts = {}          # name -> [rev, convert function, its arguments, JSON once made]
        self.robots = {}         # robot id -> the same, of convert.robot
        self._robot_msgs = {}    # robot id -> robot_state_t, for the derived series
        self.series = Series()
        self.events = collections.deque(maxlen=EVENTS)
        self.event_counts = collections.Counter()
        self.has_swarm = False
        self.clock = None        # simulated time of the run's latest message, s (None: real robots)
        self.control = None      # the latest control_status_t (its key: what commands carry)
        self.run_info = None     # the latest run_info_t (its groups)
        if self.cuts:
            self._set("limits", self._limits_text)

    def note(self, cuts, times=1):
        """What limits.bound (or this view) cut, for the page to say."""
        if cuts:
            for c in cuts:
                self.cuts[c] += times
            self._set("limits", self._limits_text)

    def _limits_text(self):
        shown = sorted(self.cuts.items())
        more = f"; and {len(shown) - 8} more" if len(shown) > 8 else ""
        return ("Not all of the telemetry is shown (the live view's limits, swarmtools/live/limits.py): "
                + "; ".join(f"{c} x{n:,}" if n > 1 else c for c, n in shown[:8]) + more)

    def _set(self, name, to_json, *args):
        self.rev += 1
        self.parts[name] = [self.rev, to_json, args, None]

    def group_of(self, robot):
        """The name of robot `robot`'s group (ids are consecutive, group
        after group: run_info_t), or None."""
        first = 0
        for name, count in zip(self.run_info.group_names, self.run_info.group_counts, strict=True) if self.run_info else ():
            if first <= robot < first + count:
                return name
            first += count
        return None

    def error(self, text):
        """Something the page should say (a message of another toolkit version)."""
        self._set("error", str, text)

    def _follow(self, kind, msg):
        """True if msg belongs to the run shown: the latest whose RUN_INFO or
        SWARM_STATE came (a new one starts the view afresh, as in the
        terminal monitor; so does a RUN_INFO at time 0 after the run's
        start: the same seed run again).  Real robots' messages carry run 0."""
        run = msg.run
        again = kind == "run_info_t" and msg.utime == 0 and self.clock
        if self.run is None:
            self.run = run
        elif (run != self.run and kind in ("run_info_t", "swarm_state_t")) or again:
            self._new_run(run)
        return run == self.run

    def apply(self, t, channel, msg):
        """Takes one decoded message (None: not ours) that came at feed time t."""
        self.time = t
        ours = common.split_channel(channel)
        if msg is None or ours is None or ours[0] != self.prefix:
            return
        kind = type(msg).__name__
        if kind == "bridge_status_t":
            self._set("bridge", convert.bridge, msg)
            return
        if kind == "control_t":          # a command on the bus: the run's answer tells
            return
        if kind == "control_status_t":   # a run under control (sim_host/core/control.h)
            self.control = msg
            self._set("control", convert.control, msg)
            return
        if kind == "robot_detail_t":
            self._set("detail", convert.detail, msg)
            return
        if kind == "schema_t":
            if self.schemas.count() >= limits.MAX_SCHEMAS and self.schemas.get(msg.kind, msg.name, msg.run) is None:
                self.note([f"schemas past the first {limits.MAX_SCHEMAS}"])
                return
            self.schemas.add(msg)
            self._set("schemas", convert.schemas, self.schemas)
            return
        if not self._follow(kind, msg):
            return
        if msg.run != 0 and hasattr(msg, "utime"):
            self.clock = msg.utime / 1e6
        if kind == "run_info_t":
            self.run_info = msg
            self._set("info", convert.info, msg)
        elif kind == "scene_t":
            self._set("scene", convert.scene, msg)
        elif kind == "task_drawing_t":
            self._set("drawing", convert.drawing, msg)
        elif kind == "swarm_state_t":
            self._swarm(msg)
        elif kind == "robot_state_t":
            self._robot(t, msg)
        elif kind == "event_t":
            self.events.append((msg, t))
            kinds = self.event_counts
            if msg.kind not in kinds and len(kinds) >= limits.MAX_EVENT_KINDS:
                self.note([f"event kinds past the first {limits.MAX_EVENT_KINDS} (counted as 'other')"])
                kinds["other"] += 1
            else:
                kinds[msg.kind] += 1
            self._set("events", self._events_json)
        elif kind == "run_summary_t":
            self._set("summary", convert.summary, msg)

    def _events_json(self):
        return {"counts": dict(self.event_counts.most_common()), "latest": [convert.event(m, t) for m, t in self.events]}

    def _swarm(self, msg):
        self.has_swarm = True
        self._set("swarm", convert.swarm, msg)
        schema = self.schemas.of(msg)
        values, units = {}, {}
        for k, v in enumerate(msg.values):
            e = schema.entry(k)
            if e.name not in common.TIME_VALUES:
                name = common.value_column("swarm", e.name)
                values[name], units[name] = convert.num(v), e.unit
        for name, count in zip(msg.state_names, msg.state_counts, strict=True):
            values[f"state.{name}"], units[f"state.{name}"] = count, "robots"
        self._add_series(msg.utime / 1e6, values, units)

    def _add_series(self, t, values, units):
        dropped = len(self.series.dropped)
        self.series.add(t, values, units)
        if len(self.series.dropped) > dropped:
            self.note([f"chart columns past the first {limits.MAX_SERIES}"], len(self.series.dropped) - dropped)

    def _robot(self, t, msg):
        if msg.robot_id not in self.robots and len(self.robots) >= limits.MAX_ROBOTS:
            self.note([f"robots past the first {limits.MAX_ROBOTS:,}"])
            return
        self.rev += 1
        self.robots[msg.robot_id] = [self.rev, convert.robot, (msg, t), None]
        self._robot_msgs[msg.robot_id] = msg
        s = self.series
        if self.has_swarm:
            return
        s.min_dt = max(s.min_dt, ROBOT_SERIES_DT)
        if s.t and t - s.t[-1] < s.min_dt:
            return
        values, units = {}, {}
        by_ctrl = collections.defaultdict(list)
        for m in self._robot_msgs.values():
            name = f"state.{m.state}"
            values[name], units[name] = values.get(name, 0) + 1, "robots"
            by_ctrl[m.controller].append(m)
        for ctrl, robots in by_ctrl.items():
            schema = self.schemas.of(robots[0])
            for k in range(max(len(m.values) for m in robots)):
                got = [m.values[k] for m in robots if k < len(m.values) and convert.num(m.values[k]) is not None]
                e = schema.entry(k)
                name = common.value_column(ctrl, e.name)
                values[name], units[name] = (sum(got) / len(got) if got else None), e.unit
        self._add_series(t, values, units)

    def frame(self, sync):
        """What a page with `sync` (its dict, updated here; {} at first)
        lacks: {"reset": bool, "time", "clock", then each changed part,
        "robots" (the changed ones) and "series" (new points, or whole with
        "series_reset")}."""
        full = sync.get("epoch") != self.epoch
        since = -1 if full else sync["rev"]
        out = {"reset": full, "time": self.time, "clock": self.clock}
        for name, part in self.parts.items():
            if part[0] > since:
                out[name] = _json(part)
        robots = [_json(r) for r in self.robots.values() if r[0] > since]
        if robots or full:
            out["robots"] = robots
        s = self.series
        if full or sync.get("series_epoch") != s.epoch:
            out["series"], out["series_reset"] = s.since(0), True
        elif len(s.t) > sync["series_len"]:
            out["series"] = s.since(sync["series_len"])
        sync.update(epoch=self.epoch, rev=self.rev, series_epoch=s.epoch, series_len=len(s.t))
        return out


def _json(entry):
    """The JSON of a [rev, convert function, arguments, JSON] entry, made once."""
    if entry[3] is None:
        entry[3] = entry[1](*entry[2])
    return entry[3]
