"""swarm-calibrate run --live: the robot's telemetry and every prompt and
progress line also go out on LCM, the prompts as events (kind
"calibrate") the live view's events panel lists; the answers still come
from the terminal."""

from __future__ import annotations

import io
import os
import unittest

from swarmtools.calibrate.link import RobotLink
from swarmtools.calibrate.operator import EVENT_KIND, LiveOperator, TerminalOperator
from swarmtools.calibrate.procedures import Placement
from swarmtools.telemetry import common


class LivePrompts(unittest.TestCase):
    def setUp(self):
        self.lc = common.lcm_module().LCM("memq://")
        self.got = []
        self.lc.subscribe("SWARM_EVENT", lambda ch, data: self.got.append(common.decode(data, ch)))

    def drain(self):
        while self.lc.handle_timeout(0) > 0:
            pass

    def test_prompts_and_progress_are_events(self):
        answers = iter(["", "", "120 -3 2"])
        out = io.StringIO()
        op = LiveOperator(TerminalOperator(read=lambda prompt: next(answers), out=out), self.lc.publish,
                          robot_id=lambda: 7, clock=lambda: 12.5)
        op.setup("wheels", "a flat floor")
        op.place(Placement("ir", sensor=0, gap_mm=8), "[1/57] Put IR0 ...")
        self.assertEqual(op.measure_move(Placement("wheels"), "Where did it end?"), (120.0, -3.0, 2.0))
        op.progress("wheels: 1/5 done")
        self.drain()
        self.assertEqual([m.kind for m in self.got], [EVENT_KIND] * 5)
        self.assertEqual([m.detail for m in self.got], [
            "setup: wheels: a flat floor", "place: [1/57] Put IR0 ...", "measure: Where did it end?",
            "measured: 120, -3, 2", "progress: wheels: 1/5 done"])
        self.assertEqual([m.value for m in self.got], [0, 1, 2, 3, 4])
        self.assertEqual({m.robot_id for m in self.got}, {7})
        self.assertEqual({m.utime for m in self.got}, {12_500_000})
        self.assertIn("wheels: 1/5 done", out.getvalue())       # the terminal still says it

    def test_the_robots_frames_go_out_too(self):
        master, slave = os.openpty()
        seen = []
        try:
            link = RobotLink(os.ttyname(slave), also_publish=lambda ch, data: seen.append((ch, data)))
            link._publish("BRIDGE_STATUS", b"frame")
            link.close()
        finally:
            os.close(master)
            os.close(slave)
        self.assertEqual(seen, [("BRIDGE_STATUS", b"frame")])


if __name__ == "__main__":
    unittest.main()
