"""swarm-fake-epuck against the real-robot tools: the flasher (epuck-flash)
writes a stand-in image into two fake robots at once, which then run it as
the host build and stream its telemetry; the serial bridge republishes it
into an LCM log that load_log reads with the image's schema; the flasher's
errors against a bootloader that answers 'N'; the host link's poses and
messages reach the robot; the command line's run/stop and its errors."""
import os
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

import swarmtools
from swarmtools.fake_epuck.bootloader import Faults
from swarmtools.fake_epuck.images import declaration, stand_in_hex
from swarmtools.fake_epuck.server import FakeEpucks
from swarmtools.telemetry.host_link import HostLink

PYTHON = sys.executable


def wait_for(what, until, timeout=120.0, detail=None):   # a bound for a hang only
    end = time.monotonic() + timeout
    while not until():
        if time.monotonic() > end:
            raise AssertionError(f"timed out waiting for {what}{detail() if detail else ''}")
        time.sleep(0.05)


class FakeCase(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = Path(self._tmp.name)
        self.hex = self.tmp / "forager.hex"
        self.hex.write_text(stand_in_hex(declaration("forager")))

    def tearDown(self):
        self._tmp.cleanup()

    def flash(self, link, *args):
        return subprocess.run([PYTHON, "-m", "swarmtools.flash.epuck", str(self.hex), link, *args],
                              capture_output=True, text=True, timeout=60)


class FlashBridgeLog(FakeCase):
    def test_flash_two_robots_then_bridge_them_into_a_log(self):
        with FakeEpucks(2, self.tmp / "fake", speed=4.0) as fakes:
            for k, link in enumerate(fakes.links):
                r = self.flash(link, "--robot-id", str(7 + k))
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertIn("done: ", r.stderr)
            wait_for("both robots to run the image",
                     lambda: all(r.status()["state"] == "running" for r in fakes.robots),
                     detail=lambda: f": {[(r.status(), r.notes) for r in fakes.robots]}")
            for k, robot in enumerate(fakes.robots):
                s = robot.status()
                self.assertEqual((s["image"], s["robot_id"]), ("forager", 7 + k))
                self.assertEqual(s["deviations"], [], "the flasher did what the real bootloader expects")
                self.assertGreater(s["flashed_rows"], 0)
            log = self.tmp / "robots.lcmlog"
            r = subprocess.run([PYTHON, "-m", "swarmtools.telemetry.bridge", *fakes.links,
                                "--lcm", f"file://{log}?mode=w", "--duration", "3"],
                               capture_output=True, text=True, timeout=60)
            self.assertEqual(r.returncode, 0, r.stderr)
        data = swarmtools.load_log(log)
        robots = data.robots
        self.assertEqual(sorted(robots["robot_id"].unique()), [7, 8])
        self.assertEqual(set(robots["controller"].astype(str)), {"forager"})
        self.assertIn("threshold", robots.columns, "values named by the image's schema")
        self.assertGreater(len(robots), 10)
        self.assertIsNone(data.summary, "real robots send no run summary")

    def test_a_bootloader_that_answers_n_fails_the_flasher_as_the_real_one_does(self):
        with FakeEpucks(1, self.tmp / "fake", faults=Faults(nak={1: 100})) as fakes:
            r = self.flash(fakes.links[0], "--timeout", "0.5")
            status = fakes.robots[0].status()
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("answered 'N'", r.stderr)
        self.assertEqual(status["flashed_rows"], 1, "the first row was written, the second never")
        self.assertIn("gave up after 5 retries", r.stderr)
        self.assertEqual((status["state"], status["image"]), ("boot", None), "still in its bootloader, no image")
        self.assertEqual(status["deviations"], [])


class LateAnswer(unittest.TestCase):
    def test_handshakes_queued_behind_a_late_answer_are_not_packet_bytes(self):
        # The fake's loop can be busy (starting another robot's program) while the flasher
        # repeats 0xC1: they arrive together, and only the first is the handshake.
        from swarmtools.fake_epuck.bootloader import Bootloader, bootloader_code
        flash = bootloader_code()
        boot = Bootloader(flash, Faults(), now=0.0)
        self.assertEqual(boot.feed(b"\xc1\xc1\xc1", 0.1), b"qK")
        self.assertEqual(boot.feed(b"\xc1", 0.15), b"")          # one more, sent before the answer was read
        body = bytes([0x40, 0x00, 0x00, 0x60]) + bytes(range(96))
        packet = body + bytes([-sum(body) & 0xFF])
        self.assertEqual(boot.feed(packet, 0.2), b"K")
        self.assertEqual((boot.rows, boot.deviations, boot.late_handshakes), ([0x40], [], 3))


class HostLinkToTheRobot(FakeCase):
    def test_poses_and_messages_reach_the_flashed_robot(self):
        with FakeEpucks(1, self.tmp / "fake", images=["waypoint"], ids=[3]) as fakes:
            robot = fakes.robots[0]
            wait_for("the robot to run", lambda: robot.status()["state"] == "running")
            link = HostLink()
            fd = os.open(fakes.links[0], os.O_RDWR | os.O_NOCTTY)
            try:
                os.write(fd, link.pose(3, x_mm=250, y_mm=-400, heading_mrad=1571))
                os.write(fd, link.pose(9, x_mm=0, y_mm=0, heading_mrad=0))        # another robot's
                os.write(fd, link.message(3, b"\x01\x02"))
                wait_for("the frames to arrive", lambda: robot.status()["host_link"]["frames"] >= 3)
            finally:
                os.close(fd)
            host = robot.status()["host_link"]
        self.assertEqual((host["poses"], host["not_ours"], host["bad"]), (1, 1, 0))
        self.assertEqual(host["msgs"] + host["msg_dropped"], 1)


class CommandLine(FakeCase):
    def fake(self, *args):
        return subprocess.run([PYTHON, "-m", "swarmtools.fake_epuck", *args], capture_output=True, text=True,
                              timeout=60)

    def test_run_in_the_background_and_stop(self):
        d = self.tmp / "bg"
        r = self.fake("run", "--robots", "2", "--dir", str(d), "--image", "phototaxis", "--background")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.islink(d / "rfcomm0") and os.path.islink(d / "rfcomm1"))
        self.assertIn("image phototaxis, robot 0", r.stdout)
        r = self.fake("stop", "--dir", str(d))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse((d / "fake-epuck.pid").exists())
        self.assertFalse(os.path.lexists(d / "rfcomm0"), "the ports go with the robots")
        self.assertIn("stopped by SIGTERM", (d / "fake-epuck.log").read_text())

    def test_no_simulator_library_fails_the_background_start(self):
        """Without the library no image can run: the start says so and fails, not the log after a success."""
        d = self.tmp / "nolib"
        r = subprocess.run([PYTHON, "-m", "swarmtools.fake_epuck", "run", "--dir", str(d), "--image", "calib",
                            "--background"], capture_output=True, text=True, timeout=60,
                           env={**os.environ, "SWARMSIM_LIB": str(self.tmp / "no_such_lib.so")})
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("could run no image", r.stderr)
        self.assertIn("SWARMSIM_LIB", r.stderr)
        self.assertIn("make build/libswarmsim.so", r.stderr)
        self.assertNotIn("running in the background", r.stdout)
        self.assertFalse((d / "fake-epuck.pid").exists())
        self.assertFalse(os.path.lexists(d / "rfcomm0"))

    def test_errors(self):
        for args, words in ((["run", "--image", "no_such_image"], "no_such_image"),
                            (["run", "--robots", "2", "--id", "1"], "--id"),
                            (["run", "--boot-fault", "wobble"], "wobble"),
                            (["hex", "no_such_image"], "no_such_image")):
            with self.subTest(args=args):
                r = self.fake(*args, *(["--dir", str(self.tmp / "e")] if args[0] == "run" else []))
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(words, r.stderr)
        r = self.fake("stop", "--dir", str(self.tmp / "none"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("no fake robots", r.stderr)


if __name__ == "__main__":
    unittest.main()
