"""swarmtools.study.eaipp: its arithmetic and tables on hand-made rows (the
Wilson interval on a known case, the controllers named by their scenario
files, success rates, the completion times over the successes and with the
failures at the budget, the paper's columns), and one tiny real run through
the sweep engine (2 controllers x 1 distance x 2 seeds, cut at 300 steps;
then one controller's rows alone with --controllers) and the frame strip, with the real simulator (env SWARMSIM)."""
from __future__ import annotations

import contextlib
import io
import json
import math
import os
import tempfile
import unittest
from pathlib import Path

from swarmtools.study import eaipp as E
from swarmtools.study.common import json_safe

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
SQUARE = "../sim_host/scenarios/eaipp_square.yaml"


def row(key: str, value: float, success: int, t: float | None = None, scenario: str | None = SQUARE,
        status: str = "ok", seed: int = 1) -> dict[str, str]:
    r = {key: str(value), "status": status, "seed": str(seed), "run_id": f"r{seed}",
         "success": str(success), "merge_time_s": "" if t is None else str(t),
         "merge_time_capped_s": str(t if success else 1000.0), "food_perceived": "1",
         "chain_nodes": "4" if success else ""}
    if scenario is not None:
        r["scenario"] = scenario
    return r


def quiet_main(args: list[str]) -> int:
    """E.main without its tables and progress on the test's output."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return E.main(args)


def wilson_by_hand(k: int, n: int, z: float = 1.959963984540054) -> tuple[float, float]:
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return centre - half, centre + half


class Arithmetic(unittest.TestCase):
    def test_wilson_known_cases(self) -> None:
        p, lo, hi = E.wilson(8, 10)     # the textbook case: 0.490 .. 0.943
        self.assertEqual(p, 0.8)
        self.assertAlmostEqual(lo, 0.4902, places=4)
        self.assertAlmostEqual(hi, 0.9433, places=4)
        for k, n in ((0, 2), (2, 2), (54, 100), (1, 7)):
            _, lo, hi = E.wilson(k, n)
            hand = wilson_by_hand(k, n)
            self.assertAlmostEqual(lo, hand[0], places=9)
            self.assertAlmostEqual(hi, hand[1], places=9)
        self.assertTrue(all(math.isnan(x) for x in E.wilson(0, 0)))

    def test_controllers_from_scenario_names(self) -> None:
        self.assertEqual(E.controller({"scenario": "../sim_host/scenarios/pfias_square.yaml"}), "PFIAS")
        self.assertEqual(E.controller({"scenario": "tsasr_square.yaml"}), "TSASR")
        self.assertEqual(E.controller({}, "/x/sim_host/scenarios/eaipp_maze.yaml"), "EAIPP")
        self.assertEqual(E.controller_order(["ZED", "PFIAS", "NNEA", "EAIPP", "TSASR", "ABC"]),
                         ["EAIPP", "TSASR", "PFIAS", "NNEA", "ABC", "ZED"])
        self.assertEqual(E.distance({E.NEST_X: "-0.7", E.FOOD_X: "0.7"}), 1.4)

    def test_cells_rates_and_times(self) -> None:
        fig = E.FIGURES["loss"]
        # loss 0: 9 of 10 merged at 10..90 s, one failed; one more run crashed (not counted)
        rows = [row(E.LOSS, 0.0, 1, 10.0 * (i + 1), seed=i + 1) for i in range(9)]
        rows += [row(E.LOSS, 0.0, 0, seed=10), row(E.LOSS, 0.0, 0, status="failed", seed=11)]
        # loss 0.2: 2 of 4 (the paper's 86 % falls outside our interval)
        rows += [row(E.LOSS, 0.2, s, 100.0 if s else None, seed=i) for i, s in enumerate((1, 0, 1, 0))]
        cs = E.cells(rows, fig, [E.LOSS])
        self.assertEqual([(c["controller"], c["condition"]) for c in cs], [("EAIPP", 0.0), ("EAIPP", 0.2)])
        c0, c2 = cs
        self.assertEqual((c0["runs"], c0["ok"], c0["failed_runs"], c0["successes"]), (11, 10, 1, 9))
        self.assertEqual(c0["success_rate"], 0.9)
        lo, hi = wilson_by_hand(9, 10)
        self.assertAlmostEqual(c0["ci_low"], lo)
        self.assertAlmostEqual(c0["ci_high"], hi)
        self.assertEqual((c0["time_q1_s"], c0["time_median_s"], c0["time_q3_s"]), (30.0, 50.0, 70.0))
        # the paper's convention: the failure counted at 1000 s among 10 runs
        self.assertEqual(c0["capped_median_s"], 55.0)
        self.assertAlmostEqual(c0["capped_mean_s"], (450 + 1000) / 10)
        self.assertEqual((c0["paper_success"], c0["paper_within_ci"]), (0.92, True))
        self.assertEqual((c2["success_rate"], c2["paper_success"], c2["paper_within_ci"]), (0.5, 0.86, False))
        self.assertEqual(c2["chain_nodes_median"], 4.0)
        md = "\n".join(E.render(fig, cs))
        self.assertIn("| EAIPP | 0 % | 10 (+1 failed) | 90 [60, 98] | 92 | yes | 50 [30, 70] | 55 [32, 78] | 10 | 4 |",
                      md)
        self.assertIn("| EAIPP | 20 % | 4 | 50 [15, 85] | 86 | no | 100 [100, 100] | 550 [100, 1000] | 4 | 4 |", md)
        self.assertIn("92, 86, 83, 89, 91 %", md)
        self.assertIn("0 % at 100 % loss", md)

    def test_paper_columns(self) -> None:
        maze = E.FIGURES["maze"]
        rows = [row(E.COUNT, 40, 1, 300.0, scenario=None, seed=1), row(E.COUNT, 40, 0, scenario=None, seed=2)]
        cs = E.cells(rows, maze, [E.COUNT], "/r/sim_host/scenarios/eaipp_maze.yaml")
        self.assertEqual((cs[0]["controller"], cs[0]["paper_success"], cs[0]["paper_within_ci"]), ("EAIPP", 0.54, True))
        self.assertIn("| EAIPP | 40 | 2 | 50 [9, 91] | 54 | yes |", "\n".join(E.render(maze, cs)))
        self.assertEqual([E.FIGURES["maze"].paper[n] for n in range(40, 75, 5)],
                         [0.54, 0.57, 0.64, 0.68, 0.77, 0.81, 0.88])
        self.assertEqual(list(E.FIGURES["bias"].paper.values()), [0.92, 0.87, 0.78, 0.63, 0.45])
        # obstacles: "above 90 %" for EAIPP only; PFIAS has no paper column
        obst = E.FIGURES["obstacles"]
        rows = [row(E.CYLINDERS, 10, 1, 200.0, seed=s) for s in range(1, 5)]
        rows += [row(E.CYLINDERS, 10, 0, scenario="../sim_host/scenarios/pfias_square.yaml", seed=s)
                 for s in range(1, 5)]
        md = "\n".join(E.render(obst, E.cells(rows, obst, ["scenario", E.CYLINDERS])))
        self.assertIn("| EAIPP | 10 | 4 | 100 [51, 100] | > 90 | yes |", md)
        self.assertIn("| PFIAS | 10 | 4 | 0 [0, 49] | - | - | - | 1000 [1000, 1000] | 4 | - |", md)
        self.assertIn("above 90 %", md)
        # Figures 11-12 and 15: the text gives no numbers, and says so
        for name in ("distance", "bearing"):
            self.assertFalse(E.FIGURES[name].paper)
            self.assertIn("no numbers in the text", E.FIGURES[name].note)

    def test_scaled_bias_and_turning_radii(self) -> None:
        fig = E.FIGURES["bias_scaled"]
        # the sweep's e-puck levels read back as the paper's marXbot levels
        for level in (0.018929, 0.037857, 0.056786, 0.075714):
            self.assertIn(fig.value({E.BIAS: str(level)}), fig.paper)
        # no bias: straight; small bias: R ~ L v / |b_r - b_l|, so the
        # e-puck at sd x 53/140 turns as a marXbot at sd, and at the same sd
        # 140/53 times tighter
        self.assertTrue(math.isinf(float(E.turning_radii(0.0, E.EPUCK_AXLE_M)[0])))
        m = float(E.np.median(E.turning_radii(0.005, E.MARXBOT_AXLE_M)))
        e = float(E.np.median(E.turning_radii(0.005 * E.AXLE_RATIO, E.EPUCK_AXLE_M)))
        same = float(E.np.median(E.turning_radii(0.005, E.EPUCK_AXLE_M)))
        self.assertAlmostEqual(e / m, 1.0, delta=0.02)
        self.assertAlmostEqual(m / same, 1 / E.AXLE_RATIO, delta=0.1)
        self.assertAlmostEqual(m, E.MARXBOT_AXLE_M * 0.05 / (0.005 * math.sqrt(2) * 0.6745), delta=0.1 * m)
        table = "\n".join(E.render_radii(fig.paper))
        self.assertIn("| 5 | 87 % |", table)

    def test_another_varied_key_keeps_cells_apart(self) -> None:
        fig = E.FIGURES["bias"]
        rows = [row(E.BIAS, 0.05, 1, 50.0) | {"robots.2.count": "10"},
                row(E.BIAS, 0.05, 0) | {"robots.2.count": "20"}]
        cs = E.cells(rows, fig, [E.BIAS, "robots.2.count"])
        self.assertEqual([c["extra"] for c in cs], ["robots.2.count=10", "robots.2.count=20"])
        self.assertIn("| EAIPP | 5 (robots.2.count=10) |", "\n".join(E.render(fig, cs)))

    def test_plot_and_json(self) -> None:
        fig = E.FIGURES["obstacles"]
        rows = [row(E.CYLINDERS, k, s, 100.0 * (k + 1) if s else None, scenario=sc, seed=i)
                for k in (0, 5) for sc in (SQUARE, "../sim_host/scenarios/pfias_square.yaml")
                for i, s in enumerate((1, 0, 1))]
        cs = E.cells(rows, fig, ["scenario", E.CYLINDERS])
        with tempfile.TemporaryDirectory() as d:
            E.plot(fig, rows, cs, Path(d) / "f.png")
            self.assertGreater((Path(d) / "f.png").stat().st_size, 1000)
        e = E.run_entry(fig, rows[1], ["scenario", E.CYLINDERS], "")
        self.assertEqual((e["controller"], e["condition"], e["success"], e["merge_time_s"],
                          e["merge_time_capped_s"]), ("EAIPP", 0.0, 0.0, None, 1000.0))
        json.dumps(json_safe({"cells": cs}), allow_nan=False)


@unittest.skipUnless(SWARMSIM.is_file(), f"no simulator at {SWARMSIM}")
class EndToEnd(unittest.TestCase):
    def test_tiny_study(self) -> None:
        with tempfile.TemporaryDirectory() as d:
            studies = Path(d) / "studies"
            studies.mkdir()
            scen = ROOT / "sim_host" / "scenarios"
            (studies / "eaipp_distance.yaml").write_text(
                "name: tiny_eaipp_distance\n"
                f"scenario: {scen / 'eaipp_square.yaml'}\n"
                "axes:\n  - list:\n"
                f"      - {{scenario: {scen / 'eaipp_square.yaml'}}}\n"
                f"      - {{scenario: {scen / 'pfias_square.yaml'}}}\n"
                "  - zip:\n"
                f"      {E.NEST_X}: [-0.5]\n      {E.FOOD_X}: [0.5]\n"
                "repetitions: 2\n"
                "metrics: [success, merge_time_s, merge_time_capped_s, food_perceived, food_time_s, "
                "chain_nodes, nodes_end, distance_m]\nkeep_timeseries: false\n")
            out = Path(d) / "out"
            rc = quiet_main(["--figures", "distance", "--studies", str(studies), "--steps", "300", "--out", str(out),
                         "--sim", str(SWARMSIM), "--jobs", "2"])
            self.assertEqual(rc, 0)
            md = (out / "results.md").read_text()
            self.assertIn("Every run was cut at 300 steps", md)
            self.assertIn("| EAIPP | 1.0 | 2 |", md)
            self.assertIn("| PFIAS | 1.0 | 2 |", md)
            self.assertIn("Wall time", md)
            res = json.loads((out / "results.json").read_text())
            self.assertEqual(len(res["runs"]), 4)
            self.assertEqual(sorted({(r["controller"], r["seed"]) for r in res["runs"]}),
                             [("EAIPP", 1), ("EAIPP", 2), ("PFIAS", 1), ("PFIAS", 2)])
            self.assertTrue(all(r["status"] == "ok" and r["distance_m"] == 1.0 for r in res["runs"]))
            self.assertEqual([c["controller"] for c in res["cells"]["distance"]], ["EAIPP", "PFIAS"])
            self.assertEqual(res["sweeps"]["distance"]["controllers"], ["EAIPP", "PFIAS"])
            self.assertGreater(res["wall_time_s"], 0)
            self.assertGreater((out / "fig11_12_distance.png").stat().st_size, 1000)
            # resumable: the same command runs nothing again and gives the same cells
            self.assertEqual(quiet_main(["--figures", "distance", "--studies", str(studies), "--steps", "300",
                                     "--out", str(out), "--sim", str(SWARMSIM)]), 0)
            again = json.loads((out / "results.json").read_text())
            self.assertEqual(again["cells"], res["cells"])
            # --controllers: one controller's rows alone
            one = Path(d) / "one"
            self.assertEqual(quiet_main(["--figures", "distance", "--studies", str(studies), "--steps", "300",
                                         "--out", str(one), "--sim", str(SWARMSIM), "--controllers", "pfias"]), 0)
            res1 = json.loads((one / "results.json").read_text())
            self.assertEqual(sorted({(r["controller"], r["seed"]) for r in res1["runs"]}), [("PFIAS", 1), ("PFIAS", 2)])
            self.assertEqual(res1["cells"]["distance"], [c for c in res["cells"]["distance"]
                                                         if c["controller"] == "PFIAS"])
            # a controller no sweep runs is an error, nothing run
            err = io.StringIO()
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
                rc = E.main(["--figures", "distance", "--studies", str(studies), "--steps", "300",
                             "--out", str(Path(d) / "none"), "--sim", str(SWARMSIM), "--controllers", "NNEA"])
            self.assertEqual(rc, 2)
            self.assertIn("none of the sweeps (distance) runs it (the paper's controllers: EAIPP, TSASR, PFIAS, "
                          "NNEA)", err.getvalue())
            self.assertFalse((Path(d) / "none" / "results.json").exists())

    def test_bad_figure(self) -> None:
        self.assertEqual(quiet_main(["--figures", "fig99", "--sim", str(SWARMSIM)]), 2)

    def test_picture(self) -> None:
        with tempfile.TemporaryDirectory() as d:
            png = Path(d) / "strip.png"
            caption = E.picture(SWARMSIM, png, Path(d) / "work", ROOT / "sim_host" / "scenarios" / "pfias_square.yaml",
                                seed="auto", px=160, frames=3, search=2)
            self.assertGreater(png.stat().st_size, 1000)
            self.assertIn("pfias_square, seed", caption)
            self.assertEqual(len(list((Path(d) / "work" / "frames").glob("run_*/frames/*.png"))) >= 3, True)


if __name__ == "__main__":
    unittest.main()
