"""Shared by the telemetry tools' tests."""
import ctypes
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

HERE = Path(__file__).resolve().parent
TOOLS = HERE.parent
ROOT = TOOLS.parents[1]
sys.path.insert(0, str(TOOLS))

import common  # noqa: E402

PYTHON = sys.executable
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
FRAME_SO = Path(os.environ.get("TELEMETRY_FRAME_SO", ROOT / "build" / "telemetry" / "libtelemetry_frame.so"))
if not FRAME_SO.is_absolute():
    FRAME_SO = ROOT / FRAME_SO


def c_encoder():
    """firmware/telemetry/telemetry_frame.c through ctypes (built by the make target)."""
    if not FRAME_SO.exists():
        raise unittest.SkipTest(f"{FRAME_SO} not built (make telemetry-tests builds it)")
    lib = ctypes.CDLL(str(FRAME_SO))
    lib.telemetry_frame_encode.restype = ctypes.c_uint16
    lib.telemetry_frame_encode.argtypes = [ctypes.c_char_p, ctypes.c_uint16, ctypes.c_uint8, ctypes.c_uint16,
                                           ctypes.c_uint16, ctypes.c_char_p, ctypes.c_uint16]
    lib.telemetry_crc16.restype = ctypes.c_uint16
    lib.telemetry_crc16.argtypes = [ctypes.c_uint16, ctypes.c_char_p, ctypes.c_uint16]
    lib.telemetry_cobs_encode.restype = ctypes.c_uint16
    lib.telemetry_cobs_encode.argtypes = [ctypes.c_char_p, ctypes.c_uint16, ctypes.c_char_p, ctypes.c_uint16]

    def frame(channel, robot_id, seq, payload):
        out = ctypes.create_string_buffer(300)
        n = lib.telemetry_frame_encode(out, 300, channel, robot_id, seq, bytes(payload), len(payload))
        return out.raw[:n]
    frame.lib = lib
    return frame


def robot_state(robot_id=0, state="search", oae=0, **fields):
    m = common.type_class("robot_state_t")()
    m.robot_id = robot_id
    m.controller = "forager"
    m.state = state
    m.task_state = ord("S")
    m.policy = "drtm"
    m.oae_count = oae
    m.carried_item = -2
    for k, v in fields.items():
        setattr(m, k, v)
    return m


def event(robot_id=0, kind=1, value=0, detail=""):
    e = common.type_class("event_t")()
    e.robot_id = robot_id
    e.kind = kind
    e.value = value
    e.detail = detail
    return e


def run_sim(out_dir, *args):
    if not SWARMSIM.exists():
        raise unittest.SkipTest(f"{SWARMSIM} not built")
    r = subprocess.run([str(SWARMSIM), *args, "--out", str(out_dir), "--quiet"], cwd=ROOT,
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError(f"swarmsim failed ({r.returncode}): {r.stderr}")
    return r


def tool(name, *args, check=True, timeout=120):
    r = subprocess.run([PYTHON, str(TOOLS / name), *map(str, args)], cwd=ROOT, capture_output=True,
                       text=True, timeout=timeout)
    if check and r.returncode != 0:
        raise AssertionError(f"{name} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


class TempDir(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="telemetry_test_")
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()
