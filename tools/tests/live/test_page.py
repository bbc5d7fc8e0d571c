"""The live view in a real headless browser (make live-tests): Debian's
chromium through chromium-driver, driven by Selenium (browser.py).

A short run of the walkthrough's scenario is replayed by swarm-live; the
page must show its 12 robots where the log has them (the page's own state
and the canvas's pixels), the obstacle, the lamp and the task's goal ring,
move its clock while playing, stand still when paused, seek both ways, and
end with the run's summary.  Real robots (a hand-built log of robot states
without a pose, and the bridge's counters) show as tiles with 'no
positions'.  A simulation published live over UDP multicast reaches the
page.  If the browser cannot start, the tests fail with the reason.
"""
import json
import math
import re
import subprocess
import tempfile
import threading
import time
import unittest
from pathlib import Path

import swarmlcm

from swarmtools.telemetry import common

from ..telemetry.helpers import ROOT, SCENARIOS, SWARMSIM, robot_state, run_sim, schema, write_log
from .browser import Browser
from .serve import LONG, Server, first, free_udp_port, picture_at, poses_at, wait_for

GATHER = SCENARIOS / "phototaxis_gather.yaml"
FORAGING = SCENARIOS / "foraging_base.yaml"
STEPS = 300                    # 30 s: the log's end
POSITION_TOL = 1e-5            # m: the page shows the log's float32 poses, through JSON

# The share of a robot's body (pixels between 0.35 and 0.75 of its radius
# from its centre, where no LED or heading bar is) that has the colour it
# should have.
BODY_JS = """
const [robots, r] = arguments;
const ctx = document.getElementById('arena').getContext('2d');
const hex = (d) => '#' + [d[0], d[1], d[2]].map((v) => v.toString(16).padStart(2, '0')).join('');
return robots.map(([x, y, want]) => {
  let n = 0, hit = 0;
  for (let px = Math.floor(x - r); px <= x + r; px++) for (let py = Math.floor(y - r); py <= y + r; py++) {
    const d = Math.hypot(px + 0.5 - x, py + 0.5 - y);
    if (d < 0.35 * r || d > 0.75 * r) continue;
    n++;
    if (hex(ctx.getImageData(px, py, 1, 1).data) === want) hit++;
  }
  return hit / Math.max(n, 1);
});
"""
PIXEL_JS = """
const ctx = document.getElementById('arena').getContext('2d');
return arguments[0].map(([x, y]) => Array.from(ctx.getImageData(Math.floor(x), Math.floor(y), 1, 1).data.slice(0, 3))
  .map((v) => v.toString(16).padStart(2, '0')).join(''));
"""


def rgb(n):
    return f"{n & 0xFFFFFF:06x}"


class Recorder:
    """Writes what comes on `channel` of LCM bus `url` to an LCM log file,
    on a thread of its own, until close()."""

    def __init__(self, url, channel, path):
        lcm = common.lcm_module()
        self.bus, self.log = lcm.LCM(url), lcm.EventLog(str(path), "w", overwrite=True)
        self.bus.subscribe(channel, lambda ch, data: self.log.write_event(time.time_ns() // 1000, ch, data))
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        while not self.stop.is_set():
            self.bus.handle_timeout(50)

    def close(self):
        if not self.stop.is_set():
            self.stop.set()
            self.thread.join()
            self.log.close()


class BrowserTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not SWARMSIM.exists():
            raise AssertionError(f"{SWARMSIM} not built (make live-tests builds it)")
        cls._tmp = tempfile.TemporaryDirectory(prefix="live_test.")
        cls.tmp = Path(cls._tmp.name)
        cls.browser = Browser()
        cls.driver = cls.browser.driver

    @classmethod
    def tearDownClass(cls):
        cls.browser.quit()
        cls._tmp.cleanup()

    def setUp(self):
        self.servers = []

    def tearDown(self):
        for s in self.servers:
            status, err = s.stop()
            self.assertEqual(status, 0, err)
            self.assertNotIn("Traceback", err)

    def serve(self, *args):
        s = Server(*args)
        self.servers.append(s)
        self.driver.get(s.url)
        wait_for(lambda: self.state()["connected"] and self.state()["frames"] > 0, "the page's first frame")
        return s

    def state(self):
        return self.driver.execute_script("return window.liveState")

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def click(self, element_id):
        self.driver.find_element("id", element_id).click()

    def seek(self, t):
        # A range input's value set and its change event: what letting go of the slider does.
        self.js("const s = document.getElementById('seek'); s.value = arguments[0];"
                "s.dispatchEvent(new Event('change'));", str(t))
        return wait_for(lambda: (st := self.state())["time"] == t and st, f"the page at t = {t} s")


class ReplayedRun(BrowserTest):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        run_sim(cls.tmp / "gather", GATHER, "--steps", STEPS)
        cls.run_dir = cls.tmp / "gather" / "run_1"
        cls.log = cls.run_dir / "telemetry.lcmlog"

    has_scene = True    # the log has SCENE and TASK_DRAWING

    def check_robots_at(self, st, t):
        """The page's robots are the log's at time t: states, and places both
        in the page's state and on the canvas."""
        want = poses_at(self.log, t)
        self.assertEqual(len(want), 12)
        got = {r["id"]: r for r in st["robots"]}
        self.assertEqual(set(got), set(want))
        for rid, m in want.items():
            r = got[rid]
            self.assertTrue(r["pose"])
            self.assertAlmostEqual(r["x"], m.x, delta=POSITION_TOL, msg=rid)
            self.assertAlmostEqual(r["y"], m.y, delta=POSITION_TOL, msg=rid)
            self.assertAlmostEqual(r["theta"], m.theta, delta=POSITION_TOL, msg=rid)
            self.assertEqual(r["state"], m.state)
        self.assertEqual(len(st["placed"]), 12)
        self.assertEqual(st["tiles"], 0)
        self.assertFalse(st["noPositions"])
        # On the canvas: where the log's pose maps, the robot's body is drawn.
        where = [self.js("return window.liveView.toCanvas(arguments[0], arguments[1])", m.x, m.y) for m in want.values()]
        placed = {p["id"]: (p["x"], p["y"]) for p in st["placed"]}
        for rid, (x, y) in zip(want, where, strict=True):
            self.assertAlmostEqual(placed[rid][0], x, delta=0.01)
            self.assertAlmostEqual(placed[rid][1], y, delta=0.01)
        # Its colour: the fill its task gives it now, else the default body,
        # as the PNG frames draw it (both from the log's SCENE and
        # TASK_DRAWING); in a log without them, a colour per state.
        scene, drawing = picture_at(self.log, t) if self.has_scene else (None, None)
        fills = dict(zip(drawing.fill_robot, drawing.fill_rgb, strict=True)) if drawing else {}
        colours = ["#" + rgb(fills.get(rid, scene.robot_rgb)) if scene else st["stateColours"][m.state]
                   for rid, m in want.items()]
        shares = self.js(BODY_JS, [[x, y, c] for (x, y), c in zip(where, colours, strict=True)], st["radiusPx"])
        for rid, share in zip(want, shares, strict=True):
            self.assertGreater(share, 0.5, f"robot {rid}: {share:.0%} of its body in its colour")
        if scene:
            # The legend: the scene's keys in its colours, each robot key
            # with the robots of its colour, the task's goal among them.
            keys = [{"kind": k, "colour": "#" + rgb(c), "label": label,
                     "count": colours.count("#" + rgb(c)) if k == 0 else None}
                    for k, c, label in zip(scene.key_kind, scene.key_rgb, scene.key_label, strict=True)]
            self.assertEqual(st["legend"], keys)
            self.assertIn({"kind": 2, "colour": "#" + rgb(drawing.shapes[0].rgb), "label": "goal", "count": None}, keys)
            text = self.driver.find_element("id", "legend").text
            for k in keys:
                self.assertIn(k["label"] if k["count"] is None else f"{k['label']} {k['count']}", text)

    def test_robots_at_the_logs_places_and_seek(self):
        self.serve("--log", self.log, "--paused")
        st = self.state()
        self.assertEqual((st["mode"], st["scenario"], st["run"], st["playing"], st["time"]),
                         ("log", "phototaxis_gather", 1, False, 0))
        self.assertEqual(st["end"], STEPS / 10)
        self.assertEqual((st["obstacles"], st["lights"], st["shapes"], st["items"]), (1, 1, 2, 0))
        self.check_robots_at(st, 0.0)
        time.sleep(0.3)
        self.assertEqual(self.state()["time"], 0)           # paused: nothing moves

        st = self.seek(10.0)
        self.assertEqual((st["clock"], st["step"]), (10.0, 100))
        self.check_robots_at(st, 10.0)
        self.assertIn("t = 10.0 s", self.driver.find_element("id", "clock").text)
        # The arena, the obstacle, the lamp and the task's ring where the log puts them.
        scene, drawing = first(self.log, "scene_t"), first(self.log, "task_drawing_t")
        w, wall = scene.arena_width, scene.wall_thickness
        o, lamp, ring = scene.obstacles[0], scene.lights[0], drawing.shapes[0]
        self.assertEqual(ring.kind, 1)
        at = [self.js("return window.liveView.toCanvas(arguments[0], arguments[1])", x, y)
              for x, y in ((w / 2 - 0.02, 0), (w / 2 + wall / 2, 0), (o.x, o.y), (lamp.x, lamp.y))]
        self.assertEqual(self.js(PIXEL_JS, at), ["eeebe0", "3c3c46", rgb(o.rgb), "ffc814"])
        x, y = self.js("return window.liveView.toCanvas(arguments[0], arguments[1])", ring.x + ring.radius, ring.y)
        near = self.js(PIXEL_JS, [[x + dx, y] for dx in (-2, -1, 0, 1, 2)])
        self.assertIn(rgb(ring.rgb), near)

        st = self.seek(3.0)                                   # backwards: the page starts over
        self.check_robots_at(st, 3.0)
        self.assertEqual(st["seriesPoints"], 31)              # swarm states 0..3 s at 10 Hz

    def test_a_log_from_before_the_scene(self):
        """A v2 log without SCENE and TASK_DRAWING: the robots on the arena
        of RUN_INFO, nothing else drawn."""
        lcm = common.lcm_module()
        old = self.tmp / "before_scene.lcmlog"
        write_log(old, [(ev.timestamp, ev.channel, bytes(ev.data)) for ev in lcm.EventLog(str(self.log), "r")
                        if ev.channel not in ("SCENE", "TASK_DRAWING")])
        self.serve("--log", old, "--paused")
        st = self.seek(10.0)
        self.assertEqual((st["obstacles"], st["lights"], st["shapes"]), (0, 0, 0))
        self.has_scene = False
        self.check_robots_at(st, 10.0)
        self.assertEqual({e["label"] for e in st["legend"]}, {m.state for m in poses_at(self.log, 10.0).values()})

    def test_plays_pauses_and_ends_with_the_summary(self):
        self.serve("--log", self.log, "--speed", "4")
        t0 = self.state()["time"]
        # The log plays (the rate itself, 4x of real time, is exact in
        # test_server's Session test: measured here, it would be a timing
        # assertion that a busy machine fails).
        st = wait_for(lambda: (s := self.state())["time"] >= t0 + 16 and s, "16 s of the log played")
        self.assertTrue(st["playing"])
        self.assertEqual(st["speed"], 4)
        self.assertGreater(st["step"], 0)
        self.click("play")                                    # it says pause while playing
        st = wait_for(lambda: (s := self.state()) and not s["playing"] and s, "the pause")
        time.sleep(0.4)
        self.assertEqual(self.state()["time"], st["time"])
        self.driver.find_element("css selector", "#speed option[value='20']").click()
        self.click("play")
        st = wait_for(lambda: (s := self.state())["ended"] and s, "the end of the log")
        summary = json.loads((self.run_dir / "summary.json").read_text())
        self.assertEqual((st["summary"], st["time"], st["playing"], st["speed"]),
                         (summary["state_hash"], STEPS / 10, False, 20))
        self.assertIn(summary["state_hash"], self.driver.find_element("id", "summary").text)
        self.assertEqual(st["seriesPoints"], STEPS + 1)
        self.assertIn("swarm.in_goal", st["charts"])          # the swarm schema's values, and the states
        self.assertIn("state.", st["charts"])
        # Every chart has a time axis and a value axis in its value's unit
        # (the swarm schema's; robots by state: "robots"), with ticks.
        swarm = next(m for _, m in common.read_log(self.log, "test")
                     if type(m).__name__ == "schema_t" and m.kind == "swarm")
        units = {f"swarm.{n}": u for n, u in zip(swarm.names, swarm.units, strict=True)} | {"state.": "robots"}
        self.assertEqual(set(st["chartAxes"]), set(st["charts"]))
        for key, axes in st["chartAxes"].items():
            self.assertEqual(axes["x"]["label"], "time (s)", key)
            self.assertEqual(axes["y"]["label"], units.get(key, axes["y"]["label"]), key)
            xs = [float(v) for v in axes["x"]["ticks"]]
            self.assertGreaterEqual(len(xs), 2, key)
            self.assertTrue(all(0 <= v <= STEPS / 10 for v in xs) and xs == sorted(xs), (key, xs))
            self.assertGreaterEqual(len(axes["y"]["ticks"]), 2, key)
        self.assertTrue(any(units[k] for k in st["chartAxes"] if k in units))
        # The robots by state: a line a state, named in its colour.
        lines = st["chartAxes"]["state."]["lines"]
        self.assertTrue(lines)
        self.assertEqual({li["name"]: li["colour"] for li in lines},
                         {li["name"]: st["stateColours"][li["name"]] for li in lines})
        self.check_robots_at(st, STEPS / 10)


class ReplayedForaging(BrowserTest):
    """Seed 000's base run: the page's legend has the task's nest and food
    in SCENE's colours, and a searching robot's body has the legend's
    colour for searching, as in the PNG frames (tests/test_legend.c)."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        run_sim(cls.tmp / "foraging", FORAGING, "--steps", STEPS)
        cls.log = cls.tmp / "foraging" / "run_1" / "telemetry.lcmlog"

    def test_the_legend_has_the_nest_and_the_food(self):
        self.serve("--log", self.log, "--paused")
        t = STEPS / 10
        st = self.seek(t)
        scene, drawing = picture_at(self.log, t)
        legend = {e["label"]: e for e in st["legend"]}
        sent = {label: (k, "#" + rgb(c)) for k, c, label in zip(scene.key_kind, scene.key_rgb, scene.key_label,
                                                                 strict=True)}
        self.assertEqual({label: (e["kind"], e["colour"]) for label, e in legend.items()}, sent)
        self.assertEqual(legend["nest"]["kind"], 1)                           # a floor area
        self.assertEqual(legend["nest"]["colour"], "#" + rgb(drawing.shapes[0].rgb))
        self.assertEqual((legend["food"]["kind"], legend["food"]["colour"]), (3, "#" + rgb(drawing.items[0].rgb)))
        searching = legend["searching"]["colour"]
        ids = [r for r, c in zip(drawing.fill_robot, drawing.fill_rgb, strict=True) if "#" + rgb(c) == searching]
        self.assertTrue(ids, "no robot searching at 30 s")
        self.assertEqual(legend["searching"]["count"], len(ids))
        robots = poses_at(self.log, t)
        where = [self.js("return window.liveView.toCanvas(arguments[0], arguments[1])", robots[r].x, robots[r].y)
                 for r in ids]
        shares = self.js(BODY_JS, [[x, y, searching] for x, y in where], st["radiusPx"])
        self.assertGreater(sum(share > 0.5 for share in shares), len(ids) / 2, shares)
        self.assertTrue(all(st["bodies"][str(r)] == searching for r in ids))


class RealRobots(BrowserTest):
    """What the bridge publishes: robot states without a pose, their
    controller's schema in pieces, the bridge's counters; stamped with the
    wall clock as lcm-logger records them."""

    def test_tiles_and_no_positions(self):
        t0 = 1_780_000_000_000_000
        events = [(t0 + k, "TELEMETRY_SCHEMA", schema("sorter", [name], units=[unit], first=k, total=2))
                  for k, (name, unit) in enumerate((("load", "g"), ("hits", "")))]
        for k in range(20):           # 10 s, robots 3, 7 and 12 at 2 Hz each, in turn
            for rid in (3, 7, 12):
                state = "sort" if (k + rid) % 3 else "rest"
                events.append((t0 + k * 500_000 + rid * 1000, "ROBOT_STATE",
                               robot_state(rid, state, controller="sorter", values=[rid + k, k], utime=k * 500_000)))
            if k % 2 == 0:
                status = swarmlcm.bridge_status_t()
                status.utime = t0 + k * 500_000
                status.devices = []
                for rid in (3, 7):
                    d = swarmlcm.bridge_device_t()
                    d.device, d.robot_id, d.connected, d.frames = f"/dev/rfcomm{rid}", rid, True, k
                    status.devices.append(d)
                status.n_devices = len(status.devices)
                events.append((t0 + k * 500_000 + 20_000, "BRIDGE_STATUS", status))
        log = write_log(self.tmp / "robots.lcmlog", events)
        self.serve("--log", log, "--speed", "5")
        st = wait_for(lambda: (s := self.state())["tiles"] == 3 and s["seriesPoints"] >= 3 and s, "three tiles")
        self.assertTrue(st["noPositions"])
        self.assertEqual(st["placed"], [])
        self.assertIsNone(st["clock"])                        # no simulated time: the log's
        nopos = self.driver.find_element("id", "nopos")
        self.assertTrue(nopos.is_displayed())
        self.assertIn("no positions", nopos.text)
        self.assertFalse(self.driver.find_element("id", "arena").is_displayed())
        tiles = self.driver.find_element("id", "tiles").text
        for rid in (3, 7, 12):
            self.assertIn(f"robot {rid} sorter", tiles)
        self.assertIn("load", tiles)                          # the values, named by the pieces of the schema
        self.assertEqual(st["bridgeDevices"], 2)
        self.assertIn("/dev/rfcomm7", self.driver.find_element("id", "bridge").text)
        self.assertTrue({"state.", "sorter.load", "sorter.hits"} <= set(st["charts"]), st["charts"])
        later = wait_for(lambda: (s := self.state())["time"] > st["time"] + 1 and s, "the clock moving")
        self.assertIn("since the log's first message", self.driver.find_element("id", "clock").text)
        self.assertGreater(later["seriesPoints"], st["seriesPoints"])


class LiveBus(BrowserTest):
    def test_a_simulation_over_udp(self):
        steps = 60
        run_sim(self.tmp / "reference", GATHER, "--steps", steps)      # the same run, to a log
        url = f"udpm://239.255.76.67:{free_udp_port()}?ttl=0"
        self.serve("--lcm", url)
        st = self.state()
        self.assertEqual((st["mode"], st["robots"]), ("live", []))
        self.assertFalse(self.driver.find_element("id", "seek").is_displayed())
        args = [SWARMSIM, GATHER, "--steps", steps, "--lcm", url, "--realtime", 5, "--out", self.tmp / "live", "--quiet"]
        sim = subprocess.run(list(map(str, args)), cwd=ROOT, capture_output=True, text=True, timeout=LONG)
        self.assertEqual(sim.returncode, 0, sim.stderr)
        st = wait_for(lambda: (s := self.state())["summary"] and s, "the run's summary")
        ref = json.loads((self.tmp / "reference" / "run_1" / "summary.json").read_text())
        self.assertEqual((st["summary"], st["clock"], len(st["placed"])), (ref["state_hash"], steps / 10, 12))
        final = poses_at(self.tmp / "reference" / "run_1" / "telemetry.lcmlog", steps / 10)
        for r in st["robots"]:
            self.assertAlmostEqual(r["x"], final[r["id"]].x, delta=POSITION_TOL)
            self.assertAlmostEqual(r["y"], final[r["id"]].y, delta=POSITION_TOL)
        self.click("play")                                    # live: freezes the view
        wait_for(lambda: not self.state()["playing"], "the view frozen")
        self.assertEqual(self.driver.find_element("id", "play").text, "follow")


# Mouse events on the arena canvas at canvas pixels: what a hand does (the
# page's own handlers; the canvas is not scaled by CSS, but at() allows it).
MOUSE_JS = """
const [kind, u, v, extra] = arguments;
const cv = document.getElementById('arena'), b = cv.getBoundingClientRect();
const x = b.left + u * b.width / cv.width, y = b.top + v * b.height / cv.height;
const target = kind === 'mouseup' ? window : cv;
const ev = kind === 'wheel' ? new WheelEvent('wheel', { clientX: x, clientY: y, deltaY: extra, bubbles: true, cancelable: true })
                            : new MouseEvent(kind, { clientX: x, clientY: y, bubbles: true });
target.dispatchEvent(ev);
"""


class ControlledRun(BrowserTest):
    """A simulation under swarmsim --control, steered from the page."""

    def test_pause_step_inspect_move_zoom(self):
        url = f"udpm://239.255.76.67:{free_udp_port()}?ttl=0"
        self.serve("--lcm", url, "--control-lcm", url)
        args = [SWARMSIM, GATHER, "--steps", 3000, "--lcm", url, "--realtime", 5, "--control", "--paused",
                "--control-lcm", url, "--telemetry-rate", 10, "--out", self.tmp / "controlled", "--quiet"]
        # The run's robot states recorded from the bus into an LCM log (lcm.EventLog), to read the panel against.
        self.log = self.tmp / "robot_states.lcmlog"
        recorder = Recorder(url, "ROBOT_STATE", self.log)
        sim = subprocess.Popen(list(map(str, args)), cwd=ROOT, stderr=subprocess.PIPE, text=True)
        try:
            self._steer(sim, recorder)
        finally:
            recorder.close()
            if sim.poll() is None:
                sim.kill()
            sim.communicate()

    def _mouse(self, kind, u, v, extra=0):
        self.js(MOUSE_JS, kind, u, v, extra)

    def _control(self, check, what):
        return wait_for(lambda: (s := self.state())["control"] and check(s["control"]) and s, what)

    def _step(self, n):
        self.js("document.getElementById('step-n').value = arguments[0];", str(n))
        self.click("step")

    def _steer(self, sim, recorder):
        st = self._control(lambda c: c["paused"] and c["step"] == 0, "the run waiting at step 0 (--paused)")
        self.assertEqual(self.driver.find_element("id", "play").text, "resume")
        self.assertTrue(self.driver.find_element("id", "step").is_displayed())
        self._step(10)
        st = self._control(lambda c: c["paused"] and c["step"] == 10, "the run paused again at step 10")
        self.assertIn("step 10 of 3000", self.driver.find_element("id", "clock").text)
        self.assertIn("PAUSED", self.driver.find_element("id", "clock").text)
        self.click("play")                                    # resume ...
        self._control(lambda c: not c["paused"] and c["step"] > 10, "the run going on")
        self.click("play")                                    # ... and pause: the counter stops
        st = self._control(lambda c: c["paused"], "the run paused")
        stopped = st["control"]["step"]
        self._step(10)                                        # so the next 10 steps are exactly 10
        st = self._control(lambda c: c["paused"] and c["step"] == stopped + 10 and c["pending"] == 0,
                           f"the run at step {stopped + 10}")
        # Click robot 3: its panel, from the run's details of it.
        st = wait_for(lambda: (s := self.state())["placed"] and len(s["placed"]) == 12 and s, "the robots drawn")
        p3 = next(p for p in st["placed"] if p["id"] == 3)
        self._mouse("mousedown", p3["x"], p3["y"])
        self._mouse("mouseup", p3["x"], p3["y"])
        st = wait_for(lambda: (s := self.state())["detail"] and s["detail"]["id"] == 3 and s["control"]["selected"] == 3
                      and s, "robot 3's details")
        d = st["detail"]
        self.assertEqual(d["clock"], (stopped + 10) / 10)    # the paused step's readings
        self.assertEqual(len(d["prox"]), 8)
        self.assertIn("robot 3", st["panel"])
        self.assertIn("IR prox " + " ".join(map(str, d["prox"])), st["panel"])
        self.assertIn(f"robot 3 phototaxis {d['state']}", st["panel"])
        self.assertIn(f"wheels {d['wheels'][0]} / {d['wheels'][1]} steps/s", st["panel"])
        shown = re.search(r"robot 3 phototaxis \S+ for ([0-9.]+) s", st["panel"])
        self.assertIsNotNone(shown, st["panel"])              # its time in its state
        self.assertAlmostEqual(float(shown.group(1)), d["state_time_s"], delta=0.05)
        clicked = d                                          # read against the run's log at the end
        # Drag it 40 px to the right: the simulator's pose moves there.
        x0, y0 = p3["x"], p3["y"]
        want = self.js("return window.liveView.toWorld(arguments[0], arguments[1]);", x0 + 40, y0)
        self._mouse("mousedown", x0, y0)
        self._mouse("mousemove", x0 + 20, y0)
        self._mouse("mousemove", x0 + 40, y0)
        self._mouse("mouseup", x0 + 40, y0)
        # A mouse event's coordinates are whole CSS pixels: about 5 mm of this 3 m arena each.
        tol = 0.01
        before = st["detail"]
        st = wait_for(lambda: (s := self.state())["control"]["commands"] == 5 and s, "the move done")
        self.assertAlmostEqual(st["detail"]["x"], want[0], delta=tol)
        self.assertAlmostEqual(st["detail"]["y"], want[1], delta=tol)
        self.assertGreater(math.hypot(st["detail"]["x"] - before["x"], st["detail"]["y"] - before["y"]), 0.1)
        commands = st["control"]["commands"]
        # Zoom out (the wheel, about the centre), and drag it off the arena: refused, said, nothing changes.
        self._mouse("wheel", 320, 320, 700)
        st = wait_for(lambda: (s := self.state())["zoom"]["k"] < 0.5 and s, "the arena zoomed out")
        p3 = next(p for p in st["placed"] if p["id"] == 3)
        self._mouse("mousedown", p3["x"], p3["y"])
        self._mouse("mousemove", 5, 5)
        self._mouse("mouseup", 5, 5)
        wait_for(lambda: "outside the arena" in (self.driver.find_element("id", "error").text or ""),
                 "the refusal on the page")
        st = self.state()
        self.assertEqual(st["control"]["commands"], commands)
        self.assertAlmostEqual(st["detail"]["x"], want[0], delta=tol)
        # Its live keys: a value out of range is refused, said, and changes nothing; one in range is set.
        st = wait_for(lambda: (s := self.state())["detail"]["params"] and s, "robot 3's live keys in its details")
        self.assertEqual({p["name"]: p["value"] for p in st["detail"]["params"]}["speed_steps_s"], "400")
        box = self.driver.find_element("id", "param-speed_steps_s")
        box.send_keys("5000")
        self.click("set-speed_steps_s")
        wait_for(lambda: "speed_steps_s: 5000 is out of range [0, 1000]" in (self.driver.find_element("id", "error").text
                                                                              or ""), "the set's refusal on the page")
        st = self.state()
        self.assertEqual(st["control"]["commands"], commands)
        self.assertEqual({p["name"]: p["value"] for p in st["detail"]["params"]}["speed_steps_s"], "400")
        box.clear()
        box.send_keys("120")
        self.click("set-speed_steps_s")
        st = wait_for(lambda: (s := self.state())["control"]["commands"] == commands + 1
                      and {p["name"]: p["value"] for p in s["detail"]["params"]}["speed_steps_s"] == "120" and s,
                      "the set done, its value in the details")
        self.assertIn("120", self.driver.find_element("id", "now-speed_steps_s").text)
        # Zoom in about robot 3: it stays under the cursor, its neighbours move away.
        self.js("document.getElementById('arena').dispatchEvent(new MouseEvent('dblclick', {bubbles: true}));")
        st = wait_for(lambda: (s := self.state())["zoom"]["k"] == 1 and s, "the whole arena again")
        before = {p["id"]: p for p in st["placed"]}
        self._mouse("wheel", before[3]["x"], before[3]["y"], -350)
        st = wait_for(lambda: (s := self.state())["zoom"]["k"] > 1.5 and s, "the arena zoomed in")
        after = {p["id"]: p for p in st["placed"]}
        self.assertAlmostEqual(after[3]["x"], before[3]["x"], delta=2)     # the cursor's whole pixel
        self.assertAlmostEqual(after[3]["y"], before[3]["y"], delta=2)
        far = max((p for p in before.values() if p["id"] != 3),
                  key=lambda p: math.hypot(p["x"] - before[3]["x"], p["y"] - before[3]["y"]))
        grown = (math.hypot(after[far["id"]]["x"] - after[3]["x"], after[far["id"]]["y"] - after[3]["y"])
                 / math.hypot(far["x"] - before[3]["x"], far["y"] - before[3]["y"]))
        self.assertAlmostEqual(grown, st["zoom"]["k"], delta=0.02 * st["zoom"]["k"])
        self.assertLess(st["scaleM"], 1.0)
        # Follow robot 3: it comes to the middle of the canvas, and stays there.
        self.click("follow")
        st = wait_for(lambda: (s := self.state()) and (p := {q["id"]: q for q in s["placed"]}[3])
                      and abs(p["x"] - 320) < 1 and abs(p["y"] - 320) < 1 and s, "robot 3 in the middle")
        self.click("follow")
        # Fast to the end: the summary says what was done.
        self.js("const s = document.getElementById('speed'); s.append(new Option('1000x', '1000')); s.value = '1000';"
                "s.dispatchEvent(new Event('change'));")
        self._control(lambda c: c["realtime"] == 1000, "the real-time factor 1000")
        self.click("play")
        self.assertEqual(sim.wait(timeout=LONG), 0)
        summary = json.loads((self.tmp / "controlled" / "run_1" / "summary.json").read_text())
        self.assertTrue(summary["control"]["touched"])
        self.assertEqual([c["command"].split()[0] for c in summary["control"]["listed"]],
                         ["step", "resume", "pause", "step", "move", "set", "realtime", "resume"])
        self.assertIn({"step": stopped + 10, "robot": 3, "command": "set 3 speed_steps_s 120"},
                      summary["control"]["listed"])
        # What the panel showed of robot 3 is what the run's log recorded of it at that step.
        recorder.close()
        logged = [m for ev, m in common.read_log(self.log, "test")
                  if ev.channel == "ROBOT_STATE" and m.robot_id == 3 and m.utime == round(clicked["clock"] * 1e6)]
        self.assertEqual(len(logged), 1, "robot 3's ROBOT_STATE at the paused step")
        m = logged[0]
        self.assertEqual((m.state, [m.wheel_left, m.wheel_right]), (clicked["state"], clicked["wheels"]))
        self.assertEqual((m.x, m.y), (clicked["x"], clicked["y"]))      # float32 both, through JSON
        self.assertEqual(list(m.values), clicked["values"])
        self.assertEqual((m.ir_max, m.ambient_min), (max(clicked["prox"]), min(clicked["ambient"])))
        # Its time in its state: since the log's first message of robot 3 in
        # that state after the last one in another (bounds when the log is
        # sparser than the steps).
        trail = sorted((m.utime / 1e6, m.state) for ev, m in common.read_log(self.log, "test")
                       if ev.channel == "ROBOT_STATE" and m.robot_id == 3 and m.utime <= round(clicked["clock"] * 1e6))
        first, before = trail[-1][0], 0.0
        for t, state in reversed(trail):
            if state != clicked["state"]:
                before = t
                break
            first = t
        self.assertGreaterEqual(clicked["state_time_s"], clicked["clock"] - first - 1e-3, trail[-5:])
        self.assertLessEqual(clicked["state_time_s"], clicked["clock"] - before + 1e-3, trail[-5:])


if __name__ == "__main__":
    unittest.main()
