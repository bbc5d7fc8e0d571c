"""Tests of swarmtools.study.drtm (plain unittest, no simulator needed).

    .venv/bin/python tools/tests/run.py   (make python-tests)

The statistics (the pooled t-test against scipy.stats.ttest_ind(equal_var=True)
and against hand-computed examples, the paper's sign convention), the
summary.json / timeseries.csv readers on synthetic run folders, the rendering
of results.md from synthetic results, and the driver end to end against a fake
swarmsim (success, a failing run, garbled output, a missing binary).
"""

from __future__ import annotations

import contextlib
import inspect
import io
import json
import math
import os
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

import swarmtools.study.drtm as sd


def write_run(folder, seed, steps=100, policy="drtm", robots=20, every=10,
              scenario="foraging_base"):
    """A synthetic run_<seed>/ in the simulator's exact format; returns its metrics.

    Standard library only: the fake simulator below runs this function's source.
    """
    import json
    import random
    from pathlib import Path
    header = ("step,time_s,oae_total,robot_contacts,static_contacts,distance_m,"
              "food_nest,food_collected,waiting,searching,returning,active")
    rng = random.Random(seed * 7 + ("drtm", "artm", "frtm").index(policy))
    run = Path(folder) / f"run_{seed}"
    run.mkdir(parents=True, exist_ok=True)
    rows = [header]
    steps_list = list(range(0, steps + 1, every))
    if steps_list[-1] != steps:
        steps_list.append(steps)
    oae = food_c = 0
    food = 5.0
    dist = 0.0
    for s in steps_list:
        if s:
            oae += rng.randrange(0, 5)
            food_c += rng.randrange(0, 2)
            food = 5.0 + food_c - s / 600.0 * 2.0 / 1.0 * 0.1
            dist += 0.5
        searching = rng.randrange(0, robots // 2)
        returning = rng.randrange(0, robots // 4)
        rows.append(f"{s},{s / 10:g},{oae},{oae // 3},{oae // 10},{dist:.6g},{food:.10g},"
                    f"{food_c},{robots - searching - returning},{searching},{returning},"
                    f"{searching + returning}")
    (run / "timeseries.csv").write_text("\n".join(rows) + "\n")
    metrics = {
        "oae_total": oae, "oae_per_robot": oae / robots, "robot_contacts": oae // 3,
        "static_contacts": oae // 10, "distance_per_robot_m": dist / robots,
        "mean_speed_mm_s": 42.0, "min_wall_clearance_mm": 3.5, "escaped": 0,
        "V_f": rng.uniform(1, 20), "E_e": rng.uniform(-0.2, 0.3),
        "food_collected": food_c,
        "food_net": food, "food_dropped": 0,
        "tau_s": rng.uniform(60, 110), "tau_search_s": rng.uniform(40, 80),
        "active_mean": rng.uniform(5, 15), "oae_at_nest": oae // 2,
        "wait_radius_m": rng.uniform(0.3, 0.7),
    }
    summary = {"scenario": scenario, "scenario_file": f"sim_host/scenarios/{scenario}.yaml",
               "seed": seed,
               "groups": [{"name": "foragers", "controller": "forager", "policy": policy, "count": robots},
                          {"name": "nest_beacon", "controller": "nest_beacon", "policy": "", "count": 1}],
               "tasks": ["foraging"], "robots": robots + 1, "steps": steps,
               "control_period_ms": 100, "state_hash": f"{seed:016x}", "metrics": metrics}
    (run / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return metrics


def synthetic_results(conditions=("base", "nr30"), policies=sd.POLICIES, reps=50,
                      steps=12000, quick=False) -> dict:
    """A results dict as run_study makes it, with made-up numbers."""
    rng = np.random.default_rng(42)
    res = {"format": sd.FORMAT, "command": ".venv/bin/python tools/study/study_drtm.py",
           "cwd": "/srv/project", "wall_time_s": 123.4, "generated_utc": "2026-01-01 00:00:00 UTC",
           "source": "git abc1234",
           "machine": {"cores": 2, "cpu": "Test CPU @ 1 GHz", "platform": "Linux", "python": "3.11"},
           "settings": {"reps": reps, "first_seed": 1, "steps": None, "threads": 2, "quick": quick,
                        "sim": "build/swarmsim", "conditions": list(conditions),
                        "policies": list(policies), "control_period_ms": 100},
           "conditions": {}}
    t = np.arange(0, 11.0)
    for cond in conditions:
        c = res["conditions"][cond] = {"scenario_file": f"sim_host/scenarios/foraging_{cond}.yaml",
                                       "desired_food": 20.0, "robots": 20, "policies": {}}
        for i, p in enumerate(policies):
            runs = []
            for seed in range(1, reps + 1):
                m = {"V_f": 2.5 + i + rng.normal(0, 0.5), "E_e": 0.12 - 0.02 * i + rng.normal(0, 0.01),
                     "food_collected": 170 + rng.normal(0, 10), "food_net": 20 - 2 * i + rng.normal(0, 3),
                     "oae_total": 900 + 200 * i + rng.normal(0, 150), "oae_per_robot": 45 + 10 * i,
                     "tau_s": 90 + rng.normal(0, 5), "active_mean": 12 + rng.normal(0, 1),
                     "oae_at_nest": 400 + rng.normal(0, 50), "wait_radius_m": 0.5}
                runs.append({"seed": seed, "steps": steps, "robots": 20, "state_hash": "x",
                             "metrics": m})
            c["policies"][p] = {"wall_s": 1.0, "runs": runs, "series": {
                "n": reps, "step": [int(x * 10) for x in t], "time_s": list(t),
                "food_nest": {"mean": list(5 + t), "sd": [1.0] * len(t)},
                "oae_total": {"mean": list(10 * t), "sd": list(t)},
                "active": {"mean": [5.0] * len(t), "sd": [1.0] * len(t)}}}
    return res


def t4_cdf(t: float) -> float:
    """Student's t CDF for 4 degrees of freedom, closed form (by hand, not scipy)."""
    x = t / math.sqrt(4.0 + t * t)
    return 0.5 + 0.75 * x * (1.0 - x * x / 3.0)


class TestStatistics(unittest.TestCase):
    def test_hand_example_equal_n(self):
        # a: mean 4, b: mean 2, both variance 1 -> s_p^2 = 1, se = sqrt(2/3), t = sqrt(6)
        r = sd.pooled_t_test([3, 4, 5], [1, 2, 3])
        self.assertAlmostEqual(r["t"], math.sqrt(6.0), places=12)
        self.assertEqual(r["df"], 4)
        p = 2.0 * (1.0 - t4_cdf(math.sqrt(6.0)))
        self.assertAlmostEqual(p, 0.070484, places=6)     # 1 - 0.964758, twice
        self.assertAlmostEqual(r["p"], p, places=12)

    def test_hand_example_unequal_n(self):
        # a: mean 2.5, SS 5; b: mean 7, SS 2 -> s_p^2 = 7/4, se^2 = 1.75 * 3/4, t = -4.5/se
        r = sd.pooled_t_test([1, 2, 3, 4], [6, 8])
        t = -4.5 / math.sqrt(1.75 * 0.75)
        self.assertAlmostEqual(t, -3.927922, places=6)
        self.assertAlmostEqual(r["t"], t, places=12)
        self.assertEqual(r["df"], 4)
        self.assertAlmostEqual(r["p"], 2.0 * t4_cdf(t), places=12)

    def test_against_scipy(self):
        from scipy import stats
        rng = np.random.default_rng(1)
        for na, nb, shift in ((50, 50, 0.0), (50, 50, 0.6), (50, 37, -1.0), (2, 3, 0.3), (200, 9, 2.0)):
            a = rng.normal(10 + shift, 2, na)
            b = rng.normal(10, 3, nb)
            ref = stats.ttest_ind(a, b, equal_var=True)
            r = sd.pooled_t_test(a, b)
            self.assertAlmostEqual(r["t"], float(ref.statistic), places=10)
            self.assertAlmostEqual(r["p"], float(ref.pvalue), places=12)
            self.assertEqual(r["df"], na + nb - 2)

    def test_paper_trip_economics(self):
        # The paper's base DRTM row: F(T) 20.84, collected 173.76, M_T 925.96, E_a 10:
        # 1500 (5 + 173.76 - 40 - 20.84) - 9259.6 = 167,620.4 robot-steps foraging.
        m = sd.PAPER_MEANS["base"]["drtm"]
        self.assertAlmostEqual(m["active_mean"], 167620.4 / 12000.0, places=6)
        self.assertAlmostEqual(m["tau_s"], 16762.04 / 173.76, places=6)
        # Every row of the paper, both policies: tau 90-112 s.
        for arms in sd.PAPER_MEANS.values():
            for means in arms.values():
                self.assertTrue(90.0 < means["tau_s"] < 112.0, means)

    def test_paper_df(self):
        r = sd.pooled_t_test(range(50), range(1, 51))
        self.assertEqual(r["df"], 98)

    def test_degenerate(self):
        r = sd.pooled_t_test([1, 1, 1], [1, 1])
        self.assertTrue(math.isnan(r["t"]) and math.isnan(r["p"]))
        r = sd.pooled_t_test([2, 2, 2], [1, 1])
        self.assertEqual(r["t"], math.inf)
        self.assertEqual(r["p"], 0.0)
        r = sd.pooled_t_test([1], [2])          # df = 0
        self.assertTrue(math.isnan(r["t"]))
        r = sd.pooled_t_test([3, 4, 5, float("nan")], [1, 2, 3])   # NaN dropped
        self.assertAlmostEqual(r["t"], math.sqrt(6.0), places=12)

    def test_sign_convention(self):
        more_food_drtm = sd.compare_policies([21, 22, 23, 20], [15, 16, 17, 18], better=+1)
        self.assertGreater(more_food_drtm["t"], 0)
        self.assertTrue(more_food_drtm["significant"])
        fewer_oae_drtm = sd.compare_policies([900, 950, 920], [1100, 1150, 1200], better=-1)
        self.assertGreater(fewer_oae_drtm["t"], 0)
        worse = sd.compare_policies([10, 11, 12], [20, 21, 22], better=+1)
        self.assertLess(worse["t"], 0)
        same = sd.compare_policies([1, 2, 3], [1, 2, 3], better=+1)
        self.assertFalse(same["significant"])
        self.assertAlmostEqual(same["p"], 1.0)

    def test_mean_sd(self):
        m, s, n = sd.mean_sd([1, 2, 3, 4, float("nan")])
        self.assertEqual((m, n), (2.5, 4))
        self.assertAlmostEqual(s, math.sqrt(5 / 3))
        self.assertTrue(math.isnan(sd.mean_sd([7])[1]))


class TestReaders(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_read_group(self):
        m = [write_run(self.dir, seed, steps=95) for seed in (3, 4, 5)]
        runs, agg = sd.read_runs([(self.dir / f"run_{s}", s) for s in (3, 4, 5)], expect_steps=95)
        self.assertEqual([r["seed"] for r in runs], [3, 4, 5])
        self.assertEqual(runs[0]["robots"], 20)
        self.assertEqual(runs[1]["metrics"]["food_net"], m[1]["food_net"])
        self.assertEqual(runs[2]["metrics"]["E_e"], m[2]["E_e"])
        self.assertEqual(agg["n"], 3)
        self.assertEqual(list(agg["step"][-3:]), [80, 90, 95])     # the final row
        self.assertEqual(agg["time_s"][-1], 9.5)
        ts = [sd.read_timeseries(self.dir / f"run_{s}" / "timeseries.csv") for s in (3, 4, 5)]
        stack = np.vstack([t["oae_total"] for t in ts])
        np.testing.assert_allclose(agg["oae_total"]["mean"], stack.mean(axis=0))
        np.testing.assert_allclose(agg["oae_total"]["sd"], stack.std(axis=0, ddof=1))
        self.assertEqual(agg["oae_total"]["mean"][-1], np.mean([x["oae_total"] for x in m]))

    def test_summary_errors(self):
        write_run(self.dir, 1)
        path = self.dir / "run_1" / "summary.json"
        with self.assertRaisesRegex(sd.StudyError, "missing"):
            sd.read_summary(self.dir / "run_9" / "summary.json")
        with self.assertRaisesRegex(sd.StudyError, "seed 1, expected 2"):
            sd.read_summary(path, expect_seed=2)
        doc = json.loads(path.read_text())
        path.write_text(json.dumps(doc)[:-20])
        with self.assertRaisesRegex(sd.StudyError, "garbled JSON") as cm:
            sd.read_summary(path)
        self.assertIn(str(path), str(cm.exception))
        del doc["metrics"]["oae_total"]
        path.write_text(json.dumps(doc))
        with self.assertRaisesRegex(sd.StudyError, "lack oae_total"):
            sd.read_summary(path)
        doc["metrics"]["oae_total"] = "many"
        path.write_text(json.dumps(doc))
        with self.assertRaisesRegex(sd.StudyError, "not a number"):
            sd.read_summary(path)
        doc["metrics"]["oae_total"] = None                 # null -> NaN
        path.write_text(json.dumps(doc))
        self.assertTrue(math.isnan(sd.read_summary(path)["metrics"]["oae_total"]))
        doc["control"] = {"touched": False, "commands": 2, "listed": []}      # paused and resumed: the same run
        path.write_text(json.dumps(doc))
        self.assertEqual(sd.read_summary(path)["seed"], 1)
        doc["control"]["touched"] = True                   # a robot moved by hand: never pooled
        path.write_text(json.dumps(doc))
        with self.assertRaisesRegex(sd.StudyError, "touched by hand"):
            sd.read_summary(path)
        del doc["control"]
        path.write_text("[]")
        with self.assertRaisesRegex(sd.StudyError, "no \"metrics\""):
            sd.read_summary(path)

    def test_group_errors(self):
        write_run(self.dir, 1, steps=100)
        write_run(self.dir, 2, steps=100)
        with self.assertRaisesRegex(sd.StudyError, "run_3.*missing"):
            sd.read_runs([(self.dir / f"run_{s}", s) for s in (1, 2, 3)])
        with self.assertRaisesRegex(sd.StudyError, "100 steps, expected 200"):
            sd.read_runs([(self.dir / f"run_{s}", s) for s in (1, 2)], expect_steps=200)

    def test_timeseries_errors(self):
        write_run(self.dir, 1)
        path = self.dir / "run_1" / "timeseries.csv"
        lines = path.read_text().splitlines()
        path.write_text("\n".join([lines[0].replace(",active", "")] + [line.rsplit(",", 1)[0] for line in lines[1:]]))
        with self.assertRaisesRegex(sd.StudyError, "header lacks active"):
            sd.read_timeseries(path)
        path.write_text("\n".join(lines[:3] + [lines[3] + ",7"] + lines[4:]))
        with self.assertRaisesRegex(sd.StudyError, r"timeseries.csv:4: .*13 fields"):
            sd.read_timeseries(path)
        path.write_text("\n".join(lines[:2] + [lines[2].replace(",", ",x", 1)]))
        with self.assertRaisesRegex(sd.StudyError, "not a number"):
            sd.read_timeseries(path)
        path.write_text("\n".join([lines[0], lines[2], lines[1]]))
        with self.assertRaisesRegex(sd.StudyError, "do not increase"):
            sd.read_timeseries(path)
        path.write_text("\n".join(lines + [lines[-1]]))       # a repeated final row is fine
        self.assertEqual(len(sd.read_timeseries(path)["step"]), len(lines) - 1)
        path.write_text("\n".join(lines + [lines[-1].replace(",", ",1", 2)]))
        with self.assertRaisesRegex(sd.StudyError, "do not increase"):
            sd.read_timeseries(path)
        path.write_text(lines[0] + "\n")
        with self.assertRaisesRegex(sd.StudyError, "no rows"):
            sd.read_timeseries(path)
        path.write_text("")
        with self.assertRaisesRegex(sd.StudyError, "empty"):
            sd.read_timeseries(path)

    def test_desired_food(self):
        real = sd.REPO_ROOT / "sim_host" / "scenarios" / "foraging_base.yaml"
        if real.is_file():
            self.assertEqual(sd.read_desired_food(real), 20.0)
        p = self.dir / "x.yaml"
        p.write_text("# desired_food: 99\nforaging: { desired_food: 12.5, consumption: 2 }\n")
        self.assertEqual(sd.read_desired_food(p), 12.5)
        p.write_text("foraging:\n  enabled: true\n")
        self.assertIsNone(sd.read_desired_food(p))


class TestRendering(unittest.TestCase):
    def test_tables(self):
        md = sd.render_markdown(synthetic_results())
        self.assertNotIn("Not the paper's design", md)
        self.assertIn("| metric | DRTM (ours) | DRTM-clip (ours) | ARTM (ours) | FRTM (ours) | DRTM (paper) "
                      "| ARTM (paper) |", md)
        self.assertIn("| V_f of the mean curve", md)
        self.assertIn("### DRTM-clip vs ARTM", md)
        # the paper's numbers beside ours
        for text in ("| 2.55 | 4.74 |", "| 11.99 | 9.99 |", "| 173.76 | 183.46 |", "| 20.84 | 18.34 |",
                     "| 925.96 | 1148.44 |", "| 46.30 | 57.42 |", "| 1203.32 | 1612.26 |", "| 40.11 | 53.74 |"):
            self.assertIn(text, md)
        self.assertRegex(md, r"\| E_e, energy efficiency \(%\) \| 1\d\.\d\d ± \d\.\d\d \|")
        self.assertIn("t > 0 means DRTM is better", md)
        self.assertIn("| base | Table 2 | F_t |", md)
        self.assertIn("| 3.1918 | 0.0019 | YES |", md)
        self.assertIn("| nr30 | Table 4, 5.3 | M_T |", md)
        self.assertIn("| 3.9267 | 1.60e-04 | YES |", md)
        self.assertIn("| 98 |", md)
        self.assertIn("### DRTM vs FRTM", md)
        self.assertIn("2 cores, Test CPU @ 1 GHz", md)
        self.assertIn("`.venv/bin/python tools/study/study_drtm.py`", md)
        self.assertIn("runs: 400 = 2 condition(s)", md)
        self.assertIn("wall time: 123.4 s", md)
        self.assertNotIn("nan", md.lower())

    def test_ttest_rows_match_scipy(self):
        from scipy import stats
        res = synthetic_results(conditions=("l3",))
        rows = sd.compute_ttests(res, "artm")
        self.assertEqual([r["name"] for r in rows], ["F_t", "M_T"])
        d = [r["metrics"]["oae_total"] for r in res["conditions"]["l3"]["policies"]["drtm"]["runs"]]
        a = [r["metrics"]["oae_total"] for r in res["conditions"]["l3"]["policies"]["artm"]["runs"]]
        ref = stats.ttest_ind(a, d, equal_var=True)      # other - DRTM for OAEs
        self.assertAlmostEqual(rows[1]["t"], float(ref.statistic), places=10)
        self.assertAlmostEqual(rows[1]["p"], float(ref.pvalue), places=12)
        self.assertEqual((rows[1]["paper_t"], rows[1]["paper_p"]), (2.6984, 8.21e-3))

    def test_quick_and_subset(self):
        md = sd.render_markdown(synthetic_results(conditions=("ea20",), policies=("drtm", "frtm"),
                                                  reps=4, steps=2000, quick=True))
        self.assertIn("Not the paper's design", md)
        self.assertIn("--quick", md)
        self.assertIn("| metric | DRTM (ours) | FRTM (ours) | DRTM (paper) | ARTM (paper) |", md)
        self.assertIn("(not run", md)                       # no ARTM, no DRTM vs ARTM test
        self.assertIn("| ea20 | F_t |", md)                  # DRTM vs FRTM still there
        self.assertIn("| 6 |", md)                           # df = 4 + 4 - 2

    def test_formatting(self):
        self.assertEqual(sd.fmt_p(2.89e-6), "2.89e-06")
        self.assertEqual(sd.fmt_p(0.0242), "0.0242")
        self.assertEqual(sd.fmt_p(float("nan")), "—")
        self.assertEqual(sd.fmt_t(-2.28994), "-2.2899")
        self.assertEqual(sd.fmt_mean_sd([0.1, 0.2, 0.3], scale=100), "20.00 ± 10.00")
        self.assertEqual(sd.fmt_mean_sd([5.0]), "5.00")
        self.assertEqual(sd.fmt_mean_sd([]), "—")

    def test_json_round_trip_and_atomic_outputs(self):
        res = synthetic_results(conditions=("base",), reps=5)
        res["conditions"]["base"]["policies"]["artm"]["runs"][0]["metrics"]["E_e"] = math.nan
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            sd.write_outputs(res, out, figures=False)
            self.assertEqual(sorted(p.name for p in out.iterdir()), ["results.json", "results.md"])
            back = sd.load_results(out / "results.json")
            self.assertTrue(math.isnan(back["conditions"]["base"]["policies"]["artm"]["runs"][0]
                                       ["metrics"]["E_e"]))
            md1 = (out / "results.md").read_text()
            sd.write_outputs(back, out, figures=False, rerender_command="x --from-json")
            md2 = (out / "results.md").read_text()
            self.assertEqual(md1, md2.replace("Re-rendered from results.json by `x --from-json`.\n", ""))
            (out / "bad.json").write_text('{"format": "other"}')
            with self.assertRaisesRegex(sd.StudyError, "not a study_drtm/1"):
                sd.load_results(out / "bad.json")

    def test_figures(self):
        res = synthetic_results(conditions=("l3",), reps=3)
        with tempfile.TemporaryDirectory() as d:
            made = sd.render_figures(res, Path(d))
            self.assertEqual(made, {"l3": ["food_l3.png", "oae_l3.png", "active_l3.png"]})
            for name in made["l3"]:
                self.assertEqual((Path(d) / name).read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.assertEqual(len(list(Path(d).iterdir())), 3)     # no temporary files left


FAKE_SIM = """#!{python}
# A stand-in for build/swarmsim: writes synthetic runs in its exact format.
import os, sys
from pathlib import Path
{write_run}
a = sys.argv[1:]
opt = lambda k, d=None: a[a.index(k) + 1] if k in a else d
if "--help" in a:
    print("  seed                               int    1            [0, 9007199254740991]  base random seed")
    sys.exit(0)
if "--check" in a:
    sys.exit(0)
sets = [a[i + 1] for i in range(len(a) - 1) if a[i] == "--set"]
policy = next(v.split("=", 1)[1] for v in sets if v.startswith("robots.0.policy="))
if os.environ.get("FAKE_SIM_FAIL") == policy:
    sys.stderr.write("swarmsim: run 2 failed: boom\\n")
    sys.exit(1)
out = Path(opt("--out"))
reps, seed, steps = int(opt("--reps", "1")), int(opt("--seed")), int(opt("--steps", "120"))
for s in range(seed, seed + reps):
    write_run(out, s, steps=steps, policy=policy)
if os.environ.get("FAKE_SIM_GARBLE") == policy:
    (out / f"run_{{seed}}" / "summary.json").write_text("{{ not json")
"""


class TestEndToEnd(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)
        self.sim = self.dir / "swarmsim"
        self.sim.write_text(FAKE_SIM.format(python=sys.executable,
                                            write_run=inspect.getsource(write_run)))
        self.sim.chmod(0o755)
        self.scen = self.dir / "scenarios"
        self.scen.mkdir()
        for c in sd.CONDITIONS.values():
            (self.scen / f"{c['scenario']}.yaml").write_text(f"# {c['scenario']}\nforaging: {{ desired_food: 20 }}\n")
        self.env = dict(os.environ)

    def tearDown(self):
        os.environ.clear()
        os.environ.update(self.env)
        self.tmp.cleanup()

    def main(self, *extra):
        args = ["--sim", str(self.sim), "--scenario-dir", str(self.scen), "--out", str(self.dir / "out"),
                "--reps", "3", "--steps", "40", "--threads", "1", "--no-figures", *extra]
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = sd.main(args)
        return rc, out.getvalue(), err.getvalue()

    def test_study(self):
        rc, out, err = self.main("--conditions", "foraging_base,l3", "--policies", "artm,drtm")
        self.assertEqual(rc, 0, err)
        self.assertIn("  l3    artm: F(T)", out)
        self.assertIn("total wall time", out)
        md = (self.dir / "out" / "results.md").read_text()
        self.assertIn("### base:", md)
        self.assertIn("### l3:", md)
        self.assertNotIn("### nf25", md)
        self.assertIn("| l3 | Table 4, 5.4 | M_T |", md)
        self.assertIn("## Sensitivity to the robot's speed (base condition)", md)
        self.assertIn("| 0.1 | ARTM |", md)
        self.assertIn("| tau, robot-seconds of foraging per delivered token (tau_s) |", md)
        self.assertIn("| v (m/s) | arm | V_f | E_e % | collected | F(T) | M_T | tau (s) | robots foraging |", md)
        res = json.loads((self.dir / "out" / "results.json").read_text())
        self.assertEqual(list(res["conditions"]), ["base", "l3"])
        self.assertEqual(list(res["conditions"]["l3"]["policies"]), ["drtm", "artm"])
        runs = res["conditions"]["base"]["policies"]["drtm"]["runs"]
        self.assertEqual([r["seed"] for r in runs], [1, 2, 3])
        self.assertEqual(res["conditions"]["base"]["desired_food"], 20.0)
        self.assertEqual(res["conditions"]["base"]["policies"]["drtm"]["series"]["step"][-1], 40)
        # the runs are a sweep's: its table has one row per run, and a rerun
        # resumes (runs nothing) and renders the same results
        table = (self.dir / "out" / "sweep" / "results.csv").read_text().splitlines()
        self.assertEqual(len(table), 1 + 2 * 2 * 3)
        self.assertIn("scenario,robots.0.policy,robots.0.params.drtm_theta,seed,status", table[0])
        rc, out, err = self.main("--conditions", "foraging_base,l3", "--policies", "artm,drtm")
        self.assertEqual(rc, 0, err)
        self.assertIn("12 already done", err)
        again = json.loads((self.dir / "out" / "results.json").read_text())
        self.assertEqual(again["conditions"]["l3"]["policies"]["artm"]["runs"],
                         res["conditions"]["l3"]["policies"]["artm"]["runs"])

    def test_run_failure(self):
        os.environ["FAKE_SIM_FAIL"] = "artm"
        rc, out, err = self.main("--conditions", "base")
        self.assertEqual(rc, 1)
        self.assertIn("3 of 12 runs failed", err)
        self.assertIn("foraging_base.yaml artm seed 1: exit status 1: swarmsim: run 2 failed: boom", err)
        self.assertFalse((self.dir / "out" / "results.md").exists())

    def test_garbled_output(self):
        os.environ["FAKE_SIM_GARBLE"] = "drtm"
        rc, _, err = self.main("--conditions", "nf25")
        self.assertEqual(rc, 1)
        self.assertIn("no readable summary.json", err)
        self.assertIn("foraging_nf25.yaml drtm seed 1", err)
        self.assertFalse((self.dir / "out" / "results.md").exists())

    def test_missing_binary_and_bad_args(self):
        self.sim.unlink()
        rc, _, err = self.main()
        self.assertEqual(rc, 2)
        self.assertIn("run `make` first", err)
        rc, _, err = self.main("--conditions", "base,xyz")
        self.assertEqual(rc, 2)
        self.assertIn("unknown condition 'xyz'", err)


if __name__ == "__main__":
    unittest.main()
