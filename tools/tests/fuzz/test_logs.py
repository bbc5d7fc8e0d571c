"""Properties of the checked LCM log reader (swarmtools.telemetry.logfile)
and of the CSV export's file names, which every tool builds from logs,
untrusted input:

- any bytes as a log: the reader yields events or raises LogError naming a
  byte offset, never anything else, and reads nothing past the file;
- two different channel names (any bytes) never read as the same text, and
  a name in UTF-8 without a backslash reads as itself;
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


class ChannelNames(unittest.TestCase):
    @given(st.binary(max_size=30), st.binary(max_size=30))
    def test_two_names_never_read_alike(self, a, b):
        # Before: b"X\xff" and the plain text "X\\xff" both read "X\\xff".
        self.assertEqual(logfile.channel_name(a) == logfile.channel_name(b), a == b)

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
