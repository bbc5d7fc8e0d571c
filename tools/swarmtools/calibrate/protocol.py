"""The calibration image's side of the link (firmware/calib/calib.h and
calib_msg.h): the host's commands as bytes, the robot's windows of readings
as they come in its robot_state_t messages."""

from __future__ import annotations

import struct
from dataclasses import dataclass

CONTROLLER = "calib"
CHANNELS = 8
#: Values per robot_state_t: mean0..7, var0..7 (calib_def.c's observables).
N_VALUES = 2 * CHANNELS

#: The state a stream reports once its windows are valid, per command letter.
STREAM_STATES = {b"P": "prox", b"A": "ambient", b"M": "mic", b"C": "camera", b"F": "frame"}
SETTLE = "settle"
DRIVE, DRIVEN, IDLE, NO_SOUND, TONE = "drive", "driven", "idle", "no_sound", "tone"
NO_FRAME = "no_frame"


def prox() -> bytes:
    return b"P"


def ambient() -> bytes:
    return b"A"


def mic(band: int) -> bytes:
    return b"M" + bytes([band])


def camera(colour: int) -> bytes:
    return b"C" + bytes([colour])


def frame(colour: int) -> bytes:
    """The latest frame's pixel statistics: every pixel's (colour 0) or
    those the detector gives `colour`: pixels, R, G, B mean, R, G, B sd."""
    return b"F" + bytes([colour])


def stop() -> bytes:
    return b"S"


def tone(band: int) -> bytes:
    return b"T" + bytes([band])


def drive(left: int, right: int, periods: int) -> bytes:
    """Wheel speeds (steps/s) for exactly `periods` control periods."""
    return b"D" + struct.pack(">hhH", left, right, periods)


@dataclass(frozen=True)
class Window:
    """One window of readings (calib.h): the state it was taken in, the
    robot's clock, the channels' means and variances."""
    state: str
    utime: int
    robot_id: int
    mean: tuple
    var: tuple


def window_of(msg) -> Window | None:
    """The window a robot_state_t carries, or None when it is not the
    calibration image's."""
    if msg.controller != CONTROLLER or msg.n_values != N_VALUES:
        return None
    v = tuple(float(x) for x in msg.values)
    return Window(msg.state, int(msg.utime), int(msg.robot_id), v[:CHANNELS], v[CHANNELS:])
