"""A simulated lab: a fake e-puck (swarmtools.fake_epuck) flashed with the
calibration image plays the real robot, in a world whose models were given
known, perturbed parameters for its id, and an operator who puts it where
each step asks (the fake's own simulation: set_pose) and reads the ruler
(its true pose, with a ruler's error).  The kit must recover the
parameters: tools/tests/calibrate/ and `make calibrate-sweep`."""

from __future__ import annotations

import math
import random
import tempfile
from pathlib import Path

import yaml

from ..fake_epuck.server import FakeEpucks
from . import procedures

ARENA_M = 2.4
LAMP = {"x": 0.0, "y": 0.0, "height": 0.1, "intensity": 1.0}
#: The camera procedure's card, far from the other procedures' places.
CARD = (0.0, 0.9)
#: The colours procedure's cards (procedures.COLOUR_CARDS), upright cylinders
#: by the arena's right wall, out of the camera procedure's view: x, y, radius.
COLOUR_CARDS = {0: (1.0, -0.1), 1: (1.0, 0.15), 2: (1.0, -0.65), 3: (1.0, -0.9)}
COLOUR_CARD_RADIUS = 0.1
#: The sensor noise of the fake robot's frames (camera.noise), counts.
CAMERA_NOISE = 4.0
#: The emitter of the sound procedure: the world's second robot, out of the others' way.
EMITTER = (-1.0, -1.0)


def perturbed(rng: random.Random, spread: float = 1.0) -> dict:
    """Model parameters for one robot, drawn around the defaults as a lab's
    robots differ (IR gains by a factor of two)."""
    return {
        "ir": {"noise_rel": round(rng.uniform(0.005, 0.03), 4), "noise_abs": round(rng.uniform(2, 10), 2),
               "sensors": [{"gain": round(math.exp(rng.uniform(-0.35, 0.35) * spread), 3),
                            "offset": round(rng.uniform(20, 90) * spread, 1)} for _ in range(8)]},
        "ambient": {"dark": round(rng.uniform(3500, 4090), 1), "half": round(math.exp(rng.uniform(-1, 1) * spread), 3),
                    "noise_rel": round(rng.uniform(0.005, 0.02), 4)},
        "wheels": {"gain_left": round(1 + rng.uniform(-0.05, 0.05) * spread, 4),
                   "gain_right": round(1 + rng.uniform(-0.05, 0.05) * spread, 4)},
        "camera": {"range": round(0.9 + rng.uniform(-0.3, 0.3) * spread, 3),
                   "fov": round(56 + rng.uniform(-8, 8) * spread, 2),
                   # The colour response against green (the exposure sets the level).
                   "gain_r": round(math.exp(rng.uniform(-0.15, 0.15) * spread), 3),
                   "gain_b": round(math.exp(rng.uniform(-0.15, 0.15) * spread), 3)},
        "sound": {"alpha": round(0.726 * math.exp(rng.uniform(-0.3, 0.3) * spread), 4),
                  "ae": round(48.18 * math.exp(rng.uniform(-0.3, 0.3) * spread), 3),
                  "noise": round(rng.uniform(0.03, 0.09), 4),
                  **{f"gain{b}": round(math.exp(rng.uniform(-0.3, 0.3) * spread), 4) for b in (1, 2, 3)}},
    }


def world(robot_id: int, truth: dict) -> dict:
    """The fake robot's world: an empty arena with one lamp at its centre,
    its models' parameters for `robot_id` as `truth` says."""
    return {
        "name": "calibration_lab",
        "arena": {"width": ARENA_M, "height": ARENA_M},
        "lights": [LAMP],
        "robots": [{"count": 1, "controller": "calib", "placement": {"shape": "poses",
                                                                     "poses": [{"x": 0.0, "y": -0.5, "heading": 0}]}},
                   {"name": "emitter", "count": 1, "controller": "calib", "moves": False, "placement": {
                       "shape": "poses", "poses": [{"x": EMITTER[0], "y": EMITTER[1], "heading": 0}]}}],
        "ir": {"robots": [{"id": robot_id, **truth["ir"]}]},
        "ambient": {"robots": [{"id": robot_id, **truth["ambient"]}]},
        "wheels": {"robots": [{"id": robot_id, **truth["wheels"]}]},
        "camera": {"noise": CAMERA_NOISE, "robots": [{"id": robot_id, **truth["camera"]}]},
        "sound": {"enabled": True, **{k: v for k, v in truth["sound"].items() if not k.startswith("gain")},
                  "robots": [{"id": robot_id, **{k: v for k, v in truth["sound"].items() if k.startswith("gain")}}]},
        "objects": [{"shape": "cylinder", "x": CARD[0], "y": CARD[1], "radius": procedures.CARD_DIAMETER_MM / 2000,
                     "height": 0.08, "colour": "red"}]
        + [{"shape": "cylinder", "x": x, "y": y, "radius": COLOUR_CARD_RADIUS, "height": 0.15,
            "colour": procedures.COLOUR_CARDS[c] if c else "none"} for c, (x, y) in COLOUR_CARDS.items()],
    }


class SimOperator:
    """Places the fake robot in its world and measures it."""

    def __init__(self, fakes: FakeEpucks, ruler_mm: float = 0.5, protractor_deg: float = 0.5, seed: int = 1):
        self.fakes = fakes
        self.ruler_mm = ruler_mm
        self.protractor_deg = protractor_deg
        self.rng = random.Random(seed)
        self.start = None
        self.log = []

    def _sim(self):
        rt = self.fakes.robots[0].runtime
        if rt is None:
            raise RuntimeError("the fake robot runs no program")
        return rt.sim, rt.index

    def setup(self, procedure, text):
        self.log.append(("setup", procedure))

    def place(self, placement, text):
        hw = ARENA_M / 2
        if placement.procedure == "ir" and placement.gap_mm is None:
            pose = (0.0, -0.5, 0.0)                          # 30 cm from every wall, the lamp's light irrelevant
        elif placement.procedure == "ir":
            x, y, th = procedures.robot_pose_for(placement)   # the wall's face at x = 0
            pose = (hw + x, -0.4, th)
        elif placement.procedure == "sound":
            pose = (EMITTER[0] + placement.distance_mm / 1000.0, EMITTER[1], 0.0)
        elif placement.procedure == "camera":
            x, y, th = procedures.camera_pose_for(placement)  # the card's centre at the origin, looking along +y here
            pose = (CARD[0] - y, CARD[1] + x, th + math.pi / 2)
        elif placement.procedure == "colours":
            x, y, th = procedures.colour_pose_for(placement)  # the card's face at x = 0
            cx, cy = COLOUR_CARDS[placement.colour]
            pose = (cx - COLOUR_CARD_RADIUS + x, cy + y, th)
        elif placement.procedure == "ambient":
            x, y, th = procedures.robot_pose_for(placement)   # the lamp's foot at the origin
            pose = (LAMP["x"] + x, LAMP["y"] + y, th)
        else:
            pose = (-0.3, -0.3, 0.0)
        with self.fakes.locked():
            sim, i = self._sim()
            sim.set_pose(i, *pose)
        self.start = pose

    def tone(self, band, text):
        """Without the kit's --emitter: the operator makes the emitter (the
        world's second robot, also the calibration image) play `band`."""
        self.log.append(("tone", band))
        with self.fakes.locked():
            sim, _ = self._sim()
            sim.host_send(1, procedures.protocol.tone(band))

    def measure_move(self, placement, text):
        with self.fakes.locked():
            sim, i = self._sim()
            x, y, th = (float(v) for v in sim.robots.pose[i])
        x0, y0, th0 = self.start
        dx, dy = x - x0, y - y0
        fwd = dx * math.cos(th0) + dy * math.sin(th0)
        left = -dx * math.sin(th0) + dy * math.cos(th0)
        turned = math.degrees(th - th0)
        while turned - 0.0 > 180:
            turned -= 360
        while turned < -180:
            turned += 360
        # A turn in place of more than half a revolution: the operator counts it whole.
        if placement.left == -placement.right and abs(turned) > 1e-9:
            expected = 1 if placement.right > 0 else -1
            while turned * expected < 0:
                turned += 360 * expected
        return (fwd * 1000 + self.rng.gauss(0, self.ruler_mm), left * 1000 + self.rng.gauss(0, self.ruler_mm),
                turned + self.rng.gauss(0, self.protractor_deg))

    def progress(self, text):
        pass


def emitter_id(robot_id: int) -> int:
    """The emitter's id beside robot `robot_id`."""
    return robot_id + 1 if robot_id < 0xFFFE else robot_id - 1


def start(robot_id: int, truth: dict, directory: str | Path, speed: float = 200.0, platform: str = "host") -> tuple:
    """Starts the fake robot in its world, and the emitter (the world's
    second robot, on the calibration image too, id emitter_id(robot_id))
    on a port of its own: (fakes, link path, world file); the emitter's
    port is fakes.links[1].  `platform`: the robot's calibration image as
    the host build, or its ELF on an emulated MCU (pil_avr, pil_m4: the
    processor-in-the-loop robot; the emitter is host-built)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    world_file = directory / "world.yaml"
    world_file.write_text(yaml.safe_dump(world(robot_id, truth), sort_keys=False), encoding="utf-8")
    fakes = FakeEpucks(2, directory, images=["calib", "calib"], ids=[robot_id, emitter_id(robot_id)],
                       world=str(world_file), speed=speed, platform=platform, shared_world=True)
    fakes.start()
    return fakes, fakes.links[0], world_file


__all__ = ["SimOperator", "emitter_id", "perturbed", "start", "world", "tempfile"]
