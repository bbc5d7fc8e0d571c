"""Commands to a running simulation (swarmsim --realtime X --control) over
LCM, from a script or a shell; swarm-live's buttons send the same ones.

    python -m swarmtools.control status              # what the run is doing
    python -m swarmtools.control pause
    python -m swarmtools.control resume
    python -m swarmtools.control step 10             # 10 control periods, then paused
    python -m swarmtools.control status --wait-step 500   # wait until the run has done 500 steps
    python -m swarmtools.control realtime 5          # 5 times real time
    python -m swarmtools.control move 3 0.2 -0.1 90  # robot 3 to (0.2, -0.1) m, heading 90 degrees
    python -m swarmtools.control select 3            # ROBOT_DETAIL of robot 3 every step (-1: none)
    python -m swarmtools.control set 3 alpha 5       # robot 3's controller key (one it declares live)
    python -m swarmtools.control set foragers beta 2 # every robot of group "foragers"

Each waits for the run's answer (its control_status_t) and prints it; a
refused command exits 1 with the run's reason, no run heard exits 2, and a
run heard that had not done --wait-step's steps within --timeout exits 3
(a paused run, or one that stopped before: say where it is).  The
run announces a key with its status (sim_host/core/control.h); a command
counts only with it, so this listens for a status before it sends.
"""
import argparse
import math
import sys
import threading
import time

from swarmtools.telemetry import common

#: Channels of sim_host/core/control.h.
CHANNEL = "SWARM_CONTROL"
STATUS_CHANNEL = "SWARM_CONTROL_STATUS"
DETAIL_CHANNEL = "ROBOT_DETAIL"
#: The loopback-only bus swarmsim --control listens on by default.
DEFAULT_URL = common.DEFAULT_URL
#: Commands and what each needs (control_t's fields).
COMMANDS = ("pause", "resume", "step", "realtime", "move", "select", "set")


class NoRun(RuntimeError):
    """No simulation under control was heard on the bus."""


class NotYet(RuntimeError):
    """The run was heard but what was waited for did not come in time."""


class Refused(RuntimeError):
    """The run refused a command: its reason."""


def message(key, seq, command, robot_id=-1, steps=0, value=0.0, x=0.0, y=0.0, theta=0.0, group="", param="",
            param_value=""):
    """An encoded control_t."""
    m = common.type_class("control_t")()
    m.version = m.VERSION
    m.seq, m.key, m.command = int(seq), key, command
    m.robot_id, m.steps, m.value = int(robot_id), int(steps), float(value)
    m.x, m.y, m.theta = float(x), float(y), float(theta)
    m.group, m.param, m.param_value = str(group), str(param), str(param_value)
    return m.encode()


def set_target(text):
    """`set`'s first word as control_t fields: a robot id (digits), else a
    group's name (`group:NAME` for a name of digits)."""
    if text.startswith("group:"):
        return {"robot_id": -1, "group": text[len("group:"):]}
    if text.lstrip("-").isdigit():
        return {"robot_id": int(text), "group": ""}
    return {"robot_id": -1, "group": text}


class Controller:
    """Follows a run's control status on `url` and sends it commands.

    Messages are handled on a thread of its own; `status` is the latest
    control_status_t (None until one came)."""

    def __init__(self, url=DEFAULT_URL):
        lcm = common.lcm_module()
        try:
            self.lcm = lcm.LCM(url)
        except Exception as e:
            raise SystemExit(f"swarmtools.control: cannot open LCM URL {url!r}: {e}") from None
        self.status = None
        self.detail = None
        self.answer = None
        self._seq = int(time.time() * 1000) % (1 << 40)
        self._cond = threading.Condition()
        self._stop = threading.Event()
        self.lcm.subscribe(STATUS_CHANNEL, self._on_status)
        self.lcm.subscribe(DETAIL_CHANNEL, self._on_detail)
        self._thread = threading.Thread(target=self._run, name="swarm-control", daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.is_set():
            self.lcm.handle_timeout(100)

    def _on_status(self, channel, data):
        try:
            msg = common.decode(data, channel)
        except common.IncompatibleMessage:
            return
        with self._cond:
            self.status = msg
            # The first status of a command's seq is its answer, sent as the
            # command was taken; later ones carry the same seq (a step's
            # "done" among them), so the latest status alone would let
            # send("step") return after the steps were done, its .step late.
            if self.answer is None or msg.seq != self.answer.seq:
                self.answer = msg
            self._cond.notify_all()

    def _on_detail(self, channel, data):
        try:
            msg = common.decode(data, channel)
        except common.IncompatibleMessage:
            return
        with self._cond:
            self.detail = msg
            self._cond.notify_all()

    def close(self):
        self._stop.set()
        self._thread.join(timeout=1)

    def wait(self, test, timeout):
        """Waits until test(status) holds; returns the status, or raises
        NoRun (none heard) or NotYet (heard, the test never held) after
        `timeout` seconds."""
        return self._wait_for("status", test, timeout)

    def wait_detail(self, test, timeout):
        """Waits until test(detail) holds for the latest robot_detail_t (the
        selected robot's); returns it, or raises NoRun after `timeout` s."""
        return self._wait_for("detail", test, timeout)

    def _wait_for(self, name, test, timeout):
        end = time.monotonic() + timeout
        with self._cond:
            while getattr(self, name) is None or not test(getattr(self, name)):
                left = end - time.monotonic()
                if left <= 0:
                    if self.status is None:
                        raise NoRun("no simulation under control answered on the bus "
                                    "(swarmsim --realtime X --control)")
                    raise NotYet(f"not there after {timeout:g} s: {describe(self.status)}")
                self._cond.wait(left)
            return getattr(self, name)

    def send(self, command, timeout=10.0, **fields):
        """Sends a command and waits for the run's answer: its status as it
        took the command (for `step`, before the steps).  Raises Refused
        with the run's reason, NoRun if none answers."""
        status = self.wait(lambda s: True, timeout)
        self._seq += 1
        seq = self._seq
        self.lcm.publish(CHANNEL, message(status.key, seq, command, **fields))
        try:
            answer = self._wait_for("answer", lambda s: s.seq == seq, timeout)
        except NotYet:
            raise NoRun(f"the run ({describe(self.status)}) did not answer {command} "
                        f"within {timeout:g} s") from None
        if not answer.ok:
            raise Refused(answer.text)
        return answer


def describe(s):
    state = "paused" if s.paused else f"running at {s.realtime:g}x real time"
    pending = f", {s.steps_pending} steps to go" if s.steps_pending else ""
    sel = f", robot {s.selected} selected" if s.selected >= 0 else ""
    return f"run {s.run}: step {s.step}, {state}{pending}{sel}; {s.commands} command(s) recorded"


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m swarmtools.control", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    ap.add_argument("command", choices=("status",) + COMMANDS)
    ap.add_argument("args", nargs="*", help="step: N; realtime: X; move: ROBOT X Y [THETA_DEG]; select: ROBOT; "
                    "set: ROBOT|GROUP KEY VALUE")
    ap.add_argument("--lcm", default=DEFAULT_URL, help="the control bus (default %(default)s)")
    ap.add_argument("--timeout", type=float, default=10.0, help="seconds to wait for the run (default %(default)s)")
    ap.add_argument("--wait-step", type=int, metavar="N",
                    help="then wait until the run has done N steps (and is paused, after `step`)")
    o = ap.parse_args(argv)
    want = {"status": (0, 0), "pause": (0, 0), "resume": (0, 0), "step": (1, 1), "realtime": (1, 1),
            "move": (3, 4), "select": (1, 1), "set": (3, 3)}[o.command]
    if not want[0] <= len(o.args) <= want[1]:
        ap.error(f"{o.command} takes {want[0]}" + (f" to {want[1]}" if want[1] != want[0] else "") + " values")
    try:
        if o.command in ("step", "select", "move"):
            try:
                ints = [int(o.args[0])]
            except ValueError:
                raise ValueError(f"{o.args[0]!r} is not a whole number "
                                 + ("of steps" if o.command == "step" else "(a robot id)")) from None
        if o.command == "step":
            fields = {"steps": ints[0]}
        elif o.command == "realtime":
            fields = {"value": float(o.args[0])}
        elif o.command == "select":
            fields = {"robot_id": ints[0]}
        elif o.command == "move":
            theta = math.radians(float(o.args[3])) if len(o.args) > 3 else 0.0
            fields = {"robot_id": ints[0], "x": float(o.args[1]), "y": float(o.args[2]), "theta": theta}
        elif o.command == "set":
            fields = dict(set_target(o.args[0]), param=o.args[1], param_value=o.args[2])
        else:
            fields = {}
    except ValueError as e:
        ap.error(f"{o.command}: {e}")
    c = Controller(o.lcm)
    try:
        s = c.wait(lambda s: True, o.timeout) if o.command == "status" else c.send(o.command, o.timeout, **fields)
        if o.wait_step is not None:
            s = c.wait(lambda s: s.step >= o.wait_step and (o.command != "step" or s.paused), o.timeout)
        print(describe(s))
        return 0
    except Refused as e:
        print(f"swarmtools.control: {o.command} refused: {e}", file=sys.stderr)
        return 1
    except NoRun as e:
        print(f"swarmtools.control: {e}", file=sys.stderr)
        return 2
    except NotYet as e:
        print(f"swarmtools.control: --wait-step {o.wait_step}: {e}", file=sys.stderr)
        return 3
    finally:
        c.close()


if __name__ == "__main__":
    sys.exit(main())
