"""Shared by the telemetry tools' tests: the simulator and the C encoder
(env SWARMSIM, TELEMETRY_FRAME_SO), hand-built messages and logs, running a
tool as `python -m swarmtools.telemetry.<tool>`."""
import ctypes
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

import swarmlcm

from swarmtools.telemetry import common

ROOT = Path(__file__).resolve().parents[3]
PYTHON = sys.executable
SWARMSIM = Path(os.environ.get("SWARMSIM", ROOT / "build" / "swarmsim"))
if not SWARMSIM.is_absolute():
    SWARMSIM = ROOT / SWARMSIM
FRAME_SO = Path(os.environ.get("TELEMETRY_FRAME_SO", ROOT / "build" / "telemetry" / "libtelemetry_frame.so"))
if not FRAME_SO.is_absolute():
    FRAME_SO = ROOT / FRAME_SO
SCENARIOS = ROOT / "sim_host" / "scenarios"
#: Seconds a test waits for something that takes well under one: only a
#: hang reaches it (a loaded machine only makes the wait longer).
LONG = 300


def default_sigint():
    """For a child that a test stops with SIGINT (preexec_fn): SIGINT at its
    default.  A test runner started in the background (`make test &`, a CI
    job) passes on an ignored SIGINT, which the tools rightly keep ignored
    (a shell's background job is not for Ctrl-C): such a child would never
    stop."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def wait_for(check, what, timeout=LONG, every=0.02):
    """Polls check() until it gives something true (and returns it);
    fails naming `what`."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        got = check()
        if got:
            return got
        time.sleep(every)
    raise AssertionError(f"timed out after {timeout:g} s waiting for {what}")


def c_encoder():
    """firmware/telemetry/telemetry_frame.c through ctypes (built by the make target)."""
    if not FRAME_SO.exists():
        raise unittest.SkipTest(f"{FRAME_SO} not built (make python-tests builds it)")
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


def robot_state(robot_id=0, state="search", controller="sorter", values=(), utime=0, run=0, **fields):
    """A robot_state_t as a robot sends it (no pose, sensors not read)."""
    m = swarmlcm.robot_state_t()
    m.version = m.VERSION
    m.utime = utime
    m.run = run
    m.robot_id = robot_id
    m.controller = controller
    m.state = state
    m.ir_max = m.ambient_min = -1
    m.ir_max_index = m.blobs = -1
    m.values = [float(v) for v in values]
    m.n_values = len(m.values)
    for k, v in fields.items():
        setattr(m, k, v)
    return m


def event(robot_id=0, kind="oae", value=0, detail="", utime=0, run=0):
    e = swarmlcm.event_t()
    e.version = e.VERSION
    e.utime = utime
    e.run = run
    e.robot_id = robot_id
    e.kind = kind
    e.value = value
    e.detail = detail
    return e


def schema(name, names, kind="controller", units=None, counters=None, first=0, total=None, utime=0, run=0):
    """A schema_t: the whole schema, or with `first` and `total` one piece
    of it (as a robot sends it)."""
    m = swarmlcm.schema_t()
    m.version = m.VERSION
    m.utime = utime
    m.run = run
    m.kind = kind
    m.name = name
    m.names = list(names)
    m.n = len(m.names)
    m.first = first
    m.total = m.n if total is None else total
    m.units = list(units) if units is not None else [""] * m.n
    m.counters = list(counters) if counters is not None else [0] * m.n
    m.docs = [""] * m.n
    return m


def swarm_state(step, values, states=(), utime=None, run=0, robots=0):
    m = swarmlcm.swarm_state_t()
    m.version = m.VERSION
    m.utime = step * 100000 if utime is None else utime
    m.run = run
    m.step = step
    m.robots = robots
    m.state_names = [n for n, _ in states]
    m.state_counts = [c for _, c in states]
    m.n_states = len(m.state_names)
    m.values = [float(v) for v in values]
    m.n_values = len(m.values)
    return m


def write_log(path, events):
    """An LCM log of (utime, channel, message or bytes) events."""
    lcm = common.lcm_module()
    log = lcm.EventLog(str(path), "w", overwrite=True)
    for utime, channel, msg in events:
        log.write_event(utime, channel, msg if isinstance(msg, (bytes, bytearray)) else msg.encode())
    log.close()
    return path


def raw_events(path):
    """(channel, bytes) of each event of a log, undecoded."""
    return [(ev.channel, bytes(ev.data)) for ev in common.lcm_module().EventLog(str(path), "r")]


def read_log(path):
    """(channel, decoded message) of each event of a log."""
    return [(ch, common.decode(data, ch)) for ch, data in raw_events(path)]


def monitor_of(path):
    """A monitor Model (clock at 0) fed every event of a log."""
    from swarmtools.telemetry import monitor
    m = monitor.Model(clock=lambda: 0.0)
    for ch, data in raw_events(path):
        m.add(ch, data)
    return m


def run_sim(out_dir, *args):
    if not SWARMSIM.exists():
        raise unittest.SkipTest(f"{SWARMSIM} not built")
    r = subprocess.run([str(SWARMSIM), *map(str, args), "--out", str(out_dir), "--quiet"], cwd=ROOT,
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError(f"swarmsim failed ({r.returncode}): {r.stderr}")
    return r


def tool(name, *args, check=True, timeout=LONG):
    """Runs python -m swarmtools.telemetry.<name> with `args`."""
    r = subprocess.run([PYTHON, "-m", f"swarmtools.telemetry.{name}", *map(str, args)], cwd=ROOT,
                       capture_output=True, text=True, timeout=timeout)
    if check and r.returncode != 0:
        raise AssertionError(f"{name} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def has_matplotlib():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


class TempDir(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="telemetry_test_")
        self.tmp = Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()
