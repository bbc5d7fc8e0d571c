"""The longer check of the calibration kit (make calibrate-sweep): many
perturbed robots, each calibrated end to end on a fake e-puck (fake_lab.py)
with the kit's default procedures, and the worst error per parameter
against the stated tolerances, as a table (CSV and Markdown).

    python -m swarmtools.calibrate.sweep --robots 10 --out out/calibrate-sweep [--spread 1.0] [--platform pil_avr]
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
              "camera.fov_deg": 1.0, "colours.gain": 0.03, "sound.alpha": 0.07, "sound.ae": 0.05, "sound.noise": 0.25, "sound.gain": 0.05}


UNITS = {"ir.offset": " counts", "camera.range_m": " m", "camera.fov_deg": " deg"}


def errors(truth: dict, fits: dict) -> dict:
    """The error of each parameter (worst over sensors and wheels) of the
    procedures fitted."""
    def rel(a, b):
        return abs(a - b) / abs(b)
    t = truth
    out = {}
    if "ir" in fits:
        ir = fits["ir"].params
        out.update({
            "ir.gain": max(rel(ir["sensors"][s]["gain"], t["ir"]["sensors"][s]["gain"]) for s in range(8)),
            "ir.offset": max(abs(ir["sensors"][s]["offset"] - t["ir"]["sensors"][s]["offset"]) for s in range(8)),
            "ir.noise_rel": rel(ir["noise_rel"], t["ir"]["noise_rel"]),
            "ir.noise_abs": rel(ir["noise_abs"], t["ir"]["noise_abs"])})
    if "ambient" in fits:
        amb = fits["ambient"].params
        out.update({"ambient.dark": rel(amb["dark"], t["ambient"]["dark"]),
                    "ambient.half": rel(amb["half"], t["ambient"]["half"]),
                    "ambient.noise_rel": rel(amb["noise_rel"], t["ambient"]["noise_rel"])})
    if "wheels" in fits:
        wh = fits["wheels"].params
        out["wheels.gain"] = max(rel(wh[k], t["wheels"][k]) for k in ("gain_left", "gain_right"))
    if "camera" in fits:
        out.update({"camera.range_m": abs(fits["camera"].params["range"] - t["camera"]["range"]),
                    "camera.fov_deg": abs(fits["camera"].params["fov"] - t["camera"]["fov"])})
    if "colours" in fits:
        co = fits["colours"].params
        out["colours.gain"] = max(rel(co[k], t["camera"][k]) for k in ("gain_r", "gain_b"))
    if "sound" in fits:
        so = fits["sound"].params
        out.update({"sound.alpha": rel(so["alpha"], t["sound"]["alpha"]), "sound.ae": rel(so["ae"], t["sound"]["ae"]),
                    "sound.noise": rel(so["noise"], t["sound"]["noise"]),
                    "sound.gain": max(rel(so[f"gain{b}"], t["sound"][f"gain{b}"]) for b in (1, 2, 3))})
    return out


def outside(errs: dict) -> list[str]:
    """The parameters whose error is beyond the tolerance."""
    return [n for n, v in errs.items() if v > TOLERANCES[n]]


def procedures_on(platform: str) -> list[str]:
    """Every procedure, but the colours on a processor-in-the-loop robot
    (its link carries blobs, not frames: hal_camera_colour_stats is
    unavailable there)."""
    return [p for p in procedures.PROCEDURES if platform == "host" or p != "colours"]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="calibrate-sweep", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--robots", type=int, default=10)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--spread", type=float, default=1.0, help="scales the perturbations' ranges")
    ap.add_argument("--speed", type=float, default=500.0, help="the fake robot's simulated time per wall second")
    ap.add_argument("--platform", choices=("host", "pil_avr", "pil_m4"), default="host",
                    help="what runs the calibration image: its host build, or its ELF on an emulated MCU "
                         "(the processor-in-the-loop robot: make pil-avr / pil-m4)")
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args(argv)
    rows = []
    for k in range(args.robots):
        truth = fake_lab.perturbed(random.Random(args.seed + k), args.spread)
        with tempfile.TemporaryDirectory() as tmp:
            fakes, link, _ = fake_lab.start(100 + k, truth, Path(tmp) / "lab", speed=args.speed,
                                            platform=args.platform)
            try:
                _, fits = cli.calibrate(link, Path(tmp) / "out", procedures_on(args.platform), procedures.Setup(),
                                        fake_lab.SimOperator(fakes, seed=k), timeout_s=60, log=lambda s: None,
                                        emitter=fakes.links[1])
                with fakes.locked():
                    pil = fakes.robots[0].runtime.sim.summary().get("pil") or {}
            finally:
                fakes.stop()
        if args.platform != "host" and pil.get("robots") != 1:
            print(f"calibrate-sweep: robot {k + 1} was not on {args.platform} (summary: {pil})", file=sys.stderr)
            return 1
        e = errors(truth, fits)
        rows.append(e)
        print(f"robot {k + 1}/{args.robots}: " + ", ".join(f"{n} {v:.3g}" for n, v in e.items()), file=sys.stderr)
    names = [n for n in TOLERANCES if n in rows[0]]
    worst = {n: max(r[n] for r in rows) for n in names}
    csv = "robot," + ",".join(names) + "\n" + "".join(
        f"{k}," + ",".join(f"{r[n]:.5g}" for n in names) + "\n" for k, r in enumerate(rows))
    md = ["| parameter | tolerance | worst error | within |", "|---|---|---|---|"]
    md += [f"| {n} | {TOLERANCES[n]:g}{UNITS.get(n, ' (relative)')} | {worst[n]:.3g} | "
           f"{'yes' if worst[n] <= TOLERANCES[n] else 'NO'} |" for n in names]
    atomic_write(args.out / "errors.csv", csv)
    atomic_write(args.out / "summary.md", f"{args.robots} robots on {args.platform}, seed {args.seed}, "
                 f"spread {args.spread:g}\n\n"
                 + "\n".join(md) + "\n")
    print("\n".join(md))
    bad = outside(worst)
    if bad:
        print(f"calibrate-sweep: outside the tolerance: {', '.join(bad)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
