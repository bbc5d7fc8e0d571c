"""A sweep figure's y axis names the metric as the simulator declared it:
summary.json's metric_docs (unit and one-line meaning, written by every run
beside the values), the raw name when no run has a doc for it."""
import json
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

from swarmtools.sweep.figure import metric_label

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM


class MetricLabel(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        cls.tmp = tempfile.TemporaryDirectory()
        cls.runs = Path(cls.tmp.name) / "runs"
        subprocess.run([str(SWARMSIM), str(ROOT / "sim_host/scenarios/phototaxis_gather.yaml"),
                        "--set", "duration=1", "--out", str(cls.runs / "abc")],
                       check=True, capture_output=True, cwd=ROOT, timeout=120)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.tmp.cleanup()

    def test_every_metric_has_its_doc_beside_its_value(self) -> None:
        doc = json.loads((self.runs / "abc" / "run_1" / "summary.json").read_text())
        self.assertEqual(set(doc["metric_docs"]), set(doc["metrics"]))
        for name, d in doc["metric_docs"].items():
            self.assertTrue(d["doc"], name)

    def test_documented_metrics(self) -> None:
        self.assertEqual(metric_label("mean_speed_mm_s", self.runs),
                         "mean ground speed of the robots that can move, mm/s (mean_speed_mm_s)")
        self.assertEqual(metric_label("completed", self.runs),
                         "1 when a task's stop condition ended the run (completed)")

    def test_unknown_metric_or_no_runs_keeps_the_name(self) -> None:
        self.assertEqual(metric_label("no_such_metric", self.runs), "no_such_metric")
        self.assertEqual(metric_label("mean_speed_mm_s", Path(self.tmp.name) / "nothing"), "mean_speed_mm_s")
        self.assertEqual(metric_label("mean_speed_mm_s", None), "mean_speed_mm_s")


if __name__ == "__main__":
    unittest.main()
