"""What runs a fake e-puck's program once its bootloader starts it.

The seam: runtime_for(program) picks how the flashed image runs.  SimRobot:
the image's declaration (its controller, period, telemetry and host link,
images.py) runs in a simulated world (swarmtools.Sim over the public C
API), with the robots' own telemetry on (robot_telemetry.enabled: the
image's sender, firmware/telemetry/robot_telemetry.c, byte for byte as the
robot's), its id the one the flasher wrote (hal_robot_id), and with the
image's host link the live host link (host.live: poses and messages from
the serial port go to hal_pose and hal_host_receive).  On platform "host"
(the default) the image's controller is the host build; on "pil_avr" or
"pil_m4" the image itself, cross-compiled, runs as machine code on an
emulated MCU through the simulator's processor-in-the-loop model
(docs/reference/pil.md: `make pil-avr` / `make pil-m4` build the ELFs),
the rest of its world host-built.

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


PLATFORMS = ("host", "pil_avr", "pil_m4")
#: Where `make pil-avr` leaves the emulator and the AVR images (the M4's
#: are in its sibling pil_m4, as the pil model expects).
PIL_DIR = ROOT / "build" / "firmware" / "pil_avr"


def world_for(decl: ImageDecl, world: str | None) -> tuple[str | None, int, int]:
    """(scenario file, the fake robot's index in it, its group) for an
    image; (None, 0, 0) for the robot alone.  ValueError when `world` runs
    no robot of the image's controller."""
    candidates = [world] if world else [str(p) for p in sorted(SCENARIOS.glob("*.yaml"))]
    for path in candidates:
        first = 0
        for group, (controller, count) in enumerate(_groups(path)):
            if controller == decl.controller and count > 0:
                return path, first, group
            first += count
    if world:
        raise ValueError(f"--world {world}: no group runs controller {decl.controller} (image {decl.name})")
    return None, 0, 0


def overrides_for(decl: ImageDecl, seed: int) -> dict:
    """The keys a fake robot's world gets: the image's period, the robots'
    own telemetry at the UART's rate, the live host link, no end."""
    out = {"seed": seed, "duration": 1e7, "control_period_ms": decl.period_ms,
           "robot_telemetry.enabled": True, "robot_telemetry.baud": 115200}
    if decl.host_link:
        out["host.live"] = True
    return out


def platform_overrides(decl: ImageDecl, group: int, robot_id: int, platform: str) -> dict:
    """The keys that put the fake robot (its group's first robot) on an
    emulated MCU: the group runs the image, its first robot on `platform`
    with the flashed id (an MCU learns its id when it boots: first_id, the
    group's others following it), the scenario's IR messages the image's
    (the turret's 16 bits)."""
    if platform not in PLATFORMS:
        raise ValueError(f"platform {platform!r}: one of {', '.join(PLATFORMS)}")
    if platform == "host":
        return {}
    return {f"robots.{group}.image": decl.name, f"robots.{group}.platform": platform,
            f"robots.{group}.platform_robots": 1, f"robots.{group}.first_id": robot_id, "pil.dir": str(PIL_DIR),
            "ircom.payload_bits": 16 if decl.ir == "randb" else 8}


class SimRobot:
    """The image in its world: its controller built into the simulator
    (platform "host") or the image on an emulated MCU (pil_avr, pil_m4)."""

    def __init__(self, decl: ImageDecl, robot_id: int, world: str | None = None, seed: int | None = None,
                 platform: str = "host"):
        self.decl = decl
        self.robot_id = robot_id
        self.platform = platform
        self.period_s = decl.period_ms / 1000.0
        self.path, self.index, self.group = world_for(decl, world)
        self.seed = seed if seed is not None else robot_id + 1
        self.restarts = 0
        self.views: dict[int, list] = {}      # world index -> [robot id, UART bytes not yet taken]
        self.sim = self._world()

    def _world(self):
        from ..sim import Sim
        overrides = overrides_for(self.decl, self.seed + self.restarts)
        overrides.update(platform_overrides(self.decl, self.group, self.robot_id, self.platform))
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
        for index, (rid, _) in self.views.items():
            sim.set_robot_id(index, rid)
        return sim

    def attach(self, decl: ImageDecl, robot_id: int) -> int:
        """Another fake robot's port onto a robot of this world: the first
        robot after this one that runs `decl`'s controller and no port yet
        (its index).  ValueError when there is none."""
        first = 0
        for controller, count in (_groups(self.path) if self.path else []):
            for index in range(first, first + count):
                if controller == decl.controller and index != self.index and index not in self.views:
                    self.views[index] = [robot_id, bytearray()]
                    self.sim.set_robot_id(index, robot_id)
                    return index
            first += count
        raise ValueError(f"{self.world_name}: no other robot runs controller {decl.controller} "
                         f"(image {decl.name}) for a second port")

    @property
    def world_name(self) -> str:
        where = Path(self.path).name if self.path else "a 2 m arena, alone"
        return where if self.platform == "host" else f"{where}, on {self.platform}"

    def step(self) -> bytes:
        if self.sim.step(1) == 0:        # the world's task ended its run: a new one
            self.sim.close()
            self.restarts += 1
            self.sim = self._world()
            self.sim.step(1)
        for index, (_, pending) in self.views.items():
            pending += self.sim.uart(index)
        return self.sim.uart(self.index)

    def host_pose(self, x_mm: int, y_mm: int, heading_mrad: int) -> None:
        if self.decl.host_link:
            self.sim.host_pose(self.index, x_mm, y_mm, heading_mrad)

    def host_message(self, payload: bytes) -> bool:
        return self.decl.host_link and self.sim.host_send(self.index, payload)

    def close(self) -> None:
        self.sim.close()


class WorldView:
    """A fake robot that is a robot of another fake's world (FakeEpucks
    shared_world): the owner steps the world; this one takes its robot's
    UART bytes and gives it the host link's poses and messages (a second
    e-puck beside the first, each on its own port)."""

    def __init__(self, decl: ImageDecl, robot_id: int, owner):
        self.decl = decl
        self.robot_id = robot_id
        self.owner = owner              # the FakeRobot whose runtime (a SimRobot) holds the world
        self.period_s = decl.period_ms / 1000.0
        self.world = None
        self.index = None
        self._attach()

    def _attach(self) -> SimRobot | None:
        rt = self.owner.runtime
        if rt is None:
            return None
        if rt is not self.world:
            self.index = rt.attach(self.decl, self.robot_id)
            self.world = rt
        return rt

    @property
    def world_name(self) -> str:
        return f"robot {self.index} of {self.owner.name}'s world"

    def step(self) -> bytes:
        rt = self._attach()
        if rt is None:
            return b""
        pending = rt.views[self.index][1]
        out = bytes(pending)
        pending.clear()
        return out

    def host_pose(self, x_mm: int, y_mm: int, heading_mrad: int) -> None:
        rt = self._attach()
        if rt is not None and self.decl.host_link:
            rt.sim.host_pose(self.index, x_mm, y_mm, heading_mrad)

    def host_message(self, payload: bytes) -> bool:
        rt = self._attach()
        return rt is not None and self.decl.host_link and rt.sim.host_send(self.index, payload)

    def close(self) -> None:
        if self.world is not None:
            self.world.views.pop(self.index, None)
        self.world = None


def runtime_for(program: Program, world: str | None = None, seed: int | None = None,
                platform: str = "host", owner=None) -> Runtime:
    """How `program` (what the bootloader left) runs: its image in its world, on `platform`;
    with `owner` (a FakeRobot running), a robot of the owner's world."""
    if owner is not None:
        if owner.runtime is None:
            raise ValueError(f"{owner.name}, whose world it shares, runs nothing")
        return WorldView(program.image, program.robot_id, owner)
    return SimRobot(program.image, program.robot_id, world, seed, platform)


__all__ = ["ALONE", "PLATFORMS", "Runtime", "SimRobot", "WorldView", "runtime_for", "world_for"]
