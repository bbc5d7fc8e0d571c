"""The page's commands over the WebSocket, checked before anything acts on
them: a command is a JSON object {"cmd": NAME, FIELD: VALUE, ...} of at
most MAX_TEXT characters whose fields are exactly those COMMANDS gives
NAME, each of its kind.  Anything else (not JSON, too deep, a
number too long for Python's int, `true` for a speed, a field too many) is
answered with one line of text, never a traceback.
"""
import json
import math

#: Characters of one command's text: a command is a few words.
MAX_TEXT = 1000

#: Field kinds: a test of the decoded JSON value, and what it must be.
KINDS = {
    # An int of 900 digits is a JSON number too: compared, never made a float.
    "number": (lambda v: not isinstance(v, bool) and (isinstance(v, float) and math.isfinite(v)
                                                      or isinstance(v, int) and abs(v) <= 1e308),
               "a finite number"),
    "integer": (lambda v: not isinstance(v, bool) and isinstance(v, int) and -(1 << 31) <= v < (1 << 31),
                "a whole number"),
    # A controller's key or its value as a scenario writes it: a word, never a document.
    "word": (lambda v: isinstance(v, str) and 0 < len(v) <= 64 and v.isprintable(), "a word of 1 to 64 characters"),
    "boolean": (lambda v: isinstance(v, bool), "true or false"),
}

#: Command name -> {field: kind}.  A new command is a line here and a
#: branch in server.Session.apply.
COMMANDS = {
    "play": {},
    "pause": {},
    "speed": {"value": "number"},
    "seek": {"value": "number"},
    # A run under control (swarmsim --control); step also steps a log.
    "step": {"value": "integer"},
    "move": {"robot": "integer", "x": "number", "y": "number", "theta": "number"},
    "select": {"robot": "integer"},
    # A live key of the robot's controller; group: of every robot of the robot's group.
    "set": {"robot": "integer", "group": "boolean", "key": "word", "value": "word"},
}


class BadCommand(ValueError):
    """A command the page should not have sent: its text says why."""


def parse(text):
    """The command in a WebSocket text message: (name, {field: value})."""
    if len(text) > MAX_TEXT:
        raise BadCommand(f"a command is at most {MAX_TEXT} characters (got {len(text):,})")
    try:
        cmd = json.loads(text)
    except (ValueError, RecursionError):     # JSONDecodeError, an int of over 4,300 digits, too deep
        raise BadCommand("a command is a JSON object") from None
    return check(cmd)


def check(cmd):
    """(name, fields) of a decoded command, or BadCommand."""
    if not isinstance(cmd, dict):
        raise BadCommand("a command is a JSON object")
    name = cmd.get("cmd")
    if not isinstance(name, str) or name not in COMMANDS:
        shown = repr(name) if isinstance(name, str) and len(name) <= 40 else "that"
        raise BadCommand(f"unknown command {shown}: one of {', '.join(COMMANDS)}")
    want = COMMANDS[name]
    extra = sorted(k for k in cmd if k != "cmd" and k not in want)
    if extra:
        raise BadCommand(f"{name}: unknown field {', '.join(repr(k[:40]) for k in extra[:3])}"
                         + (f" (it takes {', '.join(want)})" if want else " (it takes none)"))
    fields = {}
    for field, kind in want.items():
        if field not in cmd:
            raise BadCommand(f"{name}: needs {field}, {KINDS[kind][1]}")
        ok, what = KINDS[kind]
        if not ok(cmd[field]):
            raise BadCommand(f"{name}: {field} needs {what}, got {_shown(cmd[field])}")
        fields[field] = cmd[field]
    return name, fields


def _shown(v):
    try:
        text = json.dumps(v)
    except (ValueError, RecursionError):
        text = type(v).__name__
    return text if len(text) <= 40 else text[:37] + "..."
