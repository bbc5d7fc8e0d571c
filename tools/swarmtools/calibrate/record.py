"""A robot's recording: every procedure's steps as measured, as JSON, so the
fits can be made (and made again) from the file alone.  Loading checks
every value (its type, its count, that it is finite) so that a hand-edited
or truncated file is refused naming the file, the step and the key, not
deep inside a fit."""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

from ..sweep.store import atomic_write
from .procedures import COLOUR_CARDS, PROCEDURES, Placement, Setup, Step
from .protocol import CHANNELS

FORMAT = "swarm-calibrate-recording/1"


class RecordingError(ValueError):
    pass


@dataclass
class Recording:
    robot_id: int
    setup: Setup = field(default_factory=Setup)
    steps: dict = field(default_factory=dict)        # procedure -> [Step]
    device: str = ""

    def save(self, path: str | Path):
        data = {"format": FORMAT, "robot_id": self.robot_id, "device": self.device, "setup": asdict(self.setup),
                "procedures": {k: [s.as_dict() for s in v] for k, v in self.steps.items()}}
        atomic_write(Path(path), json.dumps(data, indent=1) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> Recording:
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
            raise RecordingError(f"{path}: not a recording: {e}") from e
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise RecordingError(f"{path}: not a recording of swarm-calibrate (format {FORMAT!r})")

        def bad(where, what):
            return RecordingError(f"{path}: {where}: {what}")

        for key in ("robot_id", "setup", "procedures"):
            if key not in data:
                raise bad(key, "missing")
        rid = data["robot_id"]
        if not _is_int(rid) or not 0 <= rid <= 0xFFFE:
            raise bad("robot_id", f"{rid!r} is not a robot id (an integer 0..65534)")
        device = data.get("device", "")
        if not isinstance(device, str):
            raise bad("device", f"{device!r} is not a string")
        setup = _setup(data["setup"], bad)
        procs = data["procedures"]
        if not isinstance(procs, dict):
            raise bad("procedures", "not a mapping of procedure names to steps")
        unknown = [k for k in procs if k not in PROCEDURES]
        if unknown:
            raise RecordingError(f"{path}: unknown procedure {unknown[0]!r} (procedures: {', '.join(PROCEDURES)})")
        steps = {}
        for proc, rows in procs.items():
            if not isinstance(rows, list):
                raise bad(f"procedures.{proc}", "not a list of steps")
            steps[proc] = [_step(proc, row, f"procedures.{proc}[{k}]", bad) for k, row in enumerate(rows)]
        return cls(rid, setup, steps, device)


def _is_int(v) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _is_number(v) -> bool:
    """A finite int or float (JSON's NaN and Infinity, which Python's json
    reads, are no measurement)."""
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _numbers(value, count: int, where: str, what: str, bad) -> tuple:
    if not isinstance(value, list) or len(value) != count:
        n = f"{len(value)} values" if isinstance(value, list) else repr(value)
        raise bad(where, f"{n}: give {count} numbers ({what})")
    for k, v in enumerate(value):
        if not _is_number(v):
            raise bad(f"{where}[{k}]", f"{v!r} is not a finite number ({what})")
    return tuple(float(v) for v in value)


def _setup(d, bad) -> Setup:
    # The setup says what the lab was (the lamp, the control period, the
    # emitter's level): a fit against defaults the lab did not have would
    # be wrong without a word, so it is required and every key checked.
    if not isinstance(d, dict):
        raise bad("setup", "not a mapping")
    known = {f.name: f for f in fields(Setup)}
    for key, v in d.items():
        if key not in known:
            raise bad(f"setup.{key}", f"not a setup key ({', '.join(known)})")
        integer = known[key].type in ("int", int)
        if not (_is_int(v) if integer else _is_number(v)) or v <= 0:
            raise bad(f"setup.{key}", f"{v!r} is not a positive {'integer' if integer else 'number'}")
    return Setup(**d)


#: The placement keys each procedure needs to have a value (not None).
NEEDED = {"ambient": ("sensor", "distance_mm"), "camera": ("distance_mm",), "colours": ("colour", "distance_mm"),
          "sound": ("distance_mm",), "ir": (), "wheels": ()}


def _placement(proc: str, d, where: str, bad) -> Placement:
    if not isinstance(d, dict):
        raise bad(where, "not a mapping")
    known = {f.name: f for f in fields(Placement)}
    for key, v in d.items():
        if key not in known:
            raise bad(f"{where}.{key}", f"not a placement key ({', '.join(known)})")
        t = str(known[key].type)
        if key == "procedure":
            if v != proc:
                raise bad(f"{where}.procedure", f"{v!r} under {proc!r}")
        elif v is None and "None" in t:
            pass
        elif t.startswith("bool"):
            if not isinstance(v, bool):
                raise bad(f"{where}.{key}", f"{v!r} is not true or false")
        elif t.startswith("int"):
            if not _is_int(v):
                raise bad(f"{where}.{key}", f"{v!r} is not an integer")
        elif not _is_number(v):
            raise bad(f"{where}.{key}", f"{v!r} is not a finite number")
    p = Placement(**{"procedure": proc, **d})
    need = NEEDED[proc] + (("sensor",) if proc == "ir" and p.gap_mm is not None else ())
    for key in need:
        if getattr(p, key) is None:
            raise bad(f"{where}.{key}", f"missing (a {proc} step needs it)")
    if p.sensor is not None and not 0 <= p.sensor < 8:
        raise bad(f"{where}.sensor", f"{p.sensor} is not a sensor (IR0..IR7)")
    if p.colour is not None and p.colour not in COLOUR_CARDS:
        raise bad(f"{where}.colour", f"{p.colour} is not a card ({', '.join(map(str, COLOUR_CARDS))})")
    return p


def _step(proc: str, d, where: str, bad) -> Step:
    if not isinstance(d, dict):
        raise bad(where, "not a mapping")
    if "placement" not in d:
        raise bad(f"{where}.placement", "missing")
    p = _placement(proc, d["placement"], f"{where}.placement", bad)
    windows = d.get("windows") or []
    if not isinstance(windows, list):
        raise bad(f"{where}.windows", "not a list of windows")
    ws = []
    for k, w in enumerate(windows):
        if not isinstance(w, list) or len(w) != 2:
            raise bad(f"{where}.windows[{k}]", "give [means, variances]")
        ws.append((_numbers(w[0], CHANNELS, f"{where}.windows[{k}][0]", "the channels' means", bad),
                   _numbers(w[1], CHANNELS, f"{where}.windows[{k}][1]", "the channels' variances", bad)))
    if proc != "wheels" and not ws:
        raise bad(f"{where}.windows", f"none recorded (a {proc} step streams at least one)")
    moved = d.get("moved")
    if moved is not None:
        moved = _numbers(moved, 3, f"{where}.moved", "forward mm, left mm, turned deg", bad)
    counted = d.get("steps")
    if counted is not None:
        counted = _numbers(counted, 2, f"{where}.steps", "left and right steps counted", bad)
    return Step(p, ws, moved, counted)
