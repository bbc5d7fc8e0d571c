"""A robot running the calibration image, through the telemetry bridge: its
serial device (a Bluetooth rfcomm port, a fake e-puck's pty) read by the
bridge's own decoder (swarmtools.telemetry.bridge), its windows taken from
the robot_state_t messages it republishes, and the host's commands written
back on the same device as HOST_MSG frames (docs/host_link.md)."""

from __future__ import annotations

import time

from ..telemetry import common
from ..telemetry.bridge import Bridge, Device
from ..telemetry.frames import BROADCAST_ID
from ..telemetry.host_link import HostLink
from . import protocol

#: A robot_state_t goes out every 10 periods (ROBOT_TELEMETRY_STEPS): a
#: drive this long is seen driving at least once.
MIN_DRIVE_PERIODS = 12


class LinkError(RuntimeError):
    """The robot does not answer (or answers with another image)."""


class RobotLink:
    """One robot on one device.  `timeout_s` bounds every wait for the
    robot (a robot that does not answer is an error, never a hang)."""

    def __init__(self, device: str, robot_id: int | None = None, baud: int = 115200, timeout_s: float = 10.0,
                 clock=time.monotonic, also_publish=None):
        self.device = Device(device, baud=baud, writable=True)
        self.bridge = Bridge([self.device], self._publish, clock=clock)
        self.robot_id = robot_id
        self.timeout_s = timeout_s
        self.clock = clock
        self.host = HostLink()
        self.windows: list[protocol.Window] = []
        self.cursor = 0                  # the next window not yet looked at
        self.other_controller = None
        self.commands = 0
        self.also_publish = also_publish   # every frame on, as the bridge would (the live view: --live)
        if not self.device.open():
            raise LinkError(f"{device}: cannot open it ({self.device.last_error or 'no such device'})")

    def close(self):
        self.device.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ------------------------------------------------------------ input

    def _publish(self, channel, data):
        if self.also_publish is not None:
            self.also_publish(channel, data)
        if not channel.endswith("ROBOT_STATE"):
            return
        msg = common.decode(data, "ROBOT_STATE")
        w = protocol.window_of(msg)
        if w is None:
            self.other_controller = msg.controller
            return
        if self.robot_id is None:
            self.robot_id = w.robot_id
        if w.robot_id == self.robot_id:
            self.windows.append(w)

    def _poll(self, until: float):
        self.bridge.poll(max(0.0, min(0.05, until - self.clock())))

    def _not_answering(self, what: str) -> LinkError:
        if self.other_controller is not None:
            return LinkError(f"{self.device.path}: the robot runs {self.other_controller!r}, not the calibration "
                             f"image: flash it (make flash HEX=build/firmware/xc16/calib.hex DEVICE=... ROBOT_ID=...)")
        return LinkError(f"{self.device.path}: the robot did not answer within {self.timeout_s:g} s ({what}): "
                         f"is it on, flashed with the calibration image, its link up?")

    def _next(self, accept, until: float):
        """The next window not yet looked at for which accept(window) is
        true, polling until `until`; None then."""
        while True:
            while self.cursor < len(self.windows):
                w = self.windows[self.cursor]
                self.cursor += 1
                if accept(w):
                    return w
            if self.clock() >= until:
                return None
            self._poll(until)

    def wait_window(self, accept, what: str) -> protocol.Window:
        """The next window for which accept(window) is true."""
        w = self._next(accept, self.clock() + self.timeout_s)
        if w is None:
            raise self._not_answering(what)
        return w

    def hello(self) -> int:
        """Waits for the robot's first window: its id."""
        self.wait_window(lambda w: True, "its telemetry")
        return self.robot_id

    # ------------------------------------------------------------ output

    def send(self, payload: bytes):
        frame = self.host.message(self.robot_id if self.robot_id is not None else BROADCAST_ID, payload)
        if not self.device.write(frame):
            raise LinkError(f"{self.device.path}: the link is down ({self.device.last_error or 'closed'})")
        self.commands += 1

    def command(self, payload: bytes, started, what: str, resend_s: float = 2.5) -> protocol.Window:
        """Sends `payload` until a window says the robot took it
        (started(window)), resending every `resend_s` (a frame can be lost
        on the way)."""
        end = self.clock() + self.timeout_s
        self.cursor = len(self.windows)      # what came before the command says nothing of it
        while self.clock() < end:
            self.send(payload)
            w = self._next(started, min(end, self.clock() + resend_s))
            if w is not None:
                return w
        raise self._not_answering(what)

    def stream(self, payload: bytes, windows: int, what: str) -> list[protocol.Window]:
        """Starts a stream and returns its first `windows` valid windows
        (after the robot's settling)."""
        want = protocol.STREAM_STATES[payload[:1]]
        lacking = (protocol.NO_SOUND, protocol.NO_FRAME)
        self.command(payload, lambda w: w.state in (protocol.SETTLE, *lacking), what)
        out = []
        while len(out) < windows:
            w = self.wait_window(lambda w: w.state in (want, *lacking), what)
            if w.state == protocol.NO_SOUND:
                raise LinkError(f"{self.device.path}: {what}: the robot has no microphones (an image "
                                f"built without sound?)")
            if w.state == protocol.NO_FRAME:
                raise LinkError(f"{self.device.path}: {what}: the robot passes no camera frames on (no "
                                f"camera, or a processor-in-the-loop robot): leave out the colour cards "
                                f"(--procedures without colours)")
            out.append(w)
        return out

    def tone(self, band: int, what: str) -> protocol.Window:
        """Has this robot (the emitter of another's microphone procedure)
        play `band` (0: silence) until a window says it does."""
        w = self.command(protocol.tone(band), lambda w: w.state == protocol.NO_SOUND
                         or (w.state == protocol.TONE and int(w.mean[0]) == band), what)
        if w.state == protocol.NO_SOUND:
            raise LinkError(f"{self.device.path}: {what}: the emitter has no speaker (an image built without sound?)")
        return w

    def drive(self, left: int, right: int, periods: int, what: str) -> protocol.Window:
        """Drives for `periods` control periods; the final window (steps
        counted, periods driven).  A drive of at least MIN_DRIVE_PERIODS
        shows "drive" in at least one message: the sign it was taken."""
        if periods < MIN_DRIVE_PERIODS:
            raise ValueError(f"a drive of {periods} periods: at least {MIN_DRIVE_PERIODS}")
        self.command(protocol.drive(left, right, periods), lambda w: w.state == protocol.DRIVE, what)
        return self.wait_window(lambda w: w.state == protocol.DRIVEN and w.mean[2] == periods, what)
