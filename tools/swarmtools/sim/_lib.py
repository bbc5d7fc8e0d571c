"""The simulator's public C API (sim_host/include/swarmsim/) through ctypes:
the shared library build/libswarmsim.so, the structs the binding reads and
every function's prototype.  Nothing here is a second API: each name is a C
function of sim.h, scenario.h, metrics.h or command.h, documented there.

The library is found at $SWARMSIM_LIB, else at build/libswarmsim.so of the
checkout this package lives in (`make` builds it).
"""

from __future__ import annotations

import ctypes
import os
from ctypes import (
    POINTER,
    Structure,
    c_char_p,
    c_double,
    c_float,
    c_int,
    c_int16,
    c_int32,
    c_size_t,
    c_uint,
    c_uint8,
    c_uint16,
    c_uint32,
    c_uint64,
    c_void_p,
)
from pathlib import Path

#: The checkout this package belongs to (tools/swarmtools/sim/ -> the root).
ROOT = Path(__file__).resolve().parents[3]
SIM_ERR_MAX = 512
METRICS_MAX = 64
HAL_HOST_MSG_MAX = 64


class LibraryMissing(ImportError):
    """The shared library is not built (or $SWARMSIM_LIB names no file)."""


class Field(Structure):
    """sim_field_t: a per-robot value where it lives."""
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("doc", c_char_p), ("type", c_int),
                ("base", c_void_p), ("stride", c_size_t), ("count", c_uint32)]


class MetricList(Structure):
    """metric_list_t."""
    _fields_ = [("count", c_uint), ("name", c_char_p * METRICS_MAX), ("unit", c_char_p * METRICS_MAX),
                ("doc", c_char_p * METRICS_MAX), ("value", c_double * METRICS_MAX)]


class Override(Structure):
    """scenario_override_t."""
    _fields_ = [("text", c_char_p)]


class EventRec(Structure):
    """sim_event_rec_t."""
    _fields_ = [("robot", c_uint32), ("kind", c_char_p), ("detail", c_char_p), ("value", c_int32)]


class Pose(Structure):
    """hal_pose_t."""
    _fields_ = [("x_mm", c_int32), ("y_mm", c_int32), ("heading_mrad", c_int16), ("age_ms", c_uint16)]


#: sim_field_type_t -> numpy type string.
FIELD_TYPES = ("|u1", "|i1", "<u2", "<i2", "<u4", "<i4", "<u8", "<f4", "<f8")

_PROTOTYPES = {
    # scenario.h
    "scenario_create": (c_void_p, [c_char_p, POINTER(Override), c_size_t, c_char_p]),
    "scenario_destroy": (None, [c_void_p]),
    "scenario_steps": (c_uint64, [c_void_p]),
    "scenario_seed": (c_uint64, [c_void_p]),
    "scenario_robot_count": (c_uint32, [c_void_p]),
    # sim.h
    "sim_create_threads": (c_void_p, [c_void_p, c_uint64, c_uint32, c_char_p]),
    "sim_destroy": (None, [c_void_p]),
    "sim_step": (None, [c_void_p]),
    "sim_step_n": (c_uint64, [c_void_p, c_uint64]),
    "sim_done": (c_int, [c_void_p]),
    "sim_error": (c_char_p, [c_void_p]),
    "sim_step_count": (c_uint64, [c_void_p]),
    "sim_time_s": (c_double, [c_void_p]),
    "sim_seed": (c_uint64, [c_void_p]),
    "sim_state_hash": (c_uint64, [c_void_p]),
    "sim_robot_count": (c_uint32, [c_void_p]),
    "sim_group_count": (c_uint32, [c_void_p]),
    "sim_group_name": (c_char_p, [c_void_p, c_uint32]),
    "sim_group_robots": (None, [c_void_p, c_uint32, POINTER(c_uint32), POINTER(c_uint32)]),
    "sim_group_observable_at": (c_int, [c_void_p, c_uint32, c_uint32, POINTER(Field), POINTER(c_float)]),
    "sim_robot_def": (c_void_p, [c_void_p, c_uint32]),
    "sim_robot_state_names": (None, [c_void_p, c_uint32, c_uint32, POINTER(c_void_p)]),
    "sim_field_at": (c_int, [c_void_p, c_uint32, POINTER(Field)]),
    "sim_set_robot_pose": (None, [c_void_p, c_uint32, c_double, c_double, c_double]),
    "sim_robot_pose": (None, [c_void_p, c_uint32, POINTER(c_double), POINTER(c_double), POINTER(c_double)]),
    "sim_robot_id": (c_uint16, [c_void_p, c_uint32]),
    "sim_set_robot_id": (None, [c_void_p, c_uint32, c_uint16]),
    "sim_robot_uart": (c_uint32, [c_void_p, c_uint32, POINTER(POINTER(c_uint8))]),
    "sim_host_send": (c_int, [c_void_p, c_uint32, c_char_p, c_uint8]),
    "sim_host_pose": (c_int, [c_void_p, c_uint32, POINTER(Pose)]),
    "sim_host_dropped": (c_uint32, [c_void_p, c_uint32]),
    "sim_events": (c_uint32, [c_void_p, POINTER(POINTER(EventRec))]),
    "sim_summary_json": (c_void_p, [c_void_p, c_char_p, c_char_p, POINTER(Override), c_size_t, c_char_p]),
    # metrics.h
    "metrics_sample": (None, [c_void_p, POINTER(MetricList)]),
    "metrics_final": (None, [c_void_p, POINTER(MetricList)]),
    # command.h
    "swarmsim_command": (c_int, [c_int, POINTER(c_char_p), c_char_p, POINTER(c_int)]),
    "swarmsim_code_version": (c_char_p, []),
}

_lib = None


def library_path() -> Path:
    """Where the shared library is looked for."""
    env = os.environ.get("SWARMSIM_LIB")
    return Path(env) if env else ROOT / "build" / "libswarmsim.so"


def lib():
    """The loaded library, its prototypes set (loaded once per process)."""
    global _lib
    if _lib is not None:
        return _lib
    path = library_path()
    if not path.is_file():
        why = "$SWARMSIM_LIB names no such file" if os.environ.get("SWARMSIM_LIB") else "it is not built"
        raise LibraryMissing(f"the simulator library {path}: {why}: build it with `make build/libswarmsim.so` "
                             f"in {ROOT} (`make` builds it too), or set SWARMSIM_LIB to a built libswarmsim.so")
    loaded = ctypes.CDLL(str(path))
    libc = ctypes.CDLL(None)
    for name, (restype, argtypes) in _PROTOTYPES.items():
        fn = getattr(loaded, name)
        fn.restype = restype
        fn.argtypes = argtypes
    loaded.free_text = libc.free
    loaded.free_text.restype = None
    loaded.free_text.argtypes = [c_void_p]
    _lib = loaded
    return loaded


def take_text(pointer) -> str:
    """A malloc'd C string as str; frees it."""
    try:
        return ctypes.string_at(pointer).decode("utf-8", errors="replace")
    finally:
        lib().free_text(pointer)


def overrides_array(texts: list[bytes]):
    """A scenario_override_t array over `texts` (kept alive by the caller)."""
    arr = (Override * max(1, len(texts)))()
    for i, t in enumerate(texts):
        arr[i].text = t
    return arr


def err_buffer():
    return ctypes.create_string_buffer(SIM_ERR_MAX)


def controller_name(def_pointer) -> str:
    """The name of a controller_def_t (its first member, `const char *name`)."""
    return ctypes.cast(def_pointer, POINTER(c_char_p))[0].decode()


__all__ = ["FIELD_TYPES", "Field", "LibraryMissing", "MetricList", "Pose", "ROOT", "lib", "library_path"]
