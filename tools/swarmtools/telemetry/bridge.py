#!/usr/bin/env python3
"""Serial bridge: real e-pucks' telemetry frames -> LCM.

Reads one or several serial devices (the Bluetooth rfcomm ports of e-pucks,
or any tty or pseudo-terminal), decodes the frames of
firmware/telemetry/telemetry_frame.h and republishes each payload on LCM on the
channel its channel id names (ROBOT_STATE, SWARM_EVENT, SWARM_STATE, ...:
the simulator's channels, so the same monitor, logger and tools work;
TELEMETRY_SCHEMA carries the pieces of the robot's controller schema that
name its ROBOT_STATE values), with the robot's id: the id in the frame, or
the one given with --id for that device, written into the message's
robot_id field.

It never stops on bad input: garbage bytes, truncated frames, bad stuffing,
CRC errors, payloads that are not the channel's LCM type and unknown
channel ids are counted and skipped (a robot whose firmware sends an
older telemetry version, e.g. v1, is named once on stderr: flash it
again); a device that disappears (read error,
hang-up, removed node) is closed and opened again every --reopen seconds
until it comes back.  A device that cannot be opened at start (a mistyped
path, a port not bound yet) ends the bridge at once with status 1, unless
--wait asks it to wait for the device.  Counts per device go to BRIDGE_STATUS
(swarmlcm.bridge_status_t) every --status-every seconds and once at exit, and to stderr every
--report-every seconds and at exit.

    swarm-bridge /dev/rfcomm0 /dev/rfcomm1 --lcm 'udpm://239.255.76.67:7667?ttl=0' --baud 115200
    (or .venv/bin/python -m swarmtools.telemetry.bridge ...)
"""
import argparse
import errno
import os
import select
import sys
import termios
import time
import tty

from swarmtools.telemetry import common, stop
from swarmtools.telemetry.frames import CHANNEL_IDS, FrameDecoder

PROG = "swarm-bridge"
READ_CHUNK = 4096
EPILOG = """exit status: 0 stopped after --duration; 1 a device cannot be opened at start
(without --wait) or the LCM URL is refused; 2 bad arguments; 130 / 143
stopped by Ctrl-C / SIGTERM.  The last line on stderr says why it stopped,
then what each device counted."""


class Device:
    """One serial device: its file descriptor (or None while lost), its
    decoder and counters."""

    def __init__(self, path, baud=115200, robot_id=None, writable=False):
        self.path = path
        self.writable = writable     # opened for writing too (the host's frames: docs/host_link.md)
        self.baud = baud
        self.id_override = robot_id
        self.robot_id = -1 if robot_id is None else robot_id
        self.fd = None
        self.decoder = FrameDecoder()
        self.opened = 0              # times opened
        self.bad_payload = 0
        self.unknown_channel = 0
        self.lost = 0
        self.republished = 0
        self.next_try = 0.0
        self.last_error = ""
        self.incompatible = None     # why the latest payload of another telemetry version was refused
        self._last_seq = {}          # robot id -> last sequence number

    @property
    def connected(self):
        return self.fd is not None

    @property
    def reconnects(self):
        return max(0, self.opened - 1)

    def open(self):
        """Tries to open the device; returns True if it is open."""
        try:
            mode = os.O_RDWR if self.writable else os.O_RDONLY
            fd = os.open(self.path, mode | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError as e:
            self.last_error = e.strerror or str(e)
            return False
        try:
            if os.isatty(fd):
                tty.setraw(fd, termios.TCSANOW)   # keep what already arrived
                attrs = termios.tcgetattr(fd)
                speed = getattr(termios, f"B{self.baud}", None)
                if speed is not None:
                    attrs[4] = attrs[5] = speed
                attrs[2] |= termios.CLOCAL | termios.CREAD
                termios.tcsetattr(fd, termios.TCSANOW, attrs)
        except (OSError, termios.error) as e:   # a tty that refuses: read it as it is
            self.last_error = str(e)
        self.fd = fd
        self.opened += 1
        self.decoder.reset()
        return True

    def write(self, data):
        """Writes host frames to a writable device, all of them; False when
        the device is down (or not writable)."""
        if self.fd is None or not self.writable:
            return False
        view = memoryview(data)
        while view:
            try:
                n = os.write(self.fd, view)
            except BlockingIOError:
                select.select([], [self.fd], [], 0.1)
                continue
            except OSError as e:
                self.last_error = e.strerror or str(e)
                return False
            view = view[n:]
        return True

    def close(self):
        if self.fd is not None:
            try:
                os.close(self.fd)
            except OSError:
                pass
        self.fd = None
        self.decoder.reset()

    def note_seq(self, robot_id, seq):
        """Counts frames missing before `seq` (a restart resets silently)."""
        last = self._last_seq.get(robot_id)
        self._last_seq[robot_id] = seq
        if last is not None:
            gap = (seq - last - 1) & 0xFFFF
            if gap < 0x8000:
                self.lost += gap

    def counters(self):
        s = self.decoder.stats
        return dict(bytes=s.bytes, frames=self.republished, crc_errors=s.crc_errors,
                    framing_errors=s.framing_errors, oversize=s.oversize,
                    bad_payload=self.bad_payload, unknown_channel=self.unknown_channel,
                    lost=self.lost, reconnects=self.reconnects)


class Bridge:
    """Devices -> frames -> `publish(channel, data)`."""

    def __init__(self, devices, publish, prefix="", reopen_s=1.0, clock=time.monotonic):
        self.devices = devices
        self.publish = publish
        self.prefix = prefix
        self.reopen_s = reopen_s
        self.clock = clock
        self.publish_errors = 0
        self._types = {name: common.type_class(common.CHANNEL_TYPES[name]) for name in CHANNEL_IDS.values()}

    def handle_frame(self, dev, frame):
        """Republishes one good frame; returns (channel, data) or None."""
        # Only a robot's channels: a host's (frames.HOST_CHANNEL_IDS: poses,
        # messages to robots) has no LCM type and counts as unknown here.
        name = CHANNEL_IDS.get(frame.channel)
        if name is None:
            dev.unknown_channel += 1
            return None
        robot_id = dev.id_override if dev.id_override is not None else frame.robot_id
        dev.robot_id = robot_id
        dev.note_seq(frame.robot_id, frame.seq)
        cls = self._types[name]
        data = frame.payload
        try:
            msg = common.decode(data, name)
        except common.IncompatibleMessage as e:   # another telemetry version, or malformed
            dev.bad_payload += 1
            if e.why != "undecodable":
                dev.incompatible = e.explain(f"{dev.path} robot {robot_id}", log=False)
            return None
        if not isinstance(msg, cls):               # another of our types: not this channel's
            dev.bad_payload += 1
            return None
        if hasattr(msg, "robot_id") and msg.robot_id != robot_id:
            msg.robot_id = robot_id if robot_id < 0x8000 else robot_id - 0x10000
            data = msg.encode()
        channel = self.prefix + name
        try:
            self.publish(channel, data)
        except Exception:
            self.publish_errors += 1
            return None
        dev.republished += 1
        return channel, data

    def feed(self, dev, data):
        """Decodes bytes read from `dev` and republishes its frames."""
        out = []
        for frame in dev.decoder.feed(data):
            r = self.handle_frame(dev, frame)
            if r is not None:
                out.append(r)
        return out

    def reopen_due(self):
        now = self.clock()
        for dev in self.devices:
            if dev.fd is None and now >= dev.next_try:
                if not dev.open():
                    dev.next_try = now + self.reopen_s

    def lose(self, dev, why):
        dev.last_error = why
        dev.close()
        dev.next_try = self.clock() + self.reopen_s

    def poll(self, timeout):
        """Waits up to `timeout` s for input, reads what is there."""
        self.reopen_due()
        fds = {dev.fd: dev for dev in self.devices if dev.fd is not None}
        if not fds:
            time.sleep(min(timeout, self.reopen_s))
            return
        try:
            ready, _, broken = select.select(list(fds), [], list(fds), timeout)
        except (OSError, ValueError):   # a descriptor went bad under us
            ready, broken = list(fds), []
        for fd in set(ready) | set(broken):
            dev = fds[fd]
            try:
                data = os.read(fd, READ_CHUNK)
            except BlockingIOError:
                continue
            except OSError as e:
                # EIO: a pseudo-terminal's other end closed, a Bluetooth link dropped.
                self.lose(dev, e.strerror or errno.errorcode.get(e.errno, str(e)))
                continue
            if not data:
                self.lose(dev, "end of file (hang-up)")
                continue
            self.feed(dev, data)

    def status_message(self, utime):
        m = common.type_class("bridge_status_t")()
        m.utime = utime
        for dev in self.devices:
            d = common.type_class("bridge_device_t")()
            d.device = dev.path
            d.robot_id = dev.robot_id if -0x8000 <= dev.robot_id < 0x8000 else -1
            d.connected = dev.connected
            for key, value in dev.counters().items():
                setattr(d, key, value)
            m.devices.append(d)
        m.n_devices = len(m.devices)
        return m

    def report(self):
        parts = []
        for dev in self.devices:
            c = dev.counters()
            state = "up" if dev.connected else f"down ({dev.last_error})"
            parts.append(f"{dev.path} robot {dev.robot_id}: {state}, {c['frames']} frames, "
                         f"{c['crc_errors']} CRC errors, {c['framing_errors']} framing errors, "
                         f"{c['oversize']} garbage runs, {c['bad_payload']} bad payloads, "
                         f"{c['unknown_channel']} unknown channels, {c['lost']} lost, "
                         f"{c['reconnects']} reconnects"
                         + (f" (latest refused: {dev.incompatible})" if dev.incompatible else ""))
        return "; ".join(parts)


def bad_argument(text):
    """One line on stderr and status 2, as argparse's own errors."""
    print(f"{PROG}: {text}", file=sys.stderr)
    raise SystemExit(2)


def parse_ids(items):
    ids = {}
    for item in items or []:
        dev, sep, value = item.rpartition("=")
        if not sep or not dev:
            bad_argument(f"--id {item!r}: expected DEVICE=ID")
        try:
            ids[dev] = int(value, 0)
        except ValueError:
            bad_argument(f"--id {item!r}: {value!r} is not a robot id")
        if not 0 <= ids[dev] <= 0xFFFF:
            bad_argument(f"--id {item!r}: robot ids are 0..65535")
    return ids


def open_at_start(devices, wait):
    """Opens every device once.  Without `wait`, a device that cannot be
    opened (a mistyped path, an rfcomm port not bound) ends the bridge at
    once: returns the one line that says so.  With `wait` it is tried
    again every --reopen seconds, as a device lost later always is."""
    failed = [dev for dev in devices if not dev.open()]
    if not failed:
        return None
    what = ", ".join(f"{dev.path} ({dev.last_error})" for dev in failed)
    if wait:
        print(f"{PROG}: waiting for {what}", file=sys.stderr, flush=True)
        return None
    for dev in devices:
        dev.close()
    return (f"{PROG}: cannot open {what}; bind the robot's port first (sudo rfcomm bind ...), "
            f"or pass --wait to wait for it")


def main(argv=None):
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=EPILOG)
    ap.add_argument("devices", nargs="+", help="serial devices (/dev/rfcomm0, /dev/ttyUSB0, a pty, ...)")
    ap.add_argument("--lcm", default=common.DEFAULT_URL, help="LCM URL to publish on (default %(default)s)")
    ap.add_argument("--baud", type=int, default=115200, help="serial speed (default %(default)s)")
    ap.add_argument("--id", action="append", metavar="DEVICE=ID",
                    help="robot id for a device's messages (default: the id in its frames)")
    ap.add_argument("--prefix", default="", help="prefix for the republished channel names")
    ap.add_argument("--wait", action="store_true",
                    help="wait for devices that cannot be opened at start (default: exit at once, status 1)")
    ap.add_argument("--reopen", type=float, default=1.0,
                    help="seconds between tries to open a lost device (or, with --wait, a missing one)")
    ap.add_argument("--status-every", type=float, default=1.0, help="seconds between BRIDGE_STATUS messages")
    ap.add_argument("--report-every", type=float, default=10.0, help="seconds between reports on stderr (0: at exit only)")
    ap.add_argument("--duration", type=float, default=0.0, help="stop after this many seconds (0: run until interrupted)")
    ap.add_argument("--quiet", action="store_true", help="no reports on stderr")
    args = ap.parse_args(argv)

    ids = parse_ids(args.id)
    for dev in ids:
        if dev not in args.devices:
            bad_argument(f"--id names {dev!r}, which is not one of the devices")
    try:
        with stop.Signals() as signals:
            return serve(args, ids, signals)
    except KeyboardInterrupt:        # before the handlers were set
        return stop.interrupted(PROG)


def serve(args, ids, signals):
    devices = [Device(p, args.baud, ids.get(p)) for p in args.devices]
    refused = open_at_start(devices, args.wait)
    if refused:
        raise SystemExit(refused)
    lcm = common.lcm_module()
    try:
        lc = lcm.LCM(args.lcm)
    except Exception as e:
        for dev in devices:
            dev.close()
        raise SystemExit(f"{PROG}: cannot open LCM URL {args.lcm!r}: {e}") from None
    bridge = Bridge(devices, lc.publish, prefix=args.prefix, reopen_s=args.reopen)
    status_channel = args.prefix + "BRIDGE_STATUS"
    warned = {}                  # device -> the incompatibility told on stderr
    t0 = time.monotonic()
    next_status = t0
    next_report = t0 + args.report_every if args.report_every > 0 else float("inf")
    why, status = "", 0
    while True:
        now = time.monotonic()
        if signals:
            why, status = f"stopped by {signals.name}", 128 + signals.signum
            break
        if args.duration and now - t0 >= args.duration:
            why = f"stopped after --duration {args.duration:g} s"
            break
        bridge.poll(0.1)
        for dev in devices:
            if dev.incompatible and dev.incompatible != warned.get(dev.path) and not args.quiet:
                warned[dev.path] = dev.incompatible
                print(f"{PROG}: {dev.incompatible}", file=sys.stderr, flush=True)
        now = time.monotonic()
        if args.status_every > 0 and now >= next_status:
            next_status = now + args.status_every
            try:
                lc.publish(status_channel, bridge.status_message(int(time.time() * 1e6)).encode())
            except Exception:
                bridge.publish_errors += 1
        if now >= next_report:
            next_report = now + args.report_every
            if not args.quiet:
                print(f"{PROG}: {bridge.report()}", file=sys.stderr, flush=True)
    # A last BRIDGE_STATUS, so that a log ends with the final counts (not
    # those of up to --status-every earlier).
    if args.status_every > 0:
        try:
            lc.publish(status_channel, bridge.status_message(int(time.time() * 1e6)).encode())
        except Exception:
            bridge.publish_errors += 1
    # The last line names why the bridge stopped, then what it counted
    # (each device as it was: reported before it is closed).
    print(f"{PROG}: {why}" + ("" if args.quiet else f"; {bridge.report()}")
          + (f"; {bridge.publish_errors} messages could not be published" if bridge.publish_errors else ""),
          file=sys.stderr, flush=True)
    for dev in devices:
        dev.close()
    return status

if __name__ == "__main__":
    sys.exit(main())
