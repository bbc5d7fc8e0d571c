"""Many LCM messages of one type decoded at once with numpy (load_log's
fast path for the robots' states, the bulk of every log).

A message whose strings and arrays have given lengths has a fixed layout:
Batch.add reads only those lengths (and the run seed, for a filter) from
the bytes and files the message under its layout; Batch.columns then views
each layout's messages as one big-endian numpy structured array and
scatters its fields to typed columns in arrival order.  The checks are the
generated decoder's: the fingerprint, the lengths (a message must end
where its layout does), the version, strings as UTF-8; a message that
fails one is handed back to the caller (`add` returns False) for the
checked decoder to explain.

Supported: types of primitive scalars, strings, and 1-D arrays of a
primitive sized by an earlier integer field (robot_state_t); `supports`
says whether a type is.
"""

from __future__ import annotations

import numpy as np

_SCALARS = {"int8_t": "i1", "int16_t": ">i2", "int32_t": ">i4", "int64_t": ">i8", "byte": "u1",
            "float": ">f4", "double": ">f8", "boolean": "i1"}


def supports(cls) -> bool:
    """True when every field of the LCM type `cls` is a primitive scalar, a
    string, or a 1-D primitive array sized by an earlier field."""
    seen = set()
    for slot, typename, dim in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__, strict=True):
        if dim is None:
            if typename != "string" and typename not in _SCALARS:
                return False
        elif len(dim) != 1 or typename not in _SCALARS or not isinstance(dim[0], str) or dim[0] not in seen:
            return False
        seen.add(slot)
    return True


class Batch:
    """Messages of one LCM type, filed by layout, each with its row."""

    def __init__(self, cls, keep_run: int | None = None):
        assert supports(cls), cls.__name__
        self.cls = cls
        self.fingerprint = cls._get_packed_fingerprint()
        self.keep_run = keep_run
        sizes = {d[0] for d in cls.__dimensions__ if d is not None}
        # The walk over a message after its fingerprint: ("fixed", bytes, [(size slot, offset in the run,
        # bytes)]), ("string",), ("array", size slot, item bytes).
        self.walk: list[tuple] = []
        self.run_at = None
        run_len, run_sizes, at_start = 0, [], True
        for slot, typename, dim in zip(cls.__slots__, cls.__typenames__, cls.__dimensions__, strict=True):
            if dim is None and typename != "string":
                if slot in sizes:
                    run_sizes.append((slot, run_len, np.dtype(_SCALARS[typename]).itemsize))
                if slot == "run" and at_start and keep_run is not None:
                    self.run_at = 8 + run_len
                run_len += np.dtype(_SCALARS[typename]).itemsize
                continue
            if run_len:
                self.walk.append(("fixed", run_len, run_sizes))
            run_len, run_sizes, at_start = 0, [], False
            self.walk.append(("string",) if dim is None else ("array", dim[0], np.dtype(_SCALARS[typename]).itemsize))
        if run_len:
            self.walk.append(("fixed", run_len, run_sizes))
        if keep_run is not None and self.run_at is None and "run" in cls.__slots__:
            raise ValueError(f"{cls.__name__}: its run field is not where a filter can read it")
        self.layouts: dict[tuple, tuple[list[bytes], list[int]]] = {}

    def add(self, data: bytes, row: int) -> bool | None:
        """Files a message: True when it was, None when the run filter
        drops it, False when its bytes do not hold a message of this type
        (the checked decoder is to say why)."""
        if data[:8] != self.fingerprint:
            return False
        at = self.run_at
        if at is not None and int.from_bytes(data[at:at + 8], "big", signed=True) != self.keep_run:
            return None
        key = []
        p = 8
        counts = {}
        n = len(data)
        for w in self.walk:
            kind = w[0]
            if kind == "fixed":
                for slot, off, size in w[2]:
                    counts[slot] = int.from_bytes(data[p + off:p + off + size], "big", signed=True)
                p += w[1]
            elif kind == "string":
                length = int.from_bytes(data[p:p + 4], "big", signed=True) if p + 4 <= n else -1
                if length < 1:
                    return False
                key.append(length)
                p += 4 + length
            else:
                count = counts[w[1]]
                if count < 0:
                    return False
                key.append(count)
                p += count * w[2]
        if p != n:
            return False
        key = tuple(key)
        rows = self.layouts.get(key)
        if rows is None:
            rows = self.layouts[key] = ([], [])
        rows[0].append(data)
        rows[1].append(row)
        return True

    def dtype(self, key: tuple) -> np.dtype:
        """The structured dtype of a message of layout `key`."""
        names, formats = ["_fingerprint"], ["V8"]
        k = iter(key)
        for slot, typename, dim in zip(self.cls.__slots__, self.cls.__typenames__, self.cls.__dimensions__,
                                       strict=True):
            if dim is None and typename != "string":
                names.append(slot)
                formats.append(_SCALARS[typename])
            elif dim is None:
                length = next(k)
                names += [f"_{slot}_len", slot]
                formats += [">i4", f"S{length}"]
            else:
                count = next(k)
                if count:
                    names.append(slot)
                    formats.append((_SCALARS[typename], (count,)))
        return np.dtype({"names": names, "formats": formats})

    def layouts_decoded(self):
        """(row indices, structured array) of every layout, then forgets them."""
        layouts, self.layouts = self.layouts, {}
        for key, (datas, rows) in layouts.items():
            dt = self.dtype(key)
            arr = np.frombuffer(b"".join(datas), dtype=dt)
            del datas
            yield np.asarray(rows, dtype=np.int64), arr
