"""The longer check of the calibration kit (make calibrate-sweep): many
perturbed robots, each calibrated end to end on a fake e-puck (fake_lab.py)
with the kit's default procedures, and the worst error per parameter
against the stated tolerances, as a table (CSV and Markdown).

    python -m swarmtools.calibrate.sweep --robots 10 --out out/calibrate-sweep [--spread 1.0]
"""

from __future__ import annotations

import argparse
import random
import sys
import tempfile
from pathlib import Path

from ..sweep.store import atomic_write
from . import cli, fake_lab, procedures

#: The tolerances the kit states (docs/how-to/calibrate.md): relative, or in the units UNITS names.
TOLERANCES = {"ir.gain": 0.03, "ir.offset": 6.0, "ir.noise_rel": 0.25, "ir.noise_abs": 0.25, "ambient.dark": 0.01,
              "ambient.half": 0.05, "ambient.noise_rel": 0.25, "wheels.gain": 0.01, "camera.range_m": 0.015,
              "camera.fov_deg": 1.0, "sound.alpha": 0.07, "sound.ae": 0.05, "sound.noise": 0.25, "sound.gain": 0.05}


UNITS = {"ir.offset": " counts", "camera.range_m": " m", "camera.fov_deg": " deg"}


def errors(truth: dict, fits: dict) -> dict:
    """The error of each parameter (worst over sensors and wheels)."""
    ir, amb, wh = fits["ir"].params, fits["ambient"].params, fits["wheels"].params

    def rel(a, b):
        return abs(a - b) / abs(b)
    t = truth
    return {
        "ir.gain": max(rel(ir["sensors"][s]["gain"], t["ir"]["sensors"][s]["gain"]) for s in range(8)),
        "ir.offset": max(abs(ir["sensors"][s]["offset"] - t["ir"]["sensors"][s]["offset"]) for s in range(8)),
        "ir.noise_rel": rel(ir["noise_rel"], t["ir"]["noise_rel"]),
        "ir.noise_abs": rel(ir["noise_abs"], t["ir"]["noise_abs"]),
        "ambient.dark": rel(amb["dark"], t["ambient"]["dark"]),
        "ambient.half": rel(amb["half"], t["ambient"]["half"]),
        "ambient.noise_rel": rel(amb["noise_rel"], t["ambient"]["noise_rel"]),
        "wheels.gain": max(rel(wh[k], t["wheels"][k]) for k in ("gain_left", "gain_right")),
        "camera.range_m": abs(fits["camera"].params["range"] - t["camera"]["range"]),
        "camera.fov_deg": abs(fits["camera"].params["fov"] - t["camera"]["fov"]),
        "sound.alpha": rel(fits["sound"].params["alpha"], t["sound"]["alpha"]),
        "sound.ae": rel(fits["sound"].params["ae"], t["sound"]["ae"]),
        "sound.noise": rel(fits["sound"].params["noise"], t["sound"]["noise"]),
        "sound.gain": max(rel(fits["sound"].params[f"gain{b}"], t["sound"][f"gain{b}"]) for b in (1, 2, 3)),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="calibrate-sweep", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--robots", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--spread", type=float, default=1.0, help="scales the perturbations' ranges")
    ap.add_argument("--speed", type=float, default=500.0, help="the fake robot's simulated time per wall second")
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args(argv)
    rows = []
    for k in range(args.robots):
        truth = fake_lab.perturbed(random.Random(args.seed + k), args.spread)
        with tempfile.TemporaryDirectory() as tmp:
            fakes, link, _ = fake_lab.start(100 + k, truth, Path(tmp) / "lab", speed=args.speed)
            try:
                _, fits = cli.calibrate(link, Path(tmp) / "out", list(procedures.PROCEDURES), procedures.Setup(),
                                        fake_lab.SimOperator(fakes, seed=k), timeout_s=60, log=lambda s: None)
            finally:
                fakes.stop()
        e = errors(truth, fits)
        rows.append(e)
        print(f"robot {k + 1}/{args.robots}: " + ", ".join(f"{n} {v:.3g}" for n, v in e.items()), file=sys.stderr)
    worst = {n: max(r[n] for r in rows) for n in TOLERANCES}
    csv = "robot," + ",".join(TOLERANCES) + "\n" + "".join(
        f"{k}," + ",".join(f"{r[n]:.5g}" for n in TOLERANCES) + "\n" for k, r in enumerate(rows))
    md = ["| parameter | tolerance | worst error | within |", "|---|---|---|---|"]
    md += [f"| {n} | {TOLERANCES[n]:g}{UNITS.get(n, ' (relative)')} | {worst[n]:.3g} | "
           f"{'yes' if worst[n] <= TOLERANCES[n] else 'NO'} |" for n in TOLERANCES]
    atomic_write(args.out / "errors.csv", csv)
    atomic_write(args.out / "summary.md", f"{args.robots} robots, seed {args.seed}, spread {args.spread:g}\n\n"
                 + "\n".join(md) + "\n")
    print("\n".join(md))
    bad = [n for n in TOLERANCES if worst[n] > TOLERANCES[n]]
    if bad:
        print(f"calibrate-sweep: outside the tolerance: {', '.join(bad)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
