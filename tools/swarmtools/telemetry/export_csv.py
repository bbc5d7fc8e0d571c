"""Export channels of an LCM log to CSV.

    swarm-export run_1/telemetry.lcmlog --channel SWARM_STATE -o swarm.csv
    swarm-export run_1/telemetry.lcmlog -o csv/            # every channel: csv/<CHANNEL>.csv
    swarm-export run_1/telemetry.lcmlog --timeseries 10    # the run's timeseries.csv again
    (or .venv/bin/python -m swarmtools.telemetry.export_csv ...)

Every message of a channel becomes a row, every field a column, named as in
lcm_types/ (nested structs as parent.field).  The values[] of ROBOT_STATE
and SWARM_STATE become one column each, named <schema>.<value> by the
schema_t that names them (channel TELEMETRY_SCHEMA): the controller's for
a robot (e.g. forager.threshold), "swarm" for the swarm (swarm.step,
swarm.time_s, ...); a value not named by any schema in the log is
<schema>.value<k>.  A pair NAME_names / NAME_values (RUN_SUMMARY's metrics)
becomes one column per name, a pair NAME_names / NAME_<other> (SWARM_STATE's
state_names / state_counts) one column NAME.<name> per name; other arrays go
into one cell, joined with ';'.  A channel's columns are those of all its
messages in the log (robots of several controllers, states that appear
during the run), in their order; a row leaves the cells it has no value for
empty.

Numbers print as the simulator's own CSV does: doubles with %.10g (the same
text for the same bits), floats with the fewest digits that give the same
float32, integers as integers, booleans as 1 / 0.

--timeseries N writes SWARM_STATE as the run's timeseries.csv with
output.timeseries_every = N, byte for byte: the swarm schema's names as the
header, then the values of each step that is a multiple of N, and of the
last step.
"""
import argparse
import csv
import functools
import math
import os
import re
import struct
import sys

from swarmtools.telemetry import common

PROG = "swarm-export"
PRIMITIVES = {"int8_t", "int16_t", "int32_t", "int64_t", "byte", "float", "double", "string", "boolean"}


def fmt_double(v):
    """C's printf("%.10g"), as the simulator writes timeseries.csv (glibc
    prints a NaN with its sign bit set as -nan)."""
    if math.isnan(v):
        return "-nan" if math.copysign(1.0, v) < 0 else "nan"
    return format(v, ".10g")


def fmt_float(v):
    """Shortest text that reads back as the same float32."""
    if math.isnan(v) or math.isinf(v):
        return format(v, "g")
    packed = struct.pack("<f", v)
    for digits in range(6, 10):
        text = format(v, f".{digits}g")
        if struct.pack("<f", float(text)) == packed:
            return text
    return format(v, ".9g")


def fmt_value(typename, v):
    if typename == "double":
        return fmt_double(v)
    if typename == "float":
        return fmt_float(v)
    if typename == "boolean":
        return "1" if v else "0"
    if typename == "byte" and isinstance(v, (bytes, bytearray)):
        return bytes(v).hex()
    return str(v)


@functools.cache
def _pairs(cls):
    """{array slot: (its NAME_names slot, NAME)} for the arrays named by a
    NAME_names array of the same length (exactly one such array per NAME);
    a property of the LCM type, worked out once per type."""
    slots, dims = cls.__slots__, cls.__dimensions__
    out = {}
    for i, s in enumerate(slots):
        if not s.endswith("_names") or dims[i] is None:
            continue
        base = s[:-len("_names")]
        siblings = [t for t, d in zip(slots, dims, strict=True) if t != s and t.startswith(base + "_") and d == dims[i]]
        if len(siblings) == 1:
            out[siblings[0]] = (s, base)
    return out


def fields(msg, schemas, prefix=""):
    """(column, LCM type, value) of one message, in field order; the
    values[] of robot and swarm states named by `schemas`."""
    out = []
    pairs = _pairs(type(msg))
    named = {names for names, _ in pairs.values()}
    key = common.schema_key(msg)
    for slot, typename, dim in zip(msg.__slots__, msg.__typenames__, msg.__dimensions__, strict=True):
        v = getattr(msg, slot)
        if slot in named:
            continue
        if slot in pairs:
            names_slot, base = pairs[slot]
            for name, x in zip(getattr(msg, names_slot), v, strict=True):
                col = name if slot == base + "_values" else f"{base}.{name}"
                out.append((prefix + col, typename, x))
        elif slot == "values" and key is not None:
            for name, x in zip(schemas.names(msg), v, strict=True):
                out.append((prefix + common.value_column(key[1], name), typename, x))
        elif dim is None and typename in PRIMITIVES:
            out.append((prefix + slot, typename, v))
        elif dim is None:
            out.extend(fields(v, schemas, prefix + slot + "."))
        elif typename in PRIMITIVES:
            if typename == "byte" and isinstance(v, (bytes, bytearray)):
                out.append((prefix + slot, "byte", v))
            else:
                out.append((prefix + slot, "string", ";".join(fmt_value(typename, x) for x in v)))
        else:
            cells = ["{" + ",".join(f"{c}={fmt_value(t, x)}" for c, t, x in fields(item, schemas)) + "}"
                     for item in v]
            out.append((prefix + slot, "string", ";".join(cells)))
    return out


def flatten(msg, schemas):
    """(column, text) pairs of one message, in field order."""
    return [(c, fmt_value(t, v)) for c, t, v in fields(msg, schemas)]


class Columns:
    """The union of the columns of a channel's messages, in their order: a
    new column goes just before the next column of its message that is
    already known (or last)."""

    def __init__(self):
        self.order = []
        self._known = set()
        self._shapes = set()

    def merge(self, cols):
        shape = tuple(cols)
        if shape in self._shapes:
            return
        self._shapes.add(shape)
        for j, c in enumerate(cols):
            if c in self._known:
                continue
            nxt = next((d for d in cols[j + 1:] if d in self._known), None)
            self.order.insert(self.order.index(nxt) if nxt is not None else len(self.order), c)
            self._known.add(c)


class ChannelWriter:
    """Streams one channel's rows to a CSV file.  Rows are written one
    message late so that the last one can always be kept (--every)."""

    def __init__(self, path, header, every=None):
        self.path = path
        self.header = header
        self.every = every
        self.pending = None
        self.rows = 0
        self._file = sys.stdout if path == "-" else open(path, "w", newline="")
        self._csv = csv.writer(self._file, lineterminator="\n")
        self._csv.writerow(header)

    def add(self, row, step=None):
        keep = not self.every or (step is not None and step % self.every == 0)
        if self.pending is not None and self.pending[1]:
            self._write(self.pending[0])
        self.pending = ([row.get(c, "") for c in self.header], keep)

    def _write(self, cells):
        self._csv.writerow(cells)
        self.rows += 1

    def close(self):
        if self.pending is not None:
            self._write(self.pending[0])     # the last message always
        if self._file is not sys.stdout:
            self._file.close()
        else:
            self._file.flush()


def _scan(log_path):
    """First reading of the log: every message decodes (or the tool stops
    before writing anything).  Returns the schemas, complete, the channels
    of other programs' messages and the runs of the SWARM_STATE messages."""
    schemas, unknown, swarm_runs = common.Schemas(), set(), []
    for ev, msg in common.read_log(log_path, PROG):
        kind = type(msg).__name__
        if msg is None:
            unknown.add(ev.channel)
        elif kind == "schema_t":
            schemas.add(msg)
        elif kind == "swarm_state_t" and msg.run not in swarm_runs:
            swarm_runs.append(msg.run)
    return schemas, unknown, swarm_runs


def _selected(log_path, patterns, run):
    for ev, msg in common.read_log(log_path, PROG):
        if msg is None:
            continue
        if patterns and not any(p.fullmatch(ev.channel) for p in patterns):
            continue
        if run is not None and getattr(msg, "run", run) != run:
            continue
        yield ev, msg


def file_names(channels):
    """A file name in the output folder for each channel.  Channel names come
    from the log, untrusted: a name is kept only where it is plain (letters,
    digits, '_', '-', '.', not starting with '.'); anything else (a '/', a
    '..', bytes that were not UTF-8) becomes '_' plus a short hash of the
    name, so that no file lands outside the folder and two channels never
    share one."""
    import hashlib
    import re
    out, used = {}, set()
    for ch in channels:
        base = ch if re.fullmatch(r"[A-Za-z0-9_-][A-Za-z0-9_.-]{0,99}", ch) else None
        if base is None or base.lower() in used:
            safe = re.sub(r"[^A-Za-z0-9_-]", "_", ch)[:60].strip("_") or "channel"
            base = f"{safe}_{hashlib.sha256(ch.encode('utf-8', 'surrogateescape')).hexdigest()[:8]}"
        used.add(base.lower())
        out[ch] = base + ".csv"
    return out


def export(log_path, channels=None, out="-", fields_wanted=None, every=None, log_time=False, run=None):
    """Writes the CSV(s); returns {channel: rows}."""
    patterns = [re.compile(f"(?:{c})") for c in channels] if channels else None    # matched whole
    schemas, unknown, _ = _scan(log_path)
    if patterns:
        unknown = {ch for ch in unknown if any(p.fullmatch(ch) for p in patterns)}
    columns = {}
    for ev, msg in _selected(log_path, patterns, run):
        cols = [c for c, _, _ in fields(msg, schemas)]
        if log_time:
            cols.insert(0, "log_utime")
        columns.setdefault(ev.channel, Columns()).merge(cols)
    if not columns:
        if unknown:
            print(f"{PROG}: channels of unknown types skipped: {', '.join(sorted(unknown))}", file=sys.stderr)
        return {}
    to_dir = out != "-" and (out.endswith(os.sep) or os.path.isdir(out))
    if len(columns) > 1 and not to_dir:
        raise SystemExit(f"{PROG}: the log has several channels ({', '.join(columns)}): "
                         f"choose one with --channel, or give -o a directory")
    headers = {}
    for ch, cols in columns.items():
        if fields_wanted:
            missing = [f for f in fields_wanted if f not in cols.order]
            if missing:
                raise SystemExit(f"{PROG}: {ch} has no field(s) {', '.join(missing)}; "
                                 f"it has: {', '.join(cols.order)}")
            headers[ch] = list(fields_wanted)
        else:
            headers[ch] = cols.order
    if to_dir:
        os.makedirs(out, exist_ok=True)
    names = file_names(columns) if to_dir else {}
    writers = {ch: ChannelWriter(os.path.join(out, names[ch]) if to_dir else out, headers[ch], every)
               for ch in columns}
    try:
        for ev, msg in _selected(log_path, patterns, run):
            row = dict(flatten(msg, schemas))
            if log_time:
                row["log_utime"] = str(ev.timestamp)
            writers[ev.channel].add(row, getattr(msg, "step", None))
    finally:
        for w in writers.values():
            w.close()
    if unknown:
        print(f"{PROG}: channels of unknown types skipped: {', '.join(sorted(unknown))}", file=sys.stderr)
    return {ch: w.rows for ch, w in writers.items()}


def export_timeseries(log_path, every, out="-", run=None):
    """SWARM_STATE as timeseries.csv (every `every` steps and the last);
    returns the number of rows."""
    schemas, _, runs = _scan(log_path)
    runs = [r for r in runs if run is None or r == run]
    if not runs:
        raise SystemExit(f"{PROG}: {log_path}: no SWARM_STATE messages" + (f" of run {run}" if run is not None else ""))
    if len(runs) > 1:
        raise SystemExit(f"{PROG}: {log_path} holds several runs ({', '.join(map(str, runs))}): choose one with --run")
    schema = schemas.get("swarm", "swarm", runs[0])
    if schema is None or not schema.complete:
        raise SystemExit(f"{PROG}: {log_path}: no (whole) swarm schema on TELEMETRY_SCHEMA to name the columns")
    names = schema.names()
    f = sys.stdout if out == "-" else open(out, "w", newline="")
    steps, pending = [], None
    try:
        f.write(",".join(names) + "\n")
        for _ev, msg in _selected(log_path, [re.compile("SWARM_STATE")], runs[0]):
            if type(msg).__name__ != "swarm_state_t":
                continue
            if len(msg.values) != len(names):
                raise SystemExit(f"{PROG}: {log_path}: a SWARM_STATE of step {msg.step} has {len(msg.values)} "
                                 f"values, the swarm schema names {len(names)}")
            if pending is not None and pending[0] % every == 0:
                f.write(pending[1])
                steps.append(pending[0])
            pending = (msg.step, ",".join(fmt_double(v) for v in msg.values) + "\n")
        if pending is not None:
            f.write(pending[1])     # the last step always
            steps.append(pending[0])
    finally:
        if f is sys.stdout:
            f.flush()
        else:
            f.close()
    want = list(range(0, steps[-1], every)) + [steps[-1]] if steps else []
    if steps != want:
        gaps = sorted(set(want) - set(steps))
        print(f"{PROG}: {log_path}: SWARM_STATE misses steps {', '.join(map(str, gaps[:5]))}"
              f"{', ...' if len(gaps) > 5 else ''} of every {every}: not the whole time series "
              f"(was the swarm rate, --telemetry-rate, lower?)", file=sys.stderr)
        return -len(steps)
    return len(steps)


def main(argv=None):
    try:
        return _main(argv)
    except BrokenPipeError:     # `... | head`: the reader has what it wanted
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())   # no error at exit's flush
        return 0


def _main(argv):
    ap = argparse.ArgumentParser(prog="swarm-export", description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    ap.add_argument("log", help="an LCM log file (lcm-logger's, or a run's telemetry.lcmlog)")
    ap.add_argument("--channel", action="append", help="channel name or regular expression (repeatable; default: all)")
    ap.add_argument("-o", "--out", default="-", help="CSV file, or a directory for one file per channel (default: stdout)")
    ap.add_argument("--fields", help="comma-separated columns to keep, in this order")
    ap.add_argument("--every", type=int, help="keep messages whose step is a multiple of N, and the last one")
    ap.add_argument("--timeseries", type=int, metavar="N",
                    help="SWARM_STATE as the run's timeseries.csv with output.timeseries_every = N")
    ap.add_argument("--log-time", action="store_true", help="first column: the log event's timestamp, us")
    ap.add_argument("--run", type=int, help="only messages of the run with this seed")
    args = ap.parse_args(argv)
    for name in ("every", "timeseries"):
        value = getattr(args, name)
        if value is not None and value < 1:
            ap.error(f"--{name} takes a whole number of steps, at least 1")
    if args.timeseries:
        if args.channel or args.fields or args.every or args.log_time:
            ap.error("--timeseries takes no --channel, --fields, --every or --log-time")
        rows = export_timeseries(args.log, args.timeseries, args.out, args.run)
        return 0 if rows > 0 else 1
    fields_wanted = args.fields.split(",") if args.fields else None
    counts = export(args.log, args.channel, args.out, fields_wanted, args.every, args.log_time, args.run)
    if not counts:
        print(f"{PROG}: no messages matched", file=sys.stderr)
        return 1
    if args.out != "-":
        for ch, n in sorted(counts.items()):
            print(f"{ch}: {n} rows", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
