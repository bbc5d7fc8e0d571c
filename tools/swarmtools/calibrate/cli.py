"""swarm-calibrate: fit the simulator's models to a lab's own e-pucks.

    swarm-calibrate run /dev/rfcomm0 --out calib/robot7     guide, record, fit
    swarm-calibrate fit calib/*/recording.json --out lab    fit again, many robots
    swarm-calibrate apply scenario.yaml lab/fragment.yaml -o mine.yaml [--average]

`run` guides the owner through each procedure in the terminal, records the
robot's readings through the bridge's decoder on its serial port (the robot
runs the calibration image: make flash HEX=build/firmware/xc16/calib.hex
DEVICE=/dev/rfcomm0 ROBOT_ID=7), and
writes into --out: recording.json (every reading), fragment.yaml (the
models' parameters for the robot's id) and report/ (plots and report.md).
Nothing is written unless every procedure asked for completed and was
fitted.  docs/how-to/calibrate.md has the whole walkthrough.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..sweep.store import atomic_write
from ..telemetry import common
from . import fit as fitting
from . import fragment, procedures, report
from .link import LinkError, RobotLink
from .operator import Aborted, LiveOperator, TerminalOperator
from .record import Recording, RecordingError

PROG = "swarm-calibrate"
EPILOG = "exit status: 0 done; 1 a procedure failed (the message names it and what to redo); 2 bad arguments"


def fit_recording(rec: Recording, max_rms: dict | None = None) -> dict:
    """{procedure: Fit} of one robot's recording (FitError names the robot
    and what to redo).  `max_rms`: {procedure: largest rms residual}, the
    others fit.MAX_RMS's."""
    tol = max_rms or {}
    out = {}
    try:
        for proc, steps in rec.steps.items():
            if proc == "ir":
                out[proc] = fitting.fit_ir(steps, tol.get(proc))
            elif proc == "ambient":
                out[proc] = fitting.fit_ambient(steps, rec.setup, tol.get(proc))
            elif proc == "wheels":
                out[proc] = fitting.fit_wheels(steps, rec.setup, tol.get(proc))
            elif proc == "camera":
                out[proc] = fitting.fit_camera(steps)
            elif proc == "colours":
                out[proc] = fitting.fit_colours(steps)
            elif proc == "sound":
                out[proc] = fitting.fit_sound(steps, rec.setup, tol.get(proc))
    except fitting.FitError as e:
        raise e.of_robot(rec.robot_id) from e
    return out


def write_outputs(fits_by_robot: dict, out: Path) -> Path:
    sections = fragment.build(fits_by_robot)
    text = fragment.dump(sections)
    report.write(fits_by_robot, out / "report", "fragment.yaml")
    atomic_write(out / "fragment.yaml", text)
    return out / "fragment.yaml"


def record(device: str, procs: list[str], setup: procedures.Setup, operator, robot_id=None, timeout_s=10.0,
           log=print, emitter: str | None = None, publish=None) -> Recording:
    """`publish(channel, data)`: the robot's telemetry and the prompts also go
    out there (an LCM's publish: the live view, --live)."""
    with RobotLink(device, robot_id=robot_id, timeout_s=timeout_s, also_publish=publish) as link:
        if publish is not None:
            operator = LiveOperator(operator, publish, lambda: link.robot_id)
        rid = link.hello()
        log(f"{PROG}: robot {rid} on {device} answers")
        em = None
        try:
            if emitter is not None and "sound" in procs:
                em = RobotLink(emitter, timeout_s=timeout_s, also_publish=publish)
                eid = em.hello()
                if eid == rid:
                    raise LinkError(f"{emitter}: the emitter reports robot {rid}, the robot calibrated: "
                                    f"give the emitter's own port")
                log(f"{PROG}: the emitter, robot {eid} on {emitter}, answers")
            rec = Recording(rid, setup, {}, device)
            for proc in procs:
                rec.steps[proc] = procedures.run(proc, link, operator, setup, emitter=em)
            return rec
        finally:
            if em is not None:
                em.close()


def calibrate(device: str, out: Path, procs: list[str], setup: procedures.Setup, operator, robot_id=None,
              timeout_s=10.0, log=print, emitter: str | None = None, publish=None, max_rms: dict | None = None
              ) -> tuple:
    """Records, fits and writes; (recording, fits).  Raises LinkError,
    Aborted, FitError with nothing written.  `emitter`: the port of a
    second robot on the calibration image that plays the tones."""
    rec = record(device, procs, setup, operator, robot_id, timeout_s, log, emitter, publish)
    fits = fit_recording(rec, max_rms)
    rec.save(out / "recording.json")
    write_outputs({rec.robot_id: fits}, out)
    return rec, fits


def _procedures(text: str) -> list[str]:
    out = [p.strip() for p in text.split(",") if p.strip()]
    bad = [p for p in out if p not in procedures.PROCEDURES]
    if bad or not out:
        raise argparse.ArgumentTypeError(f"unknown procedure {bad[0] if bad else text!r} "
                                         f"(procedures: {', '.join(procedures.PROCEDURES)})")
    return out


def _max_rms(text: str) -> tuple:
    proc, sep, value = text.partition("=")
    if not sep or proc not in fitting.MAX_RMS:
        raise argparse.ArgumentTypeError(f"{text!r}: give PROCEDURE=VALUE, PROCEDURE one of "
                                         f"{', '.join(fitting.MAX_RMS)}")
    try:
        v = float(value)
    except ValueError:
        v = float("nan")
    if not v > 0 or v == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r}: the tolerance is a positive number")
    return proc, v


def _add_max_rms(p: argparse.ArgumentParser) -> None:
    p.add_argument("--max-rms", type=_max_rms, action="append", default=[], metavar="PROCEDURE=VALUE",
                   help="the largest rms residual of a procedure's fit, in its report's units, above which the "
                        "fit fails (repeatable; defaults: "
                        + ", ".join(f"{k}={v:g}" for k, v in fitting.MAX_RMS.items())
                        + ": ir and ambient counts, wheels mm / deg, sound relative)")


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog=PROG, description=__doc__, epilog=EPILOG,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="guide, record, fit one robot")
    r.add_argument("device", help="the robot's serial port (/dev/rfcomm0)")
    r.add_argument("--out", required=True, type=Path, help="folder for recording.json, fragment.yaml, report/")
    r.add_argument("--robot-id", type=int, help="expect this id (default: the id the robot reports)")
    r.add_argument("--emitter", metavar="DEVICE",
                   help="a second e-puck on the calibration image (its own port) that plays the microphone "
                        "procedure's tones as the kit tells it (default: you make the emitter play)")
    r.add_argument("--procedures", type=_procedures, default=list(procedures.PROCEDURES),
                   help="comma-separated, in order (default: " + ",".join(procedures.PROCEDURES) + ")")
    r.add_argument("--lamp-height-mm", type=float, default=100.0)
    r.add_argument("--lamp-intensity", type=float, default=1.0,
                   help="the lamp's intensity in the scenarios' units (1: it defines the unit)")
    r.add_argument("--sound-a0", type=float, default=299.18,
                   help="the emitter's sound.a0 in your scenarios: the microphone gains are against it")
    r.add_argument("--windows", type=int, default=2, help="1 s windows recorded per placement")
    r.add_argument("--timeout", type=float, default=10.0, help="s to wait for the robot before giving up")
    r.add_argument("--live", nargs="?", const=common.DEFAULT_URL, metavar="LCM_URL",
                   help="also publish the robot's telemetry and each prompt and progress line (events, kind "
                        "'calibrate') on LCM for the live view (swarm-live); default URL: the bridge's")
    _add_max_rms(r)
    f = sub.add_parser("fit", help="fit recordings again (one or many robots: the lab's fragment)")
    f.add_argument("recordings", nargs="+", type=Path)
    f.add_argument("--out", required=True, type=Path)
    _add_max_rms(f)
    a = sub.add_parser("apply", help="a scenario with a fragment's parameters")
    a.add_argument("scenario", type=Path)
    a.add_argument("fragment", type=Path)
    a.add_argument("-o", "--output", required=True, type=Path)
    a.add_argument("--average", action="store_true", help="every robot the lab's average, not its own")
    return p


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        if args.cmd == "run":
            setup = procedures.Setup(args.lamp_height_mm, args.lamp_intensity, windows=args.windows,
                                     sound_a0=args.sound_a0)
            publish = None
            if args.live is not None:
                publish = common.lcm_module().LCM(args.live).publish
            rec, fits = calibrate(args.device, args.out, args.procedures, setup, TerminalOperator(),
                                  args.robot_id, args.timeout, emitter=args.emitter, publish=publish,
                                  max_rms=dict(args.max_rms))
            print(f"{PROG}: robot {rec.robot_id}: {args.out / 'fragment.yaml'}, {args.out / 'report' / 'report.md'}")
        elif args.cmd == "fit":
            fits = {}
            for path in args.recordings:
                rec = Recording.load(path)
                if rec.robot_id in fits:
                    raise RecordingError(f"{path}: robot {rec.robot_id} again (one recording per robot)")
                try:
                    fits[rec.robot_id] = fit_recording(rec, dict(args.max_rms))
                except fitting.FitError as e:
                    raise RecordingError(f"{path}: {e}") from e
            n = len(fits)
            print(f"{PROG}: {n} robot{'' if n == 1 else 's'}: {write_outputs(fits, args.out)}")
        else:
            fragment.apply_checked(args.scenario, args.fragment, args.output, args.average)
            print(f"{PROG}: {args.output}")
    except (LinkError, Aborted, fitting.FitError, RecordingError, fragment.FragmentError, OSError) as e:
        print(f"{PROG}: {e}; nothing written", file=sys.stderr)
        return 1
    return 0
