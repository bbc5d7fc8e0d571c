"""One fake e-puck1 on a pseudo-terminal: its Bluetooth serial port.

The robot's side of the pty is what a host program opens (through a link
named like udev's rfcomm ports, e.g. out/fake/rfcomm0).  Behind it:

  reset      the bootloader listens for a handshake for a second
             (bootloader.py); the flasher's session writes program memory,
             which survives resets;
  running    the program the bootloader started: the image its program
             memory identifies (images.py), run by a runtime (runtime.py):
             each control period its UART bytes (the image's telemetry
             frames) go out on the port, and the host's frames that come in
             (POSE, HOST_MSG: docs/host_link.md) reach it as on the e-puck:
             frames for its id or the broadcast id, a POSE of 10 bytes, a
             message of 1..64 bytes into a mailbox of two;
  idle       no program to run (nothing flashed, or one it cannot run:
             said once on stderr); silent on the port.

The reset button: a real user presses it when the flasher starts; here a
lone 0xC1 (the flasher's handshake, one byte every 100 ms) arriving while
the program runs presses it (reset_on_handshake), and the bootloader
answers a following one.  Bytes the host writes while nobody reads the
port are lost, as over a radio link.
"""

from __future__ import annotations

import errno
import os
import termios
import time
import tty
from dataclasses import dataclass, field

from ..telemetry.frames import BROADCAST_ID, FrameDecoder
from ..telemetry.host_link import CH_HOST_MSG, CH_POSE, HOST_MSG_MAX, POSE_PAYLOAD, decode_pose
from . import images
from .bootloader import WINDOW_S, Bootloader, Faults, bootloader_code
from .runtime import runtime_for

#: Seconds from the flasher's first handshake to the press of the reset button.
RESET_DELAY_S = 0.15
#: Seconds of silence after which a lone 0xC1 in a stalled flashing session resets.
STALL_S = 1.0
#: A host frame the robot's decoder can hold (TELEMETRY_HOST_MAX_BODY: 6 + 64 + 2).
ROBOT_MAX_PAYLOAD = HOST_MSG_MAX


@dataclass
class HostLinkCounters:
    """As hal_epuck_host_t counts (platforms/epuck1/hal/host_link.h)."""
    frames: int = 0
    bad: int = 0
    oversize: int = 0
    poses: int = 0
    msgs: int = 0
    msg_dropped: int = 0
    not_ours: int = 0
    ignored: int = 0


@dataclass
class Port:
    """The pty: the master end the fake drives, the link a host opens."""
    link: str
    master: int = -1
    slave: int = -1
    dropped: int = 0                 # bytes lost because nobody read them
    written: int = 0

    def open(self):
        self.master, self.slave = os.openpty()
        tty.setraw(self.slave)       # before any byte: no echo, no line discipline
        os.set_blocking(self.master, False)
        path = os.ttyname(self.slave)
        tmp = f"{self.link}.tmp{os.getpid()}"
        if os.path.lexists(tmp):
            os.remove(tmp)
        os.symlink(path, tmp)
        os.replace(tmp, self.link)   # the link appears whole
        return path

    def close(self, remove_link=True):
        for fd in (self.master, self.slave):
            if fd >= 0:
                try:
                    os.close(fd)
                except OSError:
                    pass
        self.master = self.slave = -1
        if remove_link and os.path.lexists(self.link):
            os.remove(self.link)

    def write(self, data: bytes):
        view = memoryview(data)
        while view:
            try:
                n = os.write(self.master, view)
            except BlockingIOError:
                # Nobody reads the port: what waits in it is lost, as over the air.
                termios.tcflush(self.slave, termios.TCIFLUSH)
                try:
                    n = os.write(self.master, view)
                except BlockingIOError:
                    self.dropped += len(view)
                    return
            except OSError as e:
                if e.errno in (errno.EIO, errno.EBADF):
                    self.dropped += len(view)
                    return
                raise
            self.written += n
            view = view[n:]

    def read(self) -> bytes:
        try:
            return os.read(self.master, 4096)
        except (BlockingIOError, InterruptedError):
            return b""
        except OSError as e:
            if e.errno == errno.EIO:   # no program has the port open
                return b""
            raise


@dataclass
class FakeRobot:
    """One robot: its port, program memory, bootloader and program."""
    name: str
    link: str
    faults: Faults = field(default_factory=Faults)
    world: str | None = None
    speed: float = 1.0
    reset_on_handshake: bool = True
    log: object = None               # callable(str), or None for quiet
    platform: str = "host"           # what runs the image: its host build, or pil_avr / pil_m4 (runtime.py)
    shares: object = None            # a FakeRobot whose world this one is a robot of (None: its own world)

    def __post_init__(self):
        self.port = Port(self.link)
        self.flash: dict = bootloader_code()
        self.state = "off"
        self.boot: Bootloader | None = None
        self.sessions: list[Bootloader] = []     # every bootloader run since power-on
        self.runtime = None
        self.program = None
        self.image = None                        # the ImageDecl running, or None
        self.robot_id = None
        self.steps = 0
        self.next_step = 0.0
        self.reset_at = None
        self.last_rx = 0.0
        self.host = HostLinkCounters()
        self.decoder = FrameDecoder()
        self.notes: list[str] = []

    # ------------------------------------------------------------ setup

    def say(self, text: str):
        self.notes.append(text)
        if self.log:
            self.log(f"{self.name}: {text}")

    def load_image(self, name: str, robot_id: int = 0):
        """Program memory as the flasher leaves it with image `name` and
        --robot-id `robot_id` (a robot flashed before the fake started)."""
        decl = images.declaration(name)
        words = images.program_words(decl)
        user = words.pop(0), words.pop(2)
        for pc, w in words.items():
            self.flash[pc] = (w & 0xFF, (w >> 8) & 0xFF, w >> 16)
        w0, w1 = images._goto(0x17F40)
        self.flash[0], self.flash[2] = (w0 & 0xFF, (w0 >> 8) & 0xFF, w0 >> 16), (w1 & 0xFF, 0, 0)
        self.flash[0x17F38] = (user[0] & 0xFF, (user[0] >> 8) & 0xFF, user[0] >> 16)
        self.flash[0x17F3A] = (user[1] & 0xFF, (user[1] >> 8) & 0xFF, user[1] >> 16)
        self.flash[0x17F36] = (robot_id & 0xFF, robot_id >> 8, 0)

    def power_on(self, now: float):
        if self.port.master < 0:
            self.port.open()
        self.reset(now)

    def power_off(self):
        self._stop_program()
        self.port.close()
        self.state = "off"

    def disconnect(self):
        """The link goes away (the Bluetooth connection dropped): the port
        and its link vanish; the robot runs on."""
        self.port.close()

    def reconnect(self):
        """The link comes back, on a new pty behind the same name."""
        self.port.open()
        self.decoder.reset()

    # ------------------------------------------------------------ the robot

    def reset(self, now: float):
        self._stop_program()
        self.boot = Bootloader(self.flash, self.faults, now)
        self.sessions.append(self.boot)
        self.state = "boot"
        self.reset_at = None

    def _stop_program(self):
        if self.runtime is not None:
            self.runtime.close()
        self.runtime = None
        self.image = None

    def _start_program(self, now: float):
        self.program = images.read_program(self.flash)
        if self.program.image is None:
            self.state = "idle"
            self.say(f"nothing runs: {self.program.note}")
            return
        if self.program.note:
            self.say(self.program.note)
        try:
            self.runtime = runtime_for(self.program, self.world, platform=self.platform, owner=self.shares)
        except Exception as e:        # a world or controller the simulator refuses
            self.state = "idle"
            self.say(f"image {self.program.image.name} cannot run: {e}")
            return
        self.image = self.program.image
        self.robot_id = self.program.robot_id
        self.state = "running"
        self.decoder.reset()
        self.steps = 0
        self.next_step = now
        self.say(f"runs image {self.image.describe()} as robot {self.robot_id}, in "
                 f"{getattr(self.runtime, 'world_name', 'its world')}")

    def deadline(self, now: float) -> float | None:
        """When it next needs the clock (None: only input wakes it)."""
        times = [t for t in (self.reset_at,) if t is not None]
        if self.state == "boot" and self.boot.state == "listen":
            if self.boot.pending:
                times.append(now)
            elif self.boot.faults.flood and self.boot.handshakes < self.boot.faults.answer_after:
                times.append(now + 0.01)
            else:
                times.append(self.boot.started + WINDOW_S)
        if self.state == "running":
            times.append(self.next_step)
        return min(times) if times else None

    def tick(self, now: float):
        """Does what is due at `now`."""
        if self.reset_at is not None and now >= self.reset_at:
            self.reset(now)
        if self.state == "boot":
            out = self.boot.poll(now)
            if out:
                self.port.write(out)
            if self.boot.state == "timeout" or self.boot.state == "ended":
                self._start_program(now)
        started = monotonic()
        while self.state == "running" and now >= self.next_step:
            out = self.runtime.step()
            self.steps += 1
            if out:
                self.port.write(out)
            self.next_step += self.runtime.period_s / self.speed
            late = monotonic() - started > TICK_BUDGET_S
            if late or now - self.next_step > 1.0:
                # Behind (a busy machine, or steps slower than `speed` asks: an emulated MCU's):
                # no burst of catching up; the port is read before the next step.
                self.next_step = max(self.next_step, now)
                break

    def readable(self, now: float):
        data = self.port.read()
        if not data:
            return
        quiet_for = now - self.last_rx
        self.last_rx = now
        if self.state == "boot":
            stalled = self.boot.state == "gone" or (self.boot.state == "session" and quiet_for >= STALL_S)
            if stalled and data == b"\xc1" and self.reset_on_handshake:
                self.say("the flashing session stalled: reset for the new handshake")
                self.reset(now)        # the bootloader answers the handshakes that follow
                return
            out = self.boot.feed(data, now)
            if out:
                self.port.write(out)
            if self.boot.state == "ended":
                self._start_program(now)
            return
        if self.state == "running" and self.boot is not None and self.boot.ended_at is not None:
            self.boot.feed(data, now)          # a correct host sends nothing right after the end
        if data == b"\xc1" and self.reset_on_handshake:
            if self.reset_at is None:
                self.reset_at = now + RESET_DELAY_S
            return
        if self.state == "running":
            self._host_frames(data)

    def _host_frames(self, data: bytes):
        for f in self.decoder.feed(data):
            self.host.frames += 1
            if f.robot_id not in (self.robot_id, BROADCAST_ID):
                self.host.not_ours += 1
            elif len(f.payload) > ROBOT_MAX_PAYLOAD:
                self.host.oversize += 1
            elif f.channel == CH_POSE and len(f.payload) == POSE_PAYLOAD:
                self.host.poses += 1
                self.runtime.host_pose(*decode_pose(f.payload))
            elif f.channel == CH_HOST_MSG and 1 <= len(f.payload) <= HOST_MSG_MAX:
                if self.runtime.host_message(f.payload):
                    self.host.msgs += 1
                else:
                    self.host.msg_dropped += 1
            else:
                self.host.ignored += 1
        s = self.decoder.stats
        self.host.bad = s.crc_errors + s.framing_errors

    def status(self) -> dict:
        boot = self.boot
        return {
            "name": self.name, "link": self.link, "state": self.state,
            "image": self.image.name if self.image else None, "robot_id": self.robot_id, "steps": self.steps,
            "bytes_out": self.port.written, "bytes_lost": self.port.dropped,
            "flashed_rows": len(boot.rows) if boot else 0,
            "deviations": [d for b in self.sessions for d in b.deviations],
            "host_link": dict(vars(self.host)),
        }


#: Wall time one tick may spend stepping before it lets the port be read.
TICK_BUDGET_S = 0.02


def monotonic() -> float:
    return time.monotonic()


__all__ = ["FakeRobot", "HostLinkCounters", "Port"]
