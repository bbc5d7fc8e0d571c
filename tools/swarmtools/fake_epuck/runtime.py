"""What runs a fake e-puck's program once its bootloader starts it.

The seam: runtime_for(program) picks how the flashed image runs.  Today
there is one way, HostBuild: the image's declaration (its controller,
period, telemetry and host link, images.py) runs as the host build in a
simulated world (swarmtools.Sim over the public C API), with the robots'
own telemetry on (robot_telemetry.enabled: the image's sender,
firmware/telemetry/robot_telemetry.c, byte for byte as the robot's), its
id the one the flasher wrote (hal_robot_id), and with the image's host link
the live host link (host.live: poses and messages from the serial port go
to hal_pose and hal_host_receive).  A runtime that runs the flashed program
itself on an emulated MCU implements the same methods.

The world: the first shipped scenario (sim_host/scenarios/, by name) with a
group that runs the image's controller, or the scenario given (--world):
the fake robot is that group's first robot and the scenario's other robots
run around it, simulated (a forager among its swarm, with its nest beacon
and its task).  For a controller no scenario runs, a 2 m square arena with
a lamp at its centre, the robot alone.  When the world's task ends the run
(a stop condition), the world starts again.
"""

from __future__ import annotations

import os
import tempfile
from functools import cache
from pathlib import Path
from typing import Protocol

import yaml

from .images import ROOT, ImageDecl, Program

SCENARIOS = ROOT / "sim_host" / "scenarios"
ALONE = {
    "name": "fake_epuck",
    "arena": {"width": 2.0, "height": 2.0},
    "lights": [{"x": 0.0, "y": 0.0, "height": 0.3, "intensity": 1.0}],
}


class Runtime(Protocol):
    """A running program: one control period at a time."""

    period_s: float

    def step(self) -> bytes:
        """Runs one control period; returns the bytes the program wrote to
        its UART in it."""

    def host_pose(self, x_mm: int, y_mm: int, heading_mrad: int) -> None:
        """A POSE frame for this robot arrived (hal_pose)."""

    def host_message(self, payload: bytes) -> bool:
        """A HOST_MSG frame arrived (hal_host_receive); False when the
        robot's mailbox was full and it was dropped."""

    def close(self) -> None:
        ...


@cache
def _groups(path: str) -> list[tuple[str, int]]:
    """(controller, count) of each group of a scenario file."""
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f) or {}
    out = []
    for g in data.get("robots") or []:
        if isinstance(g, dict):
            out.append((str(g.get("controller", "random_walk")), int(g.get("count", 20))))
    return out


def world_for(decl: ImageDecl, world: str | None) -> tuple[str | None, int]:
    """(scenario file, the fake robot's index in it) for an image; (None,
    0) for the robot alone.  ValueError when `world` runs no robot of the
    image's controller."""
    candidates = [world] if world else [str(p) for p in sorted(SCENARIOS.glob("*.yaml"))]
    for path in candidates:
        first = 0
        for controller, count in _groups(path):
            if controller == decl.controller and count > 0:
                return path, first
            first += count
    if world:
        raise ValueError(f"--world {world}: no group runs controller {decl.controller} (image {decl.name})")
    return None, 0


def overrides_for(decl: ImageDecl, seed: int) -> dict:
    """The keys a fake robot's world gets: the image's period, the robots'
    own telemetry at the UART's rate, the live host link, no end."""
    out = {"seed": seed, "duration": 1e7, "control_period_ms": decl.period_ms,
           "robot_telemetry.enabled": True, "robot_telemetry.baud": 115200}
    if decl.host_link:
        out["host.live"] = True
    return out


class HostBuild:
    """The image's controller built into the simulator, in its world."""

    def __init__(self, decl: ImageDecl, robot_id: int, world: str | None = None, seed: int | None = None):
        self.decl = decl
        self.robot_id = robot_id
        self.period_s = decl.period_ms / 1000.0
        self.path, self.index = world_for(decl, world)
        self.seed = seed if seed is not None else robot_id + 1
        self.restarts = 0
        self.sim = self._world()

    def _world(self):
        from ..sim import Sim
        overrides = overrides_for(self.decl, self.seed + self.restarts)
        if self.path is not None:
            sim = Sim(self.path, overrides=overrides)
        else:
            alone = dict(ALONE, robots=[{"name": self.decl.name, "count": 1, "controller": self.decl.controller}])
            fd, path = tempfile.mkstemp(prefix=f"fake_epuck_{self.decl.name}_", suffix=".yaml")
            try:
                with os.fdopen(fd, "w") as f:
                    yaml.safe_dump(alone, f, sort_keys=False)
                sim = Sim(path, overrides=overrides)
            finally:
                os.unlink(path)
        sim.set_robot_id(self.index, self.robot_id)
        return sim

    @property
    def world_name(self) -> str:
        return Path(self.path).name if self.path else "a 2 m arena, alone"

    def step(self) -> bytes:
        if self.sim.step(1) == 0:        # the world's task ended its run: a new one
            self.sim.close()
            self.restarts += 1
            self.sim = self._world()
            self.sim.step(1)
        return self.sim.uart(self.index)

    def host_pose(self, x_mm: int, y_mm: int, heading_mrad: int) -> None:
        if self.decl.host_link:
            self.sim.host_pose(self.index, x_mm, y_mm, heading_mrad)

    def host_message(self, payload: bytes) -> bool:
        return self.decl.host_link and self.sim.host_send(self.index, payload)

    def close(self) -> None:
        self.sim.close()


def runtime_for(program: Program, world: str | None = None, seed: int | None = None) -> Runtime:
    """How `program` (what the bootloader left) runs: its image's host build."""
    return HostBuild(program.image, program.robot_id, world, seed)


__all__ = ["ALONE", "HostBuild", "Runtime", "runtime_for", "world_for"]
