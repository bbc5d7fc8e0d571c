"""The robots' serial framing, host side (see firmware/telemetry/telemetry_frame.h).

On the wire:  0x00, COBS(body), 0x00, where the body is
    version (1), channel id (1), robot id (2, big-endian),
    sequence number (2, big-endian), payload (an LCM-encoded message,
    0..240 bytes), CRC-16/CCITT-FALSE of all that (2, big-endian).

The same frames go from a host to robots on the channels of
HOST_CHANNEL_IDS (host_link.py encodes them).

`FrameDecoder` turns any byte stream into frames and never raises: garbage,
truncated frames, bad stuffing and CRC errors are counted and skipped, and
the decoder resynchronises at the next zero byte.
"""
import binascii
from dataclasses import dataclass, field

VERSION = 1
HEADER_BYTES = 6
CRC_BYTES = 2
MAX_PAYLOAD = 240
MAX_BODY = HEADER_BYTES + MAX_PAYLOAD + CRC_BYTES           # 248
MAX_ENCODED = MAX_BODY + 1 + MAX_BODY // 254                # COBS of the largest body
MIN_BODY = HEADER_BYTES + CRC_BYTES

#: Channel id -> LCM channel (firmware/telemetry/telemetry_frame.h: telemetry_channel_t and
#: TELEMETRY_CHANNEL_NAMES; a test compares them).
CHANNEL_IDS = {
    1: "ROBOT_STATE",
    2: "SWARM_EVENT",
    3: "SWARM_STATE",
    4: "RUN_INFO",
    5: "RUN_SUMMARY",
    6: "TELEMETRY_SCHEMA",
}

#: Channel ids of the frames a host sends robots (telemetry_frame.h: telemetry_host_channel_t;
#: a test compares them).  Bit 7 set, apart from CHANNEL_IDS: the bridge never republishes
#: them (a robot does not send them; heard from one, they count as unknown channels).
HOST_CHANNEL_IDS = {
    128: "POSE",
    129: "HOST_MSG",
}
#: Robot id of a host's frame that every robot takes.
BROADCAST_ID = 0xFFFF


def crc16(data, crc=0xFFFF):
    """CRC-16/CCITT-FALSE (binascii.crc_hqx is exactly that with 0xFFFF)."""
    return binascii.crc_hqx(bytes(data), crc)


def cobs_encode(data):
    out = bytearray([0])
    code_at, code = 0, 1
    for i, b in enumerate(data):
        if b == 0:
            out[code_at] = code
            code_at, code = len(out), 1
            out.append(0)
            continue
        out.append(b)
        code += 1
        if code == 0xFF:
            out[code_at] = code
            code_at, code = len(out), 1
            if i + 1 < len(data):
                out.append(0)
            else:
                code_at = None
    if code_at is not None:
        out[code_at] = code
    return bytes(out)


def cobs_decode(data):
    """Decodes one COBS block sequence; raises ValueError when malformed."""
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        code = data[i]
        i += 1
        if code == 0 or i + code - 1 > n:
            raise ValueError("bad COBS code")
        chunk = data[i:i + code - 1]
        if 0 in chunk:
            raise ValueError("zero inside a COBS block")
        out += chunk
        i += code - 1
        if code < 0xFF and i < n:
            out.append(0)
    return bytes(out)


def encode_frame(channel, robot_id, seq, payload):
    """A whole frame on the wire, as firmware/telemetry/telemetry_frame.c writes it."""
    if len(payload) > MAX_PAYLOAD:
        raise ValueError(f"payload of {len(payload)} bytes: at most {MAX_PAYLOAD}")
    body = bytes([VERSION, channel & 0xFF, (robot_id >> 8) & 0xFF, robot_id & 0xFF,
                  (seq >> 8) & 0xFF, seq & 0xFF]) + bytes(payload)
    c = crc16(body)
    body += bytes([c >> 8, c & 0xFF])
    return b"\x00" + cobs_encode(body) + b"\x00"


@dataclass
class Frame:
    channel: int
    robot_id: int
    seq: int
    payload: bytes


@dataclass
class DecoderStats:
    bytes: int = 0
    frames: int = 0
    crc_errors: int = 0
    framing_errors: int = 0     # bad COBS, too short, unknown version
    oversize: int = 0           # runs longer than any frame: garbage, dropped


@dataclass
class FrameDecoder:
    """Feed it bytes; get whole, CRC-checked frames back."""
    stats: DecoderStats = field(default_factory=DecoderStats)

    def __post_init__(self):
        self._buf = bytearray()
        self._skipping = False      # inside an oversize run: drop until a zero

    def feed(self, data):
        """Returns the frames completed by `data` (a bytes-like object)."""
        frames = []
        data = bytes(data)
        self.stats.bytes += len(data)
        start = 0
        while start <= len(data):
            zero = data.find(b"\x00", start)
            chunk = data[start:] if zero < 0 else data[start:zero]
            if not self._skipping:
                self._buf += chunk
                if len(self._buf) > MAX_ENCODED:
                    self.stats.oversize += 1
                    self._buf.clear()
                    self._skipping = True
            if zero < 0:
                break
            if not self._skipping and self._buf:
                frame = self._unframe(bytes(self._buf))
                if frame is not None:
                    frames.append(frame)
            self._buf.clear()
            self._skipping = False
            start = zero + 1
        return frames

    def reset(self):
        """Forget a partial frame (e.g. the device was lost)."""
        self._buf.clear()
        self._skipping = False

    def _unframe(self, stuffed):
        try:
            body = cobs_decode(stuffed)
        except ValueError:
            self.stats.framing_errors += 1
            return None
        if len(body) < MIN_BODY or body[0] != VERSION:
            self.stats.framing_errors += 1
            return None
        if crc16(body) != 0:       # the CRC appended big-endian leaves residue 0
            self.stats.crc_errors += 1
            return None
        self.stats.frames += 1
        return Frame(channel=body[1], robot_id=(body[2] << 8) | body[3],
                     seq=(body[4] << 8) | body[5], payload=body[HEADER_BYTES:-CRC_BYTES])
