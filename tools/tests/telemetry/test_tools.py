"""The round trip (a simulation's LCM log exported to CSV is its own time
series and summary, exactly), the exporter, the monitor, the plots, and the
Java types lcm-spy loads."""
import csv
import json
import re
import shutil
import subprocess
import unittest

from .helpers import ROOT, TempDir, common, run_sim, tool

import export_csv
import monitor

SCENARIO = "sim_host/scenarios/foraging_base.yaml"


class RoundTrip(TempDir):
    """One short foraging run (1234 steps: the last row is not on the grid
    of timeseries_every) and one random walk, both with the default log."""

    @classmethod
    def setUpClass(cls):
        import tempfile
        cls._dir = tempfile.TemporaryDirectory(prefix="telemetry_roundtrip_")
        cls.out = __import__("pathlib").Path(cls._dir.name)
        run_sim(cls.out / "forage", SCENARIO, "--steps", "1234", "--seed", "4")
        run_sim(cls.out / "walk", "sim_host/scenarios/random_walk.yaml", "--steps", "777")
        cls.run_dir = cls.out / "forage" / "run_4"
        cls.log = cls.run_dir / "telemetry.lcmlog"

    @classmethod
    def tearDownClass(cls):
        cls._dir.cleanup()

    def test_timeseries_exactly(self):
        for run_dir in (self.run_dir, self.out / "walk" / "run_1"):
            every = 10
            out = self.tmp / "ts.csv"
            tool("export_csv.py", run_dir / "telemetry.lcmlog", "--timeseries", every, "-o", out)
            self.assertEqual(out.read_bytes(), (run_dir / "timeseries.csv").read_bytes(), run_dir)

    def test_summary_exactly(self):
        out = self.tmp / "summary.csv"
        tool("export_csv.py", self.log, "--channel", "RUN_SUMMARY", "-o", out)
        with out.open() as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), 1)
        row = rows[0]
        text = (self.run_dir / "summary.json").read_text()
        summary = json.loads(text)
        self.assertEqual(row["state_hash"], summary["state_hash"])
        self.assertEqual(int(row["steps"]), summary["steps"])
        self.assertEqual(row["scenario"], summary["scenario"])
        self.assertEqual(int(row["run"]), summary["seed"])
        for name in summary["metrics"]:
            # The same text as summary.json prints for the metric.
            printed = re.search(rf'"{re.escape(name)}": ([^,\n]+)', text).group(1)
            self.assertEqual(row[name], printed, name)

    def test_log_is_simulated_time(self):
        lcm = common.lcm_module()
        last = -1
        channels = set()
        for ev in lcm.EventLog(str(self.log), "r"):
            self.assertGreaterEqual(ev.timestamp, last)
            self.assertEqual(ev.timestamp % 100000, 0)
            last = ev.timestamp
            channels.add(ev.channel)
        self.assertEqual(last, 1234 * 100000)
        self.assertEqual(channels, {"RUN_INFO", "SWARM_STATE", "ROBOT_STATE", "SWARM_EVENT", "RUN_SUMMARY"})

    def test_every_channel_to_a_folder(self):
        d = self.tmp / "csv"
        r = tool("export_csv.py", self.log, "-o", str(d) + "/")
        self.assertIn("ROBOT_STATE:", r.stderr)
        with (d / "ROBOT_STATE.csv").open() as f:
            robots = list(csv.DictReader(f))
        self.assertEqual(len(robots), 21 * (1234 // 10 + 2))   # every 10 steps and the last, 20 + beacon
        self.assertEqual({r["task_state"] for r in robots} - {"W", "S", "R", "B"}, set())
        with (d / "SWARM_EVENT.csv").open() as f:
            events = list(csv.DictReader(f))
        kinds = {e["kind"] for e in events}
        self.assertTrue({"pickup", "deposit", "oae", "state_change"} <= kinds, kinds)
        deposits = sum(e["kind"] == "deposit" for e in events)
        summary = json.loads((self.run_dir / "summary.json").read_text())
        self.assertEqual(deposits, summary["metrics"]["food_collected"])
        # Fields, and one channel to stdout.
        r = tool("export_csv.py", self.log, "--channel", "ROBOT_STATE", "--log-time",
                 "--fields", "log_utime,robot_id,x")
        first = r.stdout.splitlines()[:2]
        self.assertEqual(first[0], "log_utime,robot_id,x")
        self.assertTrue(first[1].startswith("0,0,"))

    def test_exporter_errors(self):
        r = tool("export_csv.py", self.log, check=False)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("several channels", r.stderr)
        r = tool("export_csv.py", self.log, "--channel", "SWARM_STATE", "--fields", "nope", check=False)
        self.assertIn("no field(s) nope", r.stderr)
        r = tool("export_csv.py", self.tmp / "missing.lcmlog", check=False)
        self.assertNotEqual(r.returncode, 0)

    def test_monitor_replays_the_log(self):
        r = tool("monitor.py", "--log", self.log, "--speed", "0", "--plain", "--exit-idle", "0.5", timeout=60)
        summary = json.loads((self.run_dir / "summary.json").read_text())
        out = r.stdout
        self.assertIn("run foraging_base seed 4: forager/drtm, 20 robots + nest beacon", out)
        self.assertIn(f"collected {summary['metrics']['food_collected']:g}", out)
        self.assertIn("step 1234 of 1234 (100 %)", out)
        self.assertIn(f"run finished after 1234 steps (state {summary['state_hash']}):", out)
        self.assertEqual(len(re.findall(r"^ +\d+  (forager|nest_beacon) ", out, re.M)), 21)

    def test_monitor_model_renders_in_a_small_window(self):
        lcm = common.lcm_module()
        m = monitor.Model(clock=lambda: 0.0)
        for ev in lcm.EventLog(str(self.log), "r"):
            m.add(ev.channel, ev.data)
        lines = m.render("test", width=60, height=20, scroll=5)
        self.assertEqual(len(lines), 20)
        self.assertTrue(all(len(ln) <= 60 for ln in lines))
        self.assertTrue(any("of 21)" in ln for ln in lines))
        m.add("JUNK", b"not lcm at all")
        self.assertEqual(m.undecodable, 1)

    def test_plots(self):
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            self.skipTest("matplotlib missing: make telemetry-deps")
        out = self.tmp / "plots"
        r = tool("plot_run.py", self.log, "-o", out)
        names = sorted(p.name for p in out.iterdir())
        self.assertEqual(names, ["events.png", "food_level.png", "oae.png", "robots_by_state.png"])
        for p in out.iterdir():
            self.assertEqual(p.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.assertGreater(p.stat().st_size, 10000)
        self.assertEqual(len(r.stdout.split()), 4)
        walk = self.tmp / "walk_plots"
        tool("plot_run.py", self.out / "walk" / "run_1" / "telemetry.lcmlog", "-o", walk)
        self.assertEqual(sorted(p.name for p in walk.iterdir()), ["oae.png", "robots_by_state.png"])


class JavaTypes(TempDir):
    """build/lcm_types.jar: the classes lcm-spy finds decode our messages."""

    def test_java_decodes_a_python_message(self):
        jar = ROOT / "build" / "lcm_types.jar"
        java = shutil.which("java")
        if not jar.exists() or not java:
            self.skipTest("no JDK: the jar is built only when javac is present")
        lcm_jar = next((ROOT / ".venv").glob("lib/python*/site-packages/share/java/lcm.jar"))
        src = self.tmp / "Check.java"
        src.write_text("""
public class Check {
    public static void main(String[] a) throws Exception {
        byte[] data = java.util.HexFormat.of().parseHex(a[0]);
        swarmlcm.robot_state_t m = new swarmlcm.robot_state_t(data);
        System.out.println(m.robot_id + " " + m.controller + " " + m.state + " " + m.threshold + " "
                           + (char) m.task_state + " " + swarmlcm.robot_state_t.LCM_FINGERPRINT);
    }
}
""")
        msg = common.type_class("robot_state_t")()
        msg.robot_id, msg.controller, msg.state, msg.threshold, msg.task_state = 5, "forager", "return", 2.5, ord("R")
        r = subprocess.run([java, "-cp", f"{lcm_jar}:{jar}", str(src), msg.encode().hex()],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        fp = int.from_bytes(type(msg)._get_packed_fingerprint(), "big", signed=True)
        self.assertEqual(r.stdout.split(), ["5", "forager", "return", "2.5", "R", str(fp)])


if __name__ == "__main__":
    unittest.main()
