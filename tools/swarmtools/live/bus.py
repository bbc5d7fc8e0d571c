"""A live LCM bus feeding one View that every page shares.

LCM's file descriptor is watched by the asyncio loop (add_reader), so
messages are handled between the web server's work, on one thread.  The
feed's time is seconds since the server started; a simulation's own clock
comes with its messages.
"""
import sys
import time

from swarmtools.live.view import View
from swarmtools.telemetry import common


class Bus:
    def __init__(self, url, prog, prefix=""):
        """Opens the bus; stops the program with a clear message
        (SystemExit) if LCM cannot."""
        lcm = common.lcm_module()
        self.url = url
        self.prog = prog
        try:
            self.lcm = lcm.LCM(url)
        except Exception as e:    # lcm raises RuntimeError (or others) for a bad URL or provider
            raise SystemExit(f"{prog}: cannot open LCM URL {url!r}: {e}") from None
        self.view = View(prefix)
        self.start = time.monotonic()
        self.messages = 0
        self.incompatible = 0
        self.lcm.subscribe(".*", self._on_message)

    def attach(self, loop):
        loop.add_reader(self.lcm.fileno(), self.lcm.handle)

    def detach(self, loop):
        loop.remove_reader(self.lcm.fileno())

    def _on_message(self, channel, data):
        self.messages += 1
        now = time.monotonic() - self.start
        try:
            msg = common.decode(data, channel)
        except common.IncompatibleMessage as e:
            # One sender of another version must not stop the view of the
            # others: said once on stderr, and on the page.
            self.incompatible += 1
            text = e.explain(self.url, log=False)
            if self.incompatible == 1:
                print(f"{self.prog}: {text}", file=sys.stderr, flush=True)
            self.view.error(f"{text} ({self.incompatible} such messages)")
            return
        self.view.apply(now, channel, msg)

    def status(self):
        return {"playing": True, "speed": 1.0, "ended": False, "end": None}
