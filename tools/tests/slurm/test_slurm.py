"""The slurm backend on a real single-node SLURM (make slurm-tests).

    .venv/bin/python -m unittest tools.tests.slurm.test_slurm

Starts munged, slurmctld and slurmd on this machine with a generated key and
configuration (tools/slurm/local_cluster.sh), runs a small sweep through
sbatch job arrays and the dependent merge job, checks the merged table
against the local backend's, resumes after losing records, and stops SLURM.
If SLURM cannot start here the tests fail with its reason; they never skip.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from tools.tests.sweep.test_sweep import SMALL, SWARMSIM, read_table

ROOT = Path(__file__).resolve().parents[3]
CLUSTER = ROOT / "tools" / "slurm" / "local_cluster.sh"
SWEEP = (f"name: on_slurm\nscenario: {SMALL}\nsteps: 40\n"
         "axes:\n  - grid:\n      robots.0.count: [2, 3]\n      arena.width: [1.5, 2.0]\n"
         "repetitions: 3\n")


class SlurmBackend(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        cls._tmp = tempfile.TemporaryDirectory(prefix="slurm_test.")
        cls.dir = Path(cls._tmp.name)
        check = subprocess.run(["bash", str(CLUSTER), "check"], capture_output=True, text=True, check=False)
        if check.returncode != 0:
            cls._tmp.cleanup()
            raise AssertionError(f"SLURM is not installed here: {check.stderr.strip()}")
        cls.cluster = cls.dir / "cluster"
        start = subprocess.run(["bash", str(CLUSTER), "start", str(cls.cluster)], capture_output=True,
                               text=True, timeout=300, check=False)
        if start.returncode != 0:
            subprocess.run(["bash", str(CLUSTER), "stop", str(cls.cluster)], capture_output=True, check=False)
            cls._tmp.cleanup()
            raise AssertionError(f"single-node SLURM did not start:\n{start.stderr.strip()}")
        cls.env = dict(os.environ, SLURM_CONF=str(cls.cluster / "slurm.conf"))
        cls.sweep = cls.dir / "sweep.yaml"
        cls.sweep.write_text(SWEEP)
        local = cls.dir / "local"
        r = cls.swarm_sweep("run", str(cls.sweep), "--out", str(local), "--jobs", "2")
        if r.returncode != 0:
            cls.tearDownClass()
            raise AssertionError(f"the local backend failed: {r.stderr}")
        cls.local_table = read_table(local)

    @classmethod
    def tearDownClass(cls) -> None:
        stop = subprocess.run(["bash", str(CLUSTER), "stop", str(cls.cluster)], capture_output=True,
                              text=True, timeout=300, check=False)
        cls._tmp.cleanup()
        if stop.returncode != 0:
            raise AssertionError(f"stopping SLURM failed: {stop.stderr}")

    @classmethod
    def swarm_sweep(cls, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "swarmtools.sweep", *args, "--sim", str(SWARMSIM)],
                              capture_output=True, text=True, timeout=600, check=False,
                              env=getattr(cls, "env", None), cwd=ROOT)

    def run_slurm(self, out: Path, chunk: int) -> subprocess.CompletedProcess:
        return self.swarm_sweep("run", str(self.sweep), "--out", str(out), "--backend", "slurm",
                                "--chunk-size", str(chunk), "--poll", "0.5", "--time", "00:05:00")

    def test_job_array_matches_the_local_backend(self) -> None:
        out = self.dir / "slurm"
        r = self.run_slurm(out, chunk=5)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("12 of 12 runs ok", r.stderr)
        self.assertIn("(3 tasks of up to 5 runs)", r.stderr)
        self.assertIn("slurm tasks:", r.stderr)     # squeue-based progress
        self.assertEqual(read_table(out), self.local_table)
        sub = next((out / "slurm").iterdir())
        jobs = json.loads((sub / "jobs.json").read_text())
        self.assertEqual(jobs["chunks"], 3)
        # the merge job ran after the array and wrote its log; each array task logged
        logs = sorted(p.name for p in (sub / "logs").iterdir())
        self.assertEqual(len([n for n in logs if n.startswith(f"{jobs['arrays'][0]}_")]), 3, logs)
        merge_log = sub / "logs" / f"merge_{jobs['merge']}.out"
        self.assertIn("12 of 12 runs ok", merge_log.read_text())
        # hosts: the rows say where they ran
        self.assertTrue(all(row["host"] for row in read_table(out, drop=())))

    def test_resume_submits_only_what_is_missing(self) -> None:
        out = self.dir / "slurm_resume"
        r = self.run_slurm(out, chunk=4)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(read_table(out), self.local_table)
        # two records lost: exactly those two are submitted again
        for row in read_table(out)[4:6]:
            (out / "records" / f"{row['run_id']}.json").unlink()
        r = self.run_slurm(out, chunk=1)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("10 already done", r.stderr)
        self.assertIn("(2 tasks of up to 1 runs)", r.stderr)
        self.assertEqual(read_table(out), self.local_table)
        # nothing left: nothing submitted
        r = self.run_slurm(out, chunk=1)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("submitted", r.stderr)

    def test_study_runs_on_slurm_with_the_local_results(self) -> None:
        """make study-drtm STUDY_ARGS="--backend slurm ...", narrowed to 2 x 2 x 2 short runs."""
        narrow = ["--quick", "--conditions", "base,l3", "--policies", "drtm,artm", "--reps", "2",
                  "--steps", "300", "--no-figures", "--sim", str(SWARMSIM)]
        results = {}
        for backend in ("local", "slurm"):
            out = self.dir / f"study_{backend}"
            r = subprocess.run([sys.executable, "-m", "swarmtools.study.drtm", *narrow, "--out", str(out),
                                "--backend", backend, "--chunk-size", "3", "--poll", "0.5"],
                               capture_output=True, text=True, timeout=600, check=False, env=self.env, cwd=ROOT)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertIn("study_drtm: 8 runs; wrote", r.stdout)
            doc = json.loads((out / "results.json").read_text())
            results[backend] = {(c, p): [run["metrics"] for run in cell["runs"]]
                                for c, cond in doc["conditions"].items() for p, cell in cond["policies"].items()}
        self.assertEqual(len(results["slurm"]), 4)
        self.assertEqual(results["slurm"], results["local"])


if __name__ == "__main__":
    unittest.main()

