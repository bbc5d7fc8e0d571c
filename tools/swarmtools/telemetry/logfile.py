"""A checked reader of LCM log files: every event is validated against the
file before it is trusted.

A log is untrusted input. The lcm package's C reader allocates whatever an
event's length field says and reads into it: a length of 0x7FFFFFFF made the
tools die with SIGSEGV inside it. The log format is small and documented
(LCM's "Log File Format"), so it is read here:

    uint32  sync word 0xEDA1DA01
    int64   event number
    int64   timestamp, microseconds
    int32   channel length
    int32   data length
    bytes   channel (not NUL-terminated)
    bytes   data

all big-endian. An event whose sync word, lengths or size do not fit the
file is an error naming the byte offset where it starts (LogError). Channel
names are bytes: a name that is not UTF-8 is rendered with backslash escapes
(``chan\\xff``), never a decoding traceback, and a backslash in a name is
doubled (``a\\\\b``), so that two different names never read alike (the
CSV export writes a file per name).
"""

from __future__ import annotations

import os
import struct
from collections.abc import Iterator
from typing import NamedTuple

SYNC = 0xEDA1DA01
HEADER = struct.Struct(">Iqqii")
#: Longer channel names than this are taken for corruption (LCM's own
#: limit is far lower).
MAX_CHANNEL = 1024


class LogError(Exception):
    """A file that is not (or no longer) a well-formed LCM log."""


class Event(NamedTuple):
    eventnum: int
    timestamp: int
    channel: str
    data: bytes
    offset: int


def channel_name(raw: bytes) -> str:
    """A channel's bytes as text: UTF-8, with `\\xNN` for each byte that is
    not and `\\\\` for a backslash: one text per name (0x5C is never part
    of a multi-byte UTF-8 sequence, so doubling it in the bytes is safe)."""
    return raw.replace(b"\\", b"\\\\").decode("utf-8", errors="backslashreplace")


#: Bytes read from the file at a time (events are cut from these blocks:
#: three small reads an event cost more than the decoding).
BLOCK = 1 << 20


def events(path: str | os.PathLike) -> Iterator[Event]:
    """Every event of the log at `path`, in order; LogError at the first
    event the file cannot hold."""
    path = os.fspath(path)
    size = os.path.getsize(path)
    hsize = HEADER.size
    unpack = HEADER.unpack_from
    with open(path, "rb") as f:
        buf, pos, offset = b"", 0, 0        # buf[pos] is the file's byte `offset`
        names: dict[bytes, str] = {}
        while offset < size:
            if len(buf) - pos < hsize:
                buf, pos = buf[pos:] + f.read(BLOCK), 0
                if len(buf) < hsize:
                    raise LogError(f"{path}: truncated event at byte {offset}: {len(buf)} of the "
                                   f"{hsize} header bytes")
            sync, num, stamp, clen, dlen = unpack(buf, pos)
            if sync != SYNC:
                raise LogError(f"{path}: corrupt event at byte {offset}: sync word 0x{sync:08X}, "
                               f"expected 0x{SYNC:08X}")
            left = size - offset - hsize
            if not 0 <= clen <= MAX_CHANNEL:
                raise LogError(f"{path}: corrupt event at byte {offset}: channel length {clen}")
            if dlen < 0 or clen + dlen > left:
                raise LogError(f"{path}: corrupt event at byte {offset}: channel and data lengths "
                               f"{clen} + {dlen}, but only {left} bytes are left in the file")
            total = hsize + clen + dlen
            if len(buf) - pos < total:
                buf, pos = buf[pos:] + f.read(max(BLOCK, total)), 0
                if len(buf) < total:
                    raise LogError(f"{path}: truncated event at byte {offset}")
            at = pos + hsize
            raw = buf[at:at + clen]
            name = names.get(raw)
            if name is None:
                name = channel_name(raw)
                if len(names) < 256:        # a log has a few channels; a damaged one, any number
                    names[raw] = name
            yield Event(num, stamp, name, buf[at + clen:at + clen + dlen], offset)
            pos += total
            offset += total


def check(path: str | os.PathLike) -> int:
    """Reads the whole log once; returns its event count (LogError if bad)."""
    return sum(1 for _ in events(path))
