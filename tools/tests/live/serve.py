"""Shared by the live view's tests: swarm-live started on a free port, and
what a log says the page should show (the robots' poses at a time)."""
import selectors
import socket
import subprocess
import sys
import time

from swarmtools.telemetry import common

from ..telemetry.helpers import ROOT

#: Seconds to wait for something that takes well under one: only a hang reaches it.
LONG = 300


class Server:
    """`python -m swarmtools.live ARGS --port 0` until stop(); .url is the
    address it printed."""

    def __init__(self, *args, timeout=LONG):
        self.proc = subprocess.Popen([sys.executable, "-m", "swarmtools.live", *map(str, args), "--port", "0"],
                                     cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        sel = selectors.DefaultSelector()
        sel.register(self.proc.stdout, selectors.EVENT_READ)
        line = self.proc.stdout.readline() if sel.select(timeout) else ""
        sel.close()
        if not line.startswith("swarm-live: http://"):
            self.proc.kill()
            _, err = self.proc.communicate()
            raise AssertionError(f"swarm-live did not start (status {self.proc.returncode}): {line}{err}")
        self.url = line.split()[1]

    def stop(self):
        """Stops it as Ctrl-C would; returns (status, stderr)."""
        if self.proc.poll() is None:
            self.proc.send_signal(2)
        try:
            _, err = self.proc.communicate(timeout=LONG)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            _, err = self.proc.communicate()
        return self.proc.returncode, err


def poses_at(log, t):
    """{robot id: robot_state_t} of the latest robot states at or before
    log time t (s from the first event), read straight from the log."""
    out, t0 = {}, None
    for ev, msg in common.read_log(log, "test"):
        t0 = ev.timestamp if t0 is None else t0
        if (ev.timestamp - t0) / 1e6 > t:
            break
        if type(msg).__name__ == "robot_state_t":
            out[msg.robot_id] = msg
    return out


def picture_at(log, t):
    """(scene_t, task_drawing_t) latest at or before log time t (s from the
    first event), None where none came: what the page draws robots' colours
    and its legend from."""
    got, t0 = {}, None
    for ev, msg in common.read_log(log, "test"):
        t0 = ev.timestamp if t0 is None else t0
        if (ev.timestamp - t0) / 1e6 > t:
            break
        if type(msg).__name__ in ("scene_t", "task_drawing_t"):
            got[type(msg).__name__] = msg
    return got.get("scene_t"), got.get("task_drawing_t")


def first(log, kind):
    """The first message of type `kind` in a log."""
    return next(msg for _, msg in common.read_log(log, "test") if type(msg).__name__ == kind)


def wait_for(check, what, timeout=LONG, every=0.05):
    """Polls check() until it returns something true; fails naming `what`
    and the last value."""
    end = time.monotonic() + timeout
    last = None
    while time.monotonic() < end:
        last = check()
        if last:
            return last
        time.sleep(every)
    raise AssertionError(f"timed out after {timeout:g} s waiting for {what}; last: {last!r}")


def free_udp_port():
    """A UDP port free here now: the tests' own multicast bus, apart from
    LCM's default one that a developer's tools may be using."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("", 0))
        return s.getsockname()[1]
