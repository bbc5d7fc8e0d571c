"""One simulation run in this process: swarmtools.Sim.

    import swarmtools
    with swarmtools.Sim("sim_host/scenarios/foraging_base.yaml", seed=3,
                        overrides={"robots.0.count": 30}) as sim:
        sim.step(100)
        print(sim.time, sim.robots.x[:5], sim.robots.state[:5])
        print(sim.task_metrics()["food_collected"])

A thin layer over the simulator's public C API (sim_host/include/swarmsim/
sim.h, through ctypes): the run is the command line's, step for step, so
stepping it for the scenario's duration ends in the state hash swarmsim
prints (tools/tests/sim/ checks every shipped scenario's golden seed).

The robots' arrays are numpy views of the simulator's own memory (each
model's per-robot layout, sim_field): reading them copies nothing, and they
show the current step's values as the run goes on (``.copy()`` keeps a
snapshot).  They are read-only.  A view keeps the run's memory alive after
close(), until the last view is dropped.

Several simulations may live in one process, and different ones may be
stepped from different threads at once (ctypes lets go of the GIL in each
call); one simulation is stepped by one thread at a time.
"""

from __future__ import annotations

import ctypes
import json
import math
import re
import threading
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from . import _lib
from ._lib import Field, MetricList, Pose

OverridesLike = Mapping[str, Any] | Iterable[str] | None


class ScenarioError(ValueError):
    """The scenario (its file or an override) is wrong: the loader's
    message, and where it points.

    Attributes: ``file`` (the scenario file, or None for an override),
    ``line`` (1-based, or None), ``override`` (the "key=value" at fault, or
    None), ``key`` (the dotted key named, or None), ``reason`` (what is
    wrong)."""

    def __init__(self, message: str, file: str | None = None, line: int | None = None,
                 override: str | None = None, key: str | None = None, reason: str | None = None):
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.override = override
        self.key = key
        self.reason = reason if reason is not None else message


class SimError(RuntimeError):
    """A run that cannot be made (robots that cannot be placed) or that
    failed while stepping (a model's error, sim_error)."""


class Event(NamedTuple):
    """An event a robot had in the last step (sim_event_rec_t)."""
    robot: int
    kind: str
    detail: str
    value: int


def override_texts(overrides: OverridesLike) -> list[str]:
    """--set texts of `overrides`: a mapping {key: value} (a value other
    than str written as YAML: true/false, numbers as Python prints them,
    lists and dicts as flow YAML, None as null) or "key=value" strings."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{key}={_yaml_value(value)}" for key, value in overrides.items()]
    if isinstance(overrides, str):
        raise TypeError("overrides: a mapping {key: value} or a list of 'key=value' strings, not one string")
    texts = [str(t) for t in overrides]
    for t in texts:
        if "=" not in t:
            raise ScenarioError(f"override {t!r}: expected key=value", override=t)
    return texts


def _yaml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not math.isfinite(v):
            raise ScenarioError(f"override value {value!r}: not a finite number")
        return repr(v)
    if isinstance(value, (list, tuple, dict)):
        return json.dumps(value)   # JSON is flow YAML
    return str(value)


def parse_loader_error(message: str, path: str, overrides: list[str]) -> ScenarioError:
    """The loader's one line ("FILE:LINE: key: what", "--set K=V: key:
    what", "FILE: cannot open: ...") as a ScenarioError."""
    for text in overrides:
        head = f"--set {text}: "
        if message.startswith(head):
            rest = message[len(head):]
            key, sep, reason = rest.partition(": ")
            return ScenarioError(message, override=text, key=key if sep else None, reason=reason if sep else rest)
    m = re.match(r"^(?P<file>.*?):(?P<line>\d+): (?P<rest>.*)$", message)
    if m and (m.group("file") == path or not message.startswith(path + ":")):
        rest = m.group("rest")
        key, sep, reason = rest.partition(": ")
        if not sep or " " in key:
            key, reason = None, rest
        return ScenarioError(message, file=m.group("file"), line=int(m.group("line")), key=key, reason=reason)
    if message.startswith(path + ": "):
        return ScenarioError(message, file=path, reason=message[len(path) + 2:])
    return ScenarioError(message)


class _Handle:
    """Owns the C scenario and sim; frees them when the last reference goes
    (the Sim, or a numpy view of its memory)."""

    def __init__(self, scenario: int, sim: int | None = None):
        self.scenario = scenario
        self.sim = sim
        self.lock = threading.Lock()

    def __del__(self):
        lib = _lib._lib
        if lib is None:
            return
        if self.sim:
            lib.sim_destroy(self.sim)
            self.sim = None
        if self.scenario:
            lib.scenario_destroy(self.scenario)
            self.scenario = None


class _View:
    """An __array_interface__ over the simulator's memory that keeps its
    handle alive (numpy makes it the array's base)."""

    def __init__(self, handle: _Handle, address: int, shape: tuple, strides: tuple, typestr: str):
        self.handle = handle
        self.__array_interface__ = {"data": (address, True), "shape": shape, "strides": strides,
                                    "typestr": typestr, "version": 3}


class FieldInfo(NamedTuple):
    """A per-robot field of the run (sim_field_t): name, unit, doc, numpy
    dtype and values per robot."""
    name: str
    unit: str
    doc: str
    dtype: np.dtype
    count: int


class Observable(NamedTuple):
    """One value a group's controller shows (observable.h): the raw field
    over the group's robots (a view) and its scale; value = raw * scale."""
    name: str
    unit: str
    doc: str
    raw: np.ndarray
    scale: float

    @property
    def values(self) -> np.ndarray:
        """The values as telemetry reports them (float64)."""
        return self.raw.astype(np.float64) * self.scale


class Group:
    """One of the scenario's groups in the run: its robots' ids and its
    controller's observables (views over the controllers' own states)."""

    def __init__(self, sim: Sim, index: int):
        lib, h = _lib.lib(), sim._handle
        first, count = ctypes.c_uint32(), ctypes.c_uint32()
        lib.sim_group_robots(h.sim, index, ctypes.byref(first), ctypes.byref(count))
        self.index = index
        self.name: str = lib.sim_group_name(h.sim, index).decode()
        self.first: int = first.value
        self.count: int = count.value
        self.controller: str = (_lib.controller_name(lib.sim_robot_def(h.sim, self.first))
                                if self.count else "")
        self.observables: dict[str, Observable] = {}
        f, scale = Field(), ctypes.c_float()
        k = 0
        while lib.sim_group_observable_at(h.sim, index, k, ctypes.byref(f), ctypes.byref(scale)) == 0:
            raw = sim._array(f, self.count)
            self.observables[f.name.decode()] = Observable(f.name.decode(), f.unit.decode(), f.doc.decode(),
                                                           raw, float(scale.value))
            k += 1

    @property
    def ids(self) -> range:
        return range(self.first, self.first + self.count)

    def __repr__(self) -> str:
        return f"<Group {self.index} {self.name!r}: {self.count} x {self.controller}>"


class Robots:
    """Every robot of the run, as arrays indexed by robot id (0 .. n-1).

    ``x``, ``y`` (m), ``theta`` (rad, CCW from +x), ``leds``, ``group`` and
    every model's field (``robots["wheels.cmd_left"]``, ``robots.fields``
    lists them) are read-only views of the simulator's own memory.
    ``state`` (the controllers' state names) and ``observable(name)`` are
    computed in one C call or one numpy operation per group."""

    def __init__(self, sim: Sim):
        self._sim = sim
        self.count: int = sim.robot_count
        self._views: dict[str, np.ndarray] = {}
        self._info: dict[str, FieldInfo] = {}
        lib, f = _lib.lib(), Field()
        k = 0
        while lib.sim_field_at(sim._handle.sim, k, ctypes.byref(f)) == 0:
            name = f.name.decode()
            view = sim._array(f, self.count)
            self._views[name] = view
            self._info[name] = FieldInfo(name, f.unit.decode(), f.doc.decode(), view.dtype, f.count)
            k += 1
        self._names_buf = (ctypes.c_void_p * max(1, self.count))()
        self._state_text: dict[int, str] = {}

    @property
    def fields(self) -> dict[str, FieldInfo]:
        """Every field of this run, by name (a model off allocates none)."""
        return dict(self._info)

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._views[name]
        except KeyError:
            raise KeyError(f"no field {name!r} in this run; it has: {', '.join(self._views)}") from None

    def __contains__(self, name: str) -> bool:
        return name in self._views

    def __len__(self) -> int:
        return self.count

    @property
    def x(self) -> np.ndarray:
        return self._views["pose.x"]

    @property
    def y(self) -> np.ndarray:
        return self._views["pose.y"]

    @property
    def theta(self) -> np.ndarray:
        return self._views["pose.theta"]

    @property
    def pose(self) -> np.ndarray:
        """(n, 3) float64 copy: x, y (m), theta (rad)."""
        return np.column_stack([self.x, self.y, self.theta]).astype(np.float64)

    @property
    def leds(self) -> np.ndarray:
        return self._views["leds"]

    @property
    def group(self) -> np.ndarray:
        return self._views["group"]

    @property
    def wheels(self) -> np.ndarray:
        """(n, 2) int16 copy: the commanded left and right wheel speeds, steps/s."""
        return np.column_stack([self._views["wheels.cmd_left"], self._views["wheels.cmd_right"]])

    @property
    def state(self) -> np.ndarray:
        """Each robot's controller state name (object array of str; None
        for a controller without state)."""
        codes, names = self.state_codes()
        table = np.array(list(names) + [None], dtype=object)
        return table[codes]

    def state_codes(self) -> tuple[np.ndarray, list[str]]:
        """(codes, names): each robot's state as an index into `names`
        (-1: a controller without state); for counting without strings."""
        self._sim._check_open()
        lib = _lib.lib()
        if self.count == 0:
            return np.zeros(0, dtype=np.int32), []
        lib.sim_robot_state_names(self._sim._handle.sim, 0, self.count, self._names_buf)
        pointers = np.frombuffer(self._names_buf, dtype=np.uintp, count=self.count)
        unique, inverse = np.unique(pointers, return_inverse=True)
        names: list[str] = []
        index: dict[str, int] = {}
        remap = np.empty(len(unique), dtype=np.int32)
        for j, p in enumerate(unique):
            p = int(p)
            if p == 0:
                remap[j] = -1
                continue
            text = self._state_text.get(p)
            if text is None:
                text = self._state_text[p] = ctypes.string_at(p).decode()
            if text not in index:
                index[text] = len(names)
                names.append(text)
            remap[j] = index[text]
        return remap[inverse], names

    def observable(self, name: str) -> np.ndarray:
        """Observable `name` of every robot (float64, as telemetry reports
        it: field x scale); NaN for robots whose controller shows none of
        that name."""
        out = np.full(self.count, np.nan)
        found = False
        for g in self._sim.groups:
            o = g.observables.get(name)
            if o is not None:
                out[g.first:g.first + g.count] = o.values
                found = True
        if not found:
            known = sorted({n for g in self._sim.groups for n in g.observables})
            raise KeyError(f"no controller of this run shows {name!r}; they show: {', '.join(known)}")
        return out

    def to_frame(self):
        """A pandas DataFrame snapshot: one row per robot, every
        single-valued field and observable, and the state."""
        import pandas as pd
        cols: dict[str, Any] = {"robot": np.arange(self.count)}
        for name, view in self._views.items():
            if view.ndim == 1:
                cols[name] = view.copy()
            else:
                for k in range(view.shape[1]):
                    cols[f"{name}[{k}]"] = view[:, k].copy()
        codes, names = self.state_codes()
        cols["state"] = pd.Categorical.from_codes(codes, categories=names) if names else [None] * self.count
        for n in sorted({n for g in self._sim.groups for n in g.observables}):
            cols[n] = self.observable(n)
        return pd.DataFrame(cols)


class Sim:
    """One run of a scenario, stepped from Python.

    scenario   the scenario file (sim_host/scenarios/*.yaml or your own)
    seed       the run's seed (default: the scenario's `seed`), 0 .. 2^53 - 1
    overrides  scenario keys to change, as swarmsim's --set:
               {"robots.0.count": 30, "ircom.loss": 0.1} or ["robots.0.count=30"]
    threads    threads inside the run (1 .. 64); results are identical for any

    Raises ScenarioError (file, line, key) for a bad scenario or override,
    SimError when the world cannot be built (robots that cannot be placed).
    """

    #: Seconds of work a single C call may take inside step(): longer steps
    #: are split, so Ctrl-C is seen within about this long.
    STEP_SLICE_S = 0.25

    def __init__(self, scenario: str | Path, seed: int | None = None, overrides: OverridesLike = None,
                 threads: int = 1):
        lib = _lib.lib()
        self.path = str(scenario)
        self.overrides: list[str] = override_texts(overrides)
        if seed is not None and not (isinstance(seed, (int, np.integer)) and 0 <= int(seed) <= 2**53 - 1):
            raise ValueError(f"seed {seed!r}: a whole number in [0, 2^53 - 1]")
        if not (isinstance(threads, (int, np.integer)) and 1 <= int(threads) <= 64):
            raise ValueError(f"threads {threads!r}: 1 to 64")
        self._texts = [t.encode() for t in self.overrides]
        self._ovr = _lib.overrides_array(self._texts)
        err = _lib.err_buffer()
        sc = lib.scenario_create(self.path.encode(), self._ovr, len(self._texts), err)
        if not sc:
            raise parse_loader_error(err.value.decode(errors="replace"), self.path, self.overrides)
        handle = _Handle(sc)
        run_seed = int(seed) if seed is not None else int(lib.scenario_seed(sc))
        sim = lib.sim_create_threads(sc, run_seed, int(threads), err)
        if not sim:
            raise SimError(f"{self.path}: {err.value.decode(errors='replace')}")
        handle.sim = sim
        self._handle: _Handle | None = handle
        self.seed: int = int(lib.sim_seed(sim))
        self.threads = int(threads)
        #: Control steps of the scenario's duration (what swarmsim runs).
        self.duration_steps: int = int(lib.scenario_steps(sc))
        self.robot_count: int = int(lib.sim_robot_count(sim))
        self.groups: list[Group] = [Group(self, g) for g in range(lib.sim_group_count(sim))]
        self._robots: Robots | None = None
        self._slice = 64

    # ------------------------------------------------------------ lifetime

    def close(self) -> None:
        """Ends the run: its memory goes once no array of it is referenced
        any more.  Stepping or reading it afterwards raises ValueError.
        Closing twice is fine."""
        self._handle = None
        self._robots = None
        self.groups = []

    def __enter__(self) -> Sim:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    @property
    def closed(self) -> bool:
        return self._handle is None

    def _check_open(self) -> _Handle:
        if self._handle is None:
            raise ValueError("this simulation is closed")
        return self._handle

    def __repr__(self) -> str:
        state = "closed" if self.closed else f"step {self.step_count}, t = {self.time:g} s"
        return f"<Sim {self.path} seed {self.seed}: {state}>"

    # ------------------------------------------------------------ stepping

    def step(self, n: int = 1) -> int:
        """Runs up to `n` control steps; stops early once a task's stop
        condition holds (``done``).  Returns the steps done.  Raises
        SimError if a model failed during a step."""
        h = self._check_open()
        if not isinstance(n, (int, np.integer)) or n < 0:
            raise ValueError(f"step({n!r}): a whole number of steps >= 0")
        lib = _lib.lib()
        left, done = int(n), 0
        with h.lock:
            while left > 0:
                chunk = min(left, self._slice)
                t0 = time.perf_counter()
                did = int(lib.sim_step_n(h.sim, chunk))
                spent = time.perf_counter() - t0
                done += did
                left -= chunk
                if did < chunk:
                    break
                # Keep each call near STEP_SLICE_S, so that Ctrl-C (seen
                # between calls) is never kept waiting long.
                if spent > 0:
                    self._slice = max(1, min(1 << 20, int(chunk * self.STEP_SLICE_S / spent)))
            error = lib.sim_error(h.sim)
        if error:
            raise SimError(f"{self.path}: step {self.step_count}: {error.decode(errors='replace')}")
        return done

    def run(self, steps: int | None = None) -> int:
        """Steps to the end: `steps` more (default: what is left of the
        scenario's duration), stopping early when ``done``.  Returns the
        steps done."""
        if steps is None:
            steps = max(0, self.duration_steps - self.step_count)
        return self.step(steps)

    @property
    def step_count(self) -> int:
        """Control steps done."""
        return int(_lib.lib().sim_step_count(self._check_open().sim))

    @property
    def time(self) -> float:
        """Simulated time, s (steps x control period)."""
        return float(_lib.lib().sim_time_s(self._check_open().sim))

    @property
    def done(self) -> bool:
        """True once a task's stop condition held."""
        return bool(_lib.lib().sim_done(self._check_open().sim))

    @property
    def state_hash(self) -> str:
        """The state hash as swarmsim's summary writes it (16 hex digits):
        equal hashes mean bit-identical runs."""
        return f"{_lib.lib().sim_state_hash(self._check_open().sim):016x}"

    # ------------------------------------------------------------ reading

    @property
    def robots(self) -> Robots:
        """The robots as arrays (see Robots)."""
        self._check_open()
        if self._robots is None:
            self._robots = Robots(self)
        return self._robots

    def group(self, name_or_index: str | int) -> Group:
        """A group by its index or its name."""
        self._check_open()
        if isinstance(name_or_index, (int, np.integer)):
            return self.groups[int(name_or_index)]
        for g in self.groups:
            if g.name == name_or_index:
                return g
        raise KeyError(f"no group {name_or_index!r}; groups: {', '.join(g.name for g in self.groups)}")

    def _array(self, f: Field, n: int) -> np.ndarray:
        typestr = _lib.FIELD_TYPES[f.type]
        size = np.dtype(typestr).itemsize
        if not f.base or n == 0:
            shape = (0,) if f.count == 1 else (0, f.count)
            return np.zeros(shape, dtype=typestr)
        if f.count == 1:
            view = _View(self._handle, f.base, (n,), (f.stride,), typestr)
        else:
            view = _View(self._handle, f.base, (n, f.count), (f.stride, size), typestr)
        return np.asarray(view)

    def _metrics(self, final: bool) -> dict[str, float]:
        h = self._check_open()
        m = MetricList()
        (_lib.lib().metrics_final if final else _lib.lib().metrics_sample)(h.sim, ctypes.byref(m))
        return {m.name[k].decode(): float(m.value[k]) for k in range(m.count)}

    def task_metrics(self) -> dict[str, float]:
        """The summary's metrics for the run as it stands (metrics_final:
        the core's, each model's and each task's), by name."""
        return self._metrics(final=True)

    def sample(self) -> dict[str, float]:
        """A row of the time series now (metrics_sample: timeseries.csv's
        columns), by name."""
        return self._metrics(final=False)

    def metric_units(self) -> dict[str, tuple[str, str]]:
        """{name: (unit, doc)} of the summary's and the time series' metrics."""
        h = self._check_open()
        out = {}
        for fn in (_lib.lib().metrics_sample, _lib.lib().metrics_final):
            m = MetricList()
            fn(h.sim, ctypes.byref(m))
            for k in range(m.count):
                out[m.name[k].decode()] = (m.unit[k].decode(), m.doc[k].decode())
        return out

    def summary(self, command: str | None = None) -> dict:
        """The run's summary.json as swarmsim would write it now (scenario,
        provenance, seed, steps, state hash, metrics), as a dict."""
        h = self._check_open()
        lib = _lib.lib()
        err = _lib.err_buffer()
        if command is None:
            command = "swarmtools.Sim(" + ", ".join(
                [repr(self.path), f"seed={self.seed}"] + ([f"overrides={self.overrides!r}"] if self.overrides else [])) + ")"
        p = lib.sim_summary_json(h.sim, lib.swarmsim_code_version(), command.encode(), self._ovr,
                                 len(self._texts), err)
        if not p:
            raise SimError(err.value.decode(errors="replace"))
        return json.loads(_lib.take_text(p))

    def events(self) -> list[Event]:
        """The events the robots had during the last step."""
        h = self._check_open()
        recs = ctypes.POINTER(_lib.EventRec)()
        n = _lib.lib().sim_events(h.sim, ctypes.byref(recs))
        return [Event(int(recs[k].robot), (recs[k].kind or b"").decode(), (recs[k].detail or b"").decode(),
                      int(recs[k].value)) for k in range(n)]

    # ------------------------------------------------------------ driving robots

    def set_pose(self, robot: int, x: float, y: float, theta: float) -> None:
        """Teleports a robot: m, m, rad."""
        h = self._check_open()
        self._robot_index(robot)
        _lib.lib().sim_set_robot_pose(h.sim, robot, x, y, theta)

    def robot_id(self, robot: int) -> int:
        """The id the robot reports (hal_robot_id): its index unless set."""
        return int(_lib.lib().sim_robot_id(self._check_open().sim, self._robot_index(robot)))

    def set_robot_id(self, robot: int, robot_id: int) -> None:
        if not 0 <= robot_id <= 0xFFFF:
            raise ValueError(f"robot id {robot_id}: 0 to 65535")
        _lib.lib().sim_set_robot_id(self._check_open().sim, self._robot_index(robot), robot_id)

    def uart(self, robot: int) -> bytes:
        """The bytes the robot's image wrote to its UART in the last step
        (robot_telemetry.enabled; b"" otherwise)."""
        h = self._check_open()
        p = ctypes.POINTER(ctypes.c_uint8)()
        n = _lib.lib().sim_robot_uart(h.sim, self._robot_index(robot), ctypes.byref(p))
        return ctypes.string_at(p, n) if n else b""

    def host_send(self, robot: int, message: bytes) -> bool:
        """A message from the host to the robot over its live link
        (host.live): False when its mailbox (2 messages) was full and it
        was dropped.  ValueError for a run without host.live, or a message
        of 0 or more than 64 bytes."""
        h = self._check_open()
        message = bytes(message)
        if not 1 <= len(message) <= _lib.HAL_HOST_MSG_MAX:
            raise ValueError(f"a message to a robot is 1 to {_lib.HAL_HOST_MSG_MAX} bytes, not {len(message)}")
        rc = _lib.lib().sim_host_send(h.sim, self._robot_index(robot), message, len(message))
        if rc == -2:
            raise ValueError("the run has no live host link: load the scenario with host.live: true")
        return rc == 0

    def host_pose(self, robot: int, x_mm: int, y_mm: int, heading_mrad: int) -> None:
        """A pose fix from the host for the robot (host.live): hal_pose
        gives it from the next step, aging, until 1 s old."""
        h = self._check_open()
        pose = Pose(int(x_mm), int(y_mm), int(heading_mrad), 0)
        if _lib.lib().sim_host_pose(h.sim, self._robot_index(robot), ctypes.byref(pose)) != 0:
            raise ValueError("the run has no live host link: load the scenario with host.live: true")

    def host_dropped(self, robot: int) -> int:
        """Messages host_send dropped for the robot (its mailbox was full)."""
        return int(_lib.lib().sim_host_dropped(self._check_open().sim, self._robot_index(robot)))

    def _robot_index(self, robot: int) -> int:
        if not isinstance(robot, (int, np.integer)) or not 0 <= robot < self.robot_count:
            raise IndexError(f"robot {robot!r}: the run has robots 0 to {self.robot_count - 1}")
        return int(robot)


__all__ = ["Event", "FieldInfo", "Group", "Observable", "Robots", "ScenarioError", "Sim", "SimError"]
