"""The e-puck facts the fits need, read from where they are written once:
hal/units.h (wheels, body, IR sensors' mount and bearings) and the
simulator's own IR curve (ir_curve of sim_host/models/ir/ir.h, through the
shared library)."""

from __future__ import annotations

import ctypes
import math
import re
from functools import cache

from ..sim import _lib

UNITS_H = _lib.ROOT / "hal" / "units.h"


@cache
def _units() -> dict:
    text = UNITS_H.read_text(encoding="utf-8")
    out = {name: int(v) for name, v in re.findall(r"#define (EPUCK_\w+_UM|EPUCK_STEPS_PER_REV) (\d+)L", text)}
    out.update({name: int(v) for name, v in re.findall(r"#define (EPUCK_CAMERA_\w+_PX) (\d+)u", text)})
    m = re.search(r"#define EPUCK_IR_BEARINGS\(X\) ((?:X\(-?\d+\) ?)+)", text)
    out["bearings"] = tuple(int(d) for d in re.findall(r"X\((-?\d+)\)", m.group(1)))
    return out


def step_m() -> float:
    """Wheel travel per motor step, m."""
    u = _units()
    return math.pi * u["EPUCK_WHEEL_DIAMETER_UM"] / 1e6 / u["EPUCK_STEPS_PER_REV"]


def axle_m() -> float:
    return _units()["EPUCK_AXLE_UM"] / 1e6


def body_radius_m() -> float:
    return _units()["EPUCK_BODY_DIAMETER_UM"] / 2e6


def ir_mount_m() -> float:
    return _units()["EPUCK_IR_MOUNT_RADIUS_UM"] / 1e6


def ir_height_m() -> float:
    return _units()["EPUCK_IR_HEIGHT_UM"] / 1e6


def camera_width_px() -> int:
    """The e-puck image's frame width, the camera model's columns."""
    return _units()["EPUCK_CAMERA_WIDTH_PX"]


def camera_height_px() -> int:
    """The e-puck image's frame height, rows."""
    return _units()["EPUCK_CAMERA_HEIGHT_PX"]


def ir_bearings_deg() -> tuple:
    return _units()["bearings"]


@cache
def _curve_fn():
    f = _lib.lib().ir_curve
    f.argtypes = [ctypes.c_float, ctypes.c_float]
    f.restype = ctypes.c_float
    return f


def ir_curve(d_m: float, range_m: float = 0.1) -> float:
    """The simulator's noise-free proximity at d_m from a surface, before a
    sensor's gain and offset."""
    return float(_curve_fn()(d_m, range_m))


RENDER_H = _lib.ROOT / "sim_host" / "core" / "render.h"


@cache
def obstacle_grey() -> tuple:
    """R, G, B (0..255) the simulator draws an obstacle without colour in
    (RENDER_RGB_OBJ_NONE): the colours procedure's grey card, the
    reference of the camera's colour response."""
    m = re.search(r"#define RENDER_RGB_OBJ_NONE\s+0x([0-9A-Fa-f]{6})u", RENDER_H.read_text(encoding="utf-8"))
    v = int(m.group(1), 16)
    return (v >> 16 & 0xFF, v >> 8 & 0xFF, v & 0xFF)
