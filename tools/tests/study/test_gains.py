"""swarmtools.study.gains on hand-made tables: the paper's scoring (ranks by
mean time per world, summed), the stages' sweeps built from the screen
file, and the race's choice of combinations."""
import unittest
from pathlib import Path

from swarmtools.study import gains as G
from swarmtools.sweep import spec


def row(world: str, c: G.Combo, t: float, noise: float = 0.06, seed: int = 1) -> dict[str, str]:
    r = {"scenario": f"../sim_host/scenarios/repatt_{world}.yaml", G.NOISE: str(noise), G.TIME: str(t),
         "status": "ok", "seed": str(seed), "finished": "1"}
    r.update({k: str(v) for k, v in zip(G.GAIN_KEYS, c, strict=True)})
    return r


A, B, C = (4, 100, 1, 10), (1, 10, 1, 100), (1, 1, 1, 1)


class Scoring(unittest.TestCase):
    def test_names_and_rows(self) -> None:
        self.assertEqual(G.name(A), "A4m100d-R1m10d")
        r = row("uniform100", B, 5.0, noise=0)
        self.assertEqual((G.world(r), G.arm(r), G.combo(r)), ("Uniform100m", "N0-Q1", B))

    def test_rank_sums_as_the_paper(self) -> None:
        # One100m: A 10, B 30, C 20 -> ranks 1, 3, 2; Uniform100m: A 50, B 40, C 60 -> 2, 1, 3.
        rows = [row("one100", A, 10), row("one100", B, 30), row("one100", C, 20),
                row("uniform100", A, 50), row("uniform100", B, 40), row("uniform100", C, 60)]
        scored = G.rank_sums(G.cells(rows), "N100-Q40")
        self.assertEqual([(s, c) for s, c, _ in scored], [(3, A), (4, B), (5, C)])
        self.assertEqual(scored[0][2], {"One100m": 1, "Uniform100m": 2})
        # ranks use the mean over seeds; a failed run does not count; the other arm is apart
        rows += [row("one100", B, -100.0, seed=2) | {"status": "failed"}, row("one100", C, 2, seed=2),
                 row("uniform100", C, 20, seed=2), row("one100", A, 1, noise=0)]
        scored = G.rank_sums(G.cells(rows), "N100-Q40")
        # C: means 11 (rank 2) and 40 (ties B, the lower combination first: 1): 3; A 1 + 3; B 3 + 2
        self.assertEqual([(s, c) for s, c, _ in scored], [(3, C), (4, A), (5, B)])
        self.assertEqual(G.rank_sums(G.cells(rows), "N0-Q1"), [(1, A, {"One100m": 1})])

    def test_combinations_in_one_world_only_are_not_ranked(self) -> None:
        rows = [row("one100", A, 10), row("uniform100", A, 10), row("one100", B, 5)]
        self.assertEqual([c for _, c, _ in G.rank_sums(G.cells(rows), "N100-Q40")], [A])


class Stages(unittest.TestCase):
    def setUp(self) -> None:
        self.base = spec.load(G.SCREEN_FILE, 2**53)

    def test_screen_file_is_the_papers_grid(self) -> None:
        self.assertEqual(len(self.base.axes[-1].combos), 900)
        self.assertIn(("duration", 3600), self.base.fixed)

    def test_fixed_values_fill_the_rows(self) -> None:
        r = row("one100", A, 10)
        del r[G.NOISE]                       # results.csv has columns for the axes only
        self.assertEqual(G.arm(r), "N0-Q1")
        G.with_fixed([r], self.base)         # the screen fixes sound.noise 0.06
        self.assertEqual(G.arm(r), "N100-Q40")

    def test_race_sweep(self) -> None:
        sw = G.stage_sweep(self.base, "race", [A, B], range(1, 31), [{G.QUEUE: 40, G.NOISE: 0.06}], uncap=True)
        keys = [k for k, _ in sw.fixed]
        self.assertNotIn("duration", keys)        # the scenarios' own cap
        self.assertNotIn(G.NOISE, keys)           # now an axis
        self.assertEqual(sw.axes[-1].combos, [dict(zip(G.GAIN_KEYS, A, strict=True)),
                                              dict(zip(G.GAIN_KEYS, B, strict=True))])
        self.assertEqual(sw.seeds, list(range(1, 31)))
        self.assertEqual(Path(sw.path), G.SCREEN_FILE)

    def test_race_takes_the_confirmed_best_and_the_named(self) -> None:
        D = (2, 50, 2, 50)
        screen = [row(w, c, t) for w in ("one100", "uniform100") for c, t in ((D, 1), (A, 9), (B, 9), (C, 9))]
        confirm = [row(w, c, t, seed=2) for w in ("one100", "uniform100") for c, t in ((D, 50), (A, 2))]
        got = G.race_combos({"screen": screen, "confirm": confirm}, 1)
        self.assertEqual(got[0], A)              # over its 2 seeds A (5.5) beats D (25.5)
        self.assertEqual(set(got), {A, B, C})    # the named always race


if __name__ == "__main__":
    unittest.main()
