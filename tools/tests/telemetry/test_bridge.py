"""The serial bridge (tools/telemetry/bridge.py): republishing with the
robot's id, counting what is wrong, pseudo-terminal pairs standing in for
e-pucks' rfcomm ports (garbage, several devices, a device that disappears
and comes back), the command line writing an LCM log, and memq://."""
import os
import random
import signal
import subprocess
import time
import tty

from .helpers import PYTHON, TOOLS, TempDir, c_encoder, common, event, robot_state

import bridge
from frames import encode_frame


class Collect:
    def __init__(self):
        self.got = []

    def __call__(self, channel, data):
        self.got.append((channel, common.decode(data)))


class PtyRobot:
    """An e-puck stand-in: the master side of a pty, reached by the bridge
    through a symlink (as udev names rfcomm ports), which can disappear and
    come back on a new pty."""

    def __init__(self, link):
        self.link = link
        self.master = None
        self.connect()

    def connect(self):
        self.master, slave = os.openpty()
        tty.setraw(slave)            # before any byte: no line discipline on the way
        self.slave_path = os.ttyname(slave)
        os.close(slave)
        if os.path.lexists(self.link):
            os.remove(self.link)
        os.symlink(self.slave_path, self.link)

    def disconnect(self):
        os.remove(self.link)
        os.close(self.master)
        self.master = None

    def send(self, data):
        view = memoryview(data)
        while view:
            n = os.write(self.master, view)
            view = view[n:]

    def close(self):
        if self.master is not None:
            os.close(self.master)
            self.master = None


def pump(br, until, timeout=5.0):
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
        data = encode_frame(1, 7, 0, robot_state(robot_id=0, oae=3).encode())
        self.br.feed(self.dev, data)
        (ch, m), = self.out.got
        self.assertEqual((ch, m.robot_id, m.oae_count, m.state), ("ROBOT_STATE", 7, 3, "search"))
        self.assertEqual(self.dev.robot_id, 7)
        # --id DEVICE=42 overrides it; events carry it too.
        self.dev.id_override = 42
        self.br.feed(self.dev, encode_frame(2, 7, 1, event(robot_id=7, kind=2, value=5).encode()))
        ch, m = self.out.got[-1]
        self.assertEqual((ch, m.robot_id, m.kind, m.value), ("SWARM_EVENT", 42, 2, 5))

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
        bus.subscribe("ROBOT_STATE", lambda ch, data: seen.append(common.decode(data)))
        br = bridge.Bridge([self.dev], bus.publish)
        br.feed(self.dev, encode_frame(1, 12, 0, robot_state(robot_id=0, state="wait").encode()))
        while bus.handle_timeout(0) > 0:
            pass
        self.assertEqual([(m.robot_id, m.state) for m in seen], [(12, "wait")])


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
                    r.send(c_frame(1, 10 + k, seq, robot_state(robot_id=10 + k, oae=seq).encode()))
            pump(br, lambda: len(out.got) == 40)
            for k in range(2):
                self.assertEqual([m.oae_count for ch, m in out.got if m.robot_id == 10 + k], list(range(20)))
            self.assertTrue(all(d.connected for d in devs))

            # Robot 0's link drops: its port vanishes.  The bridge notices,
            # keeps serving robot 1, and reopens robot 0 when it is back.
            robots[0].send(c_frame(1, 10, 20, robot_state(robot_id=10, oae=20).encode())[:30])   # cut mid-frame
            robots[0].disconnect()
            pump(br, lambda: not devs[0].connected)
            robots[1].send(c_frame(1, 11, 20, robot_state(robot_id=11, oae=20).encode()))
            pump(br, lambda: len(out.got) == 41)
            for _ in range(5):
                br.poll(0.02)                      # tries to reopen a missing node: no crash
            self.assertFalse(devs[0].connected)
            robots[0].connect()
            pump(br, lambda: devs[0].connected)
            robots[0].send(c_frame(1, 10, 21, robot_state(robot_id=10, oae=21).encode()))
            pump(br, lambda: len(out.got) == 42)
            self.assertEqual(out.got[-1][1].oae_count, 21)
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
        proc = subprocess.Popen([PYTHON, str(TOOLS / "bridge.py"), robot.link, "--lcm", f"file://{log}?mode=w",
                                 "--id", f"{robot.link}=3", "--status-every", "0.2", "--report-every", "0"],
                                stderr=subprocess.PIPE, text=True)
        try:
            time.sleep(0.5)
            robot.send(b"\xff" * 50)
            for seq in range(10):
                robot.send(c_frame(1, 99, seq, robot_state(robot_id=99, oae=seq).encode()))
            bad = bytearray(c_frame(2, 99, 10, event(kind=3).encode()))
            bad[8] ^= 0x40
            robot.send(bytes(bad))
            robot.send(c_frame(2, 99, 11, event(kind=3, value=4).encode()))
            time.sleep(1.0)
        finally:
            proc.send_signal(signal.SIGINT)
            _, err = proc.communicate(timeout=10)
            robot.close()
        self.assertEqual(proc.returncode, 0, err)
        self.assertIn("11 frames, 1 CRC errors", err)
        lcm = common.lcm_module()
        got = [(ev.channel, common.decode(ev.data)) for ev in lcm.EventLog(str(log), "r")]
        states = [m for ch, m in got if ch == "ROBOT_STATE"]
        self.assertEqual([m.oae_count for m in states], list(range(10)))
        self.assertTrue(all(m.robot_id == 3 for m in states))
        events = [m for ch, m in got if ch == "SWARM_EVENT"]
        self.assertEqual([(m.robot_id, m.value) for m in events], [(3, 4)])
        status = [m for ch, m in got if ch == "BRIDGE_STATUS"]
        self.assertTrue(status)
        self.assertEqual(status[-1].devices[0].crc_errors, 1)

    def test_command_line_rejects_bad_arguments(self):
        r = subprocess.run([PYTHON, str(TOOLS / "bridge.py"), "/dev/null", "--id", "nope"],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("DEVICE=ID", r.stderr)


if __name__ == "__main__":
    import unittest
    unittest.main()
