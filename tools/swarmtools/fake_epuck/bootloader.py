"""The e-puck1's bootloader as the flasher sees it: the dsPIC Tiny
Bootloader at the top of program memory (docs/EPUCK.md, "Flashing an
e-puck1"), byte by byte, with no I/O of its own (robot.py feeds it).

After a reset it listens for about a second: each 0xC1 the host sends
(one every 100 ms) is a handshake; it answers 'q' (its PIC type) then 'K'
and takes packets of 101 bytes: a 3-byte little-endian row address (PC),
0x60, 32 instructions of 3 bytes and a checksum byte that makes the 101
bytes sum to 0.  It answers 'N' to a bad checksum and waits for the packet
again, else erases and writes the row and answers 'K'.  A header whose
count byte is 0xFF (the host sends 95 00 00 FF) ends it: the program starts.
Without a handshake within its window it starts the program too.

Like the real one it checks nothing else: a row written over the
bootloader is written.  What a correct host never does is recorded in
`deviations` (a byte other than 0xC1 before the answer, a count byte other
than 0x60, a row not on a row boundary or inside the bootloader, an end
other than 95 00 00 FF, bytes right after the end), which the fake prints
and its tests assert empty.

Faults make it misbehave on purpose, to rehearse the flasher's errors:
answer only the n-th handshake, never answer, answer 'N' to given packets,
stop answering after some packets (the robot went away), send bytes or
flood the line before answering (a running program's output).
"""

from __future__ import annotations

from dataclasses import dataclass, field

HANDSHAKE = 0xC1
ANSWER = b"qK"
PACKET = 101
ROW_PC = 64                   # PC units per flash row (32 instructions)
BOOT_ROW = 0x17F00            # the row it shares with the user's reset GOTO and id
BOOT_CODE = 0x17F40           # its own code
FLASH_END = 0x18000
END = bytes([0x95, 0x00, 0x00, 0xFF])
#: Seconds it listens for a handshake after a reset.
WINDOW_S = 1.0
#: Seconds after the end sequence during which a byte is a host's mistake.
END_GRACE_S = 0.3


@dataclass
class Faults:
    """Misbehaviour on purpose (all off by default)."""
    answer_after: int = 1             # answer the n-th 0xC1 after the reset
    silent: bool = False              # never answer the handshake
    nak: dict = field(default_factory=dict)   # packet index -> 'N' answers before a 'K'
    stop_after: int | None = None     # no answer from this packet on (the robot went away)
    noise: bytes = b""                # bytes the program sent just before the reset
    flood: bool = False               # the line floods with 'x' until the answer

    @classmethod
    def parse(cls, specs: list[str]) -> Faults:
        """From `KEY=VALUE` words: answer_after=N, silent, nak=P:N[,P:N],
        stop_after=N, noise=HEX, flood."""
        f = cls()
        for spec in specs or []:
            key, _, value = spec.partition("=")
            try:
                if key == "answer_after":
                    f.answer_after = int(value)
                elif key == "silent":
                    f.silent = True
                elif key == "nak":
                    for item in value.split(","):
                        p, _, n = item.partition(":")
                        f.nak[int(p)] = int(n or 1)
                elif key == "stop_after":
                    f.stop_after = int(value)
                elif key == "noise":
                    f.noise = bytes.fromhex(value)
                elif key == "flood":
                    f.flood = True
                else:
                    raise ValueError(f"unknown fault {key!r} (answer_after=N, silent, nak=P:N,..., "
                                     f"stop_after=N, noise=HEX, flood)")
            except ValueError as e:
                raise ValueError(f"--boot-fault {spec!r}: {e}") from None
        return f


def bootloader_code() -> dict[int, tuple[int, int, int]]:
    """The bootloader's own words (a recognisable pattern, so that a test
    can tell they were left alone)."""
    return {pc: (0xB0, 0x07, pc >> 9 & 0xFF) for pc in range(BOOT_CODE, FLASH_END, 2)}


class Bootloader:
    """One listening window and flashing session after a reset.

    feed(data, now) takes what arrived and returns the bytes to send;
    state is "listen", "session", "gone" (answers no more), "ended" (the
    end sequence came) or "timeout" (the window passed without a
    handshake).  `flash` is program memory: {PC: (low, middle, upper)},
    shared with the robot (it survives resets)."""

    def __init__(self, flash: dict, faults: Faults | None = None, now: float = 0.0):
        self.flash = flash
        self.faults = faults or Faults()
        self.state = "listen"
        self.started = now
        self.handshakes = 0
        self.late_handshakes = 0       # handshakes after the answer (see feed)
        self.buf = bytearray()
        self.index = 0                 # packets written
        self.rows: list[int] = []      # row PCs written, in order
        self.receptions: dict[int, int] = {}
        self.nak_left = dict(self.faults.nak)
        self.deviations: list[str] = []
        self.ended_at: float | None = None
        self.after_end = b""
        self.pending = bytes(self.faults.noise)   # sent before anything else

    @property
    def answered(self) -> bool:
        return self.state not in ("listen", "timeout")

    def poll(self, now: float) -> bytes:
        """Bytes to send with no input (the noise, a flood); moves the
        state on when the window passes."""
        out, self.pending = self.pending, b""
        if self.state == "listen":
            if now - self.started >= WINDOW_S:
                self.state = "timeout"
            elif self.faults.flood:
                out += b"x" * 256
        return out

    def feed(self, data: bytes, now: float) -> bytes:
        out = bytearray(self.poll(now))
        for i, b in enumerate(data):
            if self.state == "listen":
                if b != HANDSHAKE:
                    self.deviations.append(f"handshake: got 0x{b:02X}, expected 0xC1")
                    continue
                self.handshakes += 1
                if not self.faults.silent and self.handshakes >= self.faults.answer_after:
                    self.state = "session"
                    out += ANSWER
            elif self.state == "session":
                if b == HANDSHAKE and not self.buf and not self.receptions:
                    # A handshake after the answer, before the first packet: the flasher sent it
                    # because the fake's loop answered late (busy starting another robot's
                    # program), which a real bootloader, answering at once, never is.  No
                    # packet starts with 0xC1 (a row's address is a multiple of 0x40).
                    self.late_handshakes += 1
                    continue
                self.buf.append(b)
                out += self._take(now)
            elif self.state == "ended":
                if self.ended_at is not None and now - self.ended_at < END_GRACE_S:
                    rest = bytes(data[i:])
                    self.after_end += rest
                    self.deviations.append(f"bytes after the end sequence: {rest.hex()}")
                break
            else:                      # gone, timeout: nobody answers
                break
        return bytes(out)

    def _take(self, now: float) -> bytes:
        if len(self.buf) == 4 and self.buf[3] == 0xFF:
            if bytes(self.buf) != END:
                self.deviations.append(f"end sequence {bytes(self.buf).hex()} != 950000ff")
            self.state = "ended"
            self.ended_at = now
            self.buf.clear()
            return b""
        if len(self.buf) < PACKET:
            return b""
        pkt, index = bytes(self.buf), self.index
        self.buf.clear()
        self.receptions[index] = self.receptions.get(index, 0) + 1
        if self.faults.stop_after is not None and index >= self.faults.stop_after:
            self.state = "gone"
            return b""
        if sum(pkt) & 0xFF:
            self.deviations.append(f"packet {index}: checksum does not make the sum 0")
            return b"N"
        if self.nak_left.get(index, 0) > 0:
            self.nak_left[index] -= 1
            return b"N"                # as if the line had corrupted it
        pc = pkt[0] | (pkt[1] << 8) | (pkt[2] << 16)
        if pkt[3] != 0x60:
            self.deviations.append(f"packet {index}: count byte 0x{pkt[3]:02X} != 0x60")
        if pc % ROW_PC:
            self.deviations.append(f"packet {index}: address 0x{pc:X} not on a row boundary")
        if pc >= FLASH_END or (pc + ROW_PC > BOOT_CODE and pc != BOOT_ROW):
            self.deviations.append(f"packet {index}: row 0x{pc:X} overwrites the bootloader")
        for k in range(32):            # erase and write the row
            self.flash[pc + 2 * k] = tuple(pkt[4 + 3 * k:7 + 3 * k])
        self.rows.append(pc)
        self.index += 1
        return b"K"


__all__ = ["Bootloader", "Faults", "bootloader_code"]
