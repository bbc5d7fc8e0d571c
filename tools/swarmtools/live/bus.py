"""A live LCM bus feeding one View that every page shares.

LCM is handled on a thread of its own, so the web server's event loop
never waits for telemetry: messages are cut to the view's limits
(limits.py) and applied under `lock`, which the pages' frames take too.
The feed's time is seconds since the server started; a simulation's own
clock comes with its messages.
"""
import sys
import threading
import time

from swarmtools.live import limits
from swarmtools.live.view import View
from swarmtools.telemetry import common

#: Milliseconds the bus thread waits for a message before it looks whether to stop.
POLL_MS = 100


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
        self.lock = threading.Lock()
        self.start_time = time.monotonic()
        self.messages = 0
        self.incompatible = 0
        self._stop = threading.Event()
        self._thread = None
        self.lcm.subscribe(".*", self._on_message)

    def start(self):
        """Handles the bus on its own thread until stop()."""
        self._thread = threading.Thread(target=self._run, name="swarm-live-bus", daemon=True)
        self._thread.start()

    def stop(self):
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5 * POLL_MS / 1000)

    def _run(self):
        while not self._stop.is_set():
            try:
                self.lcm.handle_timeout(POLL_MS)
            except Exception as e:      # a defect of ours: said, and the view goes on with the next message
                import traceback
                traceback.print_exc()
                with self.lock:
                    self.view.error(f"{self.prog}: a message could not be shown ({type(e).__name__}: {e}); "
                                    "please report it")

    def _on_message(self, channel, data):
        self.messages += 1
        now = time.monotonic() - self.start_time
        try:
            msg, cut = limits.decode(data, channel)
        except common.IncompatibleMessage as e:
            # One sender of another version must not stop the view of the
            # others: said once on stderr, and on the page.
            self.incompatible += 1
            text = e.explain(self.url, log=False)
            if self.incompatible == 1:
                print(f"{self.prog}: {text}", file=sys.stderr, flush=True)
            with self.lock:
                self.view.error(f"{text} ({self.incompatible} such messages)")
            return
        with self.lock:
            self.view.note(cut)
            self.view.apply(now, channel, msg)

    def status(self):
        return {"playing": True, "speed": 1.0, "ended": False, "end": None}
