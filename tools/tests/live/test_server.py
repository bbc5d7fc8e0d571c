"""swarm-live without a browser (make live-tests): its command line and
errors, what its View keeps and sends, the WebSocket's commands, and that
the page needs nothing from outside the package."""
import asyncio
import contextlib
import io
import json
import math
import re
import signal
import socket
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import aiohttp
import swarmlcm

from swarmtools.live import server
from swarmtools.live.bus import Bus
from swarmtools.live.replay import Log
from swarmtools.live.view import Series, View

from ..telemetry.helpers import ROOT, robot_state, swarm_state, write_log
from .serve import Server

STATIC = ROOT / "tools" / "swarmtools" / "live" / "static"
LIVE = ROOT / "tools" / "swarmtools" / "live"


def live(*args):
    return subprocess.run([sys.executable, "-m", "swarmtools.live", *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True, timeout=30)


class CommandLine(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="live_cli.")
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def refused(self, status, text, *args):
        r = live(*args)
        self.assertEqual(r.returncode, status, r.stderr)
        self.assertIn(text, r.stderr)
        self.assertNotIn("Traceback", r.stderr)
        self.assertEqual(r.stdout, "")           # it never said it was serving

    def test_bad_input_is_refused_with_a_reason(self):
        text = self.tmp / "notes.txt"
        text.write_text("not a log\n")
        empty = self.tmp / "empty.lcmlog"
        empty.write_bytes(b"")
        old = write_log(self.tmp / "v1.lcmlog", [(0, "ROBOT_STATE", bytes.fromhex("3715081f471fd9b6") + bytes(40))])
        self.refused(1, "missing.lcmlog: no such file", "--log", self.tmp / "missing.lcmlog")
        self.refused(1, f"{text}: not an LCM log", "--log", text)
        self.refused(1, f"{empty}: empty (no events)", "--log", empty)
        self.refused(1, "written by an older version of the toolkit (telemetry v1, robot_state_t)", "--log", old)
        self.refused(1, "cannot open LCM URL 'nosuch://x'", "--lcm", "nosuch://x")
        self.refused(2, "the speed is a factor of real time in [0.01, 10000]", "--log", text, "--speed", "0")
        self.refused(2, "not a number: 'fast'", "--log", text, "--speed", "fast")
        self.refused(2, "a port is 0..65535", "--port", "70000")
        self.refused(2, "not allowed with argument", "--log", text, "--lcm", "udpm://239.255.76.67:7667?ttl=0")

    def test_a_port_in_use(self):
        with socket.create_server(("127.0.0.1", 0)) as busy:
            port = busy.getsockname()[1]
            log = write_log(self.tmp / "one.lcmlog", [(0, "SWARM_STATE", swarm_state(0, [0, 0], run=1))])
            self.refused(1, f"cannot listen on 127.0.0.1:{port}", "--log", log, "--port", port)

    def test_help_and_the_console_script(self):
        r = live("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn("usage: swarm-live", r.stdout)
        text = (ROOT / "pyproject.toml").read_text()
        self.assertIn('swarm-live = "swarmtools.live.server:main"', text)
        self.assertIn('"swarmtools.live" = ["static/*"]', text)      # the page ships with the package

    def test_a_signal_stops_it_cleanly(self):
        log = write_log(self.tmp / "one.lcmlog", [(0, "SWARM_STATE", swarm_state(0, [0, 0], run=1))])
        for sig in (signal.SIGTERM, signal.SIGINT):     # as soon as it says where it is
            s = Server("--log", log)
            s.proc.send_signal(sig)
            _, err = s.proc.communicate(timeout=10)
            self.assertEqual(s.proc.returncode, 0, err)
            self.assertEqual(err, "swarm-live: stopped\n")


def two_runs():
    """Messages of run 1, then run 2: (time, channel, message)."""
    out = []
    for run in (1, 2):
        for step in range(3):
            t = (run - 1) * 10 + step * 0.1
            out.append((t, "SWARM_STATE", swarm_state(step, [step, step / 10, float("nan")], run=run)))
            out.append((t, "ROBOT_STATE", robot_state(run, "go", run=run, pose_known=True, x=0.5, y=-0.5)))
    return out


class TheView(unittest.TestCase):
    def test_frames_carry_what_changed_and_json_has_no_nan(self):
        v, sync = View(), {}
        events = two_runs()
        for t, ch, m in events[:2]:
            v.apply(t, ch, m)
        f = v.frame(sync)
        self.assertTrue(f["reset"])
        self.assertEqual([r["id"] for r in f["robots"]], [1])
        self.assertEqual(f["swarm"]["values"][2], None)                 # NaN: null in JSON
        json.dumps(f, allow_nan=False)
        self.assertEqual(set(v.frame(sync)), {"reset", "time", "clock"})  # nothing new
        v.apply(*events[2])
        f = v.frame(sync)
        self.assertEqual((f["reset"], "robots" in f, f["series"]["t"]), (False, False, [0.1]))
        for e in events[3:8]:
            v.apply(*e)
        f = v.frame(sync)                          # run 2 started: a new view
        self.assertTrue(f["reset"])
        self.assertEqual([r["id"] for r in f["robots"]], [2])
        self.assertEqual(f["series"]["t"], [0.0])

    def test_other_prefixes_are_not_shown(self):
        v = View(prefix="FW_")
        v.apply(0, "ROBOT_STATE", robot_state(4))
        self.assertEqual(v.robots, {})
        v.apply(0, "FW_ROBOT_STATE", robot_state(4))
        self.assertEqual(list(v.robots), [4])

    def test_series_keep_at_most_their_points(self):
        s = Series(max_points=100)
        for k in range(1000):
            s.add(k * 0.1, {"a": k}, {"a": "m"})
        self.assertLessEqual(len(s.t), 100)
        self.assertGreater(len(s.t), 40)
        self.assertEqual(len(s.cols["a"]), len(s.t))
        self.assertGreater(s.epoch, 0)
        self.assertTrue(all(b > a for a, b in zip(s.t, s.t[1:], strict=False)))
        self.assertAlmostEqual(s.t[-1], 99.9, delta=2.0)                 # it reaches the end
        s.add(200, {"b": 1}, {"b": "g"})                                # a later column: None before
        self.assertEqual((s.cols["b"][0], s.cols["b"][-1], s.units["b"]), (None, 1, "g"))


class LiveBus(unittest.TestCase):
    def test_a_sender_of_another_version_is_said_once_and_the_rest_shown(self):
        bus = Bus("memq://", "swarm-live")
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            for _ in range(3):
                bus.lcm.publish("ROBOT_STATE", bytes.fromhex("3715081f471fd9b6") + bytes(40))
            bus.lcm.publish("ROBOT_STATE", robot_state(5).encode())
            while bus.lcm.handle_timeout(50) > 0:
                pass
        self.assertEqual(err.getvalue().count("telemetry v1, robot_state_t"), 1)
        f = bus.view.frame({})
        self.assertIn("comes from an older version of the toolkit (telemetry v1, robot_state_t)", f["error"])
        self.assertIn("(3 such messages)", f["error"])
        self.assertEqual([r["id"] for r in f["robots"]], [5])

    def test_the_same_seed_again_starts_afresh(self):
        v, info = View(), swarmlcm.run_info_t()
        info.version, info.run = info.VERSION, 1
        for utime in (0, 10_000_000):
            info.utime = utime
            v.apply(utime / 1e6, "RUN_INFO", info)
            v.apply(utime / 1e6, "SWARM_STATE", swarm_state(utime // 100_000, [0], run=1))
        epoch = v.epoch
        info.utime = 0
        v.apply(11.0, "RUN_INFO", info)
        self.assertEqual(v.epoch, epoch + 1)


class Commands(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="live_ws.")
        cls.log = write_log(Path(cls._tmp.name) / "runs.lcmlog",
                            [(round(t * 1e6), ch, m) for t, ch, m in two_runs()])

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def test_session_commands(self):
        opts = server.argparse.Namespace(speed=2.0, paused=True, prefix="")
        s = server.Session(Log(self.log, "test"), opts)
        self.assertIsNone(s.command({"cmd": "seek", "value": 10.1}))
        self.assertEqual((s.player.time, s.view.run), (10.1, 2))
        self.assertIsNone(s.command({"cmd": "seek", "value": 0.05}))   # backwards: run 1 again
        self.assertEqual(s.view.run, 1)
        self.assertIn("outside", s.command({"cmd": "speed", "value": 0}))
        self.assertIn("needs a number", s.command({"cmd": "seek", "value": "x"}))
        self.assertIn("needs a number", s.command({"cmd": "seek", "value": math.nan}))
        self.assertIn("unknown command 'jump'", s.command({"cmd": "jump"}))
        self.assertIsNone(s.command({"cmd": "play"}))
        s.frame(100.0)                                                  # to the end, then stops
        self.assertEqual((s.player.time, s.player.playing, s.player.ended), (10.2, False, True))

    def test_websocket_answers_bad_commands(self):
        srv = Server("--log", self.log, "--paused")
        try:
            asyncio.run(self._talk(srv.url))
        finally:
            status, err = srv.stop()
        self.assertEqual(status, 0, err)

    def test_only_its_own_page_may_connect(self):
        srv = Server("--log", self.log, "--paused")
        try:
            asyncio.run(self._foreign(srv.url))
        finally:
            status, err = srv.stop()
        self.assertEqual(status, 0, err)

    async def _foreign(self, url):
        async with aiohttp.ClientSession() as http:
            with self.assertRaises(aiohttp.WSServerHandshakeError) as cm:
                await http.ws_connect(url + "ws", origin="http://example.com")
            self.assertEqual(cm.exception.status, 403)
            async with http.ws_connect(url + "ws", origin=url.rstrip("/")) as ws:    # the page's own
                self.assertEqual(json.loads((await ws.receive()).data)["type"], "hello")

    async def _talk(self, url):
        async with aiohttp.ClientSession() as http, http.ws_connect(url + "ws") as ws:
            hello = json.loads((await ws.receive()).data)
            self.assertEqual((hello["type"], hello["mode"], hello["playing"], hello["end"]), ("hello", "log", False, 10.2))
            for cmd, text in (("not json", "a command is a JSON object"), ('{"cmd": "fly"}', "unknown command")):
                await ws.send_str(cmd)
                while (msg := json.loads((await ws.receive()).data))["type"] != "error":
                    pass
                self.assertIn(text, msg["text"])


class ThePage(unittest.TestCase):
    def test_everything_is_served_from_the_package(self):
        html = (STATIC / "index.html").read_text()
        refs = re.findall(r'(?:src|href)="([^"]+)"', html)
        self.assertGreater(len(refs), 4)
        for ref in refs:
            self.assertTrue(ref.startswith("/static/") or ref.startswith("data:"), ref)
            if ref.startswith("/static/"):
                self.assertTrue((STATIC / ref[len("/static/"):]).is_file(), ref)
        for p in STATIC.iterdir():
            self.assertNotRegex(p.read_text(), r"https?://(?!\$\{)", p.name)   # no CDN, no outside address

    def test_no_controller_task_or_value_names(self):
        words = re.compile(r"forag|\bnest|threshold|token|pickup|deposit|random_walk|phototaxis|gather|drtm|oae",
                           re.I)
        for p in sorted(LIVE.glob("*.py")) + sorted(STATIC.iterdir()):
            self.assertEqual(words.findall(p.read_text()), [], p.name)


if __name__ == "__main__":
    unittest.main()
