"""What one message may carry into the live view, and what the view keeps.

Telemetry is untrusted input, and the view's work grows with a message's
arrays: a log whose swarm states carried 32,000 values each cost 0.8 s a
state and a page, on the one event loop every page shares.  A message is
cut to these limits as it comes (bound(), once: a log when it is read, a bus
as it hears it), and the page says what was cut (View.note).  Far above
what the toolkit sends (a run's swarm schema has tens of values, a
controller's a few), so a real run is never cut.
"""
from swarmtools.telemetry import common

#: A message's bytes: a bigger one is not decoded at all.
MAX_MESSAGE_BYTES = 16 << 20
#: Characters of one text field (names, labels, paths, details).
MAX_TEXT = 1000
#: Elements an array keeps, by its length field: values, names and metrics
#: become chart columns and table rows.
MAX_BY_LENGTH = {"n_values": 256, "n_states": 256, "n": 256, "n_metrics": 1024, "n_groups": 256, "n_tasks": 64}
#: Any other array (obstacles, lights, shapes, items, robot fills, bridge devices).
MAX_ITEMS = 20_000
#: Robots, schemas, event kinds and chart columns a view keeps (view.py).
MAX_ROBOTS = 20_000
MAX_SCHEMAS = 256
MAX_EVENT_KINDS = 64
MAX_SERIES = 512

_STRUCTS = {}     # LCM class -> its (slot, type name, length field) fields, worked out once


def _fields(cls):
    f = _STRUCTS.get(cls)
    if f is None:
        # A fixed length (robot_detail_t's prox[8]: an int) needs no bound.
        f = _STRUCTS[cls] = [(s, t, d[0] if d and isinstance(d[0], str) else None)
                             for s, t, d in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__, strict=True)]
    return f


def _struct(typename):
    """The class of an inner type ("swarmlcm.scene_shape_t")."""
    return getattr(common.swarmlcm, typename.rsplit(".", 1)[-1])


def _has_text(cls):
    return any(t == "string" or (t not in _PRIMITIVE and _has_text(_struct(t))) for _, t, _ in _fields(cls))


_PRIMITIVE = {"int8_t", "int16_t", "int32_t", "int64_t", "byte", "float", "double", "string", "boolean"}


def bound(msg, where=""):
    """Cuts msg's arrays and texts in place to the limits; returns what was
    cut, one text each ("SWARM_STATE values: 32,000 (first 256 kept)")."""
    cut = []
    fields = _fields(type(msg))
    lengths = {}
    for slot, typename, length in fields:
        v = getattr(msg, slot)
        if length is not None:
            cap = MAX_BY_LENGTH.get(length, MAX_ITEMS)
            if len(v) > cap:
                cut.append(f"{where}{slot}: {len(v):,} (first {cap:,} kept)")
                v = list(v[:cap])
                setattr(msg, slot, v)
            lengths[length] = len(v)       # and a negative length field says 0
            if typename == "string":
                _cut_texts(msg, slot, v, where, cut)
            elif typename not in _PRIMITIVE and _has_text(_struct(typename)):
                for item in v:
                    cut += bound(item, f"{where}{slot}[].")
        elif typename == "string" and len(v) > MAX_TEXT:
            cut.append(f"{where}{slot}: a text of {len(v):,} characters (first {MAX_TEXT:,} kept)")
            setattr(msg, slot, v[:MAX_TEXT])
        elif typename not in _PRIMITIVE:
            cut += bound(v, f"{where}{slot}.")
    for length, n in lengths.items():
        setattr(msg, length, n)
    if type(msg).__name__ == "schema_t":        # a schema names at most as many values as a message keeps
        cap = MAX_BY_LENGTH["n_values"]
        if msg.total > cap or msg.first + msg.n > cap:
            cut.append(f"{where}names past the first {cap}")
            keep = max(0, min(msg.n, cap - msg.first))
            msg.total, msg.first, msg.n = min(msg.total, cap), min(max(msg.first, 0), cap), keep
            msg.names, msg.units, msg.counters, msg.docs = (list(a[:keep]) for a in
                                                            (msg.names, msg.units, msg.counters, msg.docs))
    return sorted(set(cut))


def _cut_texts(msg, slot, texts, where, cut):
    if any(len(t) > MAX_TEXT for t in texts):
        cut.append(f"{where}{slot}: texts of over {MAX_TEXT:,} characters (cut)")
        setattr(msg, slot, [t[:MAX_TEXT] for t in texts])


def decode(data, channel):
    """common.decode, with the message cut to the limits: (message or None,
    what was cut).  A message over MAX_MESSAGE_BYTES is not decoded (None)."""
    if len(data) > MAX_MESSAGE_BYTES:
        return None, [f"{channel}: a message of {len(data):,} bytes (not read; the limit is {MAX_MESSAGE_BYTES:,})"]
    msg = common.decode(data, channel)
    if msg is None:
        return None, []
    return msg, bound(msg, f"{channel} ")
