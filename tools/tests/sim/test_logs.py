"""Telemetry logs as DataFrames (swarmtools.load_log, iter_log): the
batched decoder of the robots' states and events gives what the generated
LCM decoder reads message by message; chunks, the run filter and the
progress report; a damaged message inside a good log is an error naming
the file, never a wrong table."""
import os
import struct
import subprocess
import tempfile
import unittest
from pathlib import Path

import numpy as np
import pandas as pd

import swarmtools
from swarmtools.dataframes import LogReadError
from swarmtools.telemetry import common, logfile

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = os.environ.get("SWARMSIM", str(ROOT / "build" / "swarmsim"))


def write_log(path, events):
    """An LCM log of (channel, bytes) events."""
    with open(path, "wb") as f:
        for k, (channel, data) in enumerate(events):
            ch = channel.encode()
            f.write(struct.pack(">Iqqii", logfile.SYNC, k, 1000 * k, len(ch), len(data)) + ch + data)


class LogTables(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls._tmp = tempfile.TemporaryDirectory()
        cls.tmp = Path(cls._tmp.name)
        # Two seeds of the foraging scenario: several controllers' values, events, two runs in one log.
        subprocess.run([SWARMSIM, str(ROOT / "sim_host" / "scenarios" / "foraging_base.yaml"), "--steps", "300",
                        "--seed", "3", "--reps", "2", "--threads", "1", "--out", str(cls.tmp / "out")],
                       check=True, capture_output=True)
        cls.path = cls.tmp / "out" / "run_3" / "telemetry.lcmlog"
        # One log of both runs, as lcm-logger would record a shared bus.
        both = [(ev.channel, ev.data) for run in ("run_3", "run_4")
                for ev in logfile.events(cls.tmp / "out" / run / "telemetry.lcmlog")]
        cls.both = cls.tmp / "both.lcmlog"
        write_log(cls.both, both)

    @classmethod
    def tearDownClass(cls):
        cls._tmp.cleanup()

    def decoded(self, path, channel):
        return [common.decode(ev.data, ev.channel) for ev in logfile.events(path) if ev.channel == channel]

    def test_robot_rows_are_the_generated_decoders_messages(self):
        log = swarmtools.load_log(self.path)
        msgs = self.decoded(self.path, "ROBOT_STATE")
        robots = log.robots
        self.assertEqual(len(robots), len(msgs))
        self.assertGreater(len(msgs), 500)
        for slot in ("utime", "robot_id", "wheel_left", "ir_max", "ir_max_index", "blobs", "pose_known"):
            np.testing.assert_array_equal(robots[slot].to_numpy(), [getattr(m, slot) for m in msgs], slot)
        for slot in ("x", "y", "theta"):
            np.testing.assert_array_equal(robots[slot].to_numpy(), np.array([getattr(m, slot) for m in msgs],
                                                                            dtype=np.float32), slot)
        for slot in ("group", "controller", "state"):
            self.assertEqual(list(robots[slot].astype(str)), [getattr(m, slot) for m in msgs], slot)
        # The values by their schema: the first robot's first value under its schema's name.
        first = msgs[0]
        schema = log.schemas.get("controller", first.controller)
        name = schema.entry(0).name
        self.assertEqual(np.float32(robots[name].iloc[0]), np.float32(first.values[0]))
        events = self.decoded(self.path, "SWARM_EVENT")
        self.assertEqual(list(log.events["kind"].astype(str)), [m.kind for m in events])
        self.assertEqual(log.events["value"].tolist(), [m.value for m in events])

    def test_chunks_run_filter_and_iter_log_give_the_same_table(self):
        whole = swarmtools.load_log(self.both)
        self.assertEqual(sorted(whole.robots["run"].unique()), [3, 4])
        one = swarmtools.load_log(self.path)
        only3 = swarmtools.load_log(self.both, run=3, chunk_rows=997)
        pd.testing.assert_frame_equal(only3.robots, one.robots)
        pd.testing.assert_frame_equal(only3.events, one.events)
        parts = [df for name, df in swarmtools.iter_log(self.both, run=3, chunk_rows=200) if name == "robots"]
        self.assertGreater(len(parts), 1)
        self.assertTrue(all(len(p) <= 200 for p in parts))
        # (each chunk's categories are those heard so far: concat makes its strings objects)
        pd.testing.assert_frame_equal(pd.concat(parts, ignore_index=True), one.robots, check_dtype=False,
                                      check_categorical=False)

    def test_progress(self):
        seen = []
        swarmtools.load_log(self.both, progress=lambda done, total: seen.append((done, total)))
        size = os.path.getsize(self.both)
        self.assertEqual(seen[-1], (size, size))
        self.assertGreater(len(seen), 10)
        self.assertEqual([d for d, _ in seen], sorted(d for d, _ in seen))

    def test_a_damaged_robot_state_names_the_file(self):
        good = [(ev.channel, ev.data) for ev in logfile.events(self.path)]
        k = next(i for i, (ch, _) in enumerate(good) if ch == "ROBOT_STATE")
        channel, data = good[k]
        wrong_version = data[:8] + struct.pack(">h", 7) + data[10:]
        too_long = data[:28] + struct.pack(">i", 10_000) + data[32:]
        cut = data[:-3]
        for name, bad in (("version", wrong_version), ("string length", too_long), ("truncated", cut)):
            with self.subTest(name):
                path = self.tmp / f"bad_{name.replace(' ', '_')}.lcmlog"
                write_log(path, good[:k + 5] + [(channel, bad)] + good[k + 5:])
                with self.assertRaises(LogReadError) as e:
                    swarmtools.load_log(path)
                self.assertIn(str(path), str(e.exception))
                self.assertIn("robot_state_t", str(e.exception))


if __name__ == "__main__":
    unittest.main()
