"""swarmtools.plan.routes: the route message byte for byte as the robot's
decoder expects it (the fixed vector of tests/test_route_msg.c), the run
scenario built from a world, and a planned run in a small world that picks
up its targets sooner than the random walk (seed 002's claim for ALNS)."""
import json
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

import yaml

from swarmtools.plan import alns as A
from swarmtools.plan.routes import route_message, run_scenario

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
QUICK = ROOT / "sim_host" / "scenarios" / "repatt_quick.yaml"
# repatt_quick with 3 robots of capacity 3 (9 of 12 targets), its cluster moved out
# of the camera's 0.5 m from the nest (1.27 m away in a 3 m arena): the random
# walk must search for it.
SMALL = ("robots.0.count=3", "arena.width=3", "arena.height=3", "targets.layout_side=2.8",
         "targets.cluster_offset=0.9", "duration=1500")
# tests/test_route_msg.c's VECTOR: 2 targets (1200, -340), (-5000, 70000) mm, drop-off (-1, 2) mm.
VECTOR = bytes.fromhex("5202000004b0fffffeacffffec7800011170ffffffff00000002")


def run(scenario: Path, out: Path, seed: int, *sets: str) -> dict:
    cmd = [str(SWARMSIM), str(scenario), "--seed", str(seed), "--out", str(out), "--lcm", "off", "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    return json.loads((out / f"run_{seed}" / "summary.json").read_text())["metrics"]


class Message(unittest.TestCase):
    def test_fixed_vector(self) -> None:
        self.assertEqual(route_message([(1.2, -0.34), (-5.0, 70.0)], (-0.001, 0.002)), VECTOR)

    def test_refusals(self) -> None:
        with self.assertRaises(ValueError):
            route_message([], (0, 0))
        with self.assertRaises(ValueError):
            route_message([(0, 0)] * 7, (0, 0))
        with self.assertRaises(ValueError):
            route_message([(1000.001, 0)], (0, 0))    # beyond +-1 km

    def test_run_scenario(self) -> None:
        world = {"name": "w", "arena": {"width": 2, "height": 1}, "sound": {"enabled": True},
                 "targets": {"nest": {"x": 0, "y": 0, "radius": 0.2}},
                 "robots": [{"count": 2, "controller": "repatt", "placement": {"shape": "grid"},
                             "params": {"speed_steps_s": 776, "queue_size": 40}}]}
        doc = run_scenario(world, [[(0.1, 0.2)], [(0.3, 0.4), (0.5, 0.469)]], (0.0, 0.0), "w_alns")
        g = doc["robots"][0]
        self.assertEqual((g["controller"], g["count"], g["placement"]), ("waypoint", 2, {"shape": "grid"}))
        self.assertEqual(g["params"], {"speed_steps_s": 776, "arrive_mm": 10, "home_radius_mm": 163})
        self.assertNotIn("sound", doc)
        self.assertTrue(doc["tracker"]["enabled"])
        m = doc["host"]["messages"]
        self.assertEqual([x["robot"] for x in m], [0, 1])
        # (0.5, 0.469) is 31 mm from the wall at y = 0.5: its stop 70 mm from it
        self.assertEqual(bytes.fromhex(m[1]["hex"]), route_message([(0.3, 0.4), (0.5, 0.43)], (0, 0)))
        with self.assertRaises(ValueError):
            run_scenario(world, [[(0.1, 0.2)]], (0.0, 0.0), "x")   # 2 robots, 1 route
        with self.assertRaisesRegex(ValueError, "too near a wall"):   # 5 mm from the wall: a stop 65 mm away
            run_scenario(world, [[(0.1, 0.2)], [(0.995, 0.0)]], (0.0, 0.0), "x")
        with self.assertRaisesRegex(ValueError, "arena.width"):
            run_scenario(world | {"arena": {}}, [[(0.1, 0.2)], [(0.3, 0.4)]], (0.0, 0.0), "x")


@unittest.skipUnless(SWARMSIM.is_file(), f"{SWARMSIM} not built (make build/swarmsim)")
class PlannedRun(unittest.TestCase):
    def test_plan_beats_the_random_walk(self) -> None:
        """SMALL: the plan's scenario loads, every robot follows its route,
        and over 3 seeds the slowest planned run reaches the 9th pick-up
        sooner than the fastest random walk."""
        with tempfile.TemporaryDirectory() as tmp:
            t = Path(tmp)
            sets = [x for kv in SMALL for x in ("--set", kv)]
            rc = A.main(["--scenario", str(QUICK), *sets, "--capacity", "3",
                         "--iterations", "200", "--pyvrp-iterations", "0", "--sim", str(SWARMSIM),
                         "--out", str(t / "plan")])
            self.assertEqual(rc, 0)
            scen = yaml.safe_load((t / "plan" / "scenario.yaml").read_text())
            self.assertEqual(len(scen["host"]["messages"]), 3)
            plan, rw = [], []
            for seed in (1, 2, 3):
                m = run(t / "plan" / "scenario.yaml", t / f"alns{seed}", seed)
                self.assertEqual((m["finished"], m["picked"]), (1, 9))
                plan.append(m["time_capped_s"])
                m = run(QUICK, t / f"rw{seed}", seed, *SMALL, "robots.0.policy=random_walk")
                rw.append(m["time_capped_s"])
            self.assertLess(sum(plan) / 3, sum(rw) / 3, f"plan {plan} vs RW {rw}")
            self.assertLess(max(plan), min(rw), f"plan {plan} vs RW {rw}")


if __name__ == "__main__":
    unittest.main()
