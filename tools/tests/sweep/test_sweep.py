"""Tests of swarmtools.sweep with the real simulator (env SWARMSIM).

    .venv/bin/python tools/tests/run.py   (make python-tests)

Sweep files (strict, FILE:LINE errors), the expansion (grid, zip, list,
stable ids, the seed range), the simulator's check of every combination, a
local run against direct simulator runs, resuming, failed runs with their
stderr and bounded retries, an interrupted sweep, and chunked workers (what
slurm array tasks run) giving byte-identical metrics. The real SLURM run is
tools/tests/slurm/.
"""

from __future__ import annotations

import csv
import json
import os
import signal
import stat
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

from swarmtools.sweep import plan as planmod
from swarmtools.sweep import spec

from ..telemetry.helpers import default_sigint

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
SMALL = ROOT / "tests" / "data" / "scenarios" / "valid_small.yaml"
VOLATILE = ("wall_s", "host")      # columns that differ between two runs of one sweep


def sweep_text(extra: str = "", reps: int = 2) -> str:
    return (f"name: t\nscenario: {SMALL}\nsteps: 30\n"
            "axes:\n  - grid:\n      robots.0.count: [2, 3]\n"
            "  - zip:\n      arena.width: [1.5, 2.0]\n      arena.height: [1.5, 2.0]\n"
            f"repetitions: {reps}\n{extra}")


def swarm_sweep(*args: str, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "swarmtools.sweep", *args], capture_output=True,
                          text=True, timeout=timeout, check=False)


def read_table(folder: Path, drop: tuple[str, ...] = VOLATILE) -> list[dict[str, str]]:
    with open(folder / "results.csv", newline="") as f:
        return [{k: v for k, v in row.items() if k not in drop} for row in csv.DictReader(f)]


def fake_sim(folder: Path, body: str) -> Path:
    """A wrapper around the real simulator: `body` (bash) runs first, with
    $seed set to the run's seed and $check to 1 for --check."""
    p = folder / "fake_swarmsim"
    p.write_text("#!/bin/bash\nseed=''; check=0; prev=''\n"
                 "for a in \"$@\"; do [ \"$prev\" = --seed ] && seed=$a; [ \"$a\" = --check ] && check=1; prev=$a; done\n"
                 f"{body}\nexec {SWARMSIM} \"$@\"\n")
    p.chmod(p.stat().st_mode | stat.S_IXUSR)
    return p


#: Seconds a test waits for something that takes well under one: only a hang reaches it.
LONG = 300


def wait_for(check, what: str, timeout: float = LONG):
    """Polls check() until it gives something true; fails naming `what`."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = check()
        if got:
            return got
        time.sleep(0.05)
    raise AssertionError(f"timed out after {timeout:g} s waiting for {what}")


def lock_is_free(folder: Path) -> bool:
    import fcntl
    with open(folder / ".swarmtools-sweep.lock", "rb") as f:
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            return False
        return True


class TempDir(unittest.TestCase):
    def setUp(self) -> None:
        self._tmp = tempfile.TemporaryDirectory(prefix="sweep_test.")
        self.dir = Path(self._tmp.name)

    def tearDown(self) -> None:
        self._tmp.cleanup()

    def write(self, text: str, name: str = "s.yaml") -> Path:
        p = self.dir / name
        p.write_text(text)
        return p


class SpecErrors(TempDir):
    """Every class of mistake in a sweep file is named with its line."""

    CASES = (
        ("scenario: x.yaml\n", ":1: scenario: no such scenario file"),
        (f"scenario: {SMALL}\nrepetitions: 2\naxis: []\n", ":3: axis: unknown key 'axis' (did you mean 'axes'?)"),
        (f"scenario: {SMALL}\nrepetitions: 2\nrepetitions: 3\n", ":3: 'repetitions' given twice (first on line 2)"),
        (f"scenario: {SMALL}\n", ":1: seeds: give exactly one of"),
        (f"scenario: {SMALL}\nrepetitions: 0\n", ":2: repetitions: 0 is out of range"),
        (f"scenario: {SMALL}\nseeds: [1, 1]\n", ":2: seeds: a seed is listed twice"),
        (f"scenario: {SMALL}\nseeds: {{first: 9007199254740990, count: 3}}\n",
         ":2: seeds: seeds 9007199254740990..9007199254740992 pass the simulator's seed range [0, 9007199254740991]"),
        (f"scenario: {SMALL}\nseeds: [-1]\n", ":2: seeds[0]: -1 is out of range [0, 9007199254740991]"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - zip:\n      a.b: [1, 2]\n      c.d: [1]\n",
         ":5: axes[0].zip: zipped lists differ in length (a.b: 2, c.d: 1)"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - cross: {{a: [1]}}\n",
         ":4: axes[0]: expected one of grid:, zip:, list:, got cross"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - grid: {{seed: [1, 2]}}\n",
         ":4: axes[0].grid: seeds are not overrides"),
        (f"scenario: {SMALL}\nrepetitions: 1\nset: {{robots.0.count: 2}}\naxes:\n  - grid: {{robots.0.count: [1, 2]}}\n",
         ":5: axes[0]: 'robots.0.count' is already varied or set in set"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - list:\n      - {{a: 1}}\n      - {{b: 2}}\n",
         ":6: axes[0].list[1]: keys differ from the first entry's (a)"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - grid: {{a: [1, [[2]]]}}\n",
         ":4: axes[0].grid.a[0]: expected a single value"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes:\n  - grid: {{a: [1, [2, x]]}}\n",
         ":4: axes[0].grid.a[1]: an array holds numbers, got 'x'"),
        (f"scenario: {SMALL}\nrepetitions: 1\nset: {{a: []}}\n", ":3: set.a: expected a non-empty list"),
        (f"scenario: {SMALL}\nrepetitions: 1\nmetrics: [M_T, M_T]\n", ":3: metrics[1]: 'M_T' listed twice"),
        ("scenario: [\n", ":2: YAML syntax error"),
        # explicit tags: refused with their line, never a traceback
        *((f"scenario: {SMALL}\nrepetitions: 1\nset:\n  arena.width: {v}\n",
           f":4: set.arena.width: explicit YAML tag '{tag}' refused")
          for v, tag in (("!foo x", "!foo"), ('!!int "ten"', "tag:yaml.org,2002:int"),
                         ("!!bool 0", "tag:yaml.org,2002:bool"), ("!!timestamp 178", "tag:yaml.org,2002:timestamp"),
                         ("!!binary aGk=", "tag:yaml.org,2002:binary"), ("!!str 10", "tag:yaml.org,2002:str"))),
        (f"scenario: {SMALL}\nrepetitions: 1\nset: !!set {{a.b: null}}\n", ":3: set: explicit YAML tag"),
        (f"scenario: {SMALL}\nrepetitions: 1\naxes: !!omap [{{grid: {{a.b: [1]}}}}]\n", ":3: axes: explicit YAML tag"),
        (f"scenario: {SMALL}\nrepetitions: 1\nset: {{a: " + "[" * 5000 + "]" * 5000 + "}\n",
         ": nested too deeply to be a sweep file"),
        # names and keys are matched whole: no trailing newline
        (f'scenario: {SMALL}\nrepetitions: 1\nname: "t\\n"\n', ":3: name: use 1 to 64 letters"),
        (f"scenario: {SMALL}\nrepetitions: 1\nname: ..\n", ":3: name: use 1 to 64 letters"),
        (f'scenario: {SMALL}\nrepetitions: 1\nset: {{"robots.0.count\\n": 2}}\n',
         ":3: set: 'robots.0.count\\n' is not a scenario key path"),
        (f'scenario: {SMALL}\nrepetitions: 1\nmetrics: ["M_T\\n"]\n', ":3: metrics[0]: 'M_T\\n' is not a metric name"),
        # a sweep too large is refused before it is expanded
        (f"scenario: {SMALL}\nrepetitions: 1000\naxes:\n  - grid:\n"
         + "".join(f"      k{i}.x: [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\n" for i in range(9)),
         ":5: axes[0].grid: 10 x 10 x 10 x 10 x 10 x 10 x 10 x 10 x 10 = about 10^9 combinations, "
         "more than the cap of 1,000,000 runs (swarm-sweep --max-runs N raises it)"),
        (f"scenario: {SMALL}\nrepetitions: 1000\naxes:\n  - grid: {{a.b: [1, 2, 3]}}\n"
         "  - zip: {c.d: [1, 2], e.f: [1, 2]}\n  - grid: {g.h: " + str(list(range(200))) + "}\n",
         ":2: 1,200 combinations x 1,000 seeds = 1,200,000 runs, more than the cap of 1,000,000"),
        (f"scenario: {SMALL}\nseeds: {{first: 0, count: 9000000}}\n", ":2: 1 combinations x 9,000,000 seeds"),
    )

    def test_each_mistake_is_named_with_its_line(self) -> None:
        for text, want in self.CASES:
            with self.subTest(want=want):
                p = self.write(text)
                with self.assertRaises(spec.SweepError) as cm:
                    spec.load(p, 9007199254740991)
                self.assertIn(f"{p}{want}", str(cm.exception))

    def test_command_line_says_the_line_and_no_traceback(self) -> None:
        p = self.write(f"scenario: {SMALL}\nrepetitions: 2\nset:\n  arena.width: !!int \"ten\"\n")
        r = swarm_sweep("plan", str(p), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(f"{p}:4: set.arena.width: explicit YAML tag", r.stderr)
        self.assertNotIn("Traceback", r.stderr)

    def test_the_run_cap_can_be_raised(self) -> None:
        p = self.write(sweep_text(reps=3))              # 12 runs
        r = swarm_sweep("plan", str(p), "--sim", str(SWARMSIM), "--max-runs", "11")
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("4 combinations x 3 seeds = 12 runs, more than the cap of 11", r.stderr)
        r = swarm_sweep("plan", str(p), "--sim", str(SWARMSIM), "--max-runs", "12")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("= 12 runs; all check", r.stdout)

    def test_a_line_break_never_reaches_a_batch_script(self) -> None:
        p = self.write(sweep_text())
        for flag in ("--partition", "--account", "--mem", "--time", "--sbatch-arg"):
            r = swarm_sweep("run", str(p), "--backend", "slurm", f"{flag}=x\nrm -rf ~", "--sim", str(SWARMSIM),
                            "--out", str(self.dir / "out"))
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(f"{flag} 'x\\nrm -rf ~': a control character or line break", r.stderr)
        self.assertFalse((self.dir / "out").exists())

    def test_bad_value_is_caught_by_the_simulator_before_anything_runs(self) -> None:
        p = self.write(sweep_text().replace("[2, 3]", "[2, 2.5]"))
        out = self.dir / "out"
        r = swarm_sweep("run", str(p), "--out", str(out), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(f"{p}:6: the simulator rejects the run with robots.0.count=2.5", r.stderr)
        self.assertIn("expected an integer, got '2.5'", r.stderr)
        self.assertFalse(out.exists(), "a rejected sweep must write nothing")

    def test_array_values_reach_the_simulator_and_the_table(self) -> None:
        nnea = ROOT / "sim_host" / "scenarios" / "nnea_square.yaml"
        text = (f"name: arr\nscenario: {nnea}\nsteps: 20\nset:\n  robots.2.count: 3\n"
                "  robots.2.params.tau: [1, 2, 3, 4]\n  robots.2.params.w_out: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n"
                "axes:\n  - grid:\n"
                "      robots.2.params.b_out: [[0, 0, 0], [2047, 2000, 5]]\nrepetitions: 1\n")
        sw = spec.load(self.write(text), 2**53 - 1)
        runs = planmod.expand(sw)
        self.assertEqual(runs[1].params, {"robots.2.params.b_out": (2047, 2000, 5)})
        self.assertEqual(runs[1].overrides, [("robots.2.count", "3"), ("robots.2.params.tau", "[1, 2, 3, 4]"),
                                             ("robots.2.params.w_out", "[" + ", ".join(["0"] * 12) + "]"),
                                             ("robots.2.params.b_out", "[2047, 2000, 5]")])
        out = self.dir / "out"
        r = swarm_sweep("run", str(self.write(text)), "--out", str(out), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_table(out)
        self.assertEqual([row["robots.2.params.b_out"] for row in rows], ["[0, 0, 0]", "[2047, 2000, 5]"])
        self.assertEqual(float(rows[0]["distance_per_robot_m"]), 0.0)    # no weights out, sigma(0): stopped
        self.assertGreater(float(rows[1]["distance_per_robot_m"]), 0.0)
        import pandas as pd
        self.assertEqual(list(pd.read_parquet(out / "results.parquet")["robots.2.params.b_out"]),
                         ["[0, 0, 0]", "[2047, 2000, 5]"])
        # an element out of range: the simulator's check names the sweep's line and the element
        bad = self.write(text.replace("2047, 2000, 5", "2047, -2048, 5"), "bad.yaml")
        r = swarm_sweep("run", str(bad), "--out", str(self.dir / "bad"), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(f"{bad}:10: the simulator rejects the run with robots.2.params.b_out=[2047, -2048, 5]",
                      r.stderr)
        self.assertIn("robots[2].params.b_out[1]: -2048 is out of range [-2047, 2047]", r.stderr)

    def test_seed_range_is_the_simulators(self) -> None:
        self.assertEqual(planmod.seed_max(SWARMSIM), 2**53 - 1)

    def test_foreign_folder_is_refused(self) -> None:
        p = self.write(sweep_text())
        out = self.dir / "home"
        out.mkdir()
        (out / "notes.txt").write_text("mine")
        r = swarm_sweep("run", str(p), "--out", str(out), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 2)
        self.assertIn("not empty and not a sweep's folder", r.stderr)
        self.assertEqual(sorted(x.name for x in out.iterdir()), ["notes.txt"])


class Expansion(TempDir):
    def test_grid_zip_list_and_seeds(self) -> None:
        p = self.write(sweep_text(reps=3) + "")
        sw = spec.load(p, 2**53 - 1)
        runs = planmod.expand(sw)
        self.assertEqual(len(runs), 2 * 2 * 3)
        self.assertEqual([r.seed for r in runs[:4]], [1, 2, 3, 1])
        self.assertEqual(runs[3].params, {"robots.0.count": 2, "arena.width": 2.0, "arena.height": 2.0})
        self.assertEqual(runs[3].overrides, [("robots.0.count", "2"), ("arena.width", "2.0"),
                                             ("arena.height", "2.0")])
        self.assertEqual(len({r.run_id for r in runs}), len(runs))
        # stable: the same inputs give the same ids, in another file too
        again = planmod.expand(spec.load(self.write(p.read_text(), "copy.yaml"), 2**53 - 1))
        self.assertEqual([r.run_id for r in runs], [r.run_id for r in again])
        # a different scenario file content gives different ids
        scen = self.write(SMALL.read_text() + "\n# changed\n", "scen.yaml")
        other = planmod.expand(spec.load(self.write(p.read_text().replace(str(SMALL), str(scen)), "o.yaml"),
                                         2**53 - 1))
        self.assertFalse({r.run_id for r in runs} & {r.run_id for r in other})

    def test_run_ids_hash_an_unambiguous_encoding(self) -> None:
        # Before: "sha\n--set k=v" joined, so a value holding a line break and
        # "--set ..." hashed like a second override.
        sha = "0" * 64
        one = planmod.scenario_hash(sha, [("arena.width", "2\n--set arena.height=3")])
        two = planmod.scenario_hash(sha, [("arena.width", "2"), ("arena.height", "3")])
        self.assertNotEqual(one, two)
        self.assertNotEqual(planmod.scenario_hash(sha, [("a", "b=c")]), planmod.scenario_hash(sha, [("a=b", "c")]))
        self.assertNotEqual(planmod.run_id(one, 1, None), planmod.run_id(one, 1, 0))
        # through sweep files: the two never share an id
        a = spec.load(self.write(f"scenario: {SMALL}\nrepetitions: 1\nset:\n  arena.width: \"2\\n--set arena.height=3\"\n",
                                 "a.yaml"), 2**53 - 1)
        b = spec.load(self.write(f"scenario: {SMALL}\nrepetitions: 1\nset: {{arena.width: 2, arena.height: 3}}\n",
                                 "b.yaml"), 2**53 - 1)
        self.assertNotEqual(planmod.expand(a)[0].run_id, planmod.expand(b)[0].run_id)

    def test_list_axis_with_scenarios(self) -> None:
        scen = self.write(SMALL.read_text(), "second.yaml")
        p = self.write(f"scenario: {SMALL}\nseeds: {{first: 5, count: 2}}\naxes:\n"
                       f"  - list:\n      - {{scenario: {SMALL}, robots.0.count: 2}}\n"
                       f"      - {{scenario: second.yaml, robots.0.count: 3}}\n")
        runs = planmod.expand(spec.load(p, 2**53 - 1))
        self.assertEqual([(Path(r.scenario).name, r.seed) for r in runs],
                         [("valid_small.yaml", 5), ("valid_small.yaml", 6), ("second.yaml", 5), ("second.yaml", 6)])
        self.assertEqual(runs[2].overrides, [("robots.0.count", "3")])
        self.assertTrue(Path(runs[2].scenario).samefile(scen))


class LocalBackend(TempDir):
    def run_sweep(self, p: Path, out: Path, *extra: str, sim: Path = SWARMSIM) -> subprocess.CompletedProcess:
        return swarm_sweep("run", str(p), "--out", str(out), "--sim", str(sim), *extra)

    def test_table_matches_direct_runs_and_resume_runs_nothing(self) -> None:
        p = self.write(sweep_text())
        out = self.dir / "out"
        r = self.run_sweep(p, out, "--jobs", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("8 of 8 runs ok", r.stderr)
        rows = read_table(out, drop=())
        self.assertEqual(len(rows), 8)
        # row 5: robots.0.count=3, 1.5 m, seed 2; the same run made by hand
        row = rows[5]
        self.assertEqual((row["robots.0.count"], row["arena.width"], row["seed"]), ("3", "1.5", "2"))
        direct = self.dir / "direct"
        subprocess.run([str(SWARMSIM), str(SMALL), "--seed", "2", "--steps", "30", "--lcm", "off", "--quiet",
                        "--out", str(direct), "--set", "robots.0.count=3", "--set", "arena.width=1.5",
                        "--set", "arena.height=1.5"], check=True)
        doc = json.loads((direct / "run_2" / "summary.json").read_text())
        self.assertEqual(row["state_hash"], doc["state_hash"])
        for k, v in doc["metrics"].items():
            self.assertEqual(float(row[k]), float(v), k)
        self.assertEqual(row["sim_sha256"], planmod.file_sha256(SWARMSIM))
        # every run used the sweep's own copy of the simulator (a rebuild meanwhile changes nothing)
        frozen = out / "bin" / f"swarmsim-{row['sim_sha256'][:16]}"
        self.assertTrue(frozen.is_file())
        rec = json.loads((out / "records" / f"{row['run_id']}.json").read_text())
        self.assertEqual(rec["command"][0], str(frozen))
        self.assertEqual(row["status"], "ok")
        self.assertTrue((out / "runs" / row["run_id"] / "run_2" / "timeseries.csv").is_file())
        # pandas reads the Parquet copy in one line, with the same values
        import pandas as pd
        df = pd.read_parquet(out / "results.parquet")
        self.assertEqual(len(df), 8)
        self.assertEqual(str(df["state_hash"].dtype), "string")
        self.assertAlmostEqual(df.loc[5, "distance_per_robot_m"], float(row["distance_per_robot_m"]), places=15)
        # resume: nothing runs again, the records are untouched
        mtimes = {f.name: f.stat().st_mtime_ns for f in (out / "records").iterdir()}
        r2 = self.run_sweep(p, out)
        self.assertEqual(r2.returncode, 0, r2.stderr)
        self.assertIn("8 already done", r2.stderr)
        self.assertEqual(mtimes, {f.name: f.stat().st_mtime_ns for f in (out / "records").iterdir()})
        # one record lost: exactly that run again, same metrics
        lost = rows[3]["run_id"]
        (out / "records" / f"{lost}.json").unlink()
        r3 = self.run_sweep(p, out)
        self.assertIn("7 already done", r3.stderr)
        self.assertIn("1 to run", r3.stderr)
        self.assertEqual(read_table(out), [{k: v for k, v in x.items() if k not in VOLATILE} for x in rows])
        self.assertNotIn("another swarmsim", r3.stderr)
        # records made by another simulator binary: kept, and the resume says so
        for f in list((out / "records").iterdir())[:2]:
            rec = json.loads(f.read_text())
            rec["sim_sha256"], rec["code_version"] = "0" * 64, "v-old"
            f.write_text(json.dumps(rec))
        r4 = self.run_sweep(p, out)
        self.assertEqual(r4.returncode, 0, r4.stderr)
        self.assertIn("warning: 2 finished runs", r4.stderr)
        self.assertIn("2 by v-old", r4.stderr)

    def test_failed_run_keeps_its_stderr_and_is_retried_a_bounded_number_of_times(self) -> None:
        sim = fake_sim(self.dir, '[ "$check" = 0 ] && [ "$seed" = 2 ] && { echo "boom: out of tokens" >&2; exit 3; }')
        p = self.write(sweep_text(extra="max_attempts: 2\n"))
        out = self.dir / "out"
        r = self.run_sweep(p, out, sim=sim)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("4 of 8 runs ok, 4 failed", r.stderr)
        rows = read_table(out)
        failed = [x for x in rows if x["status"] == "failed"]
        self.assertEqual({x["seed"] for x in failed}, {"2"})
        self.assertEqual(failed[0]["error"], "exit status 3: boom: out of tokens")
        self.assertEqual(failed[0]["attempts"], "1")
        r = self.run_sweep(p, out, sim=sim)      # second and last attempt
        self.assertIn("4 to run", r.stderr)
        self.assertEqual({x["attempts"] for x in read_table(out) if x["status"] == "failed"}, {"2"})
        r = self.run_sweep(p, out, sim=sim)      # none left
        self.assertIn("4 failed for good, 0 to run", r.stderr)
        self.assertEqual(r.returncode, 1)
        r = self.run_sweep(p, out)               # the real simulator, same ids: nothing retried
        self.assertEqual(r.returncode, 1)
        # a crash by a signal is named
        sim2 = fake_sim(self.dir, '[ "$check" = 0 ] && [ "$seed" = 1 ] && kill -SEGV $$')
        r = self.run_sweep(self.write(sweep_text(reps=1), "one.yaml"), self.dir / "out2", sim=sim2)
        self.assertEqual(r.returncode, 1)
        self.assertTrue(all(x["error"].startswith("killed by SIGSEGV") for x in read_table(self.dir / "out2")))

    def test_a_run_touched_by_hand_is_never_a_result(self) -> None:
        # The simulator's summary says a run was steered (swarmsim --control:
        # a robot moved); the sweep records it as failed, with the reason.
        mark = ("import json, pathlib, sys; p = next(pathlib.Path(sys.argv[1]).glob('run_*/summary.json')); "
                "d = json.loads(p.read_text()); d['control'] = {'touched': True, 'commands': 1}; "
                "p.write_text(json.dumps(d))")
        sim = fake_sim(self.dir, '[ "$check" = 0 ] && [ "$seed" = 2 ] && { out=""; prev=""; '
                       'for a in "$@"; do [ "$prev" = --out ] && out=$a; prev=$a; done; '
                       f'{SWARMSIM} "$@" || exit $?; {sys.executable} -c "{mark}" "$out"; exit $?; }}')
        out = self.dir / "out"
        r = self.run_sweep(self.write(sweep_text()), out, sim=sim)
        self.assertEqual(r.returncode, 1, r.stderr)
        failed = [x for x in read_table(out) if x["status"] == "failed"]
        self.assertEqual({x["seed"] for x in failed}, {"2"})
        self.assertTrue(all(x["error"].startswith("touched by hand") for x in failed), failed)

    def test_interrupted_sweep_keeps_finished_runs_and_resumes_to_the_same_table(self) -> None:
        # Seeds 1 and 2 finish; each seed-3 run waits for a gate that never
        # opens, so the SIGINT finds both workers busy, whatever the load.
        gate = self.dir / "never"
        sim = fake_sim(self.dir, f'[ "$check" = 0 ] && [ "$seed" = 3 ] && '
                                 f'while [ ! -e "{gate}" ]; do sleep 0.05; done')
        p = self.write(sweep_text(reps=3))
        out = self.dir / "out"
        proc = subprocess.Popen([sys.executable, "-m", "swarmtools.sweep", "run", str(p), "--out", str(out),
                                 "--sim", str(sim), "--jobs", "2"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, preexec_fn=default_sigint)
        try:
            wait_for(lambda: len(list((out / "records").glob("*.json"))) == 4, "the 4 runs of seeds 1, 2 of the "
                     "first two combinations")
            proc.send_signal(signal.SIGINT)
            _, err = proc.communicate(timeout=LONG)
        finally:
            proc.kill()
        self.assertEqual(proc.returncode, 130, err)
        self.assertIn("interrupted by SIGINT", err)
        self.assertEqual(list(out.rglob("*.tmp")), [], "no temporary file may be left")
        recs = list((out / "records").glob("*.json"))
        self.assertEqual(len(recs), 4)
        for f in recs:
            self.assertEqual(json.loads(f.read_text())["status"], "ok")   # whole, and not the killed ones
        self.assertEqual(len(read_table(out)), len(recs))
        r = swarm_sweep("run", str(p), "--out", str(out), "--sim", str(SWARMSIM))
        self.assertEqual(r.returncode, 0, r.stderr)
        ref = self.dir / "ref"
        self.assertEqual(swarm_sweep("run", str(p), "--out", str(ref), "--sim", str(SWARMSIM)).returncode, 0)
        drop = (*VOLATILE, "sim_sha256", "attempts")
        self.assertEqual(read_table(out, drop), read_table(ref, drop))

    def test_one_sweep_at_a_time_in_a_folder_and_no_stale_lock(self) -> None:
        # Each run waits (the fake simulator) until the test releases it.
        gate = self.dir / "release"
        sim = fake_sim(self.dir, f'[ -n "$seed" ] && [ "$check" = 0 ] && {{ touch "{self.dir}/started.$$"; '
                                 f'while [ ! -e "{gate}" ]; do sleep 0.05; done; }}')
        p = self.write(sweep_text())
        out = self.dir / "out"
        argv = [sys.executable, "-m", "swarmtools.sweep", "run", str(p), "--out", str(out), "--sim", str(sim),
                "--jobs", "1"]

        def started() -> list[Path]:
            return sorted(self.dir.glob("started.*"))

        first = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            wait_for(started, "the first sweep's first run")
            plan = (out / "sweep.json").stat().st_mtime_ns
            r = self.run_sweep(p, out, sim=sim)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(f"{out}: in use by another swarm-sweep: pid {first.pid} on ", r.stderr)
            self.assertEqual(((out / "sweep.json").stat().st_mtime_ns, list((out / "records").iterdir())), (plan, []))
            gate.touch()
            _, err = first.communicate(timeout=LONG)
        finally:
            first.kill()
        self.assertEqual(first.returncode, 0, err)
        self.assertIn("8 of 8 runs ok", err)
        # Killed outright: its simulator still runs and holds the folder;
        # once that ends, the folder is free (no stale lock to remove).
        gate.unlink()
        for f in started():
            f.unlink()
        out = self.dir / "crashed"
        crashed = subprocess.Popen([*argv[:6], str(out), *argv[7:]], stderr=subprocess.DEVNULL)
        wait_for(started, "the crashing sweep's first run")
        crashed.kill()
        crashed.wait(timeout=LONG)
        r = self.run_sweep(p, out)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn(f"pid {crashed.pid} ", r.stderr)
        self.assertIn("that process has ended; simulators it started still run and hold the folder", r.stderr)
        gate.touch()
        wait_for(lambda: lock_is_free(out), "the orphaned simulator to end")
        r = self.run_sweep(p, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("8 of 8 runs ok", r.stderr)

    def test_a_folder_of_another_format_is_not_resumed(self) -> None:
        out = self.dir / "old"
        out.mkdir()
        (out / ".swarmtools-sweep").touch()
        (out / "sweep.json").write_text(json.dumps({"format": "swarmtools-sweep/1", "runs": []}))
        r = self.run_sweep(self.write(sweep_text()), out)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("made by another version of swarm-sweep (format swarmtools-sweep/1", r.stderr)
        self.assertEqual(sorted(x.name for x in out.iterdir()), [".swarmtools-sweep", ".swarmtools-sweep.lock",
                                                                 "sweep.json"])

    def test_chunked_workers_give_byte_identical_metrics(self) -> None:
        """What slurm array tasks run, at two chunkings, against the local backend."""
        p = self.write(sweep_text(reps=3))
        local = self.dir / "local"
        self.assertEqual(swarm_sweep("run", str(p), "--out", str(local), "--jobs", "2").returncode, 0)
        for size in (1, 5):
            out = self.dir / f"chunk{size}"
            # plan only (the slurm backend's folder), then the workers by hand
            self.assertEqual(swarm_sweep("run", str(p), "--out", str(out), "--jobs", "1").returncode, 0)
            for f in (out / "records").iterdir():
                f.unlink()
            ids = [r["run_id"] for r in json.loads((out / "sweep.json").read_text())["runs"]]
            chunks = [ids[i:i + size] for i in range(0, len(ids), size)]
            (out / "chunks.json").write_text(json.dumps(chunks))
            for i in reversed(range(len(chunks))):
                r = swarm_sweep("worker", str(out), "--chunks", str(out / "chunks.json"), "--index", str(i),
                                "--sim", str(SWARMSIM), "--jobs", "1")
                self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(swarm_sweep("merge", str(out), "--quiet").returncode, 0)
            self.assertEqual(read_table(out), read_table(local))


class BuildFlags(unittest.TestCase):
    def test_no_machine_specific_code_generation(self) -> None:
        """Rows from different machines compare only if no build uses -march=native."""
        files = [ROOT / "Makefile", *sorted((ROOT / "tools" / "make").glob("*.mk")), ROOT / "tools" / "deps.sh"]
        for f in files:
            for flag in ("-march=native", "-mtune=native", "-mcpu=native"):
                self.assertNotIn(flag, f.read_text(), f"{f.relative_to(ROOT)} uses {flag}")


if __name__ == "__main__":
    unittest.main()
