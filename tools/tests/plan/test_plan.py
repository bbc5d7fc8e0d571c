"""swarmtools.plan: the objective on hand-made routes, small instances with a
known optimum, the operators' invariants, determinism, improvement over the
initial plan, the PyVRP cross-check, the targets read from the simulator and
the command line on seed 002's One50m world (a few hundred iterations)."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

from swarmtools.plan import alns as A
from swarmtools.plan.crosscheck import pyvrp_plan
from swarmtools.plan.problem import PlanError, Problem, load_world, problem_of_world

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
ONE50 = ROOT / "sim_host" / "scenarios" / "repatt_one50.yaml"


def line_problem() -> Problem:
    """2 robots x 5 on a line: targets at x = +-1..+-5 and two decoys at
    +-20.  Optimum: one robot per side, the decoys left out, T = 5 m / v +
    5 picks; the nearest-10 bound is the same."""
    xs = [1, 2, 3, 4, 5, -1, -2, -3, -4, -5, 20, -20]
    return Problem(np.array([(x, 0.0) for x in xs]), (0.0, 0.0), robots=2, capacity=5, speed=0.5, pick_time=2.0)


def random_problem(seed: int = 3, robots: int = 6, m: int = 40) -> Problem:
    rng = np.random.default_rng(seed)
    return Problem(rng.uniform(-2, 2, size=(m, 2)), (0.0, 0.0), robots=robots, capacity=5)


def read_csv(path: Path) -> list[dict[str, str]]:
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def nodes(routes: list[list[int]]) -> list[int]:
    return [v for r in routes for v in r]


class Objective(unittest.TestCase):
    def test_times_and_lengths(self) -> None:
        p = Problem(np.array([(3.0, 4.0), (3.0, 0.0), (9.0, 9.0)]), (0.0, 0.0), robots=1, capacity=2)
        self.assertAlmostEqual(p.route_length([1, 2]), 5.0 + 4.0)        # open: no way back
        self.assertAlmostEqual(p.finish_time([1, 2]), 9.0 / 0.1 + 2 * 5.0)
        d = p.describe([[1, 2]])
        self.assertAlmostEqual(d["finishing_time_s"], 100.0)
        self.assertAlmostEqual(d["search_objective"], 100.0 * (1 + p.tiebreak))
        self.assertAlmostEqual(p.lower_bound(), 5.0 / 0.1 + 10.0)      # 2nd nearest target: 5 m away
        p2 = Problem(np.array([(1.0, 0.0), (2.0, 0.0), (0.0, 3.0)]), (0.0, 0.0), robots=2, capacity=1)
        self.assertAlmostEqual(p2.describe([[1], [2]])["finishing_time_s"], 2.0 / 0.1 + 5.0)   # the max
        self.assertAlmostEqual(p2.describe([[1], [2]])["total_length_m"], 3.0)

    def test_check_rejects_bad_plans(self) -> None:
        p = line_problem()
        p.check([[1, 2, 3, 4, 5], [6, 7, 8, 9, 10]])
        for bad in ([[1, 2, 3, 4, 5]], [[1, 2, 3, 4], [6, 7, 8, 9, 10]], [[1, 2, 3, 4, 5], [5, 7, 8, 9, 10]],
                    [[1, 2, 3, 4, 5], [6, 7, 8, 9, 13]]):
            with self.assertRaises(PlanError):
                p.check(bad)

    def test_impossible_problems(self) -> None:
        with self.assertRaises(PlanError):
            Problem(np.zeros((9, 2)) + 1, (0.0, 0.0), robots=2, capacity=5)        # 10 visits, 9 targets
        world = {"targets": np.ones((200, 2)), "nest": (0.0, 0.0), "robots": 36, "stop_count": 170,
                 "pick_time": 5.0}
        with self.assertRaisesRegex(PlanError, "must be equal"):
            problem_of_world(world)


class Search(unittest.TestCase):
    def test_line_reaches_the_optimum(self) -> None:
        p = line_problem()
        best = A.solve(p, 60, 4, seed=1)["best"]
        p.check(best.routes)
        optimum = 5.0 / 0.5 + 5 * 2.0
        self.assertAlmostEqual(best.finishing_time(), optimum)
        self.assertAlmostEqual(p.lower_bound(), optimum)
        self.assertEqual(sorted(best.pool), [11, 12])                         # the decoys
        self.assertEqual(sorted(sorted(r) for r in best.routes), [[1, 2, 3, 4, 5], [6, 7, 8, 9, 10]])
        self.assertEqual(best.routes[0], sorted(best.routes[0], key=lambda v: abs(p.targets[v - 1, 0])))

    def test_operators_keep_a_plan_whole(self) -> None:
        p = random_problem()
        plan = A.sweep_plan(p)
        p.check(plan.routes)
        rng = np.random.default_rng(5)
        for name, destroy in A.DESTROY.items():
            for q in (1, 7, p.visits, p.visits + 10):
                cut = destroy(plan, rng, q=q)
                self.assertEqual(len(nodes(cut.routes)), p.visits - min(q, p.visits), name)
                self.assertEqual(sorted(nodes(cut.routes) + cut.pool), list(range(1, p.m + 1)), name)
                self.assertEqual(len(nodes(plan.routes)), p.visits)             # the input is untouched
                for rname, repair in A.REPAIR.items():
                    whole = repair(cut, rng, best_t=[plan.finishing_time()])
                    p.check(whole.routes)
                    self.assertEqual(sorted(nodes(whole.routes) + whole.pool), list(range(1, p.m + 1)), rname)
                    self.assertEqual([len(r) for r in whole.routes], [p.capacity] * p.robots)

    def test_deterministic_and_improves_on_the_initial_plan(self) -> None:
        p = random_problem()
        a = A.solve(p, 150, 8, seed=7)
        b = A.solve(p, 150, 8, seed=7)
        self.assertEqual(a["best"].routes, b["best"].routes)
        self.assertEqual(a["best"].pool, b["best"].pool)
        self.assertLess(a["best"].objective(), a["initial"].objective() - 1.0)
        self.assertLess(a["best"].finishing_time(), a["initial"].finishing_time())
        self.assertGreaterEqual(a["best"].finishing_time(), p.lower_bound() - 1e-9)

    def test_bad_parameters(self) -> None:
        with self.assertRaises(PlanError):
            A.solve(line_problem(), 10, 0, seed=1)


class CrossCheck(unittest.TestCase):
    def test_pyvrp_on_the_line(self) -> None:
        p = line_problem()
        r = pyvrp_plan(p, 200, seed=1)
        self.assertTrue(r["feasible"] and r["all_full"])
        self.assertEqual(r["visited"], p.visits)
        self.assertAlmostEqual(r["total_length_m"], 10.0)                    # 5 m out on each side
        self.assertAlmostEqual(r["finishing_time_s"], 5.0 / 0.5 + 5 * 2.0)
        self.assertEqual(sorted(sorted(x) for x in r["routes"]), [[0, 1, 2, 3, 4], [5, 6, 7, 8, 9]])

    def test_pyvrp_distance_at_most_alns(self) -> None:
        p = random_problem(seed=4, robots=4, m=26)
        r = pyvrp_plan(p, 300, seed=1)
        self.assertTrue(r["feasible"] and r["all_full"])
        best = A.solve(p, 100, 6, seed=1)["best"]
        # PyVRP minimises distance, ALNS the latest finish: PyVRP is the shorter
        # (a little slack: neither is proven optimal).
        self.assertLessEqual(r["total_length_m"], p.describe(best.routes)["total_length_m"] * 1.02)


@unittest.skipUnless(SWARMSIM.exists(), f"{SWARMSIM} not built (make python-tests builds it)")
class Scenario(unittest.TestCase):
    def test_targets_from_the_simulator(self) -> None:
        w = load_world(ONE50, SWARMSIM)
        self.assertEqual((len(w["targets"]), w["robots"], w["stop_count"], w["pick_time"]), (200, 36, 180, 5.0))
        self.assertEqual(w["nest"], (0.0, 0.0))
        # targets.h: One puts every target in the disc of radius 0.826 m at (2.479, 2.479).
        r = np.hypot(w["targets"][:, 0] - 2.479, w["targets"][:, 1] - 2.479)
        self.assertLessEqual(float(r.max()), 0.826 + 1e-5)
        again = load_world(ONE50, SWARMSIM, ["targets.layout_seed=2"])
        self.assertFalse(np.allclose(again["targets"], w["targets"]))
        with self.assertRaises(PlanError):
            load_world(ROOT / "no_such.yaml", SWARMSIM)

    def run_cli(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "swarmtools.plan.alns", "--sim", str(SWARMSIM), *args],
                              capture_output=True, text=True, cwd=ROOT, check=False, timeout=120)

    def test_command_line_on_one50(self) -> None:
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "plan"
            args = ["--scenario", str(ONE50), "--iterations", "300", "--q", "50", "--seed", "1",
                    "--pyvrp-iterations", "300", "--out", str(out)]
            p = self.run_cli(*args)
            self.assertEqual(p.returncode, 0, p.stderr)
            s = json.loads((out / "summary.json").read_text())
            files = sorted(out.glob("robot_*.csv"))
            self.assertEqual(len(files), 36)
            seen = set()
            for f in files:
                rows = read_csv(f)
                self.assertEqual([int(r["seq"]) for r in rows], [1, 2, 3, 4, 5])
                seen.update(int(r["target"]) for r in rows)
                self.assertTrue(all(math.isfinite(float(r["x_m"])) for r in rows))
            self.assertEqual(len(seen), 180)
            self.assertEqual(sorted(seen | set(s["left_out"])), list(range(200)))
            self.assertLessEqual(s["finishing_time_s"], s["initial"]["finishing_time_s"])
            self.assertGreaterEqual(s["finishing_time_s"], s["lower_bound_s"])
            self.assertTrue(s["pyvrp"]["all_full"])
            self.assertLess(s["pyvrp"]["total_length_m"], s["total_length_m"])
            self.assertEqual((s["iterations"], s["q"], s["versions"]["alns"], s["versions"]["pyvrp"]),
                             (300, 50, "7.0.0", "0.14.1"))
            # The route file is the summary's route, in world coordinates.
            w = load_world(ONE50, SWARMSIM)
            first = read_csv(files[0])
            self.assertEqual([int(r["target"]) for r in first], s["routes"][0])
            self.assertAlmostEqual(float(first[0]["x_m"]), w["targets"][s["routes"][0][0], 0], places=5)
            # A folder that is not empty: refused, left as it was; --replace redoes it.
            before = (out / "summary.json").read_bytes()
            p = self.run_cli(*args[:3], "20", *args[4:])
            self.assertEqual(p.returncode, 2)
            self.assertIn("not empty", p.stderr)
            self.assertEqual((out / "summary.json").read_bytes(), before)
            p = self.run_cli(*args[:3], "20", *args[4:-4], "--pyvrp-iterations", "0", "--out", str(out),
                             "--replace")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(json.loads((out / "summary.json").read_text())["iterations"], 20)

    def test_errors_write_nothing(self) -> None:
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "plan"
            for args in (["--scenario", str(ROOT / "no_such.yaml")],
                         ["--scenario", str(ROOT / "sim_host" / "scenarios" / "random_walk.yaml")],
                         ["--scenario", str(ONE50), "--capacity", "4"],
                         ["--scenario", str(ONE50), "--q", "0"]):
                p = self.run_cli(*args, "--iterations", "5", "--out", str(out))
                self.assertEqual(p.returncode, 2, args)
                self.assertTrue(p.stderr.startswith("swarmtools.plan.alns: "), p.stderr)
                self.assertFalse(out.exists())
                self.assertEqual(os.listdir(tmp), [])


if __name__ == "__main__":
    unittest.main()
