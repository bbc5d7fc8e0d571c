"""Tests of swarmtools.evolve (swarm-evolve) with the real simulator (env SWARMSIM).

    .venv/bin/python -m unittest tools/tests/evolve/test_evolve.py

The fitness parser's whitelist (never eval), the evolution file's strict
errors with their lines, the searches' determinism (CMA-ES and the GA, given
the seed and the generation), and a tiny CMA-ES evolution on the sweep
engine: the same files, byte for byte, from two runs, from a run stopped
after its first generation and resumed, and from one interrupted in the middle
of a generation and resumed; a checkpoint of another evolution refused; the
genome and the fitness checked against the simulator before anything runs;
best_scenario.yaml's header reruns the measured fitness.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import subprocess
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from swarmtools.evolve import algorithms, cli
from swarmtools.evolve.fitness import Fitness, FitnessError
from swarmtools.evolve.spec import EvolveError, check_with_simulator, load
from swarmtools.sweep import plan as planmod
from swarmtools.sweep.store import Store

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
TINY = ROOT / "tests" / "data" / "evolve" / "tiny.yaml"
SQUARE = ROOT / "sim_host" / "scenarios" / "nnea_square.yaml"
# Every file the how-to (Determinism) says is the same byte for byte.
OUTPUTS = ("checkpoint.pkl", "generations.csv", "generations.parquet", "evaluations.csv", "fitness.png",
           "best_params.yaml", "best_params.h", "best_scenario.yaml")


def evolve(*args: str) -> subprocess.CompletedProcess:
    """swarm-evolve ARGS in this process (cma and DEAP imported once), its
    exit status and stderr as a CompletedProcess."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = cli.main([*args, "--sim", str(SWARMSIM), *(() if "--jobs" in args else ("--jobs", "2"))])
    return subprocess.CompletedProcess(args, rc, "", err.getvalue())


class FitnessExpressions(unittest.TestCase):
    def test_arithmetic_over_metrics(self) -> None:
        m = {"a": 2, "b": 0.5, "success": 1}
        self.assertEqual(Fitness("a")(m), 2.0)
        self.assertEqual(Fitness("a * (b + 1) - -3 / 2 + a ** 2 % 3")(m), 2 * 1.5 + 1.5 + 1)
        self.assertEqual(Fitness("max(a, b, 7) + min(a, b) + abs(-b) + sqrt(4) + log(exp(1))")(m), 7 + 0.5 + 0.5 + 3)
        self.assertEqual(Fitness("  success + 10 * b ").names, ["success", "b"])

    def test_everything_else_is_refused_when_read(self) -> None:
        for text, why in (("__import__('os').system('true')", "is not a function here"),
                          ("a.__class__", "is not allowed"), ("a[0]", "is not allowed"),
                          ("a if b else 1", "is not allowed"), ("a < b", "is not allowed"),
                          ("lambda: 1", "is not allowed"), ("'text'", "only numbers"), ("True", "only numbers"),
                          ("a // b", "is not allowed"), ("a << 1", "is not allowed"), ("not a", "only unary"),
                          ("max(a)", "takes 2 to 16 arguments"), ("abs(x=1)", "no keywords"),
                          ("a; b", "not an expression"), ("", "expected a metric name"), ("a +", "not an expression"),
                          ("[a, b]", "is not allowed"), ("f(*a)", "is not a function"), ("(a := 1)", "is not allowed"),
                          ("1" + "+1" * 300, "more than 200 parts")):
            with self.subTest(text=text), self.assertRaises(FitnessError) as e:
                Fitness(text)
            self.assertIn(why, str(e.exception))

    def test_a_missing_or_null_metric_is_named(self) -> None:
        with self.assertRaisesRegex(FitnessError, "no metric 'merge' .*they report: a"):
            Fitness("merge + 1")({"a": 1})
        with self.assertRaisesRegex(FitnessError, "metric 'merge_time_s' is None .*merge_time_capped_s"):
            Fitness("merge_time_s")({"merge_time_s": None})
        with self.assertRaisesRegex(FitnessError, "division by zero"):
            Fitness("a / (a - 1)")({"a": 1})


class Files(unittest.TestCase):
    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="evolve_test.")
        self.dir = Path(self._tmp.name)

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def write(self, text: str) -> Path:
        p = self.dir / "e.yaml"
        p.write_text(text)
        return p

    BASE = (f"scenarios: [{SQUARE}]\ngenome:\n  group: swarm\n  params:\n"
            "    - {key: b_out, size: 3, range: [-100, 100], integer: true}\nfitness: trips_total\ngenerations: 2\n")

    def test_a_good_file(self) -> None:
        sp = load(self.write(self.BASE + "algorithm: {name: ga, population: 6, elite: 2}\ntrials: 2\n"))
        self.assertEqual((sp.group, sp.dimension, sp.algorithm, sp.settings["elite"], sp.trials), (2, 3, "ga", 2, 2))
        self.assertEqual(sp.decode([0.0, 0.5, 1.0]), {"robots.2.params.b_out": (-100, 0, 100)})
        self.assertEqual(len(set(sp.trial_seeds(0) + sp.trial_seeds(1))), 4)   # new seeds each generation

    def test_the_shipped_evolutions_load(self) -> None:
        for f in sorted((ROOT / "studies").glob("*evolve*.yaml")):
            with self.subTest(f=f.name):
                sp = load(f)
                self.assertEqual(sp.dimension, 95)
                check_with_simulator(sp, SWARMSIM)     # their genome and fitness are the controller's and task's

    def test_each_mistake_is_named_with_its_line(self) -> None:
        cases = (
            (self.BASE + "trails: 3\n", ":8: trails: unknown key 'trails' (did you mean 'trials'?)"),
            (self.BASE.replace("fitness: trips_total", "fitness: os.system(1)"), ":6: fitness: 'os.system' is not a function"),
            (self.BASE.replace("group: swarm", "group: swarn"), ":3: genome.group: nnea_square.yaml has no group named 'swarn'"),
            (self.BASE.replace("[-100, 100]", "[100, -100]"), ":5: genome.params[0].range: expected two numbers, low < high"),
            (self.BASE.replace("size: 3", "size: 0"), ":5: genome.params[0].size: 0 is out of range"),
            (self.BASE + "algorithm: {name: pso}\n", ":8: algorithm.name: unknown algorithm 'pso' (valid: cmaes, ga)"),
            (self.BASE + "algorithm: {name: cmaes, elite: 3}\n", ":8: algorithm.elite: unknown setting 'elite' of cmaes"),
            (self.BASE + "algorithm: {name: ga, population: 4, elite: 5}\n", ":8: algorithm.elite: 5 is more than the population"),
            (self.BASE + "goal: most\n", ":8: goal: expected maximise or minimise"),
            (self.BASE.replace("generations: 2\n", ""), ": generations: missing"),
            (self.BASE.replace(str(SQUARE), "nope.yaml"), ":1: scenarios[0]: no such scenario file"),
        )
        for text, want in cases:
            with self.subTest(want=want), self.assertRaises(EvolveError) as e:
                load(self.write(text))
            self.assertIn(want, str(e.exception))


    def test_each_mistake_the_simulator_finds_is_named_with_its_line(self) -> None:
        # Found when the file is checked, before any run: the controller's own
        # descriptors judge the genome, a one-step run lists the metrics.
        two = self.BASE.replace("integer: true}\n", "integer: true}\n    - {key: tau, size: 4, range: [0, 255], "
                                                      "integer: true}\n")
        cases = (
            (two.replace("[0, 255]", "[0, 999]"),
             ":6: genome.params[1].range: [0, 999] goes beyond what nnea_square.yaml's controller takes "
             "(swarmsim: robots[2].params.tau[0]: 999 is out of range [0, 255])"),
            (two.replace("[-100, 100]", "[-9000, 100]"), ":5: genome.params[0].range: [-9000, 100] goes beyond"),
            (two.replace("size: 4", "size: 5"),
             ":6: genome.params[1].size: size 5 is not the length of 'tau' in nnea_square.yaml (swarmsim: "
             "robots[2].params.tau: expected exactly 4 numbers, got 5)"),
            (two.replace("key: tau", "key: stop_band"), ":6: genome.params[1].size: size 4 is not the length of "
                                                         "'stop_band'"),
            (two.replace("key: tau", "key: tauu"),
             ":6: genome.params[1].key: 'tauu' is not a param of the group's controller in nnea_square.yaml "
             "(swarmsim: robots[2].params.tauu: unknown key 'tauu' (did you mean 'tau'?))"),
            (two.replace("range: [0, 255], integer: true", "range: [0, 255]"),
             ":6: genome.params[1].integer: 'tau' holds integers: add `integer: true`"),
            (two.replace("group: swarm", "group: 7"), ":3: genome.group: nnea_square.yaml has no group 7"),
            (two.replace("fitness: trips_total", "fitness: trips_per_robt"),
             ":7: fitness: nnea_square.yaml's runs report no metric 'trips_per_robt' (did you mean "
             "'trips_per_robot'? they report: budget_s,"),
            (two.replace("fitness: trips_total", "fitness: 2 * trips_total + max(succes, 0)"),
             ":7: fitness: nnea_square.yaml's runs report no metric 'succes' (did you mean 'success'?"),
            ("set:\n  robots.2.count: -4\n" + two, ":2: set.robots.2.count: nnea_square.yaml refuses it: "
                                                   "robots[2].count: -4 is out of range"),
        )
        for text, want in cases:
            with self.subTest(want=want), self.assertRaises(EvolveError) as e:
                check_with_simulator(load(self.write(text)), SWARMSIM)
            self.assertIn(want, str(e.exception))
            self.assertLess(len(str(e.exception)), 600)    # the reason, not every gene's value
        check_with_simulator(load(self.write(two)), SWARMSIM)   # and the good file passes

    def test_a_bad_genome_or_argument_writes_nothing(self) -> None:
        bad = self.write(self.BASE.replace("fitness: trips_total", "fitness: trips_per_robt"))
        good = self.write_other(self.BASE)
        for args, want in (((str(bad),), ":6: fitness: nnea_square.yaml's runs report no metric 'trips_per_robt'"),
                           ((str(good), "--stop-after", "0"), "--stop-after must be at least 1 (got 0)"),
                           ((str(good), "--jobs", "-1"), "--jobs must be at least 0")):
            out = self.dir / "out"
            with self.subTest(args=args):
                r = evolve(*args, "--out", str(out))
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(want, r.stderr)
                self.assertNotIn("Traceback", r.stderr)
                self.assertFalse(out.exists())

    def write_other(self, text: str) -> Path:
        p = self.dir / "good.yaml"
        p.write_text(text)
        return p


class Searches(unittest.TestCase):
    def test_deterministic_given_seed_and_generation(self) -> None:
        for name, settings in (("cmaes", {"population": 6, "sigma": 0.3}),
                               ("ga", {"population": 10, "elite": 3, "mutation_sd": 0.2, "mutation_rate": 0.5})):
            def history(seed: int, name: str = name, settings: dict = settings) -> list:
                a = algorithms.make(name, 5, settings, seed)
                out = []
                for g in range(8):
                    X = a.ask(g)
                    a.tell(X, [-sum((x - 0.8) ** 2 for x in v) for v in X])
                    out.append(X)
                return out
            with self.subTest(name=name):
                a = history(1)
                self.assertEqual(a, history(1))
                self.assertNotEqual(a, history(2))
                self.assertTrue(all(0.0 <= x <= 1.0 for X in a for v in X for x in v))
                f = [[-sum((x - 0.8) ** 2 for x in v) for v in X] for X in a]
                best = [max(v) for v in f]
                self.assertGreater(sum(f[-1]) / len(f[-1]), sum(f[0]) / len(f[0]))   # it searches: the sphere improves
                if name == "ga":                           # the elite is kept: never worse
                    self.assertTrue(all(b >= a for a, b in zip(best, best[1:], strict=False)))


class TinyEvolution(unittest.TestCase):
    def setUp(self) -> None:
        # Never skipped: make python-tests builds the simulator first.
        self.assertTrue(SWARMSIM.is_file(), f"{SWARMSIM}: the simulator is not built (make build/swarmsim)")
        self._tmp = tempfile.TemporaryDirectory(prefix="evolve_test.")
        self.dir = Path(self._tmp.name)

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def assertSameFiles(self, out: Path, want: Path) -> None:  # noqa: N802 (unittest's style)
        for name in OUTPUTS:      # a byte diff of a pickle or a PNG says nothing: name the file
            self.assertTrue((out / name).read_bytes() == (want / name).read_bytes(), f"{out / name} differs")

    def test_same_result_twice_and_after_a_resume(self) -> None:
        spec = self.dir / "tiny.yaml"
        spec.write_text(TINY.read_text().replace("../../../sim_host", str(ROOT / "sim_host"))
                        .replace("generations: 3", "generations: 2").replace("population: 4", "population: 3"))
        whole = self.dir / "whole"
        r = evolve(str(spec), "--out", str(whole))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("generation 1 (2/2): best", r.stderr)
        self.assertTrue((whole / "fitness.png").stat().st_size > 1000)
        self.assertTrue((whole / "generations.parquet").is_file())
        gens = (whole / "generations.csv").read_text().splitlines()
        self.assertEqual(len(gens), 3)
        self.assertTrue(gens[0].startswith("generation,runs,best,mean,sd,worst,best_so_far,genome"))
        self.assertIn("#define NNEA_EVOLVED_B_OUT {", (whole / "best_params.h").read_text())
        self.assertIn("b_out:", (whole / "best_scenario.yaml").read_text())
        # stopped after one generation, then resumed: the same files
        part = self.dir / "part"
        r = evolve(str(spec), "--out", str(part), "--stop-after", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(len((part / "generations.csv").read_text().splitlines()), 2)
        r = evolve(str(spec), "--out", str(part))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("resuming after generation 0", r.stderr)
        self.assertSameFiles(part, whole)
        # interrupted in the middle of generation 1 (half its runs recorded),
        # then resumed: the same files
        cut = self.dir / "cut"
        real = cli.sweep_cli.run_sweep

        def interrupted(sw, ns, sim):
            rc = real(sw, ns, sim)
            if not sw.name.endswith("_gen00001"):
                return rc
            runs = planmod.expand(sw)
            for run in runs[len(runs) // 2:]:
                (Store(Path(ns.out)).records / f"{run.run_id}.json").unlink()
            return 130
        with mock.patch.object(cli.sweep_cli, "run_sweep", interrupted):
            r = evolve(str(spec), "--out", str(cut))
        self.assertEqual(r.returncode, 130, r.stderr)
        self.assertIn("interrupted in generation 1", r.stderr)
        r = evolve(str(spec), "--out", str(cut))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertSameFiles(cut, whole)
        # another evolution's checkpoint is refused, and nothing is overwritten
        before = (part / "checkpoint.pkl").read_bytes()
        spec.write_text(spec.read_text().replace("seed: 3", "seed: 4"))
        r = evolve(str(spec), "--out", str(part))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("made by another evolution", r.stderr)
        self.assertEqual((part / "checkpoint.pkl").read_bytes(), before)

    def test_best_scenario_reruns_the_measured_fitness(self) -> None:
        # Its header's command, at each of the seeds it names, gives back the
        # header's fitness exactly: the evolution's steps, not the scenario's.
        spec = self.dir / "tiny.yaml"
        spec.write_text(TINY.read_text().replace("../../../sim_host", str(ROOT / "sim_host"))
                        .replace("generations: 3", "generations: 1"))
        out = self.dir / "out"
        r = evolve(str(spec), "--out", str(out))
        self.assertEqual(r.returncode, 0, r.stderr)
        head = (out / "best_scenario.yaml").read_text().splitlines()[:2]
        fitness = float(re.search(r"fitness ([-0-9.e]+):", head[0]).group(1))
        m = re.search(r"seeds ([0-9, ]+): swarmsim best_scenario.yaml --steps 150 --seed", head[1])
        self.assertIsNotNone(m, head[1])
        seeds = [int(s) for s in m.group(1).split(", ")]
        self.assertEqual(len(seeds), 2)                 # the trials
        fit = Fitness(load(spec).fitness)
        values = []
        for seed in seeds:
            runs = self.dir / f"rerun{seed}"
            p = subprocess.run([str(SWARMSIM), str(out / "best_scenario.yaml"), "--steps", "150", "--seed", str(seed),
                                "--lcm", "off", "--quiet", "--out", str(runs)], capture_output=True, text=True,
                               timeout=120, check=False)
            self.assertEqual(p.returncode, 0, p.stderr)
            summary = json.loads((runs / f"run_{seed}" / "summary.json").read_text())
            self.assertEqual(summary["steps"], 150)
            values.append(fit(summary["metrics"]))
        self.assertEqual(sum(values) / len(values), fitness)


if __name__ == "__main__":
    unittest.main()
