"""The simulator from Python (swarmtools.Sim, swarmtools.run): the command
line's results through the public C API in process, for every shipped
scenario with its golden seed (the hashes and metrics tests/cli/golden.sh
pins); the robots' arrays as views of the simulator's memory; loader errors
as exceptions with file and line; several simulations in one process and
on two threads at once; a whole run with its outputs; the live host link."""
import gc
import re
import tempfile
import threading
import unittest
from pathlib import Path

import numpy as np

import swarmtools
from swarmtools.sim import RunError, ScenarioError, Sim, SimError

ROOT = Path(__file__).resolve().parents[3]
SCENARIOS = ROOT / "sim_host" / "scenarios"


def golden_pins():
    """{scenario: state hash} of tests/cli/golden.sh (the one table of pins)."""
    text = (ROOT / "tests" / "cli" / "golden.sh").read_text()
    block = text[text.index("pins=("):]
    block = block[:block.index("\n)")]
    return dict(re.findall(r'"(\w+)\s+([0-9a-f]{16})"', block))


def golden_metrics(name):
    """tests/golden/<name>.metrics as {metric: text of its value}."""
    out = {}
    for line in (ROOT / "tests" / "golden" / f"{name}.metrics").read_text().splitlines():
        key, _, value = line.partition(": ")
        out[key.strip('"')] = value
    return out


def c_number(v):
    """A value as summary.c prints it (%.10g, null for NaN)."""
    return "null" if v != v else format(v, ".10g")


class SameAsTheCommandLine(unittest.TestCase):
    def test_every_shipped_scenario_gives_its_golden_hash_and_metrics(self):
        pins = golden_pins()
        self.assertGreaterEqual(len(pins), 10)
        for name, want in pins.items():
            with self.subTest(scenario=name), Sim(SCENARIOS / f"{name}.yaml") as sim:
                sim.run()
                self.assertEqual(sim.state_hash, want)
                got = {k: c_number(v) for k, v in sim.task_metrics().items()}
                self.assertEqual(got, golden_metrics(name))
                summary = sim.summary()
                self.assertEqual(summary["state_hash"], want)
                self.assertEqual(summary["steps"], sim.step_count)

    def test_steps_in_any_slices_give_the_same_run(self):
        with Sim(SCENARIOS / "random_walk.yaml", seed=5) as a, Sim(SCENARIOS / "random_walk.yaml", seed=5) as b:
            a.step(700)
            for n in (1, 2, 97, 300, 300):
                b.step(n)
            self.assertEqual(a.step_count, 700)
            self.assertEqual(a.state_hash, b.state_hash)
            self.assertAlmostEqual(a.time, 70.0)


class Robots(unittest.TestCase):
    def setUp(self):
        self.sim = Sim(SCENARIOS / "foraging_base.yaml", seed=3, overrides={"robots.0.count": 12})

    def tearDown(self):
        self.sim.close()

    def test_arrays_are_views_of_the_simulators_memory(self):
        r = self.sim.robots
        x = r.x
        self.assertEqual(x.shape, (13,))                  # 12 foragers and the beacon
        self.assertFalse(x.flags.writeable)
        self.assertIs(r.x.base, x.base)                   # the same memory, read twice
        before = x.copy()
        self.sim.step(200)
        self.assertFalse(np.array_equal(before, x), "the view shows the new step")
        self.assertTrue(np.shares_memory(r["pose.x"], x))
        self.assertEqual(r["ir.proximity"].shape, (13, 8))
        self.assertEqual(r.wheels.shape, (13, 2))
        # Each value as the per-robot C accessors give it.
        lib = swarmtools.sim._lib.lib()
        import ctypes
        for i in (0, 5, 12):
            px, py, pt = ctypes.c_double(), ctypes.c_double(), ctypes.c_double()
            lib.sim_robot_pose(self.sim._handle.sim, i, ctypes.byref(px), ctypes.byref(py), ctypes.byref(pt))
            self.assertEqual((float(x[i]), float(r.y[i]), float(r.theta[i])),
                             (np.float32(px.value), np.float32(py.value), np.float32(pt.value)))

    def test_states_and_observables(self):
        self.sim.step(150)
        r = self.sim.robots
        states = r.state
        self.assertEqual(len(states), 13)
        self.assertTrue(set(states[:12]) <= {"start", "wait", "search", "return", "deposit", "park", "run"}, states)
        codes, names = r.state_codes()
        self.assertEqual([names[c] for c in codes], list(states))
        foragers = self.sim.group("foragers")
        self.assertEqual((foragers.first, foragers.count, foragers.controller), (0, 12, "forager"))
        th = foragers.observables["threshold"]
        self.assertEqual(th.raw.shape, (12,))
        self.assertTrue(np.shares_memory(th.raw, th.raw))
        # Counters: the summary's total is the sum of the robots' own.
        oae = r.observable("oae")
        self.assertTrue(np.isnan(oae[12]), "the beacon shows no oae")
        self.assertEqual(np.nansum(oae), self.sim.task_metrics()["oae_total"])
        with self.assertRaises(KeyError):
            r.observable("no_such_value")
        frame = r.to_frame()
        self.assertEqual(len(frame), 13)
        self.assertIn("threshold", frame.columns)
        self.assertEqual(list(frame["state"].astype(object)), list(states))

    def test_a_view_outlives_close(self):
        x = self.sim.robots.x
        want = x.copy()
        self.sim.close()
        gc.collect()
        np.testing.assert_array_equal(x, want)            # still the run's memory
        with self.assertRaises(ValueError):
            self.sim.step()
        with self.assertRaises(ValueError):
            _ = self.sim.robots
        del x
        gc.collect()


class Errors(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def test_a_bad_file_names_its_file_line_and_key(self):
        bad = self.tmp / "bad.yaml"
        bad.write_text("duration: 10\nrobots:\n  - count: 2.5\n")
        with self.assertRaises(ScenarioError) as e:
            Sim(bad)
        self.assertEqual((e.exception.file, e.exception.line, e.exception.key),
                         (str(bad), 3, "robots[0].count"))
        self.assertIn("expected an integer", e.exception.reason)
        self.assertIn(f"{bad}:3:", str(e.exception))

    def test_a_bad_override_names_itself(self):
        with self.assertRaises(ScenarioError) as e:
            Sim(SCENARIOS / "random_walk.yaml", overrides={"robots.0.count": "abc"})
        self.assertEqual((e.exception.override, e.exception.key, e.exception.file),
                         ("robots.0.count=abc", "robots[0].count", None))
        with self.assertRaises(ScenarioError) as e:
            Sim(SCENARIOS / "random_walk.yaml", overrides=["no_such_key=1"])
        self.assertEqual(e.exception.override, "no_such_key=1")

    def test_missing_file_and_syntax_error(self):
        with self.assertRaises(ScenarioError) as e:
            Sim(self.tmp / "none.yaml")
        self.assertIn("cannot open", str(e.exception))
        bad = self.tmp / "syntax.yaml"
        bad.write_text("robots: [\n")
        with self.assertRaises(ScenarioError) as e:
            Sim(bad)
        self.assertEqual(e.exception.line, 2)

    def test_a_world_that_cannot_be_built(self):
        with self.assertRaises(SimError) as e:
            Sim(SCENARIOS / "random_walk.yaml", overrides={"robots.0.count": 5000})
        self.assertIn("random_walk.yaml", str(e.exception))

    def test_bad_arguments(self):
        for kw in ({"seed": -1}, {"seed": 2**53}, {"threads": 0}):
            with self.assertRaises(ValueError):
                Sim(SCENARIOS / "random_walk.yaml", **kw)
        with Sim(SCENARIOS / "random_walk.yaml") as sim, self.assertRaises(ValueError):
            sim.step(-1)


class SeveralSimulations(unittest.TestCase):
    def test_interleaved_and_on_two_threads(self):
        path = SCENARIOS / "random_walk.yaml"
        with Sim(path, seed=2) as alone:
            alone.step(400)
            want2 = alone.state_hash
        with Sim(path, seed=9) as alone:
            alone.step(400)
            want9 = alone.state_hash
        self.assertNotEqual(want2, want9)
        a, b = Sim(path, seed=2), Sim(path, seed=9)
        for _ in range(4):
            a.step(100)
            b.step(100)
        self.assertEqual((a.state_hash, b.state_hash), (want2, want9))
        a.close()
        b.close()
        sims = [Sim(path, seed=2), Sim(path, seed=9)]
        threads = [threading.Thread(target=s.step, args=(400,)) for s in sims]
        for t in threads:
            t.start()
        for t in threads:
            t.join(60)
        self.assertEqual([s.state_hash for s in sims], [want2, want9])
        for s in sims:
            s.close()


class LiveHostLink(unittest.TestCase):
    def test_messages_and_poses_reach_the_robot(self):
        with Sim(SCENARIOS / "random_walk.yaml", overrides={"robots.0.count": 2, "host.live": True}) as sim:
            self.assertTrue(sim.host_send(1, b"\x01\x02"))
            self.assertTrue(sim.host_send(1, b"\x03"))
            self.assertFalse(sim.host_send(1, b"\x04"), "a mailbox of two: the third is dropped")
            self.assertEqual((sim.host_dropped(1), sim.host_dropped(0)), (1, 0))
            sim.host_pose(0, 100, -200, 1571)
            sim.step()
        with Sim(SCENARIOS / "random_walk.yaml") as sim, self.assertRaises(ValueError):
            sim.host_send(0, b"\x01")

    def test_robot_ids(self):
        with Sim(SCENARIOS / "random_walk.yaml") as sim:
            self.assertEqual(sim.robot_id(3), 3)
            sim.set_robot_id(3, 1234)
            self.assertEqual(sim.robot_id(3), 1234)
            with self.assertRaises(IndexError):
                sim.robot_id(20)


class WholeRuns(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()

    def test_run_writes_the_command_lines_outputs(self):
        out = swarmtools.run(SCENARIOS / "random_walk.yaml", seed=4, reps=2, steps=300, out=self.tmp / "o",
                             overrides={"robots.0.count": 8})
        self.assertEqual([r.seed for r in out.runs], [4, 5])
        first = out.runs[0]
        self.assertEqual(first.summary["steps"], 300)
        self.assertTrue(first.summary["command"].startswith("swarmsim "))
        self.assertIn("--set robots.0.count=8", first.summary["command"])
        self.assertEqual(len(first.timeseries), 31)
        self.assertEqual(out.summary["reps_done"], 2)
        with Sim(SCENARIOS / "random_walk.yaml", seed=4, overrides={"robots.0.count": 8}) as sim:
            sim.step(300)
            self.assertEqual(sim.state_hash, first.summary["state_hash"])
        log = first.log()
        self.assertEqual(len(log.swarm), 301)
        self.assertEqual(log.summary["state_hash"], first.summary["state_hash"])
        data = swarmtools.load_run(first.dir)
        self.assertEqual(data.summary["seed"], 4)
        self.assertEqual(len(swarmtools.load_run(out.out)), 2)

    def test_run_errors(self):
        bad = self.tmp / "bad.yaml"
        bad.write_text("robots:\n  - count: -3\n")
        with self.assertRaises(ScenarioError) as e:
            swarmtools.run(bad, out=self.tmp / "b")
        self.assertEqual((e.exception.file, e.exception.line), (str(bad), 2))
        self.assertFalse((self.tmp / "b").exists(), "nothing written")
        with self.assertRaises(RunError) as e:
            swarmtools.run(SCENARIOS / "random_walk.yaml", out=self.tmp / "c", extra=["--no-such-option"])
        self.assertEqual(e.exception.status, 2)
        self.assertIn("--no-such-option", e.exception.message)


if __name__ == "__main__":
    unittest.main()
