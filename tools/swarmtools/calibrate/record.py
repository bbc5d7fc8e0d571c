"""A robot's recording: every procedure's steps as measured, as JSON, so the
fits can be made (and made again) from the file alone."""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..sweep.store import atomic_write
from .procedures import PROCEDURES, Setup, Step

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
        except (OSError, json.JSONDecodeError) as e:
            raise RecordingError(f"{path}: not a recording: {e}") from e
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise RecordingError(f"{path}: not a recording of swarm-calibrate (format {FORMAT!r})")
        try:
            procs = data["procedures"]
            unknown = [k for k in procs if k not in PROCEDURES]
            if unknown:
                raise RecordingError(f"{path}: unknown procedure {unknown[0]!r} (procedures: {', '.join(PROCEDURES)})")
            return cls(int(data["robot_id"]), Setup(**data.get("setup", {})),
                       {k: [Step.from_dict(s) for s in v] for k, v in procs.items()}, data.get("device", ""))
        except (KeyError, TypeError, ValueError) as e:
            if isinstance(e, RecordingError):
                raise
            raise RecordingError(f"{path}: a malformed recording ({type(e).__name__}: {e})") from e
