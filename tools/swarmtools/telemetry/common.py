"""Shared by the telemetry tools: the channels and their types, decoding
any of our messages by its fingerprint (and refusing, with a clear message,
those of another version of the toolkit), reading LCM log files, and the
schemas that name the values of robot_state_t and swarm_state_t.

The message types are the package ``swarmlcm``, generated from lcm_types/
by ``make lcm-types`` and installed beside this package by ``make deps``.

Names are never written into the tools: a robot_state_t's values[k] is
named by the schema_t of kind "controller" whose name is the robot's
controller, a swarm_state_t's values[k] by the schema_t of kind "swarm"
(the columns of the run's timeseries.csv), both on TELEMETRY_SCHEMA.  The
simulator sends each schema whole; a robot sends its controller's a few
entries at a time (first, n of total): `Schemas` puts the pieces together.
"""
import math
import os
from collections import namedtuple

try:
    import swarmlcm
except ImportError as e:       # not generated, or not installed beside this package
    raise SystemExit(f"swarmtools: the LCM message types (package swarmlcm) are missing ({e}): "
                     f"run `make deps` (it generates and installs them)") from None

#: LCM's own default bus (what lcm_create(NULL) and lcm-spy use).
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"

#: The telemetry version these tools read: every type's VERSION constant.
VERSION = 2

#: Channel name -> swarmlcm type name.  The simulator publishes all but
#: BRIDGE_STATUS (sim_host/core/telemetry.h; SCENE and TASK_DRAWING, the
#: picture of the run, telemetry_scene.h); the bridge republishes robots'
#: frames on the same names and adds BRIDGE_STATUS.  Either may put a prefix before
#: them (the bridge's --prefix; the simulator republishes its robots' own
#: frames, robot_telemetry.enabled, on FW_ROBOT_STATE, ...).
CHANNEL_TYPES = {
    "RUN_INFO": "run_info_t",
    "TELEMETRY_SCHEMA": "schema_t",
    "SWARM_STATE": "swarm_state_t",
    "ROBOT_STATE": "robot_state_t",
    "SWARM_EVENT": "event_t",
    "RUN_SUMMARY": "run_summary_t",
    "SCENE": "scene_t",
    "TASK_DRAWING": "task_drawing_t",
    "BRIDGE_STATUS": "bridge_status_t",
    # A run under control (swarmsim --control, sim_host/core/control.h),
    # on its control bus: commands, its answers, the selected robot.
    "SWARM_CONTROL": "control_t",
    "SWARM_CONTROL_STATUS": "control_status_t",
    "ROBOT_DETAIL": "robot_detail_t",
}

#: Every type of lcm_types/, nested ones (scene_*_t, bridge_device_t) included.
TYPE_NAMES = ("robot_state_t", "swarm_state_t", "event_t", "run_info_t", "run_summary_t",
              "schema_t", "scene_t", "scene_obstacle_t", "scene_light_t", "task_drawing_t",
              "scene_shape_t", "scene_item_t", "bridge_status_t", "bridge_device_t",
              "control_t", "control_status_t", "robot_detail_t")

#: Packed fingerprints of the types of earlier telemetry versions -> (version, type).
OLD_FINGERPRINTS = {
    bytes.fromhex("3715081f471fd9b6"): (1, "robot_state_t"),
    bytes.fromhex("ef676ded075c496f"): (1, "swarm_state_t"),
    bytes.fromhex("43c251253e108b1f"): (1, "event_t"),
    bytes.fromhex("0bde89823a83dac9"): (1, "run_info_t"),
    bytes.fromhex("cf2793015152e50e"): (1, "run_summary_t"),
}


def split_channel(channel):
    """(prefix, name) of one of our channels ("FW_", "ROBOT_STATE"), or
    None for another program's channel."""
    if channel in CHANNEL_TYPES:
        return "", channel
    for name in CHANNEL_TYPES:       # no name of ours ends another
        if channel and channel.endswith(name):
            return channel[:-len(name)], name
    return None


def type_class(name):
    """The swarmlcm class of a type name ("robot_state_t")."""
    return getattr(swarmlcm, name)


#: Packed 8-byte fingerprint -> class, for every type of ours.
_by_fingerprint = {type_class(n)._get_packed_fingerprint(): type_class(n) for n in TYPE_NAMES}


class IncompatibleMessage(Exception):
    """A message written by another version of the toolkit (an older
    type's fingerprint, a `version` field that is not VERSION), or one on
    a channel of ours that does not decode as the channel's type."""

    def __init__(self, channel, type_name, why, version=None):
        self.channel = channel
        self.type_name = type_name
        self.why = why              # "old", "version" or "undecodable"
        self.version = version      # the telemetry version the message has, when known
        super().__init__(self.explain())

    def explain(self, source=None, log=True):
        """One sentence for the user; `source` is the log file or the
        bus's URL (log False: a live bus)."""
        where = f"{source}: " if source else ""
        on = f" on {self.channel}" if self.channel else ""
        newer = self.why != "undecodable" and self.version is not None and self.version > VERSION
        if self.why == "undecodable":
            what = (f"a message{on} is not a {self.type_name} of telemetry v{VERSION} (written by another "
                    f"version of the toolkit, or damaged)")
        else:
            who = (f"{'a newer' if newer else 'an older'} version of the toolkit "
                   f"(telemetry v{self.version}, {self.type_name})")
            what = f"written by {who}" if log else f"a message{on} comes from {who}"
        if newer:
            advice = "update these tools"
        elif log:
            advice = f"re-run the simulation to get a v{VERSION} log"
        else:
            advice = f"update its publisher (the simulator, or the robot's firmware) to telemetry v{VERSION}"
        return f"{where}{what}; {advice}"


def decode(data, channel=None):
    """Decodes any of our messages from its bytes.  Returns None for bytes
    that are no type of ours on a channel that is not ours (another
    program's messages on a shared bus); raises IncompatibleMessage for a
    type of an earlier telemetry version (on any channel), for a message of
    the wrong version, and for anything on one of our channels (prefixed or
    not) that does not decode."""
    data = bytes(data)
    head = data[:8]
    cls = _by_fingerprint.get(head)
    if cls is None:
        old = OLD_FINGERPRINTS.get(head)
        if old is not None:
            raise IncompatibleMessage(channel, old[1], "old", version=old[0])
        ours = split_channel(channel)
        if ours is not None:
            raise IncompatibleMessage(channel, CHANNEL_TYPES[ours[1]], "undecodable")
        return None
    try:
        msg = cls.decode(data)
    except Exception:   # malformed: a decoder raises ValueError, struct.error, UnicodeDecodeError, ...
        raise IncompatibleMessage(channel, cls.__name__, "undecodable") from None
    want = getattr(cls, "VERSION", None)
    if want is not None and msg.version != want:
        raise IncompatibleMessage(channel, cls.__name__, "version", version=msg.version)
    return msg


def lcm_module():
    try:
        import lcm
    except ImportError as e:
        raise SystemExit(f"the `lcm` Python module is missing ({e}): run the tools with .venv/bin/python "
                         f"(`make deps` installs it)") from e
    return lcm


def read_log(path, prog, decoder=None):
    """Yields (log event, message) for each event of an LCM log file;
    message is None for another program's messages.  Events are read by the
    checked reader (logfile.py), never by the lcm package's C reader, so a
    corrupt length is an error naming its byte offset, not a crash.  Stops
    the tool with a clear message (SystemExit) when the file is missing, no
    LCM log or corrupt, and at the first message of another toolkit version.
    decoder(data, channel) replaces decode (the live view's bounds it)."""
    from . import logfile
    path = str(path)
    if not os.path.isfile(path):
        raise SystemExit(f"{prog}: {path}: no such file")
    events = 0
    try:
        for ev in logfile.events(path):
            events += 1
            try:
                msg = (decoder or decode)(ev.data, ev.channel)
            except IncompatibleMessage as e:
                raise SystemExit(f"{prog}: {e.explain(path)}") from None
            yield ev, msg
    except logfile.LogError as e:
        if events == 0:
            raise SystemExit(f"{prog}: {path}: not an LCM log ({e})") from None
        raise SystemExit(f"{prog}: {e}") from None
    except OSError as e:
        raise SystemExit(f"{prog}: {path}: cannot read: {e.strerror}") from None
    if events == 0 and os.path.getsize(path) > 0:
        raise SystemExit(f"{prog}: {path}: not an LCM log (no events in it)")


# ---------------------------------------------------------------- schemas

#: One value a schema names.
Entry = namedtuple("Entry", "name unit counter doc")


class Schema:
    """One schema_t, put together from its pieces."""

    def __init__(self, kind, name, total):
        self.kind = kind
        self.name = name
        self.total = total
        self.entries = {}           # index -> Entry

    def add(self, msg):
        for k in range(msg.n):
            self.entries[msg.first + k] = Entry(msg.names[k], msg.units[k], bool(msg.counters[k]), msg.docs[k])

    @property
    def complete(self):
        return all(k in self.entries for k in range(self.total))

    def entry(self, k):
        """Entry k, or a stand-in named value<k> while that piece has not come."""
        e = self.entries.get(k)
        return e if e is not None else Entry(f"value{k}", "", False, "")

    def names(self, n=None):
        return [self.entry(k).name for k in range(self.total if n is None else n)]


#: The core's first two swarm values (every run's timeseries.csv starts with
#: them): the time axis of plots, shown apart by the monitor.
TIME_VALUES = ("step", "time_s")


def schema_key(msg):
    """(kind, name) of the schema that names msg.values, or None."""
    kind = type(msg).__name__
    if kind == "robot_state_t":
        return ("controller", msg.controller)
    if kind == "swarm_state_t":
        return ("swarm", "swarm")
    return None


class Schemas:
    """The schemas heard so far, by run, kind and name.  A schema of the
    same run, kind and name with another total starts afresh (a robot with
    other firmware); a run without its own schema of a kind and name uses
    the latest heard of any run."""

    def __init__(self):
        self._by_run = {}          # (run, kind, name) -> Schema
        self._latest = {}          # (kind, name) -> Schema

    def add(self, msg):
        key = (msg.run, msg.kind, msg.name)
        s = self._by_run.get(key)
        if s is None or s.total != msg.total or (msg.first == 0 and msg.n == msg.total):
            s = self._by_run[key] = Schema(msg.kind, msg.name, msg.total)
        s.add(msg)
        self._latest[(msg.kind, msg.name)] = s
        return s

    def get(self, kind, name, run=None):
        s = self._by_run.get((run, kind, name))
        return s if s is not None else self._latest.get((kind, name))

    def of(self, msg):
        """The schema of a robot_state_t's or swarm_state_t's values (an
        empty one while none has come)."""
        kind, name = schema_key(msg)
        s = self.get(kind, name, msg.run)
        return s if s is not None else Schema(kind, name, 0)

    def names(self, msg):
        """Names of msg.values, value<k> for those not (yet) named."""
        return self.of(msg).names(len(msg.values))

    def __iter__(self):
        return iter(self._latest.values())

    def count(self):
        """Schemas kept, every run's."""
        return len(self._by_run)


def value_column(schema_name, value_name):
    """The CSV column of a named value: "forager.threshold", "swarm.food_nest"."""
    return f"{schema_name}.{value_name}"


def fmt_number(v, counter=False, spec="{:.4g}", none="-"):
    """A value for people: counts as integers, other numbers with `spec`,
    NaN as `none`."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return none
    if counter or (isinstance(v, float) and v.is_integer() and abs(v) < 1e9):
        return str(int(v))
    return spec.format(v)
