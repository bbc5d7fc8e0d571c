"""Properties of the checked LCM log reader (swarmtools.telemetry.logfile)
and of the CSV export's file names, which every tool builds from logs,
untrusted input:

- any bytes as a log: the reader yields events or raises LogError naming a
  byte offset, never anything else, and reads nothing past the file;
- two different channel names (any bytes, and a name beside the text an
  escaping reader shows for it) never read as the same text, and a name in
  UTF-8 without a backslash reads as itself;
- well-formed logs of any events read back exactly, and a log cut anywhere
  inside an event is refused at that event's offset;
- any channel names (slashes, dots, '..', non-ASCII): the export's file
  names are plain, distinct (case-insensitively), and stay in the folder.
"""
import os
import struct
import tempfile
import unittest

from hypothesis import given
from hypothesis import strategies as st

from swarmtools.telemetry import logfile
from swarmtools.telemetry.export_csv import file_names

events_st = st.lists(st.tuples(st.integers(-2**40, 2**40), st.binary(max_size=40), st.binary(max_size=300)),
                     max_size=8)


def encode(events):
    out = b""
    for i, (stamp, channel, data) in enumerate(events):
        out += struct.pack(">Iqqii", logfile.SYNC, i, stamp, len(channel), len(data)) + channel + data
    return out


class LogReader(unittest.TestCase):
    def read(self, blob):
        with tempfile.NamedTemporaryFile(suffix=".lcmlog", delete=False) as f:
            f.write(blob)
        try:
            return list(logfile.events(f.name))
        finally:
            os.unlink(f.name)

    @given(st.binary(max_size=2000))
    def test_any_bytes_give_events_or_a_log_error(self, blob):
        try:
            evs = self.read(blob)
        except logfile.LogError as e:
            self.assertRegex(str(e), r"at byte \d+")
            return
        self.assertLessEqual(sum(logfile.HEADER.size + len(e.data) for e in evs), len(blob))

    @given(events_st)
    def test_round_trip(self, events):
        evs = self.read(encode(events))
        self.assertEqual([(e.timestamp, e.data) for e in evs], [(s, d) for s, _, d in events])
        self.assertEqual([e.channel for e in evs], [logfile.channel_name(c) for _, c, _ in events])

    @given(events_st.filter(bool), st.data())
    def test_a_cut_log_is_refused_at_the_cut_event(self, events, data):
        blob = encode(events)
        starts, at = [], 0
        for _, c, d in events:
            starts.append(at)
            at += logfile.HEADER.size + len(c) + len(d)
        cut = data.draw(st.integers(1, len(blob) - 1))
        if cut in starts:
            return      # a cut between events is a shorter, valid log
        owner = max(s for s in starts if s < cut)
        with self.assertRaisesRegex(logfile.LogError, f"at byte {owner}"):
            self.read(blob[:cut])


# Names made of the pieces an escape is made of (a backslash, 'x', hex
# digits, bytes that are not UTF-8), so that near-collisions are common.
escape_like = st.lists(st.sampled_from([b"\\", b"x", b"f", b"F", b"0", b"5", b"c", b"\xff", b"\xc3", b"\xa9",
                                        b"\x80", b"a", b"/"]), max_size=12).map(b"".join)
names = st.one_of(st.binary(max_size=30), escape_like)


class ChannelNames(unittest.TestCase):
    @given(names, names)
    def test_two_names_never_read_alike(self, a, b):
        # Before: b"X\xff" and the plain text "X\\xff" both read "X\\xff".
        self.assertEqual(logfile.channel_name(a) == logfile.channel_name(b), a == b)

    @given(names)
    def test_a_name_and_its_escaped_text_read_apart(self, raw):
        # A log may hold both a raw name and the text an escaping reader
        # would show for it (b"X\xff" and b"X\\xff"): two channels.
        twin = raw.decode("utf-8", errors="backslashreplace").encode()
        self.assertEqual(logfile.channel_name(raw) == logfile.channel_name(twin), raw == twin)

    @given(st.text(max_size=30).filter(lambda t: "\\" not in t))
    def test_plain_names_read_as_they_are(self, text):
        self.assertEqual(logfile.channel_name(text.encode()), text)     # hypothesis' text has no surrogates


class ExportNames(unittest.TestCase):
    @given(st.lists(st.text(max_size=40), unique=True, max_size=12))
    def test_file_names_are_plain_distinct_and_inside(self, channels):
        names = file_names(channels)
        self.assertEqual(set(names), set(channels))
        low = [n.lower() for n in names.values()]
        self.assertEqual(len(low), len(set(low)))
        for n in names.values():
            self.assertRegex(n, r"^[A-Za-z0-9_-][A-Za-z0-9_.-]*\.csv$")
            self.assertEqual(os.path.basename(n), n)
