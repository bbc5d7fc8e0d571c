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

from swarmtools.live import limits, server
from swarmtools.live.bus import Bus
from swarmtools.live.hosts import AllowedHosts
from swarmtools.live.replay import Log
from swarmtools.live.view import Series, View

from ..telemetry.helpers import ROOT, event, robot_state, schema, swarm_state, write_log
from .serve import LONG, Server

STATIC = ROOT / "tools" / "swarmtools" / "live" / "static"
LIVE = ROOT / "tools" / "swarmtools" / "live"


def live(*args):
    return subprocess.run([sys.executable, "-m", "swarmtools.live", *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True, timeout=LONG)


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
            _, err = s.proc.communicate(timeout=LONG)
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
        self.assertIn("value needs a finite number, got \"x\"", s.command({"cmd": "seek", "value": "x"}))
        self.assertIn("needs a finite number", s.command({"cmd": "seek", "value": math.nan}))
        self.assertIn("value needs a finite number, got true", s.command({"cmd": "speed", "value": True}))
        self.assertIn("unknown command 'jump'", s.command({"cmd": "jump"}))
        self.assertIn("pause: unknown field 'value' (it takes none)", s.command({"cmd": "pause", "value": 1}))
        self.assertEqual((s.player.speed, s.player.time), (2.0, 0.05))          # none of them acted
        self.assertIsNone(s.command({"cmd": "play"}))
        s.frame(1.5)                                                    # 1.5 s of real time at 2x
        self.assertAlmostEqual(s.player.time, 3.05, places=9)
        self.assertIsNone(s.command({"cmd": "speed", "value": 4}))
        s.frame(0.25)
        self.assertAlmostEqual(s.player.time, 4.05, places=9)
        s.frame(100.0)                                                  # to the end, then stops
        self.assertEqual((s.player.time, s.player.playing, s.player.ended), (10.2, False, True))

    def test_control_commands_on_a_log(self):
        """A log has no run to steer: step moves the replay N control
        periods (its RUN_INFO's), move and select are refused."""
        opts = server.argparse.Namespace(speed=2.0, paused=True, prefix="")
        s = server.Session(Log(self.log, "test"), opts)
        self.assertIn("no RUN_INFO", s.command({"cmd": "step", "value": 1}))      # two_runs has none
        self.assertIn("cannot be changed", s.command({"cmd": "move", "robot": 1, "x": 0, "y": 0, "theta": 0}))
        self.assertIn("cannot be changed", s.command({"cmd": "select", "robot": 1}))
        self.assertIn("robot needs a whole number, got 1.5", s.command({"cmd": "select", "robot": 1.5}))
        self.assertIn("needs theta", s.command({"cmd": "move", "robot": 1, "x": 0, "y": 0}))
        self.assertIn("cannot be changed", s.command({"cmd": "set", "robot": 1, "group": False, "key": "a", "value": "1"}))
        self.assertIn("value needs a word", s.command({"cmd": "set", "robot": 1, "group": False, "key": "a", "value": ""}))
        self.assertIn("group needs true or false", s.command({"cmd": "set", "robot": 1, "group": 1, "key": "a",
                                                               "value": "1"}))
        info = swarmlcm.run_info_t()
        info.version, info.run, info.control_period_ms = info.VERSION, 1, 100
        events = [(0, "RUN_INFO", info)] + [(round(t * 1e6), ch, m) for t, ch, m in two_runs()]
        log = write_log(Path(self._tmp.name) / "with_info.lcmlog", events)
        s = server.Session(Log(log, "test"), opts)
        self.assertIsNone(s.command({"cmd": "step", "value": 2}))
        self.assertEqual((round(s.player.time, 9), s.player.playing), (0.2, False))
        self.assertIn("not a number of control steps", s.command({"cmd": "step", "value": 0}))

    def test_a_run_under_control(self):
        """On a live bus, the page's commands go to a run that announced its
        status, with its key; the page's frames carry the status without it."""
        opts = server.argparse.Namespace(speed=1.0, paused=False, prefix="")
        bus = Bus("memq://", "swarm-live")
        s = server.Session(bus, opts)
        self.assertIn("takes no commands", s.command({"cmd": "step", "value": 3}))
        sent = []
        bus.lcm.subscribe("SWARM_CONTROL", lambda ch, data: sent.append(swarmlcm.control_t.decode(data)))
        st = swarmlcm.control_status_t()
        st.version, st.run, st.key, st.step, st.paused, st.realtime, st.seq, st.ok = \
            st.VERSION, 1, "k" * 32, 40, True, 5.0, -1, True
        st.text = ""
        bus.lcm.publish("SWARM_CONTROL_STATUS", st.encode())
        while bus.lcm.handle_timeout(50) > 0:
            pass
        self.assertEqual((s.status()["playing"], s.status()["speed"], s.status()["controlled"]), (False, 5.0, True))
        for cmd in ({"cmd": "play"}, {"cmd": "step", "value": 3}, {"cmd": "speed", "value": 20},
                    {"cmd": "move", "robot": 2, "x": 0.1, "y": -0.2, "theta": 1.0}, {"cmd": "select", "robot": 2}):
            self.assertIsNone(s.command(cmd))
        self.assertIn("not sought", s.command({"cmd": "seek", "value": 1}))
        self.assertIn("no robot 2 in this run's groups", s.command({"cmd": "set", "robot": 2, "group": True,
                                                                   "key": "alpha", "value": "5"}))
        info = swarmlcm.run_info_t()
        info.version, info.run, info.n_groups = info.VERSION, 1, 2
        info.group_names, info.group_controllers, info.group_policies, info.group_counts = \
            ["a", "b"], ["x", "y"], ["", ""], [2, 3]
        info.scenario = info.scenario_file = ""
        bus.lcm.publish("RUN_INFO", info.encode())
        while bus.lcm.handle_timeout(50) > 0:
            pass
        self.assertIsNone(s.command({"cmd": "set", "robot": 2, "group": True, "key": "alpha", "value": "5"}))
        self.assertIsNone(s.command({"cmd": "set", "robot": 1, "group": False, "key": "beta", "value": "0.5"}))
        while bus.lcm.handle_timeout(50) > 0:
            pass
        self.assertEqual([(m.command, m.key, m.steps, m.value, m.robot_id) for m in sent],
                         [("resume", "k" * 32, 0, 0.0, -1), ("step", "k" * 32, 3, 0.0, -1),
                          ("realtime", "k" * 32, 0, 20.0, -1), ("move", "k" * 32, 0, 0.0, 2),
                          ("select", "k" * 32, 0, 0.0, 2), ("set", "k" * 32, 0, 0.0, 2), ("set", "k" * 32, 0, 0.0, 1)])
        self.assertAlmostEqual(sent[3].y, -0.2, places=6)
        self.assertEqual([(m.group, m.param, m.param_value) for m in sent[5:]], [("b", "alpha", "5"), ("", "beta", "0.5")])
        self.assertEqual(len({m.seq for m in sent}), 7)
        f = bus.view.frame({})
        self.assertEqual((f["control"]["step"], f["control"]["paused"]), (40, True))
        self.assertNotIn("k" * 32, json.dumps(f))                     # the page never gets the key

    def test_default_replay_speed(self):
        """A 20-minute log plays in about a minute; a short one at 1x."""
        self.assertEqual([server.default_speed(t) for t in (30, 1200, 3600, 6000, 1e6)], [1, 20, 50, 100, 1000])

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
        self.assertNotIn("Traceback", err)      # aiohttp's 400 for a path too long: one line
        self.assertIn("swarm-live: Error handling request from 127.0.0.1: 400, message: Got more than 8190 bytes", err)

    async def _foreign(self, url):
        port = url.rstrip("/").rsplit(":", 1)[1]
        async with aiohttp.ClientSession() as http:
            with self.assertRaises(aiohttp.WSServerHandshakeError) as cm:
                await http.ws_connect(url + "ws", origin="http://example.com")
            self.assertEqual(cm.exception.status, 403)
            # DNS rebinding: a site's name made to resolve to 127.0.0.1, so
            # that Origin and Host agree; the Host is not this server's.
            rebound = {"Host": f"attacker.example:{port}", "Origin": f"http://attacker.example:{port}"}
            with self.assertRaises(aiohttp.WSServerHandshakeError) as cm:
                await http.ws_connect(url + "ws", headers=rebound)
            self.assertEqual(cm.exception.status, 403)
            async with http.get(url, headers={"Host": rebound["Host"]}) as r:
                self.assertEqual(r.status, 403)
                self.assertIn("is not this server's name", await r.text())
            async with http.get(url, headers={"Host": f"localhost:{int(port) + 1}"}) as r:   # another port
                self.assertEqual(r.status, 403)
            for host in (f"localhost:{port}", f"127.0.0.1:{port}"):
                async with http.ws_connect(url + "ws", headers={"Host": host, "Origin": f"http://{host}"}) as ws:
                    self.assertEqual(json.loads((await ws.receive()).data)["type"], "hello")
            async with http.ws_connect(url + "ws", origin=url.rstrip("/")) as ws:    # the page's own
                self.assertEqual(json.loads((await ws.receive()).data)["type"], "hello")
            # only the page's own files: no path, no folder, no 500 for a long name
            for path, status in (("static/live.js", 200), ("static/" + "a" * 5000, 404), ("static/", 404),
                                 ("static/%2e%2e%2fserver.py", 404), ("static/../server.py", 404),
                                 ("static/" + "a" * 9000, 400), ("a" * 20000, 400)):
                async with http.get(url + path) as r:
                    self.assertEqual(r.status, status, path[:40])

    def test_names_it_may_be_opened_by(self):
        h = AllowedHosts("127.0.0.1", 8080, ["tunnel.example:9000", "box.lan"])
        for host in ("127.0.0.1:8080", "localhost:8080", "LOCALHOST.:8080", "[::1]:8080", "tunnel.example:9000",
                     "box.lan:8080"):
            self.assertIsNone(h.why_not(host), host)
        for host in ("attacker.example:8080", "127.0.0.1:8081", "localhost", "10.1.2.3:8080", "tunnel.example:8080",
                     "", None, "[::1", "a:b", "localhost:99999999"):
            self.assertIsNotNone(h.why_not(host), host)
        every = AllowedHosts("0.0.0.0", 80)
        for host in ("10.1.2.3", "192.168.0.7:80", "localhost", f"{socket.gethostname()}:80"):
            self.assertIsNone(every.why_not(host), host)
        self.assertIsNotNone(every.why_not("attacker.example"))
        self.assertIsNotNone(every.why_not("10.1.2.3:81"))
        with self.assertRaises(ValueError):
            AllowedHosts("127.0.0.1", 80, ["a:b"])

    async def _talk(self, url):
        async with aiohttp.ClientSession() as http, http.ws_connect(url + "ws") as ws:
            hello = json.loads((await ws.receive()).data)
            self.assertEqual((hello["type"], hello["mode"], hello["playing"], hello["end"]), ("hello", "log", False, 10.2))
            # Each once ended the handler with a traceback (or did the wrong thing).
            for cmd, text in (("not json", "a command is a JSON object"), ('{"cmd": "fly"}', "unknown command"),
                              ("[" * 100_000 + "]" * 100_000, "a command is at most 1000 characters"),
                              ("[" * 490 + "]" * 490, "a command is a JSON object"),
                              ('{"cmd": "seek", "value": ' + "[" * 480 + "]" * 480 + "}", "value needs a finite"),
                              ('{"cmd": "seek", "value": 1' + "0" * 900 + "}", "value needs a finite number, got 1000"),
                              ('{"cmd": "seek", "value": 1e999}', "value needs a finite number, got Infinity"),
                              ('{"cmd": "speed", "value": true}', "value needs a finite number, got true"),
                              ('{"cmd": ["play"]}', "unknown command that"), ('"play"', "a command is a JSON object"),
                              ('{"cmd": "seek"}', "seek: needs value")):
                await ws.send_str(cmd)
                while (msg := json.loads((await ws.receive(timeout=LONG)).data))["type"] != "error":
                    pass
                self.assertIn(text, msg["text"])
            await ws.send_str('{"cmd": "seek", "value": 10.1}')              # and it still answers
            while (msg := json.loads((await ws.receive(timeout=LONG)).data)).get("time") != 10.1:
                pass


class Bounded(unittest.TestCase):
    """One log of huge messages must not block the server (defect: swarm
    states of 32,000 values, 0.8 s each a page, on the one event loop)."""

    VALUES = 32_000

    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory(prefix="live_big.")
        events = []
        for step in range(40):
            events.append((step * 100_000, "SWARM_STATE", swarm_state(step, range(cls.VALUES), run=1,
                                                                        states=[(f"s{k}", k) for k in range(600)])))
        events.append((0, "ROBOT_STATE", robot_state(1, "x" * 5000, run=1)))
        cls.log = write_log(Path(cls._tmp.name) / "big.lcmlog", events)

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def test_a_message_is_cut_and_the_page_says_so(self):
        m = swarm_state(1, range(self.VALUES), states=[(f"s{k}", k) for k in range(600)])
        cut = limits.bound(m, "SWARM_STATE ")
        self.assertEqual((len(m.values), m.n_values, len(m.state_names), len(m.state_counts), m.n_states),
                         (256, 256, 256, 256, 256))
        self.assertIn("SWARM_STATE values: 32,000 (first 256 kept)", cut)
        v = View()
        v.note(cut)
        v.apply(0.0, "SWARM_STATE", m)
        f = v.frame({})
        self.assertEqual(len(f["swarm"]["values"]), 256)
        self.assertLessEqual(len(f["series"]["cols"]), limits.MAX_SERIES)
        self.assertIn("SWARM_STATE values: 32,000 (first 256 kept)", f["limits"])
        self.assertEqual(limits.bound(swarm_state(1, range(10))), [])           # a real run is never cut
        d = swarmlcm.task_drawing_t()
        shape = swarmlcm.scene_shape_t()
        shape.text = "y" * 3000
        d.shapes, d.n_shapes = [shape] * (limits.MAX_ITEMS + 1), limits.MAX_ITEMS + 1
        d.fill_robot, d.fill_rgb, d.n_fills = [1, 2], [3, 4], 2
        cut = limits.bound(d)
        self.assertEqual((len(d.shapes), d.n_shapes, len(d.shapes[0].text), d.fill_rgb), (20_000, 20_000, 1000, [3, 4]))
        self.assertEqual(cut, ["shapes: 20,001 (first 20,000 kept)",
                               "shapes[].text: a text of 3,000 characters (first 1,000 kept)"])
        s = schema("c", [f"v{k}" for k in range(300)])
        limits.bound(s)
        self.assertEqual((s.total, s.n, len(s.names), len(s.docs)), (256, 256, 256, 256))

    def test_the_view_keeps_bounded_robots_schemas_and_event_kinds(self):
        v = View()
        for k in range(limits.MAX_ROBOTS + 5):
            v.apply(0.0, "ROBOT_STATE", robot_state(k % 32768, run=1) if k < 32768 else robot_state(0, run=1))
        self.assertLessEqual(len(v.robots), limits.MAX_ROBOTS)
        for k in range(limits.MAX_EVENT_KINDS + 10):
            v.apply(0.0, "SWARM_EVENT", event(1, kind=f"k{k}", run=1))
        self.assertLessEqual(len(v.event_counts), limits.MAX_EVENT_KINDS + 1)
        for k in range(limits.MAX_SCHEMAS + 10):
            v.apply(0.0, "TELEMETRY_SCHEMA", schema(f"c{k}", ["a"], run=1))
        self.assertLessEqual(v.schemas.count(), limits.MAX_SCHEMAS)
        f = v.frame({})
        for what in ("robots past the first 20,000", "event kinds past the first 64", "schemas past the first 256"):
            self.assertIn(what, f["limits"])

    def test_two_pages_of_a_huge_log_leave_the_server_answering(self):
        srv = Server("--log", self.log, "--speed", 100, timeout=LONG)
        try:
            asyncio.run(self._two_pages(srv.url))
            srv.proc.send_signal(signal.SIGTERM)     # stops at once, pages still open
            _, err = srv.proc.communicate(timeout=LONG)
        finally:
            srv.proc.kill()
        self.assertEqual((srv.proc.returncode, err), (0, "swarm-live: stopped\n"))

    async def _two_pages(self, url):
        async with aiohttp.ClientSession() as http:
            pages = [await http.ws_connect(url + "ws") for _ in range(2)]
            for ws in pages:                      # both playing: frames of the big states
                while "swarm" not in (f := json.loads((await ws.receive(timeout=LONG)).data)):
                    pass
                self.assertEqual(len(f["swarm"]["values"]), 256)
                self.assertIn("SWARM_STATE values: 32,000 (first 256 kept)", f["limits"])
                self.assertIn("ROBOT_STATE state: a text of 5,000 characters", f["limits"])
            async with http.get(url, timeout=aiohttp.ClientTimeout(total=LONG)) as r:
                self.assertEqual(r.status, 200)
                self.assertIn("swarm-live", await r.text())
            for ws in pages:
                await ws.send_str('{"cmd": "seek", "value": 0}')


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
