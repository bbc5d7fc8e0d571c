"""The default IR curve against the public e-puck models, as
docs/how-to/calibrate.md's table states them: Webots' lookup table
(E-puckDistanceSensor.proto: distance m, value, relative noise) and Enki's
fitted response (EPuck.cpp).  Facts read from their sources; a change to
our table that leaves them fails here and must update that page."""

import math
import unittest

from swarmtools.calibrate import geometry

#: Webots' e-puck lookup table: (m, counts).
WEBOTS = ((0.0, 4095), (0.005, 2133.33), (0.01, 1465.73), (0.015, 601.46), (0.02, 383.84), (0.03, 234.93),
          (0.04, 158.03), (0.05, 120), (0.06, 104.09), (0.07, 67.19))


def enki_mean(d_m):
    """Enki's response: linear below 0.5 cm, then 4526 e^(-0.9994 d/cm); x U(0.97, 1.03) + U(0, 20)."""
    d = d_m * 100
    v = -440 * d + 2965.98144 if d < 0.5 else 4526 * math.exp(-0.9994 * d)
    return v + 10


class CrossCheck(unittest.TestCase):
    def test_ours_is_webots_table(self):
        for d, v in WEBOTS:
            self.assertAlmostEqual(geometry.ir_curve(d), v, delta=0.5, msg=f"{d * 1000:g} mm")

    def test_beyond_the_table_ours_fades_to_zero(self):
        self.assertAlmostEqual(geometry.ir_curve(0.08), 67 * 20 / 30, delta=0.5)
        self.assertEqual(geometry.ir_curve(0.1), 0.0)

    def test_the_documented_enki_column(self):
        # docs/how-to/calibrate.md: 5 mm 2756, 20 mm 623, 30 mm 236, 50 mm 41
        for d, v in ((0.005, 2756), (0.02, 623), (0.03, 236), (0.05, 41)):
            self.assertAlmostEqual(enki_mean(d), v, delta=0.5)
        # Where the two agree (about 3 cm) and where Enki falls much faster.
        self.assertLess(abs(enki_mean(0.03) - geometry.ir_curve(0.03)) / geometry.ir_curve(0.03), 0.01)
        self.assertLess(enki_mean(0.06), geometry.ir_curve(0.06) / 4)


if __name__ == "__main__":
    unittest.main()
