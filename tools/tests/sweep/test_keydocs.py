"""swarmtools.keydocs names a --set key as swarmsim --help documents it (a
sweep figure's axis): its meaning and unit beside the raw key, list indices
read as the help's [], asides and remarks left out; an undocumented key, or
a simulator that cannot run, keeps the raw key."""
import os
import unittest
from pathlib import Path

from swarmtools import keydocs

ROOT = Path(__file__).resolve().parents[3]
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM


class Labels(unittest.TestCase):
    def test_documented_keys(self):
        self.assertEqual(keydocs.label("robots.0.count", SWARMSIM), "robots in the group (robots.0.count)")
        self.assertEqual(keydocs.label("duration", SWARMSIM), "simulated time, s (duration)")
        self.assertEqual(keydocs.label("robots.2.params.speed_steps_s", SWARMSIM),
                         "forward wheel speed, steps/s (robots.2.params.speed_steps_s)")
        # "(swarmsim --help lists them; default its first)": the aside goes, with its semicolon
        self.assertEqual(keydocs.meaning("robots.0.policy", SWARMSIM), "variant of the controller")

    def test_undocumented(self):
        self.assertEqual(keydocs.label("no.such.key", SWARMSIM), "no.such.key")
        self.assertEqual(keydocs.label("robots.0.count", ROOT / "no-such-simulator"), "robots.0.count")

    def test_generic(self):
        self.assertEqual(keydocs.generic("robots.10.params.a_m"), "robots[].params.a_m")
        self.assertEqual(keydocs.generic("objects.0.x"), "objects[].x")
        self.assertEqual(keydocs.generic("sound.noise"), "sound.noise")


if __name__ == "__main__":
    unittest.main()
