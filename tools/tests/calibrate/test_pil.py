"""The calibration kit against the processor-in-the-loop robot
(docs/how-to/calibrate.md): the "real" robot is the calibration image's
ELF running as machine code on the emulated ATmega2560 (the simulator's
pil model, docs/reference/pil.md), with the e-puck1's 16-bit int and
32-bit double, behind a fake e-puck's serial port, in a world whose models
were given known, perturbed parameters for its id.  swarm-calibrate talks
to it through the bridge's decoder and the host link, as to a robot, and
must recover the parameters within the stated tolerances.

Trimmed to fit make test: the ambient, wheel and camera procedures (the
image's 'A', 'D' and 'C' commands on the MCU: its float windows, its
16-bit step counters, its blobs), one window per placement.  make
calibrate-pil runs every procedure on the AVR and the Cortex-M4F."""

from __future__ import annotations

import random
import tempfile
import unittest
from pathlib import Path

from swarmtools.calibrate import cli, fake_lab, procedures, sweep
from swarmtools.fake_epuck.runtime import PIL_DIR

ROBOT_ID = 12
PROCEDURES = ["ambient", "wheels", "camera"]


class RecoveryOnTheAvr(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        for need in (PIL_DIR / "pil_avr_emu", PIL_DIR / "avr" / "calib.elf", PIL_DIR / "avr" / "calib.map"):
            if not need.is_file():
                raise AssertionError(f"{need} is not built: make pil-avr")
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = Path(cls.tmp.name)
        cls.truth = fake_lab.perturbed(random.Random(11))
        fakes, link, _ = fake_lab.start(ROBOT_ID, cls.truth, cls.dir / "lab", speed=500, platform="pil_avr")
        try:
            cls.rec, cls.fits = cli.calibrate(link, cls.dir / "out", PROCEDURES, procedures.Setup(windows=1),
                                              fake_lab.SimOperator(fakes), timeout_s=60, log=lambda s: None)
            with fakes.locked():
                cls.summary = fakes.robots[0].runtime.sim.summary()
        finally:
            fakes.stop()

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_robot_is_the_mcu(self):
        """The windows came from the ELF on the emulated AVR, which took its id from the flasher's."""
        self.assertEqual(self.rec.robot_id, ROBOT_ID)
        pil = self.summary.get("pil") or {}
        self.assertEqual((pil.get("robots"), pil.get("platform")), (1, "pil_avr"), self.summary.get("pil"))
        self.assertGreater(pil.get("cycles_per_step_mean", 0), 0)

    def test_recovered_within_the_tolerances(self):
        errs = sweep.errors(self.truth, self.fits)
        self.assertEqual(sorted({n.split(".")[0] for n in errs}), sorted(PROCEDURES))
        self.assertEqual(sweep.outside(errs), [], {n: round(v, 5) for n, v in errs.items()})

    def test_outputs(self):
        out = self.dir / "out"
        for name in ("recording.json", "fragment.yaml", "report/report.md", "report/robot12_wheels.png"):
            self.assertTrue((out / name).is_file(), name)


if __name__ == "__main__":
    unittest.main()
