"""swarmtools.study.repatt's arithmetic on hand-made tables: the arms and
worlds read from a row, RW normalisation with its bootstrap interval, E_r
(eqs 7-8), unfinished runs counted, and the tables rendered."""
import math
import unittest

import numpy as np

from swarmtools.study import repatt as R


def row(scenario: str, policy: str, queue: int, noise: float, t: float, finished: int = 1,
        count: int = 36) -> dict[str, str]:
    return {"scenario": f"../sim_host/scenarios/repatt_{scenario}.yaml", R.POLICY: policy,
            R.QUEUE: str(queue), R.NOISE: str(noise), R.TIME: str(t), R.FINISHED: str(finished),
            R.COUNT: str(count), "status": "ok"}


class Arithmetic(unittest.TestCase):
    def test_arm_and_world(self) -> None:
        self.assertEqual(R.arm(row("one50", "random_walk", 1, 0, 1)), "RW")
        self.assertEqual(R.arm(row("one50", "repatt", 1, 0, 1)), "N0-Q1")
        self.assertEqual(R.arm(row("one50", "repatt", 40, 0.06, 1)), "N100-Q40")
        self.assertEqual(R.arm(row("one50", "repatt", 40, 0.06, 1) | {R.LISTEN: "slotted"}), "N100-Q40 slotted")
        self.assertEqual(R.world(row("uniform100", "repatt", 1, 0, 1)), ("uniform", 100))
        self.assertEqual(R.world(row("half50", "repatt", 1, 0, 1)), ("half", 50))

    def test_ratio_and_interval(self) -> None:
        m, lo, hi = R.boot_ratio(np.array([50.0, 50.0]), np.array([100.0, 100.0]))
        self.assertEqual((m, lo, hi), (0.5, 0.5, 0.5))
        rng = np.random.default_rng(1)
        a, b = rng.normal(40, 5, 30), rng.normal(100, 10, 30)
        m, lo, hi = R.boot_ratio(a, b)
        self.assertAlmostEqual(m, a.mean() / b.mean())
        self.assertTrue(lo < m < hi and hi - lo < 0.1)
        self.assertTrue(all(math.isnan(x) for x in R.boot_ratio(np.array([]), b)))

    def test_normalised_by_rw_with_unfinished_runs(self) -> None:
        rows = [row("one50", "random_walk", 1, 0, t) for t in (100, 100, 100)]
        rows += [row("one50", "repatt", 1, 0, t) for t in (20, 30, 40)]
        rows += [row("one50", "repatt", 40, 0.06, 60, finished=f) for f in (1, 0, 1)]
        res = R.normalised(rows, ("RW", "N0-Q1", "N100-Q40"))
        self.assertAlmostEqual(res["One50m/N0-Q1"]["normalised"], 0.3)
        self.assertAlmostEqual(res["One50m/RW"]["normalised"], 1.0)
        self.assertEqual(res["One50m/N100-Q40"]["unfinished"], 1)
        md = "\n".join(R.render_fig3(res))
        self.assertIn("| One50m | 100 +- 0 | 30 +- 10 | 60 +- 0 | 0.30 [", md)
        self.assertIn("| - | 0, 0, 1 |", md)    # no slotted arm in this table
        self.assertIn("0.23", md)       # the paper's One50m beside ours
        self.assertIn("| 0, 0, 1 |", md)

    def test_half_table_normalises_each_shape_by_its_own_rw(self) -> None:
        rows = []
        for shape, rw, rep in (("cluster", 200.0, 50.0), ("strip", 100.0, 50.0)):
            rows += [row("half100", "random_walk", 1, 0, rw) | {R.HALF_SHAPE: shape} for _ in range(3)]
            rows += [row("half100", "repatt", 1, 0, rep) | {R.HALF_SHAPE: shape} for _ in range(3)]
        res = R.half_table(rows)
        self.assertAlmostEqual(res["Half100m/cluster/N0-Q1"]["normalised"], 0.25)
        self.assertAlmostEqual(res["Half100m/strip/N0-Q1"]["normalised"], 0.5)
        self.assertNotIn("Half100m/strip/N100-Q40", res)
        md = "\n".join(R.render_half(res))
        self.assertIn("| Half100m | cluster | 6 | 200 | 0.25 [0.25, 0.25] | - | - | 0 |", md)
        self.assertIn("| Half100m | strip | 6 | 100 | 0.50 [0.50, 0.50] | - | - | 0 |", md)

    def test_run_entry(self) -> None:
        r = row("two100", "repatt", 40, 0.06, 812.5, finished=1) | {"seed": "7", "run_id": "ab", "picked": "180"}
        e = R.run_entry(r)
        self.assertEqual((e["world"], e["arm"], e["robots"], e["seed"]), ("Two100m", "N100-Q40", 36, 7))
        self.assertEqual((e["time_capped_s"], e["finished"], e["picked"]), (812.5, 1.0, 180.0))

    def test_relative_efficiency(self) -> None:
        # one robot 900 s, ten robots 100 s: E_r = 900 / (10 x 100) = 0.9
        rows = [row("one100", "repatt", 1, 0, 900, count=1), row("one100", "repatt", 1, 0, 100, count=10)]
        res = R.efficiency(rows)
        self.assertAlmostEqual(res["One100m/N0-Q1/1"]["E_r"], 1.0)
        self.assertAlmostEqual(res["One100m/N0-Q1/10"]["E_r"], 0.9)
        self.assertIn("| One100m | N0-Q1 | 10 | 100 | 0.90 [0.90, 0.90] | 0 |", "\n".join(R.render_scale(res)))

    def test_gain_over_rw_per_size(self) -> None:
        # the lone robot's runs are the same in both arms; at 10 robots RW takes 300 s, RepAtt 100 s
        rows = [row("one100", p, 1, 0, 900, count=1) for p in ("random_walk", "repatt")]
        rows += [row("one100", "random_walk", 1, 0, 300, count=10), row("one100", "repatt", 1, 0, 100, count=10)]
        res = R.efficiency(rows)
        self.assertAlmostEqual(res["One100m/N0-Q1/10"]["vs_rw"], 3.0)
        self.assertEqual((res["One100m/N0-Q1/1"]["vs_rw_low"], res["One100m/N0-Q1/1"]["vs_rw_high"]), (1.0, 1.0))
        self.assertNotIn("vs_rw", res["One100m/RW/10"])
        md = "\n".join(R.render_scale(res))
        self.assertIn("| One100m | N0-Q1 | 10 | 3.00 [3.00, 3.00] |", md)
        self.assertIn("same E_1: yes, in every arm", md)
        # a lone RepAtt robot that differs from RW's is said so, and the ratio keeps E_1's factor
        rows[1] = row("one100", "repatt", 1, 0, 450, count=1)
        res = R.efficiency(rows)
        self.assertAlmostEqual(res["One100m/N0-Q1/10"]["vs_rw"], 1.5)
        self.assertIn("same E_1: NO", "\n".join(R.render_scale(res)))


if __name__ == "__main__":
    unittest.main()
