"""A live LCM bus feeding one View that every page shares.

LCM is handled on a thread of its own, so the web server's event loop
never waits for telemetry: messages are cut to the view's limits
(limits.py) and applied under `lock`, which the pages' frames take too.
The feed's time is seconds since the server started; a simulation's own
clock comes with its messages.

A simulation under control (swarmsim --control) is heard on the control
bus (`control_url`: the same as `url`, or another LCM of its own): its
status, the selected robot's details; the page's commands go back to it
there (send_control), with the key of its latest status.
"""
import select
import sys
import threading
import time

from swarmtools import control
from swarmtools.live import limits
from swarmtools.live.view import View
from swarmtools.telemetry import common

#: Milliseconds the bus thread waits for a message before it looks whether to stop.
POLL_MS = 100


class Bus:
    def __init__(self, url, prog, prefix="", control_url=None):
        """Opens the bus (and the control bus, when another); stops the
        program with a clear message (SystemExit) if LCM cannot."""
        lcm = common.lcm_module()
        self.url = url
        self.prog = prog
        try:
            self.lcm = lcm.LCM(url)
            self.control_lcm = self.lcm if control_url in (None, url) else lcm.LCM(control_url)
        except Exception as e:    # lcm raises RuntimeError (or others) for a bad URL or provider
            raise SystemExit(f"{prog}: cannot open LCM URL {control_url if hasattr(self, 'lcm') else url!r}: "
                             f"{e}") from None
        self.seq = 0
        self.view = View(prefix)
        self.lock = threading.Lock()
        self.start_time = time.monotonic()
        self.messages = 0
        self.incompatible = 0
        self._stop = threading.Event()
        self._thread = None
        self.lcm.subscribe(".*", self._on_message)
        if self.control_lcm is not self.lcm:
            for channel in (control.STATUS_CHANNEL, control.DETAIL_CHANNEL):
                self.control_lcm.subscribe(channel, self._on_message)

    def start(self):
        """Handles the bus on its own thread until stop()."""
        self._thread = threading.Thread(target=self._run, name="swarm-live-bus", daemon=True)
        self._thread.start()

    def stop(self):
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5 * POLL_MS / 1000)

    def _handle(self):
        if self.control_lcm is self.lcm:
            self.lcm.handle_timeout(POLL_MS)
            return
        ready, _, _ = select.select([self.lcm.fileno(), self.control_lcm.fileno()], [], [], POLL_MS / 1000)
        for fd in ready:
            (self.lcm if fd == self.lcm.fileno() else self.control_lcm).handle()

    def send_control(self, command, **fields):
        """Sends a command to the run under control (called under `lock`):
        an error text, or None (the run's answer comes with its status)."""
        status = self.view.control
        if status is None:
            return (f"{command}: this run takes no commands (start swarmsim with --realtime X --control; "
                    "the live view then steers it)")
        self.seq += 1
        self.control_lcm.publish(control.CHANNEL, control.message(status.key, self.seq, command, **fields))
        return None

    def _run(self):
        while not self._stop.is_set():
            try:
                self._handle()
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
