"""The procedures an owner goes through, step by step: what to set up, where
to put the robot, what the robot streams meanwhile.  Each step is a
Placement; running a procedure (run) asks the operator (operator.py) to make
each placement, has the robot stream its readings or drive, and records
what came back (a Recording, saved as JSON by record.py).

Distances are what a ruler gives: the gap between the robot's body and the
surface (IR) or the lamp's foot (ambient), in mm.  The models' distances
follow from hal/units.h (geometry.py).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

from . import geometry, protocol
from .link import RobotLink

#: Body-to-wall gaps of the IR procedure, mm (the table's points at 5..60
#: mm from the sensor, less the 2 mm by which the body stands in front of it).
IR_GAPS_MM = (3, 8, 13, 18, 28, 38, 58)
#: Body-to-lamp-foot distances of the ambient procedure, mm.
AMBIENT_DISTANCES_MM = (150, 250, 400, 600, 900)
#: Wheel runs: (left, right steps/s, control periods).  Straight runs at
#: three speeds and turns in place both ways.
WHEEL_RUNS = ((300, 300, 30), (600, 600, 20), (900, 900, 15), (400, -400, 15), (-400, 400, 15))

#: The camera procedure's card: a red cylinder this wide (a tin), and the
#: searches for where the camera stops seeing it (bisections).
CARD_DIAMETER_MM = 60.0
CARD_COLOUR = 1                       # hal_colour_t red
REACH_SEARCH_MM = (50.0, 1800.0)      # ahead: its near side from the body's front
FOV_SEARCH_DEG = (0.0, 60.0)          # to the left: its centre's bearing from the lens
FOV_DISTANCE_MM = 200.0
CAMERA_BISECTIONS = 7

#: The microphones' procedure: the listener this far from the emitter
#: (centre to centre, mm) while it plays each band, then once while it is
#: silent (the ambient term).
SOUND_DISTANCES_MM = (100, 200, 350, 550, 800, 1100, 1500)
#: Windows per placement (eq 4's 6 % noise per reading needs more than the others).
SOUND_WINDOWS = 3
SOUND_SILENT_MM = 200
SOUND_BANDS = (1, 2, 3)
#: hal/sound_bands.h's tones, Hz (for the operator's prompts).
BAND_HZ = {1: 1160, 2: 1960, 3: 2720}

#: The colours procedure: a card of each class the blob detector knows
#: (hal/blob_detect.h: red, green, blue) and a grey one (its "none", the
#: simulator's obstacle grey), each filling the camera's view at these
#: distances from the robot's front, mm.
COLOUR_CARDS = {0: "grey", 1: "red", 2: "green", 3: "blue"}
COLOUR_DISTANCES_MM = (30, 60)

PROCEDURES = ("ir", "ambient", "wheels", "camera", "colours", "sound")


@dataclass
class Setup:
    """What the owner sets up before a procedure's steps (lamp height and
    intensity for ambient light)."""
    lamp_height_mm: float = 100.0
    lamp_intensity: float = 1.0      # the lab's lamp is the unit: the scenario's lamp has intensity 1
    period_ms: int = 100             # the image's control period
    sound_a0: float = 299.18         # the emitter's level at 0 m (sound.a0 of your scenarios): gains are against it
    windows: int = 2                 # windows recorded per placement


@dataclass
class Placement:
    procedure: str
    sensor: int | None = None        # ir / ambient: the sensor facing the wall or the lamp
    gap_mm: float | None = None      # ir: body to wall; None: nothing within reach
    distance_mm: float | None = None  # ambient: body to the lamp's foot
    bearing_deg: float | None = None  # camera: the card's centre from the lens, CCW +
    colour: int | None = None        # colours: the card (COLOUR_CARDS)
    stats: int = 0                   # colours: the frame's pixels counted (0 all, else the detector's class)
    band: int = 0                    # sound: the band listened to
    tone: bool = False               # sound: the emitter plays it (else it is silent)
    left: int = 0                    # wheels
    right: int = 0
    periods: int = 0

    def describe(self) -> str:
        b = geometry.ir_bearings_deg()
        if self.procedure == "ir" and self.gap_mm is None:
            return "the robot in open space: nothing within 15 cm of it (the IR sensors' offsets)"
        if self.procedure == "ir":
            return (f"IR{self.sensor} (at {b[self.sensor]:+d} deg) facing a flat white wall square on, "
                    f"the body {self.gap_mm:g} mm from it")
        if self.procedure == "sound":
            return (f"the robot {self.distance_mm:g} mm (centre to centre) from the emitter, which "
                    + (f"plays band {self.band} ({BAND_HZ[self.band]} Hz)" if self.tone else "is silent"))
        if self.procedure == "colours":
            return (f"the {COLOUR_CARDS[self.colour]} card upright, square on, {self.distance_mm:g} mm from the "
                    f"robot's front, filling its camera's view")
        if self.procedure == "camera":
            where = "straight ahead" if not self.bearing_deg else f"{self.bearing_deg:.1f} deg to the left"
            return (f"the red card ({CARD_DIAMETER_MM:g} mm across) {where}, its near side {self.distance_mm:g} mm "
                    f"from the robot's front")
        if self.procedure == "ambient":
            return (f"IR{self.sensor} (at {b[self.sensor]:+d} deg) facing the lamp, the body "
                    f"{self.distance_mm:g} mm from the lamp's foot")
        return (f"the robot on a start mark with room around it; it drives left {self.left}, right "
                f"{self.right} steps/s for {self.periods} periods")


@dataclass
class Step:
    """A placement and what was recorded at it."""
    placement: Placement
    windows: list = field(default_factory=list)     # [(mean[8], var[8]), ...]
    moved: tuple | None = None                      # wheels: (dx_mm, dy_mm, dtheta_deg) measured
    steps: tuple | None = None                      # wheels: (left, right) counted

    def as_dict(self) -> dict:
        return {"placement": asdict(self.placement), "windows": [list(map(list, w)) for w in self.windows],
                "moved": list(self.moved) if self.moved is not None else None,
                "steps": list(self.steps) if self.steps is not None else None}

    @classmethod
    def from_dict(cls, d: dict) -> Step:
        w = [(tuple(m), tuple(v)) for m, v in d.get("windows") or []]
        return cls(Placement(**d["placement"]), w, tuple(d["moved"]) if d.get("moved") is not None else None,
                   tuple(d["steps"]) if d.get("steps") is not None else None)


SETUP_TEXT = {
    "ir": "IR proximity: a flat, white, matt wall (a sheet of white card on a box), a ruler; room lights "
          "as in your experiments; keep other robots and hands away from the sensors.",
    "ambient": "Ambient light: a dark room with one lamp (the lamp your scenarios model, intensity 1) at "
               "{h:g} mm above the table, a ruler or tape from the lamp's foot.",
    "camera": "Camera: a red cylinder (a can) {d:g} mm across on a plain, uncoloured floor, nothing else "
              "coloured in view, a ruler and a protractor sheet under the robot.",
    "colours": "Colour cards: four matt sheets of card at least 150 x 100 mm, red, green, blue (the blob "
               "detector's classes) and a mid grey (the simulator's obstacle grey, its reference of white "
               "balance); the room's light as in your experiments, no lamp shining into the lens. You will "
               "hold each upright, square on in front of the robot, filling its camera's view.",
    "sound": "Microphones: a quiet room; a second e-puck (or a PC speaker at the e-puck's loudness) as the "
             "emitter, on the table; you will make it play each band in turn, or stay silent.",
    "wheels": "Wheels: a flat floor with 40 cm of room around a start mark, a ruler (or the tracker) to "
              "measure where the robot ends: forward and left of its start in mm, and how far it turned "
              "(degrees, counter-clockwise positive).",
}


def placements(procedure: str, sensors=range(8)) -> list[Placement]:
    if procedure == "ir":
        out = [Placement("ir")]
        out += [Placement("ir", sensor=s, gap_mm=g) for s in sensors for g in IR_GAPS_MM]
        return out
    if procedure == "ambient":
        return [Placement("ambient", sensor=s, distance_mm=r) for s in (0, 3) for r in AMBIENT_DISTANCES_MM]
    if procedure == "wheels":
        return [Placement("wheels", left=left, right=right, periods=n) for left, right, n in WHEEL_RUNS]
    if procedure == "camera":
        return []                    # adaptive: run_camera chooses each step from the last
    if procedure == "colours":
        out = []
        for c in COLOUR_CARDS:
            for d in COLOUR_DISTANCES_MM:
                out.append(Placement("colours", colour=c, distance_mm=d, stats=0))
                if c:
                    out.append(Placement("colours", colour=c, distance_mm=d, stats=c))
        return out
    if procedure == "sound":
        out = []
        for b in SOUND_BANDS:
            out += [Placement("sound", distance_mm=d, band=b, tone=True) for d in SOUND_DISTANCES_MM]
            out.append(Placement("sound", distance_mm=SOUND_SILENT_MM, band=b, tone=False))
        return out

    raise ValueError(f"no procedure {procedure!r} (procedures: {', '.join(PROCEDURES)})")


def run(procedure: str, link: RobotLink, operator, setup: Setup, steps=None, emitter: RobotLink | None = None
        ) -> list[Step]:
    """Goes through a procedure's placements with the operator and the
    robot; the steps recorded.  `emitter`: a second robot on the
    calibration image that plays the microphone procedure's tones as the
    kit tells it (else the operator makes the emitter play)."""

    def play(band, what):
        text = f"Make the emitter play band {band} ({BAND_HZ[band]} Hz)." if band else "Make the emitter silent."
        if emitter is None:
            operator.tone(band, text)
        else:
            emitter.tone(band, f"the emitter (robot {emitter.robot_id}) for {what}")
            operator.progress(f"the emitter (robot {emitter.robot_id}) plays band {band}" if band
                              else f"the emitter (robot {emitter.robot_id}) is silent")
    operator.setup(procedure, SETUP_TEXT[procedure].format(h=setup.lamp_height_mm, d=CARD_DIAMETER_MM))
    if procedure == "camera":
        out = run_camera(link, operator, setup)
        link.send(protocol.stop())
        return out
    steps = steps if steps is not None else placements(procedure)
    out = []
    playing = None
    for k, p in enumerate(steps):
        what = f"{procedure} step {k + 1}/{len(steps)} ({p.describe()})"
        if procedure == "sound" and playing != (p.band if p.tone else 0):
            playing = p.band if p.tone else 0
            play(playing, what)
        if procedure == "colours" and k and (p.colour, p.distance_mm) == (steps[k - 1].colour,
                                                                          steps[k - 1].distance_mm):
            operator.progress(f"colours: the {COLOUR_CARDS[p.colour]} card's pixels the detector calls "
                              f"{COLOUR_CARDS[p.stats]}: keep it there")
        else:
            operator.place(p, f"[{k + 1}/{len(steps)}] Put {p.describe()}.")
        if procedure == "colours":
            ws = link.stream(protocol.frame(p.stats), setup.windows, what)
            out.append(Step(p, [(w.mean, w.var) for w in ws]))
        elif procedure == "sound":
            ws = link.stream(protocol.mic(p.band), max(setup.windows, SOUND_WINDOWS), what)
            out.append(Step(p, [(w.mean, w.var) for w in ws]))
        elif procedure in ("ir", "ambient"):
            cmd = protocol.prox() if procedure == "ir" else protocol.ambient()
            ws = link.stream(cmd, setup.windows, what)
            out.append(Step(p, [(w.mean, w.var) for w in ws]))
        else:
            w = link.drive(p.left, p.right, p.periods, what)
            moved = operator.measure_move(p, f"[{k + 1}/{len(steps)}] Where did it end, from its start mark? "
                                             f"forward mm, left mm, turned deg (CCW +)")
            out.append(Step(p, moved=tuple(float(x) for x in moved), steps=(w.mean[0], w.mean[1])))
        operator.progress(f"{procedure}: {k + 1}/{len(steps)} done")
    if procedure == "sound" and playing:
        play(0, f"{procedure}: the end")
    link.send(protocol.stop())
    return out


def seen(step: Step) -> bool:
    """The card was in view in at least half the window's frames."""
    return sum(w[0][2] for w in step.windows) / len(step.windows) >= 0.5


def run_camera(link: RobotLink, operator, setup: Setup) -> list[Step]:
    """Two bisections: how far ahead the card stays in view (the reach),
    and how far to the left at FOV_DISTANCE_MM (the field of view)."""
    out = []
    total = 2 * CAMERA_BISECTIONS

    def look(p):
        k = len(out) + 1
        operator.place(p, f"[{k}/{total}] Put {p.describe()}.")
        ws = link.stream(protocol.camera(CARD_COLOUR), setup.windows,
                         f"camera step {k}/{total} ({p.describe()})")
        out.append(Step(p, [(w.mean, w.var) for w in ws]))
        operator.progress(f"camera: {k}/{total} done")
        return seen(out[-1])

    lo, hi = REACH_SEARCH_MM
    for _ in range(CAMERA_BISECTIONS):
        mid = round(0.5 * (lo + hi))
        if look(Placement("camera", distance_mm=mid, bearing_deg=0.0)):
            lo = mid
        else:
            hi = mid
    lo, hi = FOV_SEARCH_DEG
    for _ in range(CAMERA_BISECTIONS):
        mid = round(0.5 * (lo + hi), 2)
        if look(Placement("camera", distance_mm=FOV_DISTANCE_MM, bearing_deg=mid)):
            lo = mid
        else:
            hi = mid
    return out


def camera_pose_for(p: Placement) -> tuple:
    """(x, y, heading) of the robot's centre with the card's centre at the
    origin: the lens (the body's front) looks along +x at heading 0, the
    card at the placement's distance and bearing from it."""
    r_card = CARD_DIAMETER_MM / 2000.0
    dc = p.distance_mm / 1000.0 + r_card           # lens to the card's centre (bearing 0: exactly)
    b = math.radians(p.bearing_deg or 0.0)
    lens = (-dc * math.cos(b), -dc * math.sin(b))
    return (lens[0] - geometry.body_radius_m(), lens[1], 0.0)


# ---------------------------------------------------------------- geometry of a placement

def ir_distance_m(p: Placement) -> float:
    """From the sensor to the wall: the gap plus the body's lead on the sensor."""
    return p.gap_mm / 1000.0 + geometry.body_radius_m() - geometry.ir_mount_m()


def robot_pose_for(p: Placement) -> tuple:
    """(x, y, heading) of the robot's centre in the placement's own frame:
    the wall's face on x = 0 (IR, the wall beyond +x), the lamp's foot at
    the origin (ambient); heading so that the placement's sensor looks
    along +x."""
    b = math.radians(geometry.ir_bearings_deg()[p.sensor])
    if p.procedure == "ir":
        return (-(ir_distance_m(p) + geometry.ir_mount_m()), 0.0, -b)
    return (-(p.distance_mm / 1000.0 + geometry.body_radius_m()), 0.0, -b)


def irradiance(p: Placement, setup: Setup) -> list[float]:
    """Each sensor's irradiance from the lamp at an ambient placement, in
    the ambient model's terms (sim_host/models/ir/ir.c): intensity x
    cos(incidence) / d^2, 0 for a sensor looking away."""
    x0, y0, th = robot_pose_for(p)
    h = setup.lamp_height_mm / 1000.0 - geometry.ir_height_m()
    out = []
    for deg in geometry.ir_bearings_deg():
        a = th + math.radians(deg)
        ax, ay = math.cos(a), math.sin(a)
        px, py = x0 + geometry.ir_mount_m() * ax, y0 + geometry.ir_mount_m() * ay
        hx, hy = -px, -py
        d2 = hx * hx + hy * hy + h * h
        along = (hx * ax + hy * ay) / math.sqrt(d2)
        out.append(setup.lamp_intensity * along / d2 if along > 0 else 0.0)
    return out


def colour_pose_for(p: Placement) -> tuple:
    """(x, y, heading) of the robot's centre with the card's face at x = 0
    (the card beyond +x), the robot looking at it."""
    return (-(p.distance_mm / 1000.0 + geometry.body_radius_m()), 0.0, 0.0)
