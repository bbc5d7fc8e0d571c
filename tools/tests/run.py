"""Runs the host tools' tests (tools/tests/telemetry, study, sil, sweep,
evolve, fuzz, the parsers' property tests, plan, the ALNS planner, sim, the
simulator from Python, fake_epuck, the real-robot tools against
swarm-fake-epuck, and calibrate, the calibration kit against a fake e-puck
with known model parameters; the flasher's run in `make firmware-check`) with
unittest discovery and ends with one line
'python tools: N passed, N failed, N skipped'.  Given group names
(`run.py sweep plan`), only those: make test runs two halves side by side
(python-tests-1 and python-tests-2, tools/make/python.mk)."""
import sys
import unittest
from pathlib import Path

here = Path(__file__).resolve().parent
suite = unittest.TestSuite()
GROUPS = ("telemetry", "study", "sil", "sweep", "evolve", "fuzz", "plan", "sim", "fake_epuck", "calibrate")
unknown = [g for g in sys.argv[1:] if g not in GROUPS]
if unknown:
    sys.exit(f"run.py: no test group {', '.join(unknown)} (the groups: {', '.join(GROUPS)})")
for group in sys.argv[1:] or GROUPS:
    suite.addTests(unittest.defaultTestLoader.discover(str(here / group), top_level_dir=str(here.parent)))
result = unittest.TextTestRunner(verbosity=2).run(suite)
failed = len(result.failures) + len(result.errors) + len(result.unexpectedSuccesses)
skipped = len(result.skipped)
chosen = f" ({', '.join(sys.argv[1:])})" if sys.argv[1:] else ""
print(f"python tools{chosen}: {result.testsRun - failed - skipped} passed, {failed} failed, {skipped} skipped")
sys.exit(0 if result.wasSuccessful() else 1)
