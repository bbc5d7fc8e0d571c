"""The host's frames to robots (swarmtools.telemetry.host_link) against the
robot's side in C (firmware/telemetry/: telemetry_frame.c encodes,
telemetry_rx.c decodes, telemetry_host.c lays out the pose): fixed vectors
that tests/test_telemetry_rx.c asserts of the C encoder too, the Python
frames fed byte by byte to the C decoder, and the limits."""
import ctypes
import random
import unittest

from swarmtools.telemetry import frames, host_link
from swarmtools.telemetry.frames import FrameDecoder
from swarmtools.telemetry.host_link import HostLink, decode_pose, encode_host_msg, encode_pose

from .helpers import c_encoder

# The same bytes as POSE_VECTOR and MSG_VECTOR of tests/test_telemetry_rx.c.
POSE_VECTOR = bytes([
    0x00, 0x03, 0x01, 0x80, 0x04, 0x07, 0x01, 0x02, 0x01, 0x0B, 0x04, 0xD2, 0xFF, 0xFF, 0xE9,
    0xD2, 0xF9, 0xDD, 0x10, 0xE2, 0x00])
MSG_VECTOR = bytes([
    0x00, 0x05, 0x01, 0x81, 0xFF, 0xFF, 0x03, 0x03, 0x01, 0x07, 0x02, 0x7F, 0xFF, 0x80, 0x21,
    0x52, 0x00])
MSG_BYTES = bytes([0x01, 0x00, 0x02, 0x7F, 0xFF, 0x80])


class RxFrame(ctypes.Structure):
    """telemetry_rx_frame_t (natural alignment, as the C compiler lays it out)."""
    _fields_ = [("channel", ctypes.c_uint8), ("robot_id", ctypes.c_uint16), ("seq", ctypes.c_uint16),
                ("payload", ctypes.POINTER(ctypes.c_uint8)), ("len", ctypes.c_uint16)]


class CDecoder:
    """The robot's decoder (telemetry_rx.c) through ctypes, with a body
    buffer of the robot's size (TELEMETRY_HOST_MAX_BODY)."""

    def __init__(self, lib):
        self.lib = lib
        lib.telemetry_rx_init.restype = None
        lib.telemetry_rx_init.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_uint16]
        lib.telemetry_rx_feed.restype = ctypes.c_uint8
        lib.telemetry_rx_feed.argtypes = [ctypes.c_void_p, ctypes.c_uint8, ctypes.POINTER(RxFrame)]
        self.state = (ctypes.c_uint64 * 8)()          # room for telemetry_rx_t, aligned
        self.body = (ctypes.c_uint8 * (6 + host_link.HOST_MSG_MAX + 2))()
        lib.telemetry_rx_init(self.state, self.body, len(self.body))

    def feed(self, data):
        out, f = [], RxFrame()
        for b in data:
            if self.lib.telemetry_rx_feed(self.state, b, ctypes.byref(f)):
                out.append(frames.Frame(f.channel, f.robot_id, f.seq, bytes(f.payload[:f.len])))
        return out


def c_lib():
    return c_encoder().lib


class Vectors(unittest.TestCase):
    def test_fixed_vectors(self):
        self.assertEqual(encode_pose(7, 0x0102, 1234, -5678, -1571), POSE_VECTOR)
        self.assertEqual(encode_host_msg(frames.BROADCAST_ID, 3, MSG_BYTES), MSG_VECTOR)
        self.assertEqual(len(POSE_VECTOR), 21)

    def test_python_and_c_encoders_agree(self):
        c_frame = c_encoder()
        rng = random.Random(16)
        for _ in range(200):
            rid, seq = rng.choice([0, 7, 0xFFFF, rng.randrange(65536)]), rng.randrange(65536)
            x, y = rng.randrange(-2**31, 2**31), rng.choice([0, -1, 256, rng.randrange(-2**31, 2**31)])
            h = rng.randrange(-3141, 3143)
            payload = host_link.pose_payload(x, y, h)
            self.assertEqual(encode_pose(rid, seq, x, y, h), c_frame(host_link.CH_POSE, rid, seq, payload))
            msg = bytes(rng.choice([0, 0xFF, rng.randrange(256)]) for _ in range(rng.randrange(1, 65)))
            self.assertEqual(encode_host_msg(rid, seq, msg), c_frame(host_link.CH_HOST_MSG, rid, seq, msg))

    def test_c_pose_payload_agrees(self):
        lib = c_lib()

        class Pose(ctypes.Structure):   # hal_pose_t
            _fields_ = [("x_mm", ctypes.c_int32), ("y_mm", ctypes.c_int32),
                        ("heading_mrad", ctypes.c_int16), ("age_ms", ctypes.c_uint16)]
        lib.telemetry_pose_pack.restype = None
        lib.telemetry_pose_pack.argtypes = [ctypes.POINTER(Pose), ctypes.c_char_p]
        for x, y, h in [(1234, -5678, -1571), (-2**31, 2**31 - 1, 3142), (0, -1, -3141)]:
            out = ctypes.create_string_buffer(10)
            lib.telemetry_pose_pack(ctypes.byref(Pose(x, y, h, 0)), out)
            self.assertEqual(out.raw, host_link.pose_payload(x, y, h))
            self.assertEqual(decode_pose(out.raw), (x, y, h))


class RobotDecodesHostFrames(unittest.TestCase):
    def test_c_decoder_takes_python_frames(self):
        d = CDecoder(c_lib())
        link = HostLink()
        wire = (b"\x12garbage\x00" + link.pose(7, 1234, -5678, -1571) + link.message(frames.BROADCAST_ID, MSG_BYTES)
                + link.message(7, bytes(64)) + link.pose(8, -1, -2, -3))
        got = d.feed(wire)
        self.assertEqual([(f.channel, f.robot_id, f.seq) for f in got],
                         [(128, 7, 0), (129, 0xFFFF, 1), (129, 7, 2), (128, 8, 3)])
        self.assertEqual(decode_pose(got[0].payload), (1234, -5678, -1571))
        self.assertEqual(got[1].payload, MSG_BYTES)
        self.assertEqual(got[2].payload, bytes(64))
        # The host's own decoder reads them the same (what the robot got is what was sent).
        self.assertEqual(FrameDecoder().feed(wire), got)

    def test_c_decoder_drops_what_the_robot_cannot_hold(self):
        d = CDecoder(c_lib())
        too_long = frames.encode_frame(host_link.CH_HOST_MSG, 7, 0, bytes(range(1, 66)))
        self.assertEqual(d.feed(too_long + encode_pose(7, 1, 5, 6, 7)),
                         [frames.Frame(128, 7, 1, host_link.pose_payload(5, 6, 7))])


class Limits(unittest.TestCase):
    def test_ranges(self):
        with self.assertRaises(ValueError):
            encode_host_msg(1, 0, b"")
        with self.assertRaises(ValueError):
            encode_host_msg(1, 0, bytes(65))
        with self.assertRaises(ValueError):
            encode_pose(1, 0, 2**31, 0, 0)
        with self.assertRaises(ValueError):
            encode_pose(1, 0, 0, 0, 40000)
        with self.assertRaises(ValueError):
            decode_pose(bytes(9))

    def test_sequence_wraps(self):
        link = HostLink()
        link.seq = 0xFFFF
        a, b = link.pose(1, 0, 0, 0), link.pose(1, 0, 0, 0)
        self.assertEqual([f.seq for f in FrameDecoder().feed(a + b)], [0xFFFF, 0])

    def test_channels_are_not_republished(self):
        self.assertFalse(set(frames.HOST_CHANNEL_IDS) & set(frames.CHANNEL_IDS))


if __name__ == "__main__":
    unittest.main()
