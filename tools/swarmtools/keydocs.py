"""The documented name and unit of a scenario key, read from the simulator's
own `swarmsim --help` (its table of every key, with its meaning and unit),
so that a figure's axis says "robots in the group" or "forward wheel speed
(steps/s)" beside the raw `--set` key, never a name typed twice.

    label("robots.0.count", sim)   -> "robots in the group (robots.0.count)"
    label("duration", sim)         -> "simulated time, s (duration)"

A key the help does not document keeps its raw name.
"""

from __future__ import annotations

import functools
import re
import subprocess
from pathlib import Path

# A row of the help's key table: key, type, default, range (which may hold
# spaces: "[0, 1]", "<= 63 chars"), meaning.
_ROW = re.compile(r"^  (\S+)\s+(\S+)\s+(\S+)\s+(\[[^\]]*\](?:\|\S+)?|<= \d+(?: chars)?|\S+)\s+(.*)$")


@functools.lru_cache(maxsize=8)
def key_docs(sim: str) -> dict[str, str]:
    """{key: meaning} of the help's scenario keys ("robots[].count": ...);
    a controller's params under "robots[].params.<key>", the first
    controller's meaning where several define one key.  Empty when the
    simulator cannot be run."""
    try:
        text = subprocess.run([sim, "--help"], capture_output=True, text=True, timeout=30, check=True).stdout
    except (OSError, subprocess.SubprocessError):
        return {}
    docs: dict[str, str] = {}
    on = False
    for line in text.splitlines():
        if line.startswith("Scenario keys"):
            on = True
            continue
        m = _ROW.match(line) if on else None
        if m and m.group(1) != "key":
            docs.setdefault(m.group(1), m.group(5).strip())
    return docs


def generic(key: str) -> str:
    """A --set key as the help names it: list indices become []
    (robots.0.params.speed_steps_s -> robots[].params.speed_steps_s)."""
    return re.sub(r"\.\d+(?=\.|$)", "[]", key)


def meaning(key: str, sim: str | Path) -> str | None:
    """The help's words for a key, without the parenthesised asides."""
    doc = key_docs(str(sim)).get(generic(key))
    if not doc:
        return None
    while re.search(r"\([^()]*\)", doc):        # asides, innermost first
        doc = re.sub(r"\s*\([^()]*\)", "", doc)
    return doc.split(";")[0].strip().rstrip(":") or None   # the meaning, before any remark


def label(key: str, sim: str | Path) -> str:
    """An axis label: the key's documented meaning and unit, then the key."""
    words = meaning(key, sim)
    return f"{words} ({key})" if words else key
