"""Software in the loop, through the host tools.

1. The robots' own telemetry (``robot_telemetry.enabled``): every simulated
   robot runs the image's sender (firmware/telemetry/robot_telemetry.c) and
   the simulator republishes what it deframes on the FW_ channels.  Each
   robot's raw byte stream (``robot_telemetry.dump``) fed through the serial
   bridge (swarmtools.telemetry.bridge, its FrameDecoder and Bridge, as for a
   real e-puck) gives exactly the messages the simulator published: the
   same channels, the same bytes, in the same order per robot.
2. The walkthrough's controller (phototaxis) and task (gather) go through
   the CSV export and the plots with no tool change: their declared values
   are columns and figures.
"""
import csv
import tempfile
import unittest
from collections import defaultdict
from pathlib import Path

import swarmlcm

from swarmtools.telemetry import bridge

from ..telemetry.helpers import SCENARIOS, has_matplotlib, raw_events, run_sim, tool


class RobotsOwnTelemetry(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name)
        run_sim(cls.out, SCENARIOS / "foraging_base.yaml", "--steps", "300",
                "--set", "robot_telemetry.enabled=true", "--set", "robot_telemetry.dump=true")
        cls.log = cls.out / "run_1" / "telemetry.lcmlog"

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def published(self):
        """The simulator's FW_ messages: (channel, bytes) per robot id for
        robot states, and every schema chunk in order."""
        states, schemas = defaultdict(list), []
        for channel, data in raw_events(self.log):
            if channel == "FW_ROBOT_STATE":
                states[swarmlcm.robot_state_t.decode(data).robot_id].append(data)
            elif channel == "FW_TELEMETRY_SCHEMA":
                schemas.append(data)
        return states, schemas

    def test_bridge_gives_what_the_simulator_published(self):
        states, schemas = self.published()
        self.assertEqual(sorted(states), list(range(21)))          # 20 foragers and the beacon
        bridged_schemas = []
        for robot in range(21):
            got = []
            dev = bridge.Device(f"robot_{robot}")
            b = bridge.Bridge([dev], lambda ch, data, got=got: got.append((ch, bytes(data))), prefix="FW_")
            stream = (self.out / "run_1" / "uart" / f"robot_{robot}.bin").read_bytes()
            b.feed(dev, stream)
            counters = dev.counters()
            self.assertEqual(counters["crc_errors"] + counters["framing_errors"] + counters["bad_payload"], 0)
            self.assertEqual(counters["lost"], 0)
            self.assertEqual([d for ch, d in got if ch == "FW_ROBOT_STATE"], states[robot])
            bridged_schemas += [d for ch, d in got if ch == "FW_TELEMETRY_SCHEMA"]
            self.assertEqual(len(states[robot]), 30)               # once a second for 30 s
        self.assertEqual(sorted(bridged_schemas), sorted(schemas))
        self.assertEqual(len(schemas), 21 * 30)

    def test_the_robots_values_are_named_by_their_own_schema(self):
        names = {}
        for channel, data in raw_events(self.log):
            if channel == "FW_TELEMETRY_SCHEMA":
                m = swarmlcm.schema_t.decode(data)
                table = names.setdefault(m.name, [None] * m.total)
                table[m.first:m.first + m.n] = m.names
        self.assertEqual(names["forager"][:3], ["oae", "deposits", "threshold"])
        self.assertNotIn(None, names["forager"])
        self.assertEqual(names["nest_beacon"][0], "nest_food")

    def test_the_csv_export_names_their_values_on_the_fw_channel(self):
        tool("export_csv", self.log, "--channel", "FW_ROBOT_STATE", "-o", self.out / "fw.csv")
        header = next(csv.reader((self.out / "fw.csv").open()))
        self.assertIn("forager.threshold", header)
        self.assertIn("nest_beacon.nest_food", header)


class WalkthroughThroughTheTools(unittest.TestCase):
    """A new controller's and a new task's values in the CSV and the plots,
    with no tool change."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = Path(cls.tmp.name)
        run_sim(cls.out, SCENARIOS / "phototaxis_gather.yaml", "--telemetry-rate", "2,10")
        cls.log = cls.out / "run_1" / "telemetry.lcmlog"

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_csv_has_the_declared_values(self):
        (self.out / "csv").mkdir()
        tool("export_csv", self.log, "-o", self.out / "csv")
        robots = list(csv.DictReader((self.out / "csv" / "ROBOT_STATE.csv").open()))
        self.assertIn("phototaxis.brightest", robots[0])
        self.assertIn("phototaxis.light_bearing", robots[0])
        self.assertIn("phototaxis.arrivals", robots[0])
        self.assertTrue(any(float(r["phototaxis.arrivals"]) >= 1 for r in robots))
        swarm = list(csv.DictReader((self.out / "csv" / "SWARM_STATE.csv").open()))
        self.assertIn("swarm.in_goal", swarm[0])
        self.assertIn("swarm.arrivals_total", swarm[0])
        self.assertGreaterEqual(float(swarm[-1]["swarm.in_goal"]), 9)
        # The time series, rebuilt from the telemetry, is the run's own file.
        rebuilt = tool("export_csv", self.log, "--timeseries", "10").stdout
        self.assertEqual(rebuilt, (self.out / "run_1" / "timeseries.csv").read_text())

    @unittest.skipUnless(has_matplotlib(), "matplotlib missing: make deps installs it")
    def test_plots_have_the_declared_values(self):
        tool("plot_run", self.log, "-o", self.out / "plots")
        made = sorted(p.name for p in (self.out / "plots").iterdir())
        self.assertIn("controller_phototaxis.png", made)
        self.assertIn("swarm_values.png", made)
        for name in made:
            self.assertEqual((self.out / "plots" / name).read_bytes()[:8], b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
