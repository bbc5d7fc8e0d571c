"""An LCM log played to a page at any speed, with pause and seek.

The log is read and decoded once (the 1200 s log of `make run`, 64,000
messages, in about a second), each message cut to the view's limits
(limits.py); each page then plays it with its own Player and View.  Time is the log's: each event's timestamp from the first one's,
which for the simulator's own logs is the simulated time itself.
"""
import bisect
import collections

from swarmtools.live import limits
from swarmtools.live.view import View
from swarmtools.telemetry import common


class Log:
    def __init__(self, path, prog):
        """Reads the whole log; stops the program with a clear message
        (SystemExit, from common.read_log) if it is missing, no LCM log, or
        written by another version of the toolkit."""
        self.path = str(path)
        self.events = []              # (t, channel, message or None)
        self.cuts = collections.Counter()   # what the limits cut, as every page's View.note says it

        def decode(data, channel):
            msg, cut = limits.decode(data, channel)
            self.cuts.update(cut)
            return msg

        t0 = None
        for ev, msg in common.read_log(path, prog, decoder=decode):
            if t0 is None:
                t0 = ev.timestamp
            self.events.append(((ev.timestamp - t0) / 1e6, ev.channel, msg))
        if not self.events:
            raise SystemExit(f"{prog}: {path}: empty (no events)")
        # In time order (stable): a log merged from several recorders may not be.
        self.events.sort(key=lambda e: e[0])
        self.times = [t for t, _, _ in self.events]
        self.end = self.times[-1]
        # A control period, s: what the page's step button moves by (None: no RUN_INFO).
        self.period_s = next((m.control_period_ms / 1000 for _, _, m in self.events
                              if type(m).__name__ == "run_info_t" and m.control_period_ms > 0), None)


class Player:
    """One page's playback: a position in the log, a speed, playing or not."""

    def __init__(self, log, speed=1.0, playing=True, prefix=""):
        self.log = log
        self.view = View(prefix)
        for cut, n in log.cuts.items():
            self.view.note([cut], n)
        self.speed = speed
        self.playing = playing
        self.time = 0.0
        self.next = 0                 # index of the first event not yet applied
        self._apply_until(0.0)

    @property
    def ended(self):
        return self.time >= self.log.end

    def _apply_until(self, t):
        stop = bisect.bisect_right(self.log.times, t)
        for k in range(self.next, stop):
            et, channel, msg = self.log.events[k]
            self.view.apply(et, channel, msg)
        self.next = max(self.next, stop)
        self.time = t
        self.view.time = t

    def advance(self, wall_s):
        """Moves on by wall_s seconds of real time at the speed, when playing;
        stops at the end of the log."""
        if self.playing:
            self._apply_until(min(self.log.end, self.time + wall_s * self.speed))
            if self.ended:
                self.playing = False

    def seek(self, t):
        t = min(max(0.0, t), self.log.end)
        if t < self.time:
            self.view.reset()
            self.next = 0
        self._apply_until(t)

    def step(self, n):
        """Pauses `n` control periods later (the page's step button on a
        log): None, or an error text."""
        if self.log.period_s is None:
            return "step: this log has no RUN_INFO to tell its control period (seek instead)"
        if not 1 <= n <= 1_000_000_000:
            return f"step: {n} is not a number of control steps in [1, 1000000000]"
        self.playing = False
        self.seek(self.time + n * self.log.period_s)
        return None

    def play(self):
        if self.ended:
            self.seek(0.0)
        self.playing = True

    def pause(self):
        self.playing = False

    def status(self):
        return {"playing": self.playing, "speed": self.speed, "ended": self.ended, "end": self.log.end}
