"""The calibration kit end to end without robots (docs/how-to/calibrate.md):
a fake e-puck flashed with the calibration image plays the real robot, its
world's models given known, perturbed parameters for its id; a simulated
operator places it and reads the ruler; swarm-calibrate records through
the bridge's decoder, fits, and must give back the parameters within the
stated tolerances.  Then the fragment goes into a scenario, per robot id
and as the lab's average, and the simulator runs on it."""

from __future__ import annotations

import io
import random
import tempfile
import unittest
from contextlib import redirect_stderr
from pathlib import Path

import yaml

from swarmtools.calibrate import cli, fake_lab, fragment, geometry, procedures
from swarmtools.calibrate.record import Recording
from swarmtools.sim import Sim

ROBOT_ID = 7
#: The tolerances the kit states (docs/how-to/calibrate.md), as fractions
#: of the true value, or counts for the IR offsets.
TOL = {"ir_gain": 0.03, "ir_offset": 6.0, "ir_noise": 0.25, "ambient_dark": 0.01, "ambient_half": 0.05,
       "ambient_noise": 0.25, "wheel_gain": 0.01, "camera_range_m": 0.015, "camera_fov_deg": 1.0,
       "colour_gain": 0.03, "sound_alpha": 0.07, "sound_ae": 0.05, "sound_noise": 0.25, "sound_gain": 0.05}


def rel(a, b):
    return abs(a - b) / abs(b)


class Recovery(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = Path(cls.tmp.name)
        cls.truth = fake_lab.perturbed(random.Random(3))
        fakes, link, cls.world = fake_lab.start(ROBOT_ID, cls.truth, cls.dir / "lab", speed=500)
        try:
            # One window per placement (the kit's default is two): half the time, still within tolerance.
            # The emitter: a second fake e-puck in the same world, on its own port, told by the kit.
            cls.operator = fake_lab.SimOperator(fakes)
            cls.rec, cls.fits = cli.calibrate(link, cls.dir / "out", list(procedures.PROCEDURES),
                                              procedures.Setup(windows=1), cls.operator, timeout_s=60,
                                              log=lambda s: None, emitter=fakes.links[1])
            cls.emitter = (fakes.robots[1].robot_id, fakes.robots[1].host.msgs, fakes.robots[1].host.not_ours)
        finally:
            fakes.stop()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_robot_and_outputs(self):
        self.assertEqual(self.rec.robot_id, ROBOT_ID)
        out = self.dir / "out"
        for name in ("recording.json", "fragment.yaml", "report/report.md", "report/robot7_ir.png",
                     "report/robot7_ambient.png", "report/robot7_wheels.png", "report/robot7_camera.png",
                     "report/robot7_colours.png", "report/robot7_sound.png"):
            self.assertTrue((out / name).is_file(), name)
        text = (out / "report" / "report.md").read_text()
        self.assertIn("## Not measured", text)
        self.assertIn("camera", text)

    def test_ir_recovered(self):
        got, want = self.fits["ir"].params, self.truth["ir"]
        for s in range(8):
            g, w = got["sensors"][s], want["sensors"][s]
            self.assertLess(rel(g["gain"], w["gain"]), TOL["ir_gain"], f"IR{s} gain {g} vs {w}")
            self.assertLess(abs(g["offset"] - w["offset"]), TOL["ir_offset"], f"IR{s} offset {g} vs {w}")
        self.assertLess(rel(got["noise_rel"], want["noise_rel"]), TOL["ir_noise"], got)
        self.assertLess(rel(got["noise_abs"], want["noise_abs"]), TOL["ir_noise"], got)

    def test_ambient_recovered(self):
        got, want = self.fits["ambient"].params, self.truth["ambient"]
        self.assertLess(rel(got["dark"], want["dark"]), TOL["ambient_dark"], got)
        self.assertLess(rel(got["half"], want["half"]), TOL["ambient_half"], got)
        self.assertLess(rel(got["noise_rel"], want["noise_rel"]), TOL["ambient_noise"], got)

    def test_wheels_recovered(self):
        got, want = self.fits["wheels"].params, self.truth["wheels"]
        for k in ("gain_left", "gain_right"):
            self.assertLess(rel(got[k], want[k]), TOL["wheel_gain"], f"{k}: {got} vs {want}")

    def test_camera_recovered(self):
        got, want = self.fits["camera"].params, self.truth["camera"]
        self.assertLess(abs(got["range"] - want["range"]), TOL["camera_range_m"], f"{got} vs {want}")
        self.assertLess(abs(got["fov"] - want["fov"]), TOL["camera_fov_deg"], f"{got} vs {want}")

    def test_colour_response_recovered(self):
        got, want = self.fits["colours"].params, self.truth["camera"]
        for k in ("gain_r", "gain_b"):
            self.assertLess(rel(got[k], want[k]), TOL["colour_gain"], f"{k}: {got[k]} vs {want[k]}")

    @staticmethod
    def _classified(sim, card: int, colour: int) -> float:
        """Pixels of the truth robot's frame the detector gives `colour`, the robot 30 mm from `card`."""
        p = procedures.Placement("colours", colour=card, distance_mm=30)
        x, y, th = procedures.colour_pose_for(p)
        cx, cy = fake_lab.COLOUR_CARDS[card]
        sim.set_pose(0, cx - fake_lab.COLOUR_CARD_RADIUS + x, cy + y, th)
        sim.host_send(0, procedures.protocol.frame(colour))
        sim.step(21)                   # a window to settle, and one latched
        return float(sim.robots.observable("mean0")[0])

    def test_thresholds_fitted_separate_the_classes(self):
        """The fragment's thresholds on the truth robot (its colour response, its sensor noise): every
        pixel of each card in its class, none of the grey card in any; the fitted values within the gaps
        the limits leave."""
        cam = yaml.safe_load((self.dir / "out" / "fragment.yaml").read_text())["camera"]
        keys = {f"camera.{k}": cam[k] for k in ("min_value", "min_margin", "min_saturation_q8")}
        lim = self.fits["colours"].params["limits"]
        self.assertLess(max(g["margin"] for g in lim["grey"]), cam["min_margin"])
        self.assertLess(cam["min_margin"], min(c["margin"] for c in lim["cards"]))
        frame = geometry.camera_width_px() * geometry.camera_height_px()
        with Sim(self.world, overrides={"host.live": True, **keys}) as sim:
            sim.set_robot_id(0, ROBOT_ID)
            for card in (1, 2, 3):
                self.assertGreaterEqual(self._classified(sim, card, card), 0.99 * frame, f"card {card}")
                self.assertEqual(self._classified(sim, 0, card), 0.0, f"grey as {card}")

    def test_the_emitter_played_as_the_kit_told_it(self):
        """The tones came from the second robot's calibration image, through its own port: 4 commands at
        least (bands 1, 2, 3 and silence), none for another robot, none by the operator's hand."""
        rid, msgs, not_ours = self.emitter
        self.assertEqual(rid, fake_lab.emitter_id(ROBOT_ID))
        self.assertGreaterEqual(msgs, 4)
        self.assertEqual(not_ours, 0)
        self.assertNotIn("tone", [what for what, _ in self.operator.log])

    def test_sound_recovered(self):
        got, want = self.fits["sound"].params, self.truth["sound"]
        for k in ("alpha", "ae", "noise"):
            self.assertLess(rel(got[k], want[k]), TOL[f"sound_{k}"], f"{k}: {got} vs {want}")
        for b in (1, 2, 3):
            self.assertLess(rel(got[f"gain{b}"], want[f"gain{b}"]), TOL["sound_gain"], f"band {b}: {got} vs {want}")

    def _scenario(self, average: bool) -> Path:
        base = self.dir / "base.yaml"
        base.write_text(yaml.safe_dump({"name": "lab_study", "arena": {"width": 1.0, "height": 1.0},
                                        "robots": [{"count": 2, "controller": "calib", "placement": {
                                            "shape": "poses", "poses": [{"x": 0.0, "y": 0.2, "heading": 0},
                                                                        {"x": 0.0, "y": -0.2, "heading": 0}]}}]}))
        out = self.dir / ("average.yaml" if average else "per_robot.yaml")
        args = ["apply", str(base), str(self.dir / "out" / "fragment.yaml"), "-o", str(out)]
        self.assertEqual(cli.main(args + (["--average"] if average else [])), 0)
        return out

    def _reading_at_wall(self, scenario: Path, robot_id: int) -> float:
        """Mean IR0 reading of robot 0 (given `robot_id`) 8 mm from a wall."""
        with Sim(scenario, overrides={"host.live": True}) as sim:
            sim.set_robot_id(0, robot_id)
            sim.host_send(0, b"P")
            p = procedures.Placement("ir", sensor=0, gap_mm=8)
            x, _, th = procedures.robot_pose_for(p)
            sim.set_pose(0, 0.5 + x, 0.2, th)
            total = 0.0
            for _ in range(40):
                sim.step(1)
                total += float(sim.robots["ir.proximity"][0][0])
            return total / 40

    def test_scenario_takes_the_fragment(self):
        d = procedures.ir_distance_m(procedures.Placement("ir", sensor=0, gap_mm=8))
        mine = self.fits["ir"].params["sensors"][0]
        expect = mine["gain"] * geometry.ir_curve(d) + mine["offset"]
        per_robot = self._scenario(average=False)
        self.assertAlmostEqual(self._reading_at_wall(per_robot, ROBOT_ID) / expect, 1.0, delta=0.02)
        # Another id takes the lab's average: one robot here, so the same sensors but not the entry.
        data = yaml.safe_load(per_robot.read_text())
        self.assertEqual([r["id"] for r in data["ir"]["robots"]], [ROBOT_ID])
        avg = self._scenario(average=True)
        self.assertNotIn("robots", yaml.safe_load(avg.read_text())["ir"])
        self.assertAlmostEqual(self._reading_at_wall(avg, 3) / expect, 1.0, delta=0.02)
        # Without the fragment: the default curve, far from this robot's.
        plain = self.dir / "base.yaml"
        self.assertNotAlmostEqual(self._reading_at_wall(plain, ROBOT_ID) / expect, 1.0, delta=0.02)


    def test_the_lab_from_two_recordings(self):
        """`fit` over two robots' recordings: one entry each, their average in the sections' keys,
        a fragment the simulator takes."""
        first = self.dir / "out" / "recording.json"
        rec = Recording.load(first)
        rec.robot_id = 9
        for st in rec.steps["wheels"]:       # robot 9 went 2 % further
            st.moved = (st.moved[0] * 1.02, st.moved[1] * 1.02, st.moved[2] * 1.02)
        second = self.dir / "robot9.json"
        rec.save(second)
        self.assertEqual(cli.main(["fit", str(first), str(second), "--out", str(self.dir / "lab")]), 0)
        lab = yaml.safe_load((self.dir / "lab" / "fragment.yaml").read_text())
        self.assertEqual([r["id"] for r in lab["wheels"]["robots"]], [ROBOT_ID, 9])
        g7, g9 = (r["gain_left"] for r in lab["wheels"]["robots"])
        self.assertAlmostEqual(g9 / g7, 1.02, delta=0.002)
        self.assertAlmostEqual(lab["wheels"]["gain_left"], (g7 + g9) / 2, delta=1e-4)
        self.assertTrue((self.dir / "lab" / "report" / "robot9_ir.png").is_file())
        out = self.dir / "lab_study.yaml"
        self.assertEqual(cli.main(["apply", str(self.world), str(self.dir / "lab" / "fragment.yaml"),
                                   "-o", str(out)]), 0)
        with Sim(out) as sim:
            sim.step(1)

    def test_a_recording_that_cannot_be_fitted(self):
        rec = Recording.load(self.dir / "out" / "recording.json")
        rec.steps["ir"] = [st for st in rec.steps["ir"] if st.placement.sensor != 4]
        bad = self.dir / "no_ir4.json"
        rec.save(bad)
        err = io.StringIO()
        with redirect_stderr(err):
            rc = cli.main(["fit", str(bad), "--out", str(self.dir / "lab_bad")])
        self.assertEqual(rc, 1)
        self.assertIn("no_ir4.json: robot 7: ir: IR4 has 0 usable distances", err.getvalue())
        self.assertIn("nothing written", err.getvalue())
        self.assertFalse((self.dir / "lab_bad").exists())


class CameraPerRobot(unittest.TestCase):
    """camera.robots: a robot whose id has an entry sees with its own reach, the others with the section's,
    and an id set after the run is made is followed."""

    def blobs(self, ids) -> list:
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "cam.yaml"
            path.write_text(yaml.safe_dump({
                "arena": {"width": 2.0, "height": 2.0}, "camera": {"range": 1.0, "robots": [{"id": 7, "range": 0.3}]},
                "robots": [{"count": 2, "controller": "calib", "placement": {"shape": "poses", "poses": [
                    {"x": -0.5, "y": 0.5, "heading": 0}, {"x": -0.5, "y": -0.5, "heading": 0}]}}],
                "objects": [{"shape": "cylinder", "x": 0.0, "y": 0.5, "radius": 0.03, "colour": "red"},
                            {"shape": "cylinder", "x": 0.0, "y": -0.5, "radius": 0.03, "colour": "red"}]}))
            out = []
            with Sim(path, overrides={"host.live": True}) as sim:
                for k in (0, 1):
                    sim.host_send(k, b"C\x01")
                for step_ids in ids:
                    for k, rid in enumerate(step_ids):
                        sim.set_robot_id(k, rid)
                    sim.step(10)
                    out.append([int(v) for v in sim.robots["camera.blob_count"]])
            return out

    def test_its_own_reach(self):
        # The cards 0.43 m from the lenses: within the section's 1 m, beyond robot 7's 0.3 m.
        self.assertEqual(self.blobs([(7, 1), (1, 7)]), [[0, 1], [1, 0]])


class FragmentsMerge(unittest.TestCase):
    def test_lab_average_of_two_robots(self):
        a = {"ir": fake_fit({"sensors": [{"gain": 1.0, "offset": 10.0}] * 8, "noise_rel": 0.01, "noise_abs": 4.0})}
        b = {"ir": fake_fit({"sensors": [{"gain": 2.0, "offset": 30.0}] * 8, "noise_rel": 0.03, "noise_abs": 6.0})}
        sec = fragment.build({3: a, 9: b})
        self.assertEqual(sec["ir"]["sensors"][0], {"gain": 1.5, "offset": 20.0})
        self.assertEqual(sec["ir"]["noise_abs"], 5.0)
        self.assertEqual([r["id"] for r in sec["ir"]["robots"]], [3, 9])


def fake_fit(params):
    from swarmtools.calibrate.fit import Fit
    return Fit("ir", params)


if __name__ == "__main__":
    unittest.main()
