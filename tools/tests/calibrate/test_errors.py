"""Bad input to the calibration kit: a robot that does not answer, an
operator who stops, readings that cannot be fitted, malformed recordings
and fragments, per-robot keys the simulator refuses.  Each gives a message
naming the procedure (or file) and what to redo, and writes nothing."""

from __future__ import annotations

import io
import json
import math
import os
import random
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import yaml

from swarmtools.calibrate import cli, fake_lab, fit, geometry, procedures
from swarmtools.calibrate.link import LinkError
from swarmtools.calibrate.operator import Aborted, TerminalOperator
from swarmtools.calibrate.procedures import Placement, Setup, Step
from swarmtools.calibrate.record import Recording
from swarmtools.sim import ScenarioError, Sim


class Silent(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def assertNothingWritten(self, out: Path):
        left = list(out.iterdir()) if out.exists() else []
        self.assertEqual(left, [], f"{out} has {left}")


class NoAnswer(Silent):
    def test_a_port_nobody_answers_on(self):
        master, slave = os.openpty()
        try:
            out = self.dir / "out"
            with self.assertRaises(LinkError) as cm:
                cli.calibrate(os.ttyname(slave), out, ["ir"], Setup(), TerminalOperator(), timeout_s=0.5,
                              log=lambda s: None)
            self.assertIn("did not answer within 0.5 s", str(cm.exception))
            self.assertIn("calibration image", str(cm.exception))
            self.assertNothingWritten(out)
        finally:
            os.close(master)
            os.close(slave)

    def test_the_bridge_writes_only_to_a_writable_device(self):
        from swarmtools.telemetry.bridge import Device
        master, slave = os.openpty()
        try:
            ro, rw = Device(os.ttyname(slave)), Device(os.ttyname(slave), writable=True)
            self.assertTrue(ro.open() and rw.open())
            self.assertFalse(ro.write(b"\x00abc\x00"))
            self.assertTrue(rw.write(b"\x00abc\x00"))
            self.assertEqual(os.read(master, 16), b"\x00abc\x00")
            ro.close()
            rw.close()
            self.assertFalse(rw.write(b"x"))     # closed: down
        finally:
            os.close(master)
            os.close(slave)

    def test_a_missing_device(self):
        err = io.StringIO()
        with redirect_stderr(err):
            rc = cli.main(["run", str(self.dir / "rfcomm9"), "--out", str(self.dir / "out"), "--timeout", "0.5"])
        self.assertEqual(rc, 1)
        self.assertIn("rfcomm9: cannot open it", err.getvalue())
        self.assertIn("nothing written", err.getvalue())
        self.assertNothingWritten(self.dir / "out")


class OperatorStops(Silent):
    def test_stopping_midway_writes_nothing(self):
        answers = iter(["", "", "q"])       # ready; first placement; stops at the second
        fakes, link, _ = fake_lab.start(5, fake_lab.perturbed(random.Random(1)), self.dir / "lab", speed=500)
        out = self.dir / "out"
        try:
            with self.assertRaises(Aborted):
                cli.calibrate(link, out, ["ir"], Setup(windows=1), TerminalOperator(read=lambda p: next(answers),
                                                                                    out=io.StringIO()),
                              timeout_s=60, log=lambda s: None)
        finally:
            fakes.stop()
        self.assertNothingWritten(out)


def ir_steps(value_at):
    """A recording of the IR procedure whose sensor s reads value_at(s, d)."""
    out = []
    for p in procedures.placements("ir"):
        d = procedures.ir_distance_m(p) if p.gap_mm is not None else None
        mean = [value_at(s, d if s == p.sensor else None) for s in range(8)]
        out.append(Step(p, [(tuple(mean), tuple([25.0] * 8))]))
    return out


class Unfittable(unittest.TestCase):
    def test_saturated_sensor(self):
        steps = ir_steps(lambda s, d: 4095.0 if s == 2 and d is not None else (500.0 if d is not None else 40.0))
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_ir(steps)
        msg = str(cm.exception)
        self.assertTrue(msg.startswith("ir: IR2 has 0 usable distances"), msg)
        self.assertIn("saturated at 3 mm, 8 mm", msg)
        self.assertIn("redo: the ir steps of IR2", msg)

    def test_missing_steps(self):
        def curve(s, d):
            return 30.0 if d is None else 1.2 * geometry.ir_curve(d) + 30.0
        steps = [s for s in ir_steps(curve) if s.placement.sensor != 5 or s.placement.gap_mm < 10]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_ir(steps)
        self.assertIn("IR5 has 2 usable distances", str(cm.exception))

    def test_no_straight_wheel_run(self):
        turns = [Step(Placement("wheels", left=400, right=-400, periods=15), moved=(0.0, 0.0, -160.0),
                      steps=(600.0, -600.0))] * 2
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_wheels(turns, Setup())
        self.assertIn("wheels: 2 runs measured, none straight", str(cm.exception))

    def test_clipped_wheel_steps(self):
        runs = [Step(Placement("wheels", left=300, right=300, periods=30), moved=(116.0, 0.0, 0.0),
                     steps=(850.0, 900.0)),
                Step(Placement("wheels", left=400, right=-400, periods=15), moved=(0.0, 0.0, -167.0),
                     steps=(600.0, -600.0))]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_wheels(runs, Setup())
        self.assertIn("run 300,300 x30 counted 850, 900 steps where 900, 900 were commanded", str(cm.exception))

    def test_ambient_all_dark(self):
        steps = [Step(p, [(tuple([3000.0] * 8), tuple([9.0] * 8))]) for p in procedures.placements("ambient")]
        steps = [Step(s.placement, [(tuple([5.0] * 8), s.windows[0][1])]) for s in steps]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_ambient(steps, Setup())
        self.assertIn("ambient: every lit reading is near 0", str(cm.exception))


    def test_camera_never_sees_the_card(self):
        steps = [Step(Placement("camera", distance_mm=d, bearing_deg=b), [(tuple([0.0] * 8), tuple([0.0] * 8))])
                 for d, b in ((900, 0.0), (450, 0.0), (200, 30.0))]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_camera(steps)
        self.assertIn("camera: the card was never seen ahead", str(cm.exception))
        self.assertIn("redo: the camera procedure", str(cm.exception))


    @staticmethod
    def colour_steps(read):
        """The colours procedure's steps, each window what read(card, stats) says: (mean R, G, B, sd)."""
        out = []
        for p in procedures.placements("colours"):
            (r, g, b), sd = read(p.colour, p.stats)
            values = (800.0, r, g, b, sd, sd, sd, 0.0)
            out.append(Step(p, [(values, tuple([0.0] * 8))]))
        return out

    GOOD = {0: (110.0, 110.0, 115.0), 1: (180.0, 40.0, 40.0), 2: (30.0, 160.0, 60.0), 3: (25.0, 75.0, 215.0)}

    def test_colours_fit(self):
        """The kit's own check of its rule: a neutral grey gives gains of 1, the thresholds fall between."""
        got = fit.fit_colours(self.colour_steps(lambda c, s: (self.GOOD[c], 4.0))).params
        self.assertAlmostEqual(got["gain_r"], 1.0, delta=1e-3)
        self.assertAlmostEqual(got["gain_b"], 1.0, delta=1e-3)
        self.assertLess(max(g["margin"] for g in got["limits"]["grey"]), got["min_margin"])
        self.assertLess(got["min_margin"], min(c["margin"] for c in got["limits"]["cards"]))

    def test_colours_too_few_distances(self):
        steps = [st for st in self.colour_steps(lambda c, s: (self.GOOD[c], 4.0))
                 if not (st.placement.colour == 2 and st.placement.distance_mm == 60)]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_colours(steps)
        self.assertIn("colours: the green card was recorded at 1 distances (at least 2)", str(cm.exception))
        self.assertIn("redo: the colours steps of the green card", str(cm.exception))

    def test_colours_a_saturated_card(self):
        read = {**self.GOOD, 1: (255.0, 60.0, 50.0)}
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_colours(self.colour_steps(lambda c, s: (read[c], 2.0)))
        self.assertIn("colours: the red card at 30 mm is saturated (R 255 of 255)", str(cm.exception))
        self.assertIn("with less light on it", str(cm.exception))

    def test_colours_a_class_never_seen(self):
        read = {**self.GOOD, 3: (25.0, 170.0, 150.0)}     # a teal card: green leads
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_colours(self.colour_steps(lambda c, s: (read[c], 4.0)))
        self.assertIn("colours: the blue card at 30 mm reads R, G, B 25, 170, 150: never blue", str(cm.exception))

    def test_colours_no_gap_to_the_grey(self):
        read = {**self.GOOD, 0: (150.0, 100.0, 100.0)}    # a pink "grey": it leads like a red card
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_colours(self.colour_steps(lambda c, s: (read[c], 12.0)))
        self.assertIn("no threshold separates them", str(cm.exception))

    def test_colours_nothing_written(self):
        """A recording whose colour cards cannot be fitted: `fit` names it and writes nothing."""
        from swarmtools.calibrate.record import Recording
        read = {**self.GOOD, 2: (250.0, 252.0, 250.0)}
        with tempfile.TemporaryDirectory() as tmp:
            path, out = Path(tmp) / "r.json", Path(tmp) / "out"
            Recording(7, Setup(), {"colours": self.colour_steps(lambda c, s: (read[c], 3.0))}, "dev").save(path)
            err = io.StringIO()
            with redirect_stderr(err):
                rc = cli.main(["fit", str(path), "--out", str(out)])
            self.assertEqual(rc, 1)
            self.assertIn("r.json: robot 7: colours: the green card at 30 mm is saturated (G 252 of 255)",
                          err.getvalue())
            self.assertIn("nothing written", err.getvalue())
            self.assertFalse(out.exists())

    def test_a_band_never_heard(self):
        steps = [Step(p, [(tuple([0.0] * 8), tuple([0.0] * 8))]) for p in procedures.placements("sound")]
        with self.assertRaises(fit.FitError) as cm:
            fit.fit_sound(steps, Setup())
        self.assertIn("sound: band 1 was never heard", str(cm.exception))
        self.assertIn("redo: the sound steps of band 1 (is the emitter on?)", str(cm.exception))


class BadFiles(Silent):
    def run_cli(self, args):
        err = io.StringIO()
        with redirect_stderr(err):
            rc = cli.main(args)
        return rc, err.getvalue()

    def test_not_a_recording(self):
        bad = self.dir / "r.json"
        bad.write_text('{"format": "something else"}')
        rc, err = self.run_cli(["fit", str(bad), "--out", str(self.dir / "out")])
        self.assertEqual(rc, 1)
        self.assertIn("r.json: not a recording of swarm-calibrate", err)
        self.assertNothingWritten(self.dir / "out")

    def test_fragment_with_a_foreign_section(self):
        sc = self.dir / "s.yaml"
        sc.write_text("robots: [{count: 1, controller: calib}]\n")
        fr = self.dir / "f.yaml"
        fr.write_text("arena: {width: 3}\n")
        rc, err = self.run_cli(["apply", str(sc), str(fr), "-o", str(self.dir / "o.yaml")])
        self.assertEqual(rc, 1)
        self.assertIn("f.yaml: 'arena' is not a section a calibration fragment has", err)
        self.assertFalse((self.dir / "o.yaml").exists())


def wheel_runs(moved=None):
    """The wheels procedure's runs, each counted as commanded, each measured
    where wheel gains of 1 end it (or at `moved`)."""
    period = Setup().period_ms / 1000.0
    out = []
    for p in procedures.placements("wheels"):
        fx, fy, ft = fit.wheel_end(1.0, 1.0, p.left, p.right, p.periods, period)
        end = moved if moved is not None else (fx * 1000, fy * 1000, math.degrees(ft))
        out.append(Step(p, moved=tuple(end), steps=(p.left * p.periods * period, p.right * p.periods * period)))
    return out


def ambient_steps(read):
    return [Step(p, [(tuple(read() for _ in range(8)), tuple([9.0] * 8))]) for p in procedures.placements("ambient")]


class Nonsense(Silent):
    """Readings unrelated to the placements: `fit` must not write a fit of them (docs: status 1)."""

    def fit_cli(self, steps, *options):
        path, out = self.dir / "r.json", self.dir / "out"
        Recording(7, Setup(), steps, "dev").save(path)
        err, std = io.StringIO(), io.StringIO()
        with redirect_stderr(err), redirect_stdout(std):
            rc = cli.main(["fit", str(path), "--out", str(out), *options])
        return rc, err.getvalue(), std.getvalue(), out

    def test_good_wheel_runs_fit(self):
        """The check on the nonsense below: runs that follow the model fit (and "1 robot", singular)."""
        rc, err, std, out = self.fit_cli({"wheels": wheel_runs()})
        self.assertEqual(rc, 0, err)
        self.assertIn("swarm-calibrate: 1 robot: ", std)
        self.assertTrue((out / "fragment.yaml").is_file())

    def test_wheel_runs_answered_0_0_0(self):
        rc, err, _, out = self.fit_cli({"wheels": wheel_runs(moved=(0.0, 0.0, 0.0))})
        self.assertEqual(rc, 1)
        self.assertIn("r.json: robot 7: wheels: gain_left came out 0.1, the bound of its fit (0.1 to 10)", err)
        self.assertIn("redo: the wheels procedure", err)
        self.assertIn("nothing written", err)
        self.assertFalse(out.exists())

    def test_wheel_runs_off_the_model(self):
        """Ends 40 mm off, ahead and behind in turn: gains within their bounds, residuals beyond the tolerance."""
        runs = [Step(st.placement, moved=(st.moved[0] + (40.0 if k % 2 else -40.0), st.moved[1], st.moved[2]),
                     steps=st.steps) for k, st in enumerate(wheel_runs())]
        rc, err, _, out = self.fit_cli({"wheels": runs})
        self.assertEqual(rc, 1)
        self.assertRegex(err, r"robot 7: wheels: the fit's rms residual is [0-9.e+]+ mm / deg, above the "
                              r"tolerance 5 mm / deg \(--max-rms wheels=\.\.\.\)")
        self.assertFalse(out.exists())

    def test_ambient_readings_that_do_not_change_with_distance(self):
        rng = random.Random(1)
        steps = ambient_steps(lambda: rng.uniform(0.0, 4000.0))
        rc, err, _, out = self.fit_cli({"ambient": steps})
        self.assertEqual(rc, 1)
        self.assertRegex(err, r"r\.json: robot 7: ambient: the fit's rms residual is [0-9.e+]+ counts, above the "
                              r"tolerance 100 counts")
        self.assertIn("nothing written", err)
        self.assertFalse(out.exists())
        # The tolerance is a parameter: loosened, the same readings fit.
        rc, err, _, out = self.fit_cli({"ambient": steps}, "--max-rms", "ambient=5000")
        self.assertEqual(rc, 0, err)
        self.assertTrue((out / "fragment.yaml").is_file())

    def test_ambient_readings_all_the_same(self):
        rc, err, _, out = self.fit_cli({"ambient": ambient_steps(lambda: 1510.0)})
        self.assertEqual(rc, 1)
        self.assertIn("robot 7: ambient: half came out 1e+06, the bound of its fit (1e-06 to 1e+06)", err)
        self.assertFalse(out.exists())

    def test_a_bad_tolerance_option(self):
        for bad in ("wheels", "camera=1", "wheels=-1", "wheels=nan", "wheels=x"):
            with self.subTest(option=bad), redirect_stderr(io.StringIO()) as err, self.assertRaises(SystemExit) as cm:
                cli.main(["fit", "r.json", "--out", str(self.dir / "out"), "--max-rms", bad])
            self.assertEqual(cm.exception.code, 2)
            self.assertIn("--max-rms", err.getvalue())


class MalformedRecordings(Silent):
    """Each value of a recording is checked when it is read: the error names the file, the step and the key."""

    def good(self) -> dict:
        path = self.dir / "good.json"
        Recording(7, Setup(), {"wheels": wheel_runs(), "ambient": ambient_steps(lambda: 3000.0)}, "dev").save(path)
        return json.loads(path.read_text())

    CASES = (
        # (what, change to the good recording's JSON, words the error must have)
        ("moved not a number", lambda d: d["procedures"]["wheels"][0].update(moved=["a", 0, 0]),
         "procedures.wheels[0].moved[0]: 'a' is not a finite number"),
        ("moved with 2 values", lambda d: d["procedures"]["wheels"][1].update(moved=[1.0, 2.0]),
         "procedures.wheels[1].moved: 2 values: give 3 numbers"),
        ("moved not a list", lambda d: d["procedures"]["wheels"][1].update(moved=5),
         "procedures.wheels[1].moved: 5: give 3 numbers"),
        ("a speed in words", lambda d: d["procedures"]["wheels"][2]["placement"].update(left="fast"),
         "procedures.wheels[2].placement.left: 'fast' is not an integer"),
        ("NaN moved", lambda d: d["procedures"]["wheels"][0].update(moved=[float("nan"), 0, 0]),
         "procedures.wheels[0].moved[0]: nan is not a finite number"),
        ("infinite steps counted", lambda d: d["procedures"]["wheels"][0].update(steps=[float("inf"), 0]),
         "procedures.wheels[0].steps[0]: inf is not a finite number"),
        ("steps with 3 values", lambda d: d["procedures"]["wheels"][0].update(steps=[1, 2, 3]),
         "procedures.wheels[0].steps: 3 values: give 2 numbers"),
        ("NaN in a window", lambda d: d["procedures"]["ambient"][3]["windows"][0][0].__setitem__(2, float("nan")),
         "procedures.ambient[3].windows[0][0][2]: nan is not a finite number"),
        ("a window of 7 channels", lambda d: d["procedures"]["ambient"][0]["windows"][0][1].pop(),
         "procedures.ambient[0].windows[0][1]: 7 values: give 8 numbers"),
        ("a window without variances", lambda d: d["procedures"]["ambient"][0]["windows"][0].pop(),
         "procedures.ambient[0].windows[0]: give [means, variances]"),
        ("no windows", lambda d: d["procedures"]["ambient"][0].update(windows=[]),
         "procedures.ambient[0].windows: none recorded"),
        ("a sensor that is not there", lambda d: d["procedures"]["ambient"][0]["placement"].update(sensor=9),
         "procedures.ambient[0].placement.sensor: 9 is not a sensor"),
        ("a distance missing", lambda d: d["procedures"]["ambient"][0]["placement"].update(distance_mm=None),
         "procedures.ambient[0].placement.distance_mm: missing"),
        ("a distance in words", lambda d: d["procedures"]["ambient"][0]["placement"].update(distance_mm="far"),
         "procedures.ambient[0].placement.distance_mm: 'far' is not a finite number"),
        ("a step of another procedure", lambda d: d["procedures"]["ambient"][0]["placement"].update(procedure="ir"),
         "procedures.ambient[0].placement.procedure: 'ir' under 'ambient'"),
        ("an unknown placement key", lambda d: d["procedures"]["ambient"][0]["placement"].update(tilt=3),
         "procedures.ambient[0].placement.tilt: not a placement key"),
        ("steps not a list", lambda d: d["procedures"].update(wheels={"a": 1}),
         "procedures.wheels: not a list of steps"),
        ("no setup", lambda d: d.pop("setup"), "good.json: setup: missing"),
        ("a setup in words", lambda d: d["setup"].update(period_ms="100"),
         "setup.period_ms: '100' is not a positive integer"),
        ("a NaN lamp", lambda d: d["setup"].update(lamp_height_mm=float("nan")),
         "setup.lamp_height_mm: nan is not a positive number"),
        ("an emitter level of 0", lambda d: d["setup"].update(sound_a0=0),
         "setup.sound_a0: 0 is not a positive number"),
        ("a robot id in words", lambda d: d.update(robot_id="7"), "robot_id: '7' is not a robot id"),
    )

    def test_each_malformed_value(self):
        for what, change, words in self.CASES:
            with self.subTest(what):
                d = self.good()
                change(d)
                path = self.dir / "good.json"
                path.write_text(json.dumps(d))          # NaN and Infinity as Python's json writes them
                out = self.dir / "out"
                err = io.StringIO()
                with redirect_stderr(err):
                    rc = cli.main(["fit", str(path), "--out", str(out)])
                self.assertEqual(rc, 1, err.getvalue())
                self.assertIn(f"{path}: ", err.getvalue())
                self.assertIn(words, err.getvalue())
                self.assertIn("nothing written", err.getvalue())
                self.assertFalse(out.exists())

    def test_the_good_one_loads(self):
        """The cases' base is valid: each error above is its change's."""
        self.good()
        rec = Recording.load(self.dir / "good.json")
        self.assertEqual((rec.robot_id, sorted(rec.steps)), (7, ["ambient", "wheels"]))
        self.assertEqual(rec.steps["wheels"][0].moved, wheel_runs()[0].moved)


class ApplyRefused(Silent):
    """`apply` loads the merged scenario in the simulator before writing it."""

    def apply(self, fragment_text: str):
        sc, fr, out = self.dir / "s.yaml", self.dir / "lab_fragment.yaml", self.dir / "o" / "mine.yaml"
        sc.write_text(yaml.safe_dump({"robots": [{"count": 2, "controller": "calib"}]}))
        fr.write_text(fragment_text)
        err = io.StringIO()
        with redirect_stderr(err), redirect_stdout(io.StringIO()):
            rc = cli.main(["apply", str(sc), str(fr), "-o", str(out)])
        return rc, err.getvalue(), out

    def test_fragments_the_simulator_refuses(self):
        for what, text, words in (
                ("one IR sensor", "ir:\n  sensors: [{gain: 1.0, offset: 3.0}]\n",
                 "ir.sensors: lists 1 sensors: give all 8"),
                ("a negative gain", "wheels:\n  gain_left: -3\n", "wheels.gain_left: -3 is out of range"),
                ("an id twice", "wheels:\n  robots: [{id: 1, gain_left: 1.0}, {id: 1, gain_left: 1.1}]\n",
                 "wheels.robots[1].id: robot id listed twice")):
            with self.subTest(what):
                rc, err, out = self.apply(text)
                self.assertEqual(rc, 1, err)
                self.assertIn("lab_fragment.yaml: the simulator refuses s.yaml with it: " + words, err)
                self.assertIn("nothing written", err)
                self.assertFalse(out.exists())
                self.assertEqual(list(out.parent.iterdir()), [], "no temporary file left")

    def test_a_fragment_the_simulator_takes(self):
        rc, err, out = self.apply("wheels:\n  gain_left: 1.02\n  robots: [{id: 1, gain_right: 0.98}]\n")
        self.assertEqual(rc, 0, err)
        self.assertEqual(yaml.safe_load(out.read_text())["wheels"]["gain_left"], 1.02)
        self.assertEqual(list(out.parent.iterdir()), [out])

    def test_a_fragment_yaml_error_names_the_file(self):
        rc, err, out = self.apply("wheels: [\n")
        self.assertEqual(rc, 1)
        self.assertIn('in "' + str(self.dir / "lab_fragment.yaml") + '", line 2', err)
        self.assertNotIn("<unicode string>", err)
        self.assertFalse(out.exists())


class SimulatorRefuses(Silent):
    def load(self, sections) -> str:
        path = self.dir / "s.yaml"
        path.write_text(yaml.safe_dump({"robots": [{"count": 1, "controller": "calib"}], **sections}))
        with self.assertRaises(ScenarioError) as cm:
            Sim(path)
        return str(cm.exception)

    def test_seven_sensors(self):
        msg = self.load({"ir": {"robots": [{"id": 1, "sensors": [{"gain": 1.0} for _ in range(7)]}]}})
        self.assertIn("ir.robots[0].sensors: lists 7 sensors: give all 8 (IR0 first) or none", msg)

    def test_an_id_twice(self):
        msg = self.load({"wheels": {"robots": [{"id": 4, "gain_left": 1.0}, {"id": 4, "gain_right": 1.1}]}})
        self.assertIn("wheels.robots[1].id", msg)
        self.assertIn("robot id listed twice", msg)

    def test_a_negative_gain(self):
        msg = self.load({"wheels": {"robots": [{"id": 4, "gain_left": -1.0}]}})
        self.assertIn("gain_left", msg)

    def test_a_camera_id_twice(self):
        msg = self.load({"camera": {"robots": [{"id": 4, "fov": 50.0}, {"id": 4, "range": 0.5}]}})
        self.assertIn("s.yaml:", msg)
        self.assertIn("camera.robots[1].id", msg)
        self.assertIn("robot id listed twice", msg)

    def test_per_robot_cameras_are_the_geometric_models(self):
        msg = self.load({"camera": {"model": "rendered", "robots": [{"id": 4, "fov": 50.0}]}})
        self.assertIn("camera.robots", msg)
        self.assertIn("per-robot lenses are the geometric model's", msg)

    def test_per_robot_colour_gains_the_rendered_camera_takes(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "s.yaml"
            path.write_text(yaml.safe_dump({"arena": {"width": 1.0, "height": 1.0}, "camera": {
                "model": "rendered", "robots": [{"id": 4, "gain_r": 0.9, "gain_b": 1.1}]},
                "robots": [{"count": 1, "controller": "calib"}]}))
            with Sim(path) as sim:
                sim.step(1)

    def test_a_camera_fov_out_of_range(self):
        msg = self.load({"camera": {"robots": [{"id": 4, "fov": 200.0}]}})
        self.assertIn("camera.robots[0].fov", msg)


if __name__ == "__main__":
    unittest.main()
