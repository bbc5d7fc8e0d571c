#!/usr/bin/env python3
"""Export channels of an LCM log to CSV.

Every message of a channel becomes a row, every field a column, named as in
lcm_types/ (nested structs as parent.field).  Arrays go into one cell,
joined with ';', except a pair NAME_names / NAME_values (RUN_SUMMARY's
metric_names / metric_values), which becomes one column per name.
Numbers print as the simulator's own CSV does: doubles with %.10g (the same
text for the same bits), floats with the fewest digits that give the same
float32, integers as integers, booleans as 1 / 0, robot_state_t.task_state
as its letter, event_t.kind as its name (pickup, deposit, oae, failure,
state_change).

    export_csv.py run_1/telemetry.lcmlog --channel SWARM_STATE -o swarm.csv
    export_csv.py run_1/telemetry.lcmlog -o csv/          # every channel: csv/<CHANNEL>.csv
    export_csv.py run_1/telemetry.lcmlog --timeseries 10  # the run's timeseries.csv again
"""
import argparse
import csv
import math
import os
import re
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import common  # noqa: E402

#: The columns of a run's timeseries.csv (sim_host/metrics.c), all fields
#: of swarm_state_t.
TIMESERIES_FIELDS = ["step", "time_s", "oae_total", "robot_contacts", "static_contacts", "distance_m",
                     "food_nest", "food_collected", "waiting", "searching", "returning", "active"]

def timeseries_fields(msg):
    """timeseries.csv's columns: the foraging ones only in foraging runs."""
    return TIMESERIES_FIELDS if msg.foraging else TIMESERIES_FIELDS[:6]


PRIMITIVES = {"int8_t", "int16_t", "int32_t", "int64_t", "byte", "float", "double", "string", "boolean"}


def fmt_double(v):
    return "%.10g" % v


def fmt_float(v):
    """Shortest text that reads back as the same float32."""
    if math.isnan(v) or math.isinf(v):
        return "%g" % v
    packed = struct.pack("<f", v)
    for digits in range(6, 10):
        text = "%.*g" % (digits, v)
        if struct.pack("<f", float(text)) == packed:
            return text
    return "%.9g" % v


def fmt_value(typename, v):
    if typename == "double":
        return fmt_double(v)
    if typename == "float":
        return fmt_float(v)
    if typename == "boolean":
        return "1" if v else "0"
    if typename == "byte" and isinstance(v, (bytes, bytearray)):
        return v.hex()
    return str(v)


def flatten(msg, prefix=""):
    """(column, text) pairs of one message, in field order."""
    out = []
    slots = list(msg.__slots__)
    types = list(msg.__typenames__)
    dims = list(msg.__dimensions__)
    names_of = {s[:-len("_names")]: s for s in slots if s.endswith("_names")}
    paired = set()
    for base, names_slot in names_of.items():
        if base + "_values" in slots:
            paired.update({names_slot, base + "_values"})
    for slot, typename, dim in zip(slots, types, dims):
        v = getattr(msg, slot)
        if slot in paired:
            if slot.endswith("_values"):
                base = slot[:-len("_values")]
                vtype = types[slots.index(slot)]
                for name, value in zip(getattr(msg, base + "_names"), v):
                    out.append((prefix + name, fmt_value(vtype, value)))
            continue
        if typename == "int8_t" and slot == "task_state" and dim is None:
            out.append((prefix + slot, common.task_letter(v)))
        elif slot == "kind" and type(msg).__name__ == "event_t":
            out.append((prefix + slot, common.EVENT_KINDS.get(v, str(v))))
        elif dim is None and typename in PRIMITIVES:
            out.append((prefix + slot, fmt_value(typename, v)))
        elif dim is None:
            out.extend(flatten(v, prefix + slot + "."))
        elif typename in PRIMITIVES:
            if typename == "byte" and isinstance(v, (bytes, bytearray)):
                out.append((prefix + slot, bytes(v).hex()))
            else:
                out.append((prefix + slot, ";".join(fmt_value(typename, x) for x in v)))
        else:
            cells = []
            for item in v:
                cells.append("{" + ",".join(f"{k}={t}" for k, t in flatten(item)) + "}")
            out.append((prefix + slot, ";".join(cells)))
    return out


class ChannelWriter:
    """Streams one channel's rows to a CSV file.  The header comes from the
    first message (and --fields); rows are written one message late so that
    the last one can always be kept (--every)."""

    def __init__(self, path, fields=None, every=None, log_time=False):
        self.path = path
        self.fields = fields
        self.every = every
        self.log_time = log_time
        self.header = None
        self.pending = None
        self.rows = 0
        self.dropped_columns = set()
        self._file = sys.stdout if path == "-" else open(path, "w", newline="")
        self._csv = csv.writer(self._file, lineterminator="\n")

    def add(self, utime, msg):
        cols = flatten(msg)
        if self.log_time:
            cols.insert(0, ("log_utime", str(utime)))
        row = dict(cols)
        if self.header is None:
            if callable(self.fields):
                self.fields = self.fields(msg)
            if self.fields:
                missing = [f for f in self.fields if f not in row]
                if missing:
                    raise SystemExit(f"export_csv: {type(msg).__name__} has no field(s) {', '.join(missing)}; "
                                     f"it has: {', '.join(c for c, _ in cols)}")
                self.header = list(self.fields)
            else:
                self.header = [c for c, _ in cols]
            self._csv.writerow(self.header)
        if not self.fields:
            self.dropped_columns.update(set(row) - set(self.header))
        keep = True
        if self.every:
            step = getattr(msg, "step", None)
            keep = step is not None and step % self.every == 0
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


def export(log_path, channels=None, out="-", fields=None, every=None, log_time=False, run=None):
    """Writes the CSV(s); returns {channel: rows}."""
    lcm = common.lcm_module()
    common.swarmlcm()
    patterns = [re.compile(f"^(?:{c})$") for c in channels] if channels else None
    try:
        log = lcm.EventLog(log_path, "r")
    except (IOError, OSError) as e:
        raise SystemExit(f"export_csv: {log_path}: {e}") from None
    writers = {}
    unknown = set()
    to_dir = out != "-" and (out.endswith(os.sep) or os.path.isdir(out))
    for ev in log:
        if patterns and not any(p.match(ev.channel) for p in patterns):
            continue
        msg = common.decode(ev.data)
        if msg is None:
            unknown.add(ev.channel)
            continue
        if run is not None and getattr(msg, "run", run) != run:
            continue
        w = writers.get(ev.channel)
        if w is None:
            if writers and not to_dir:
                raise SystemExit(f"export_csv: the log has several channels ({', '.join(sorted(writers))}, "
                                 f"{ev.channel}, ...): choose one with --channel, or give -o a directory")
            if to_dir:
                os.makedirs(out, exist_ok=True)
                path = os.path.join(out, f"{ev.channel}.csv")
            else:
                path = out
            w = writers[ev.channel] = ChannelWriter(path, fields, every, log_time)
        w.add(ev.timestamp, msg)
    log.close()
    for w in writers.values():
        w.close()
        if w.dropped_columns:
            print(f"export_csv: {w.path}: columns that appeared after the first row were left out: "
                  f"{', '.join(sorted(w.dropped_columns))}", file=sys.stderr)
    if unknown:
        print(f"export_csv: channels of unknown types skipped: {', '.join(sorted(unknown))}", file=sys.stderr)
    return {ch: w.rows for ch, w in writers.items()}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
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
    fields = args.fields.split(",") if args.fields else None
    channels, every = args.channel, args.every
    if args.timeseries:
        channels, fields, every = ["SWARM_STATE"], timeseries_fields, args.timeseries
    counts = export(args.log, channels, args.out, fields, every, args.log_time, args.run)
    if not counts:
        print("export_csv: no messages matched", file=sys.stderr)
        return 1
    if args.out != "-":
        for ch, n in sorted(counts.items()):
            print(f"{ch}: {n} rows", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
