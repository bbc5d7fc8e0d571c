"""Many LCM messages of one type decoded at once with numpy (load_log's
fast path for the robots' states, the bulk of every log).

A message whose strings and arrays have given lengths has a fixed layout.
Batch.add only checks a message's fingerprint (and its run seed, for a
filter) and keeps its bytes; layouts_decoded then walks all of them at
once with numpy (each string's and array's length, read at once for every
message), groups them by layout, and views each layout's messages as one
big-endian structured array.  The checks are the generated decoder's: the
fingerprint, the lengths (a message must end where its layout does; a
length that points past it is refused), then, by the caller, the version
and the strings as UTF-8.  A message that fails one is raised as
BadMessage, with its bytes, for the checked decoder to explain.

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
        self.datas: list[bytes] = []
        self.rows: list[int] = []

    def add(self, data: bytes, row: int) -> bool | None:
        """Keeps a message for the batch: True when it was, None when the
        run filter drops it, False when it is no message of this type
        (another fingerprint: the checked decoder is to say why)."""
        if data[:8] != self.fingerprint:
            return False
        at = self.run_at
        if at is not None and int.from_bytes(data[at:at + 8], "big", signed=True) != self.keep_run:
            return None
        self.datas.append(data)
        self.rows.append(row)
        return True

    @property
    def pending(self) -> int:
        return len(self.rows)

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

    def layouts_decoded(self, block: int = 8192):
        """(row indices, structured array) of each layout of the messages
        kept, then forgets them.  Raises BadMessage for the first message
        whose lengths do not hold."""
        datas, rows, self.datas, self.rows = self.datas, self.rows, [], []
        if not datas:
            return
        lengths = np.fromiter(map(len, datas), dtype=np.int64, count=len(datas))
        buf = np.frombuffer(b"".join(datas), dtype=np.uint8)
        starts = np.concatenate(([0], np.cumsum(lengths)[:-1]))
        ends = starts + lengths
        p = starts + 8
        ok = np.ones(len(datas), dtype=bool)
        keys, counts = [], {}
        for w in self.walk:
            if w[0] == "fixed":
                for slot, off, size in w[2]:
                    counts[slot] = _read_be(buf, p + off, size)
                p = p + w[1]
            elif w[0] == "string":
                ok &= p + 4 <= ends
                length = _read_be(buf, p, 4)
                ok &= length >= 1
                length = np.where(ok, length, 1)
                keys.append(length)
                p = p + 4 + length
            else:
                count = counts[w[1]]
                ok &= count >= 0
                count = np.where(ok, count, 0)
                keys.append(count)
                p = p + count * w[2]
            ok &= p <= ends
        ok &= p == ends
        if not ok.all():
            raise BadMessage(datas[int(np.flatnonzero(~ok)[0])])
        del datas
        rows = np.asarray(rows, dtype=np.int64)
        if keys:
            layout, which = np.unique(np.column_stack(keys), axis=0, return_inverse=True)
            which = which.ravel()
        else:
            layout, which = np.zeros((1, 0), dtype=np.int64), np.zeros(len(rows), dtype=np.int64)
        for j, key in enumerate(layout):
            dt = self.dtype(tuple(int(k) for k in key))
            sel = np.flatnonzero(which == j)
            parts = []
            for k in range(0, len(sel), block):
                at = starts[sel[k:k + block]]
                raw = buf[at[:, None] + np.arange(dt.itemsize)]
                parts.append(raw.view(dt).ravel())
            yield rows[sel], (np.concatenate(parts) if len(parts) > 1 else parts[0])


class BadMessage(ValueError):
    """A message whose lengths do not hold (its bytes: .data)."""

    def __init__(self, data: bytes):
        super().__init__("a message whose lengths do not hold")
        self.data = data


def _read_be(buf: np.ndarray, at: np.ndarray, size: int) -> np.ndarray:
    """The signed big-endian integers of `size` bytes at offsets `at` of
    `buf` (int64; offsets past the end read its last byte: the caller's
    length checks refuse those messages)."""
    idx = np.minimum(at[:, None] + np.arange(size), len(buf) - 1)
    raw = np.ascontiguousarray(buf[idx])
    code = {1: "i1", 2: ">i2", 4: ">i4", 8: ">i8"}[size]
    return raw.view(code).ravel().astype(np.int64)
