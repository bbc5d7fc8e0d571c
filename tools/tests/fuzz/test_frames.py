"""Properties of the telemetry frame decoder (swarmtools.telemetry.frames),
which the bridge runs on whatever a serial port delivers:

- any bytes, cut into any chunks, give the same frames and counts as fed
  whole, and never raise; every byte is counted;
- frames between arbitrary garbage all come out, in order, and every
  non-empty run of garbage between two zeros is counted once as an error;
- a single bit flipped in a frame's stuffed data (not a COBS code byte,
  not turned into a zero) loses that frame only: CRC-16 catches every
  single-bit error;
- the firmware's encoder (telemetry_frame.c, through ctypes) and the
  Python one write the same bytes, which decode to what went in.
"""
import unittest

from hypothesis import assume, given
from hypothesis import strategies as st

from swarmtools.telemetry.frames import MAX_PAYLOAD, Frame, FrameDecoder, encode_frame

from ..telemetry.helpers import c_encoder

frames_st = st.builds(Frame, channel=st.integers(0, 255), robot_id=st.integers(0, 0xFFFF),
                      seq=st.integers(0, 0xFFFF), payload=st.binary(max_size=MAX_PAYLOAD))


def feed_in_chunks(data, cuts):
    d = FrameDecoder()
    got, at = [], 0
    for cut in sorted(cuts) + [len(data)]:
        got += d.feed(data[at:cut])
        at = max(at, cut)
    return got, d.stats


def runs(garbage):
    """Non-empty runs between zeros in a garbage segment that sits between
    two frames (each frame ends and starts with a zero)."""
    return sum(1 for r in garbage.split(b"\x00") if r)


def code_positions(wire):
    """Indexes of the COBS code bytes of one frame on the wire (0, COBS, 0)."""
    out, i = set(), 1
    while i < len(wire) - 1:
        out.add(i)
        i += wire[i]
    return out


class Decoder(unittest.TestCase):
    @given(st.binary(max_size=2000), st.lists(st.integers(0, 2000), max_size=12))
    def test_any_bytes_in_any_chunks(self, data, cuts):
        whole = FrameDecoder()
        frames = whole.feed(data)
        got, stats = feed_in_chunks(data, [c for c in cuts if c <= len(data)])
        self.assertEqual(got, frames)
        self.assertEqual(stats, whole.stats)
        self.assertEqual(stats.bytes, len(data))
        for f in frames:
            self.assertLessEqual(len(f.payload), MAX_PAYLOAD)

    @given(st.lists(st.tuples(st.binary(max_size=300), frames_st), max_size=8),
           st.binary(max_size=249).map(lambda b: b.replace(b"\x00", b"\x01")),   # a frame cut short
           st.lists(st.integers(0, 5000), max_size=6))
    def test_frames_between_garbage(self, items, tail, cuts):
        for g, _ in items:
            assume(not FrameDecoder().feed(b"\x00" + g + b"\x00"))   # garbage that is not itself a frame
        wire = b"".join(g + encode_frame(f.channel, f.robot_id, f.seq, f.payload) for g, f in items)
        got, stats = feed_in_chunks(wire + tail, [c for c in cuts if c <= len(wire) + len(tail)])
        self.assertEqual(got, [f for _, f in items])
        # The garbage before the first frame runs into its leading zero; the
        # tail has no zero after it and is not finished.
        errors = stats.crc_errors + stats.framing_errors + stats.oversize
        self.assertEqual(errors, sum(runs(g) for g, _ in items))

    @given(st.lists(frames_st, min_size=1, max_size=5), st.data())
    def test_a_flipped_bit_loses_its_frame_only(self, sent, data):
        wires = [bytearray(encode_frame(f.channel, f.robot_id, f.seq, f.payload)) for f in sent]
        k = data.draw(st.integers(0, len(sent) - 1))
        w = wires[k]
        where = [i for i in range(1, len(w) - 1) if i not in code_positions(w)]
        assume(where)
        i = data.draw(st.sampled_from(where))
        bit = data.draw(st.integers(0, 7))
        assume(w[i] ^ (1 << bit) != 0)
        w[i] ^= 1 << bit
        d = FrameDecoder()
        self.assertEqual(d.feed(b"".join(wires)), sent[:k] + sent[k + 1:])
        # A CRC error, or a framing error when the bit was the version's.
        self.assertEqual(d.stats.crc_errors + d.stats.framing_errors, 1)


class Encoders(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.c_frame = staticmethod(c_encoder())

    @given(frames_st)
    def test_c_and_python_agree_and_decode(self, f):
        wire = self.c_frame(f.channel, f.robot_id, f.seq, f.payload)
        self.assertEqual(wire, encode_frame(f.channel, f.robot_id, f.seq, f.payload))
        self.assertEqual(FrameDecoder().feed(wire), [f])


if __name__ == "__main__":
    unittest.main()
