"""The serial bridge (swarmtools.telemetry.bridge): republishing with the
robot's id (schema pieces on TELEMETRY_SCHEMA too), counting what is wrong
(payloads of an older telemetry version named), pseudo-terminal pairs
standing in for e-pucks' rfcomm ports (garbage, several devices, a device
that disappears and comes back), the command line writing an LCM log, and
memq://."""
import os
import random
import signal
import subprocess
import threading
import time

from swarmtools.fake_epuck.robot import Port
from swarmtools.telemetry import bridge, common
from swarmtools.telemetry.frames import encode_frame

from .helpers import PYTHON, TempDir, c_encoder, default_sigint, event, read_log, robot_state, schema

#: A robot_state_t of telemetry v1 (its fingerprint, then whatever).
V1_ROBOT_STATE = bytes.fromhex("3715081f471fd9b6") + bytes(40)


class Collect:
    def __init__(self):
        self.got = []

    def __call__(self, channel, data):
        self.got.append((channel, common.decode(data)))


class PtyRobot(Port):
    """An e-puck stand-in that sends what a test crafts (garbage, old
    versions): swarm-fake-epuck's port (a pty behind a link that appears
    whole, as udev names rfcomm ports), written blocking so that no byte
    is lost, which can disappear and come back on a new pty."""

    def __init__(self, link):
        super().__init__(link)
        self.connect()

    def connect(self):
        self.slave_path = self.open()
        os.set_blocking(self.master, True)

    def disconnect(self):
        self.close(remove_link=True)

    def send(self, data):
        view = memoryview(data)
        while view:
            n = os.write(self.master, view)
            view = view[n:]


class StderrLines:
    """A process's stderr, line by line as it comes (a thread reads it), to
    wait for the line that says the event a test needs has happened."""

    def __init__(self, proc):
        self.proc = proc
        self.lines = []
        self.cond = threading.Condition()
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        for line in self.proc.stderr:
            with self.cond:
                self.lines.append(line)
                self.cond.notify_all()

    def wait_for(self, text, timeout=120.0):   # a bound for a hang only
        """Waits for a line that contains `text`."""
        with self.cond:
            ok = self.cond.wait_for(lambda: any(text in line for line in self.lines), timeout)
        if not ok:
            raise AssertionError(f"timed out waiting for {text!r} on stderr: {''.join(self.lines)}")

    def end(self, timeout=120.0):              # a bound for a hang only
        """The process's exit status and all its stderr, once it ended."""
        self.proc.wait(timeout)
        self.thread.join(timeout)
        return self.proc.returncode, "".join(self.lines)


def pump(br, until, timeout=120.0):   # a bound for a hang only: a busy machine is slow
    t0 = time.monotonic()
    while not until():
        if time.monotonic() - t0 > timeout:
            raise AssertionError("timed out waiting for the bridge")
        br.poll(0.02)


class HandleFrames(TempDir):
    def setUp(self):
        super().setUp()
        self.out = Collect()
        self.dev = bridge.Device("test")
        self.br = bridge.Bridge([self.dev], self.out)

    def test_robot_id_from_the_frame_or_the_device(self):
        # The robot's firmware left robot_id 0 in the message: the frame's id wins.
        data = encode_frame(1, 7, 0, robot_state(robot_id=0, values=[3, 0.5]).encode())
        self.br.feed(self.dev, data)
        (ch, m), = self.out.got
        self.assertEqual((ch, m.robot_id, m.values, m.state), ("ROBOT_STATE", 7, (3.0, 0.5), "search"))
        self.assertEqual(self.dev.robot_id, 7)
        # --id DEVICE=42 overrides it; events carry it too.
        self.dev.id_override = 42
        self.br.feed(self.dev, encode_frame(2, 7, 1, event(robot_id=7, kind="deposits", value=5).encode()))
        ch, m = self.out.got[-1]
        self.assertEqual((ch, m.robot_id, m.kind, m.value), ("SWARM_EVENT", 42, "deposits", 5))

    def test_schema_pieces_are_republished(self):
        # A controller's schema of 5 values in pieces of 3 (as robot_telemetry.c sends it), channel 6.
        names = ["carried", "rate", "drops", "heading", "spare"]
        pieces = [schema("sorter", names[0:3], first=0, total=5, counters=[0, 0, 1]),
                  schema("sorter", names[3:5], first=3, total=5, units=["rad", ""])]
        for seq, piece in enumerate(pieces):
            self.br.feed(self.dev, encode_frame(6, 9, seq, piece.encode()))
        self.assertEqual([ch for ch, _ in self.out.got], ["TELEMETRY_SCHEMA"] * 2)
        self.assertEqual([m.encode() for _, m in self.out.got], [p.encode() for p in pieces])   # as sent
        book = common.Schemas()
        for _, m in self.out.got:
            book.add(m)
        s = book.get("controller", "sorter", 0)
        self.assertTrue(s.complete)
        self.assertEqual(s.names(), names)
        self.assertEqual((s.entry(2).counter, s.entry(3).unit), (True, "rad"))
        self.assertEqual(self.dev.counters()["bad_payload"], 0)

    def test_counts_what_is_wrong(self):
        good = robot_state(robot_id=1).encode()
        self.br.feed(self.dev, encode_frame(9, 1, 0, good))                    # unknown channel
        self.br.feed(self.dev, encode_frame(2, 1, 1, good))                    # a robot_state on the event channel
        self.br.feed(self.dev, encode_frame(1, 1, 2, good[:20]))               # right fingerprint, cut short
        self.br.feed(self.dev, encode_frame(1, 1, 6, good))                    # frames 3..5 lost
        self.br.feed(self.dev, encode_frame(1, 1, 0, good))                    # a restart: not a loss
        c = self.dev.counters()
        self.assertEqual(c["unknown_channel"], 1)
        self.assertEqual(c["bad_payload"], 2)
        self.assertEqual(c["lost"], 3)
        self.assertEqual(c["frames"], 2)
        self.assertEqual(len(self.out.got), 2)
        self.assertIsNone(self.dev.incompatible)    # malformed, not another version

    def test_older_and_newer_telemetry_is_refused_and_named(self):
        self.br.feed(self.dev, encode_frame(1, 4, 0, V1_ROBOT_STATE))           # old firmware
        self.assertEqual(self.dev.counters()["bad_payload"], 1)
        self.assertIn("robot 4: a message on ROBOT_STATE comes from an older version of the toolkit "
                      "(telemetry v1, robot_state_t)", self.dev.incompatible)
        self.assertIn("robot's firmware", self.dev.incompatible)
        self.assertIn("telemetry v1", self.br.report())
        newer = robot_state(robot_id=4)
        newer.version = 3
        self.br.feed(self.dev, encode_frame(1, 4, 1, newer.encode()))
        self.assertEqual(self.dev.counters()["bad_payload"], 2)
        self.assertIn("a newer version of the toolkit (telemetry v3, robot_state_t); update these tools",
                      self.dev.incompatible)
        self.assertEqual(self.out.got, [])
        self.br.feed(self.dev, encode_frame(1, 4, 2, robot_state(robot_id=4).encode()))   # reflashed
        self.assertEqual(len(self.out.got), 1)

    def test_publish_failure_is_counted(self):
        def broken(channel, data):
            raise OSError("no route")
        br = bridge.Bridge([self.dev], broken)
        br.feed(self.dev, encode_frame(1, 1, 0, robot_state().encode()))
        self.assertEqual(br.publish_errors, 1)

    def test_status_message(self):
        self.br.feed(self.dev, b"junk\x00" + encode_frame(1, 3, 0, robot_state().encode()))
        m = self.br.status_message(123)
        self.assertEqual(m.n_devices, 1)
        d = m.devices[0]
        self.assertEqual((d.device, d.robot_id, d.frames, d.framing_errors, d.connected), ("test", 3, 1, 1, False))
        again = type(m).decode(m.encode())
        self.assertEqual(again.devices[0].frames, 1)

    def test_memq(self):
        lcm = common.lcm_module()
        bus = lcm.LCM("memq://")
        seen = []
        bus.subscribe("ROBOT_STATE|TELEMETRY_SCHEMA", lambda ch, data: seen.append(common.decode(data, ch)))
        br = bridge.Bridge([self.dev], bus.publish)
        br.feed(self.dev, encode_frame(1, 12, 0, robot_state(robot_id=0, state="wait").encode()))
        br.feed(self.dev, encode_frame(6, 12, 1, schema("sorter", ["carried"]).encode()))
        while bus.handle_timeout(0) > 0:
            pass
        self.assertEqual([(m.robot_id, m.state) for m in seen[:1]], [(12, "wait")])
        self.assertEqual([(type(m).__name__, m.names) for m in seen[1:]], [("schema_t", ["carried"])])


class PseudoTerminals(TempDir):
    def test_two_robots_garbage_and_a_device_that_comes_back(self):
        c_frame = c_encoder()
        robots = [PtyRobot(str(self.tmp / f"rfcomm{k}")) for k in range(2)]
        out = Collect()
        devs = [bridge.Device(r.link) for r in robots]
        br = bridge.Bridge(devs, out, reopen_s=0.05)
        try:
            rng = random.Random(5)
            for k, r in enumerate(robots):
                r.send(bytes(rng.randrange(256) for _ in range(300)))          # line noise, boot text
                for seq in range(20):
                    r.send(c_frame(1, 10 + k, seq, robot_state(robot_id=10 + k, values=[seq]).encode()))
            pump(br, lambda: len(out.got) == 40)
            for k in range(2):
                self.assertEqual([m.values[0] for ch, m in out.got if m.robot_id == 10 + k], list(range(20)))
            self.assertTrue(all(d.connected for d in devs))

            # Robot 0's link drops: its port vanishes.  The bridge notices,
            # keeps serving robot 1, and reopens robot 0 when it is back.
            robots[0].send(c_frame(1, 10, 20, robot_state(robot_id=10, values=[20]).encode())[:30])   # cut mid-frame
            robots[0].disconnect()
            pump(br, lambda: not devs[0].connected)
            robots[1].send(c_frame(1, 11, 20, robot_state(robot_id=11, values=[20]).encode()))
            pump(br, lambda: len(out.got) == 41)
            for _ in range(5):
                br.poll(0.02)                      # tries to reopen a missing node: no crash
            self.assertFalse(devs[0].connected)
            robots[0].connect()
            pump(br, lambda: devs[0].connected)
            robots[0].send(c_frame(1, 10, 21, robot_state(robot_id=10, values=[21]).encode()))
            pump(br, lambda: len(out.got) == 42)
            self.assertEqual(out.got[-1][1].values, (21.0,))
            c0 = devs[0].counters()
            self.assertEqual(c0["reconnects"], 1)
            self.assertEqual(c0["lost"], 1)        # sequence 20 never arrived whole
            self.assertEqual(devs[1].counters()["reconnects"], 0)
            self.assertIn("up", br.report())
        finally:
            for r in robots:
                r.close()
            for d in devs:
                d.close()

    def test_command_line_writes_an_lcm_log(self):
        c_frame = c_encoder()
        robot = PtyRobot(str(self.tmp / "rfcomm3"))
        log = self.tmp / "bridge.lcmlog"
        proc = subprocess.Popen([PYTHON, "-m", "swarmtools.telemetry.bridge", robot.link, "--lcm", f"file://{log}?mode=w",
                                 "--id", f"{robot.link}=3", "--status-every", "0.2", "--report-every", "0.1"],
                                stderr=subprocess.PIPE, text=True, preexec_fn=default_sigint)
        out = StderrLines(proc)
        try:
            out.wait_for("robot 3: up, 0 frames")          # the port is open, the loop runs
            robot.send(b"\xff" * 50)
            for seq in range(10):
                robot.send(c_frame(1, 99, seq, robot_state(robot_id=99, values=[seq]).encode()))
            bad = bytearray(c_frame(2, 99, 10, event(kind="oae").encode()))
            bad[8] ^= 0x40
            robot.send(bytes(bad))
            robot.send(c_frame(2, 99, 11, event(kind="oae", value=4).encode()))
            robot.send(c_frame(6, 99, 12, schema("sorter", ["carried"], counters=[1]).encode()))
            robot.send(c_frame(1, 99, 13, V1_ROBOT_STATE))
            out.wait_for("12 frames, 1 CRC errors")
        finally:
            proc.send_signal(signal.SIGINT)
            _, err = out.end()
            robot.close()
        self.assertEqual(proc.returncode, 130, err)
        self.assertTrue(err.splitlines()[-1].startswith("swarm-bridge: stopped by SIGINT; "), err)
        # The periodic reports (--report-every, what the test waited on) aside:
        err = "".join(line for line in err.splitlines(True) if not line.startswith(f"swarm-bridge: {robot.link} robot 3: up, "))
        self.assertIn("12 frames, 1 CRC errors", err)
        self.assertIn("1 bad payloads", err)
        self.assertEqual(err.count("comes from an older version of the toolkit (telemetry v1, robot_state_t)"), 2,
                         err)   # told when it came, and in the report at exit
        self.assertNotIn("Traceback", err)
        got = read_log(log)
        states = [m for ch, m in got if ch == "ROBOT_STATE"]
        self.assertEqual([m.values for m in states], [(float(k),) for k in range(10)])
        self.assertTrue(all(m.robot_id == 3 for m in states))
        events = [m for ch, m in got if ch == "SWARM_EVENT"]
        self.assertEqual([(m.robot_id, m.kind, m.value) for m in events], [(3, "oae", 4)])
        schemas = [m for ch, m in got if ch == "TELEMETRY_SCHEMA"]
        self.assertEqual([(m.name, m.names, m.counters) for m in schemas], [("sorter", ["carried"], (1,))])
        status = [m for ch, m in got if ch == "BRIDGE_STATUS"]
        self.assertTrue(status)
        self.assertEqual(status[-1].devices[0].crc_errors, 1)

    def test_command_line_rejects_bad_arguments(self):
        r = subprocess.run([PYTHON, "-m", "swarmtools.telemetry.bridge", "/dev/null", "--id", "nope"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr, "swarm-bridge: --id 'nope': expected DEVICE=ID\n")


class StartAndStop(TempDir):
    """A device path that does not exist is refused at once unless --wait;
    the last line names why the bridge stopped."""

    def bridge(self, *args):
        return subprocess.Popen([PYTHON, "-m", "swarmtools.telemetry.bridge", *map(str, args), "--lcm", "memq://",
                                 "--report-every", "0"], stderr=subprocess.PIPE, text=True,
                                preexec_fn=default_sigint)

    def test_a_missing_device_is_refused_at_once(self):
        missing = self.tmp / "rfcomm9"
        p = self.bridge("/dev/null", missing)
        try:
            # It ends by itself (before: it ran on, reopening the missing port
            # every second, until this bound for a hang stopped the test).
            _, err = p.communicate(timeout=120)
        finally:
            p.kill()
        self.assertEqual(p.returncode, 1, err)
        self.assertEqual(err, f"swarm-bridge: cannot open {missing} (No such file or directory); bind the robot's "
                              f"port first (sudo rfcomm bind ...), or pass --wait to wait for it\n")

    def test_wait_for_a_missing_device(self):
        link = self.tmp / "rfcomm4"
        log = self.tmp / "bridge.lcmlog"
        p = subprocess.Popen([PYTHON, "-m", "swarmtools.telemetry.bridge", link, "--wait", "--reopen", "0.1",
                              "--lcm", f"file://{log}?mode=w", "--report-every", "0.1"], stderr=subprocess.PIPE,
                             text=True, preexec_fn=default_sigint)
        out = StderrLines(p)
        robot = None
        try:
            out.wait_for(f"waiting for {link}")
            self.assertIsNone(p.poll(), "the bridge did not wait")
            robot = PtyRobot(str(link))
            robot.send(encode_frame(1, 5, 0, robot_state(robot_id=5).encode()))
            out.wait_for("robot 5: up, 1 frames")
        finally:
            p.send_signal(signal.SIGINT)
            _, err = out.end()
            if robot:
                robot.close()
        self.assertEqual(p.returncode, 130, err)
        lines = err.splitlines()
        self.assertEqual(lines[0], f"swarm-bridge: waiting for {link} (No such file or directory)")
        self.assertTrue(lines[-1].startswith(f"swarm-bridge: stopped by SIGINT; {link} robot 5: up, 1 frames"), err)
        self.assertEqual([ch for ch, _ in read_log(log) if ch == "ROBOT_STATE"], ["ROBOT_STATE"])

    def test_sigterm_and_duration_are_named(self):
        robot = PtyRobot(str(self.tmp / "rfcomm2"))          # a robot that says nothing
        try:
            p = subprocess.Popen([PYTHON, "-m", "swarmtools.telemetry.bridge", robot.link, "--lcm", "memq://",
                                  "--duration", "60", "--report-every", "0.1"], stderr=subprocess.PIPE, text=True)
            out = StderrLines(p)
            out.wait_for(f"{robot.link}")                  # a report: the loop runs, its handlers are in place
            p.send_signal(signal.SIGTERM)
            status, err = out.end()
            self.assertEqual(status, 143, err)
            self.assertTrue(err.splitlines()[-1].startswith("swarm-bridge: stopped by SIGTERM; "), err)
            p = self.bridge(robot.link, "--duration", "0.5", "--quiet")
            _, err = p.communicate(timeout=120)
            self.assertEqual((p.returncode, err), (0, "swarm-bridge: stopped after --duration 0.5 s\n"))
        finally:
            robot.close()


if __name__ == "__main__":
    import unittest
    unittest.main()
