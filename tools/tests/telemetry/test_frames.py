"""The host decoder of the robots' framing (swarmtools.telemetry.frames)
against the firmware's encoder (firmware/telemetry/telemetry_frame.c), and
a fuzz test: no input makes it raise, and no corrupted frame gets through."""
import random
import re
import unittest

from swarmtools.telemetry import common, frames
from swarmtools.telemetry.frames import FrameDecoder, cobs_decode, cobs_encode, crc16, encode_frame

from .helpers import ROOT, c_encoder


class Vectors(unittest.TestCase):
    def test_crc_check_value(self):
        self.assertEqual(crc16(b"123456789"), 0x29B1)

    def test_cobs_vectors(self):
        cases = [(b"\x00", b"\x01\x01"), (b"\x00\x00", b"\x01\x01\x01"),
                 (b"\x00\x11\x00", b"\x01\x02\x11\x01"), (b"\x11\x22\x00\x33", b"\x03\x11\x22\x02\x33"),
                 (b"\x11\x22\x33\x44", b"\x05\x11\x22\x33\x44"), (b"\x11\x00\x00\x00", b"\x02\x11\x01\x01\x01"),
                 (bytes(range(1, 255)), b"\xff" + bytes(range(1, 255))),
                 (bytes(range(0, 255)), b"\x01\xff" + bytes(range(1, 255))),
                 (bytes(range(1, 256)), b"\xff" + bytes(range(1, 255)) + b"\x02\xff")]
        for raw, enc in cases:
            self.assertEqual(cobs_encode(raw), enc)
            self.assertEqual(cobs_decode(enc), raw)

    def test_constants_match_the_firmware_header(self):
        h = (ROOT / "wire" / "telemetry" / "telemetry_frame.h").read_text()
        # The header's table of LCM channel names by id ...
        table = re.search(r"#define TELEMETRY_CHANNEL_NAMES \\\s*\{([^}]*)\}", h).group(1)
        names = re.findall(r'"(\w*)"', table)
        self.assertEqual({k: n for k, n in enumerate(names) if n}, frames.CHANNEL_IDS)
        self.assertEqual(frames.CHANNEL_IDS[6], "TELEMETRY_SCHEMA")
        # ... and its enum of ids (all but the count) name the same channels; the
        # host's channels (bit 7 set) are the other table, never republished.
        all_ids = {int(v): name for name, v in re.findall(r"TELEMETRY_CH_(\w+) = (\d+)", h) if name != "COUNT"}
        ids = {k: n for k, n in all_ids.items() if k < 128}
        self.assertEqual(set(ids), set(frames.CHANNEL_IDS))
        for k, name in ids.items():
            self.assertTrue(frames.CHANNEL_IDS[k].endswith(name), (k, name))
        self.assertEqual({k: n for k, n in all_ids.items() if k >= 128}, frames.HOST_CHANNEL_IDS)
        self.assertFalse(set(frames.HOST_CHANNEL_IDS.values()) & set(common.CHANNEL_TYPES))
        self.assertEqual(int(re.search(r"TELEMETRY_BROADCAST_ID 0x(\w+)u", h).group(1), 16), frames.BROADCAST_ID)
        # Every channel a robot may send has an LCM type the bridge checks payloads against.
        self.assertLessEqual(set(frames.CHANNEL_IDS.values()), set(common.CHANNEL_TYPES))
        self.assertEqual(int(re.search(r"TELEMETRY_MAX_PAYLOAD (\d+)u", h).group(1)), frames.MAX_PAYLOAD)
        self.assertEqual(int(re.search(r"TELEMETRY_VERSION (\d+)u", h).group(1)), frames.VERSION)
        self.assertEqual(int(re.search(r"TELEMETRY_HEADER_BYTES (\d+)u", h).group(1)), frames.HEADER_BYTES)

    def test_python_and_c_encoders_agree(self):
        c_frame = c_encoder()
        rng = random.Random(4)
        for _ in range(300):
            n = rng.choice([0, 1, 2, 100, 239, 240, rng.randrange(241)])
            payload = bytes(rng.choice([0, 0, 0xFF, rng.randrange(256)]) for _ in range(n))
            ch, rid, seq = rng.randrange(256), rng.randrange(65536), rng.randrange(65536)
            self.assertEqual(c_frame(ch, rid, seq, payload), encode_frame(ch, rid, seq, payload))
        self.assertEqual(c_frame(1, 0, 0, bytes(241)), b"")     # too long: nothing
        self.assertEqual(c_frame.lib.telemetry_crc16(0xFFFF, b"123456789", 9), 0x29B1)


def stream(n, seed=1, c=False):
    """n frames with varied payloads: (bytes on the wire, the frames)."""
    rng = random.Random(seed)
    enc = c_encoder() if c else encode_frame
    wire, sent = b"", []
    for k in range(n):
        payload = bytes(rng.randrange(256) for _ in range(rng.randrange(0, 241)))
        f = frames.Frame(channel=rng.randrange(1, 7), robot_id=rng.randrange(65536), seq=k & 0xFFFF, payload=payload)
        wire += enc(f.channel, f.robot_id, f.seq, f.payload)
        sent.append(f)
    return wire, sent


class Decoder(unittest.TestCase):
    def test_whole_stream_in_any_chunks(self):
        wire, sent = stream(50, c=True)
        for chunk in (1, 2, 7, 64, 251, 4096, len(wire)):
            d = FrameDecoder()
            got = []
            for i in range(0, len(wire), chunk):
                got += d.feed(wire[i:i + chunk])
            self.assertEqual(got, sent)
            self.assertEqual(d.stats.frames, 50)
            self.assertEqual(d.stats.bytes, len(wire))
            self.assertEqual((d.stats.crc_errors, d.stats.framing_errors, d.stats.oversize), (0, 0, 0))

    def test_garbage_truncation_and_crc_errors(self):
        wire, sent = stream(6)
        a = encode_frame(1, 5, 0, b"hello")
        b = encode_frame(2, 5, 1, b"world")
        flipped = bytearray(encode_frame(3, 5, 2, b"flip me"))
        flipped[5] ^= 0x10
        d = FrameDecoder()
        got = d.feed(b"boot message\r\n\xff\xfe" + a + a[:7] + b + bytes(flipped) + b"\x00\x00\x00" + b)
        self.assertEqual([(f.channel, f.payload) for f in got], [(1, b"hello"), (2, b"world"), (2, b"world")])
        self.assertEqual(d.stats.frames, 3)
        self.assertEqual(d.stats.crc_errors + d.stats.framing_errors, 3)   # boot text, cut frame, flipped bit
        self.assertEqual(d.stats.crc_errors >= 1, True)

    def test_oversize_garbage_resyncs(self):
        d = FrameDecoder()
        rng = random.Random(2)
        junk = bytes(rng.randrange(1, 256) for _ in range(5000))   # no zero: one endless "frame"
        ok = encode_frame(1, 1, 1, b"x")
        got = d.feed(junk + ok)
        self.assertEqual([f.payload for f in got], [b"x"])
        self.assertEqual(d.stats.oversize, 1)

    def test_short_and_bad_version(self):
        d = FrameDecoder()
        body = bytes([2, 1, 0, 0, 0, 0])
        c = crc16(body)
        bad_version = b"\x00" + cobs_encode(body + bytes([c >> 8, c & 0xFF])) + b"\x00"
        self.assertEqual(d.feed(bad_version + b"\x00\x03\x01\x02\x00" + b"\x00\x05\x01\x00"), [])
        self.assertEqual(d.stats.framing_errors, 3)


class Fuzz(unittest.TestCase):
    """Deterministic fuzzing (fixed seeds): mutated streams of valid frames
    fed in random chunks.  The decoder never raises, returns only frames
    that were sent (no corrupted one passes), and returns every frame that
    the mutations left intact with delimiters on both sides."""

    MUTATIONS = ("flip", "insert", "delete", "truncate", "duplicate", "zero", "splice")

    def mutate(self, rng, wire):
        w = bytearray(wire)
        for _ in range(rng.randrange(1, 6)):
            op = rng.choice(self.MUTATIONS)
            if not w:
                break
            i = rng.randrange(len(w))
            if op == "flip":
                w[i] ^= 1 << rng.randrange(8)
            elif op == "insert":
                w[i:i] = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 40)))
            elif op == "delete":
                del w[i:i + rng.randrange(1, 40)]
            elif op == "truncate":
                del w[i:]
            elif op == "duplicate":
                j = rng.randrange(i, len(w) + 1)
                w[j:j] = w[i:j]
            elif op == "zero":
                w[i] = 0
            elif op == "splice":
                w[i:i] = w[rng.randrange(len(w)):][:rng.randrange(1, 300)]
        return bytes(w)

    def test_mutated_streams(self):
        rng = random.Random(2024)
        wire, sent = stream(40, seed=7)
        valid = {(f.channel, f.robot_id, f.seq, f.payload) for f in sent}
        total = 0
        for it in range(1500):
            data = self.mutate(rng, wire)
            d = FrameDecoder()
            got = []
            i = 0
            while i < len(data):
                n = rng.choice([1, 3, 17, 250, 1000, 100000])
                got += d.feed(data[i:i + n])
                i += n
            for f in got:
                self.assertIn((f.channel, f.robot_id, f.seq, f.payload), valid, f"iteration {it}")
                self.assertLessEqual(len(f.payload), frames.MAX_PAYLOAD)
            s = d.stats
            self.assertEqual(s.bytes, len(data))
            self.assertEqual(s.frames, len(got))
            total += len(got)
        self.assertGreater(total, 1500 * 20)   # most frames survive a few mutations

    def test_random_bytes(self):
        rng = random.Random(99)
        for _ in range(200):
            n = rng.randrange(1, 5000)
            alphabet = rng.choice([256, 4, 2])   # dense zeros make many tiny "frames"
            data = bytes(rng.randrange(alphabet) for _ in range(n))
            d = FrameDecoder()
            for f in d.feed(data):   # a frame found in noise must be a whole, valid one
                again = FrameDecoder().feed(encode_frame(f.channel, f.robot_id, f.seq, f.payload))
                self.assertEqual(again, [f])
            self.assertEqual(d.stats.bytes, n)


if __name__ == "__main__":
    unittest.main()
