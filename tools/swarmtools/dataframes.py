"""Telemetry logs and run folders as pandas DataFrames.

    log = swarmtools.load_log("out/run/run_1/telemetry.lcmlog")
    log.swarm       # SWARM_STATE: one row per message; state counts and the swarm's values as columns
    log.robots      # ROBOT_STATE: one row per message; the controllers' values named by their schemas
    log.events      # SWARM_EVENT
    log.summary     # RUN_SUMMARY as a dict (None for a log of real robots)

    run = swarmtools.load_run("out/run/run_1")     # summary.json, timeseries.csv and the log

The log is read by the project's checked reader (telemetry/logfile.py:
every event's lengths checked against the file; telemetry/common.py: every
message by its fingerprint and version), one event at a time, and each
table is built in chunks of typed numpy columns (strings as categories),
so memory grows with the tables' size, not the log's Python objects.  The
robots' states and the events, the bulk of a log, are decoded in batches
(lcm_batch.py) with the same checks; the figures: `make bench-load-log`,
docs/development/benchmarks.md.  For a log too big for that, iter_log
yields the tables chunk by chunk.

Column names: a message's fields as in lcm_types/ (nested fields skipped),
a swarm state's ``state_names``/``state_counts`` as ``state.<name>``, and
the ``values`` of robot and swarm states by the schema that names them
(TELEMETRY_SCHEMA): the controller's value names (``threshold``, ``oae``)
for robots, one column per name over every controller that has it (NaN in
the rows of a controller without it), the swarm schema's for the swarm; a
name that is also a field's gets its schema's name before it
(``swarm.step``); a value no schema names is ``<schema>.value<k>``.
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from . import lcm_batch

#: numpy dtypes of the LCM primitive types.
_DTYPES = {"int8_t": np.int8, "int16_t": np.int16, "int32_t": np.int32, "int64_t": np.int64, "byte": np.uint8,
           "float": np.float32, "double": np.float64, "boolean": np.bool_}
#: Rows per chunk.
CHUNK_ROWS = 65536
#: The tables load_log builds: attribute, channel name (after the prefix).
TABLES = {"swarm": "SWARM_STATE", "robots": "ROBOT_STATE", "events": "SWARM_EVENT"}
_ATTR = {ch: a for a, ch in TABLES.items()}


class LogReadError(ValueError):
    """A log that is not, or no longer, a well-formed LCM log of ours."""


class _NotBatched(Exception):
    """Bytes the batch decoder does not take: the checked decoder explains them."""


def _checked_decode(data: bytes, channel: str, path: str):
    """The message of `data` through the checked decoder (LogReadError for one it refuses)."""
    from .telemetry import common
    try:
        return common.decode(data, channel)
    except common.IncompatibleMessage as e:
        raise LogReadError(e.explain(path)) from None


class _Table:
    """The rows of one channel, built in chunks of typed columns."""

    def __init__(self, cls, schemas, log_time: bool, chunk_rows: int, run: int | None = None,
                 source: tuple[str, str] = ("", "")):
        self.schemas = schemas
        self.chunk_rows = chunk_rows
        self.kind = cls.__name__
        self.fixed = []       # (slot, typename) of the primitive scalar fields
        self.pairs = []       # (names slot, values slot, column prefix)
        self.has_values = "values" in cls.__slots__
        for slot, typename, dim in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__, strict=True):
            if slot == "version" or slot.startswith("n_") or dim is not None or typename not in (*_DTYPES, "string"):
                continue
            self.fixed.append((slot, typename))
        if "state_names" in cls.__slots__ and "state_counts" in cls.__slots__:
            self.pairs.append(("state_names", "state_counts", "state."))
        self.log_time = log_time
        self.cats: dict[str, dict[str, int]] = {s: {} for s, t in self.fixed if t == "string"}
        self.chunks: list[dict[str, np.ndarray]] = []
        self.extra_dtype: dict[Any, Any] = {}
        self.cls = cls
        self.source = source      # (log path, channel): for the checked decoder's errors
        self.version = getattr(cls, "VERSION", None)
        self.batch = lcm_batch.Batch(cls, run) if not self.pairs and lcm_batch.supports(cls) else None
        self._new_chunk()

    def _new_chunk(self):
        self.rows = 0
        self.cols: dict[str, np.ndarray] = {
            s: np.empty(self.chunk_rows, dtype=np.int32 if t == "string" else _DTYPES[t]) for s, t in self.fixed}
        if self.log_time:
            self.cols["log_utime"] = np.empty(self.chunk_rows, dtype=np.int64)
        self.extra: dict[Any, np.ndarray] = {}   # (schema kind, name, k) or pair column -> chunk array

    def _extra(self, key, dtype, fill):
        a = self.extra.get(key)
        if a is None:
            a = self.extra[key] = np.full(self.chunk_rows, fill, dtype=dtype)
            self.extra_dtype[key] = (dtype, fill)
        return a

    def add(self, msg, log_utime: int) -> bool:
        """Appends a row; True when a chunk was completed."""
        row = self.rows
        for slot, typename in self.fixed:
            v = getattr(msg, slot)
            if typename == "string":
                codes = self.cats[slot]
                c = codes.get(v)
                if c is None:
                    c = codes[v] = len(codes)
                v = c
            self.cols[slot][row] = v
        if self.log_time:
            self.cols["log_utime"][row] = log_utime
        for names_slot, values_slot, prefix in self.pairs:
            for name, v in zip(getattr(msg, names_slot), getattr(msg, values_slot), strict=True):
                self._extra(("pair", prefix + name), np.int32, 0)[row] = v
        if self.has_values:
            key = ("controller", msg.controller) if self.kind == "robot_state_t" else ("swarm", "swarm")
            dtype = np.float64 if self.kind == "swarm_state_t" else np.float32
            for k, v in enumerate(msg.values):
                self._extra(("value", key[0], key[1], k), dtype, np.nan)[row] = v
        return self._next_row()

    def _next_row(self) -> bool:
        self.rows += 1
        if self.rows == self.chunk_rows:
            self.flush()
            return True
        return False

    def add_raw(self, data: bytes, log_utime: int) -> bool | None:
        """Appends a row from a message's bytes, decoded later with its
        chunk (lcm_batch): True when a chunk was completed, False when not,
        None when the run filter drops it; raises _NotBatched when the
        bytes do not hold a message of the type (add() the decoded one)."""
        filed = self.batch.add(data, self.rows)
        if filed is None:
            return None
        if not filed:
            raise _NotBatched
        if self.log_time:
            self.cols["log_utime"][self.rows] = log_utime
        return self._next_row()

    def _decode_batch(self):
        """Decodes the chunk's filed messages into its columns (new strings
        get their category codes in the order of their first row, as add()
        gives them)."""
        layouts = []
        first: dict[str, dict[str, int]] = {slot: {} for slot in self.cats}
        try:
            decoded = list(self.batch.layouts_decoded())
        except lcm_batch.BadMessage as e:
            _checked_decode(e.data, *self.source[::-1])
            raise LogReadError(f"{self.source[0]}: a {self.kind} on {self.source[1]} whose lengths do not "
                               f"hold") from None
        for rows, arr in decoded:
            bad = np.flatnonzero(arr["version"] != self.version) if self.version is not None else []
            if len(bad):
                _checked_decode(arr[bad[0]].tobytes(), *self.source[::-1])
                raise LogReadError(f"{self.source[0]}: a {self.kind} of version {arr['version'][bad[0]]}")
            strings = {}
            for slot in self.cats:
                uniq, where, inverse = np.unique(arr[slot], return_index=True, return_inverse=True)
                texts = []
                for j, raw in enumerate(uniq):
                    try:
                        text = raw.decode("utf-8")
                    except UnicodeDecodeError:
                        _checked_decode(arr[where[j]].tobytes(), *self.source[::-1])
                        raise
                    texts.append(text)
                    if text not in self.cats[slot]:
                        seen = first[slot].get(text)
                        at = int(rows[where[j]])
                        first[slot][text] = at if seen is None else min(seen, at)
                strings[slot] = (texts, inverse)
            layouts.append((rows, arr, strings))
        for slot, news in first.items():
            codes = self.cats[slot]
            for text in sorted(news, key=news.get):
                codes[text] = len(codes)
        for rows, arr, strings in layouts:
            for slot, typename in self.fixed:
                if typename != "string":
                    self.cols[slot][rows] = arr[slot]
                    continue
                texts, inverse = strings[slot]
                codes = self.cats[slot]
                lut = np.array([codes[t] for t in texts], dtype=np.int32)
                self.cols[slot][rows] = lut[inverse]
            if not self.has_values or "values" not in arr.dtype.names:
                continue
            values = arr["values"]
            if self.kind == "robot_state_t":
                texts, inverse = strings["controller"]
                groups = [(("controller", name), inverse == j) for j, name in enumerate(texts)]
            else:
                groups = [(("swarm", "swarm"), slice(None))]
            dtype = np.float64 if self.kind == "swarm_state_t" else np.float32
            for key, which in groups:
                at = rows[which]
                for k in range(values.shape[1]):
                    self._extra(("value", key[0], key[1], k), dtype, np.nan)[at] = values[which, k]

    def flush(self):
        if self.rows == 0:
            return
        n = self.rows
        if self.batch is not None and self.batch.pending:
            self._decode_batch()
        chunk = {}
        for slot, _ in self.fixed:
            chunk[slot] = self.cols[slot][:n].copy()
        if self.log_time:
            chunk["log_utime"] = self.cols["log_utime"][:n].copy()
        for key, a in self.extra.items():
            chunk[key] = a[:n].copy()
        self.chunks.append(chunk)
        self._new_chunk()

    def _column_names(self):
        """Final names of the extra columns: pairs as they are, values by
        their schema (several keys may get one name: merged)."""
        fixed = {s for s, _ in self.fixed} | {"log_utime"}
        names = {}
        for key in self.extra_dtype:
            if key[0] == "pair":
                names[key] = key[1]
                continue
            _, kind, schema_name, k = key
            s = self.schemas.get(kind, schema_name)
            name = s.entry(k).name if s is not None and k in s.entries else f"{schema_name}.value{k}"
            if name in fixed:
                name = f"{schema_name}.{name}"
            names[key] = name
        return names

    def frame(self):
        """Every row as one DataFrame (the chunks are released column by column)."""
        import pandas as pd
        self.flush()
        total = sum(len(next(iter(c.values()))) for c in self.chunks) if self.chunks else 0
        out: dict[str, Any] = {}
        lengths = [len(c[self.fixed[0][0]]) if self.fixed else 0 for c in self.chunks]
        for slot, typename in self.fixed:
            parts = [c.pop(slot) for c in self.chunks]
            col = np.concatenate(parts) if parts else np.zeros(0, dtype=np.int32 if typename == "string"
                                                                else _DTYPES[typename])
            del parts
            if typename == "string":
                cats = list(self.cats[slot])
                col = pd.Categorical.from_codes(col, categories=pd.Index(cats, dtype=object)) if cats else \
                    pd.Categorical([], categories=[])
            out[slot] = col
        if self.log_time:
            parts = [c.pop("log_utime") for c in self.chunks]
            out["log_utime"] = np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)
        names = self._column_names()
        for key, name in sorted(names.items(), key=lambda kv: (kv[0][0] != "pair", kv[0][1:])):
            dtype, fill = self.extra_dtype[key]
            parts = []
            for c, n in zip(self.chunks, lengths, strict=True):
                a = c.pop(key, None)
                parts.append(a if a is not None else np.full(n, fill, dtype=dtype))
            col = np.concatenate(parts) if parts else np.zeros(0, dtype=dtype)
            del parts
            if name in out:                     # the same name in another controller's schema
                prev = out[name]
                if prev.dtype != col.dtype:
                    prev = prev.astype(np.float64)
                    col = col.astype(np.float64)
                out[name] = np.where(np.isnan(col), prev, col)
            else:
                out[name] = col
        self.chunks = []
        df = pd.DataFrame(out, copy=False)
        assert len(df) == total
        return df


@dataclass
class LogData:
    """A telemetry log's tables (load_log)."""
    path: Path
    swarm: Any = None                 #: SWARM_STATE rows (pandas DataFrame)
    robots: Any = None                #: ROBOT_STATE rows
    events: Any = None                #: SWARM_EVENT rows
    summaries: list[dict] = field(default_factory=list)   #: every RUN_SUMMARY, in order
    run_info: list[dict] = field(default_factory=list)    #: every RUN_INFO, in order
    schemas: Any = None               #: the schemas heard (telemetry.common.Schemas)
    other_channels: dict[str, int] = field(default_factory=dict)   #: channels not read, and their messages

    @property
    def summary(self) -> dict | None:
        """The last RUN_SUMMARY (a simulator's log has one per run), or None."""
        return self.summaries[-1] if self.summaries else None


def _plain(msg) -> dict:
    out = {}
    for slot, dim in zip(msg.__slots__, msg.__dimensions__, strict=True):
        if slot == "version" or slot.startswith("n_"):
            continue
        v = getattr(msg, slot)
        if hasattr(v, "__slots__"):
            v = _plain(v)
        elif dim is not None and not isinstance(v, (bytes, str)):
            v = [(_plain(x) if hasattr(x, "__slots__") else x) for x in v]
        out[slot] = v
    return out


def _summary_dict(msg) -> dict:
    d = _plain(msg)
    d["metrics"] = {n: (None if math.isnan(v) else v) for n, v in zip(msg.metric_names, msg.metric_values,
                                                                      strict=True)}
    del d["metric_names"], d["metric_values"]
    return d


#: The channels load_log reads (after the prefix); the others are counted, not decoded.
_READ = {"TELEMETRY_SCHEMA", "RUN_SUMMARY", "RUN_INFO", *TABLES.values()}
#: Channels whose messages a table decodes in batches (lcm_batch): the bulk of a log.
_BATCHED = {"ROBOT_STATE", "SWARM_EVENT"}
#: _events' stand-in for a message left to its table's batch decoder.
_RAW = object()


def _add_row(tables: dict, attr: str, name: str, ev, msg, schemas, log_time: bool, chunk_rows: int,
             run: int | None, path: str) -> bool:
    """Adds a message (or its bytes: _RAW) to its table; True when the
    table completed a chunk."""
    t = tables.get(attr)
    if msg is _RAW:
        if t is None:
            from .telemetry import common
            cls = common.type_class(common.CHANNEL_TYPES[name])
            t = tables[attr] = _Table(cls, schemas, log_time, chunk_rows, run, (path, ev.channel))
        try:
            return bool(t.add_raw(ev.data, ev.timestamp))
        except _NotBatched:
            msg = _checked_decode(ev.data, ev.channel, path)
        if msg is None or type(msg) is not t.cls:
            raise LogReadError(f"{path}: a message on {ev.channel} is not a {t.kind}")
        if run is not None and msg.run != run:
            return False
    if t is None:
        t = tables[attr] = _Table(type(msg), schemas, log_time, chunk_rows, run, (path, ev.channel))
    return t.add(msg, ev.timestamp)


class _Progress:
    """A log's bytes read so far: a tqdm bar on stderr (progress=True), or
    progress(bytes_read, bytes_total) called about every 1 % of the file."""

    def __init__(self, progress, path: str, total: int):
        self.bar = self.call = None
        self.total = total
        self.step = max(1, total // 100)
        self.next = 0
        if callable(progress):
            self.call = progress
        elif progress:
            from tqdm import tqdm
            self.bar = tqdm(total=total, unit="B", unit_scale=True, unit_divisor=1024, mininterval=0.5,
                            desc=os.path.basename(path), file=sys.stderr, leave=False)

    def at(self, offset: int):
        if offset < self.next:
            return
        self.next = offset + self.step
        if self.bar is not None:
            self.bar.update(offset - self.bar.n)
        elif self.call is not None:
            self.call(offset, self.total)

    def close(self):
        if self.bar is not None:
            self.bar.update(self.total - self.bar.n)
            self.bar.close()
        elif self.call is not None:
            self.call(self.total, self.total)


def _events(path, prefix, progress=None):
    """(log event, name after the prefix, message) of the channels load_log
    reads, through the checked reader (every event's lengths; every
    message read by its fingerprint and version); _RAW for the message of
    a channel whose table decodes its bytes in batches (lcm_batch, with
    the same checks); None for the channels not read.  Errors as
    LogReadError."""
    from .telemetry import common, logfile
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path}: no such file")
    count = 0
    shown = _Progress(progress, path, os.path.getsize(path)) if progress else None
    try:
        for ev in logfile.events(path):
            count += 1
            if shown is not None:
                shown.at(ev.offset)
            name = _select(ev.channel, prefix)
            if name not in _READ:
                yield ev, name, None
                continue
            if name in _BATCHED:
                yield ev, name, _RAW
                continue
            try:
                msg = common.decode(ev.data, ev.channel)
            except common.IncompatibleMessage as e:
                raise LogReadError(e.explain(path)) from None
            yield ev, name, msg
    except logfile.LogError as e:
        raise LogReadError(str(e) if count else f"{path}: not an LCM log ({e})") from None
    finally:
        if shown is not None:
            shown.close()
    if count == 0 and os.path.getsize(path) > 0:
        raise LogReadError(f"{path}: not an LCM log (no events in it)")


def _select(channel: str, prefix: str):
    """The table a channel feeds (swarm, robots, events, or a special), or None."""
    if not channel.startswith(prefix):
        return None
    return channel[len(prefix):]


def iter_log(path: str | os.PathLike, prefix: str = "", run: int | None = None, chunk_rows: int = CHUNK_ROWS,
             log_time: bool = False, progress: bool | Callable[[int, int], None] = False,
             ) -> Iterator[tuple[str, Any]]:
    """The log's tables chunk by chunk: (table name, DataFrame of at most
    `chunk_rows` rows) as each fills, then the last part of each.  Values
    are named by the schemas heard so far (a simulator sends them first;
    a robot's arrive in pieces, so its first rows may say value<k>)."""
    from .telemetry import common
    schemas = common.Schemas()
    tables: dict[str, _Table] = {}
    for ev, name, msg in _events(path, prefix, progress):
        if msg is None:
            continue
        if msg is not _RAW and run is not None and getattr(msg, "run", run) != run:
            continue
        if name == "TELEMETRY_SCHEMA":
            schemas.add(msg)
            continue
        attr = _ATTR.get(name)
        if attr is None:
            continue
        if _add_row(tables, attr, name, ev, msg, schemas, log_time, chunk_rows, run, os.fspath(path)):
            t = tables[attr]
            yield attr, t.frame()
            tables[attr] = _Table(t.cls, schemas, log_time, chunk_rows, run, t.source)
            tables[attr].cats = t.cats     # keep the categories' codes stable across chunks
    for attr, t in tables.items():
        if t.rows or t.chunks:
            yield attr, t.frame()


def load_log(path: str | os.PathLike, prefix: str = "", run: int | None = None, log_time: bool = False,
             chunk_rows: int = CHUNK_ROWS, progress: bool | Callable[[int, int], None] = False) -> LogData:
    """A telemetry log (a run's telemetry.lcmlog, or lcm-logger's of the
    bridge) as DataFrames: swarm, robots, events, and the summaries.

    prefix    the channels' prefix ("FW_": the robots' own telemetry that
              the simulator republished; the bridge's --prefix)
    run       only the messages of the run with this seed
    log_time  a first column log_utime: the log event's timestamp, us
    progress  True: a progress bar of the bytes read on stderr (tqdm);
              a function: called as progress(bytes_read, bytes_total)
              about every 1 % of the file and once at its end

    Raises FileNotFoundError, or LogReadError for a file that is not a
    well-formed log of ours (naming the byte offset where it breaks)."""
    from .telemetry import common
    schemas = common.Schemas()
    data = LogData(Path(path), schemas=schemas)
    tables: dict[str, _Table] = {}
    for ev, name, msg in _events(path, prefix, progress):
        if msg is None:
            data.other_channels[ev.channel] = data.other_channels.get(ev.channel, 0) + 1
            continue
        if msg is not _RAW and run is not None and getattr(msg, "run", run) != run:
            continue
        if name == "TELEMETRY_SCHEMA":
            schemas.add(msg)
        elif name == "RUN_SUMMARY":
            data.summaries.append(_summary_dict(msg))
        elif name == "RUN_INFO":
            data.run_info.append(_plain(msg))
        else:
            attr = _ATTR.get(name)
            if attr is None:
                data.other_channels[ev.channel] = data.other_channels.get(ev.channel, 0) + 1
                continue
            _add_row(tables, attr, name, ev, msg, schemas, log_time, chunk_rows, run, os.fspath(path))
    import pandas as pd
    for attr in TABLES:
        t = tables.pop(attr, None)
        setattr(data, attr, t.frame() if t is not None else pd.DataFrame())
    return data


@dataclass
class RunData:
    """A run's folder (load_run): its summary, time series and telemetry."""
    dir: Path
    summary: dict
    timeseries: Any                   #: timeseries.csv (pandas DataFrame), or None
    scenario: str | None              #: the effective scenario (scenario.yaml)
    log_path: Path | None

    def log(self, **kwargs) -> LogData:
        """The run's telemetry log as DataFrames (load_log's arguments)."""
        if self.log_path is None:
            raise FileNotFoundError(f"{self.dir}: no telemetry.lcmlog (run with --lcm off?)")
        return load_log(self.log_path, **kwargs)

    @property
    def swarm(self):
        return self.log().swarm


def load_run(folder: str | os.PathLike) -> RunData | list[RunData]:
    """A run's folder (run_<seed>/: summary.json, timeseries.csv,
    scenario.yaml, telemetry.lcmlog) as a RunData; an output folder of
    several runs (swarmsim --out DIR) as the list of its runs' RunData, in
    seed order.  The log is read on demand (RunData.log())."""
    import pandas as pd
    d = Path(folder)
    if not d.is_dir():
        raise FileNotFoundError(f"{d}: no such folder")
    if not (d / "summary.json").is_file() or (d / ".swarmsim-out").exists() and not (d / "timeseries.csv").exists():
        runs = sorted((p for p in d.glob("run_*") if p.is_dir() and p.name[4:].isdigit()),
                      key=lambda p: int(p.name[4:]))
        if runs:
            return [load_run(p) for p in runs]
        raise FileNotFoundError(f"{d}: neither a run's folder (summary.json) nor one of runs (run_<seed>/)")
    summary = json.loads((d / "summary.json").read_text())
    ts = d / "timeseries.csv"
    sc = d / "scenario.yaml"
    log = d / "telemetry.lcmlog"
    return RunData(d, summary, pd.read_csv(ts) if ts.is_file() else None,
                   sc.read_text() if sc.is_file() else None, log if log.is_file() else None)


__all__ = ["CHUNK_ROWS", "LogData", "LogReadError", "RunData", "iter_log", "load_log", "load_run"]
