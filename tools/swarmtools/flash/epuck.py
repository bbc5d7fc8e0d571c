#!/usr/bin/env python3
"""epuck-flash (swarmtools.flash.epuck) - uploads an XC16 .hex to an e-puck1 through its
bootloader (the dsPIC "Tiny Bootloader" at the top of program memory) over a
serial device: the robot's Bluetooth serial port (/dev/rfcommN) or a
serial cable.

    .venv/bin/epuck-flash firmware.hex /dev/rfcomm0 --robot-id 7     (or make flash HEX=... DEVICE=... ROBOT_ID=7)

Start it, then press the robot's reset button: the host repeats 0xC1 every
100 ms (--handshake-tries times, 50 = 5 s) and the bootloader, which listens
for about a second after a reset, answers 'q' (its PIC type) and 'K'.

Protocol (every address is a program-counter address, PC = Intel HEX byte
address / 2; an instruction is 24 bits, stored in the .hex as 4 bytes: low,
middle, upper, and a phantom 0 that is not sent):
  - one packet per flash row of 32 instructions (64 PC units), 101 bytes:
    the row's PC as 3 bytes little-endian, 0x60 (96), 32 x 3 instruction
    bytes (low, middle, upper), and a checksum byte that makes the 101 bytes
    sum to 0 mod 256.  The bootloader erases the row, writes it and answers
    'K'; it answers 'N' when the checksum is wrong and then waits for the
    packet again (we resend it, at most --retries times).  Instructions of
    a row the .hex does not define are sent erased (0xFFFFFF).
  - the end: 0x95 0x00 0x00 0xFF (a header whose count byte is 0xFF); the
    bootloader waits a moment and starts the program.  No answer.
Reset-vector relocation: the program's reset GOTO (the two words at PC 0
and 2) is moved to PC 0x17F38/0x17F3A, where the bootloader jumps when no
host talks to it, and PC 0 gets GOTO 0x17F40, the bootloader's entry, so
that every reset goes through the bootloader.  The row 0x17F00 (up to the
bootloader's code at 0x17F40) is sent last: erased, but for the robot id
(--robot-id, the low 16 bits of the word at 0x17F36; hal/epuck reads it as
hal_robot_id) and the relocated GOTO.  A .hex with anything in
0x17F00..0x17FFF is refused: it would overwrite the bootloader.  Data
EEPROM (PC 0x7FF000..0x7FFFFF) and configuration words (PC >= 0x800000) are
skipped with a note: the bootloader writes program flash only.

Exit codes: 0 flashed; 1 the transfer failed (no answer, timeout, too many
'N', unexpected reply, device error); 2 bad arguments or a .hex that is
malformed or refused (then nothing is sent).  Standard library only.
"""
import argparse
import errno
import os
import select
import sys
import termios
import time
import tty

ROW_WORDS = 32                 # instructions per flash row
ROW_PC = 2 * ROW_WORDS         # PC units per row
PACKET_DATA = 3 * ROW_WORDS    # 96 bytes
BOOT_ROW = 0x17F00             # the row the bootloader shares with us
BOOT_ENTRY = 0x17F40           # the bootloader's code
USER_RESET = 0x17F38           # relocated user reset GOTO (2 words)
ROBOT_ID_PC = 0x17F36          # robot id word
FLASH_END = 0x18000            # end of program flash (48K instructions)
EEPROM_START, EEPROM_END = 0x7FF000, 0x800000
CONFIG_START = 0x800000
HANDSHAKE = 0xC1
PIC_TYPE = ord('q')
END_SEQUENCE = bytes([0x95, 0x00, 0x00, 0xFF])
ERASED = (0xFF, 0xFF, 0xFF)


class HexError(Exception):
    """A malformed or refused .hex: exit 2, nothing sent."""


class FlashError(Exception):
    """The transfer failed: exit 1."""


# ------------------------------------------------------------------ .hex

def parse_hex(text, name='<hex>'):
    """Intel HEX (INHX32: record types 00, 01, 02, 04; 03 and 05 ignored)
    to {byte address: byte}.  Every error names the line."""
    mem = {}
    base = 0
    eof_line = None
    lines = text.split('\n')
    for n, raw in enumerate(lines, 1):
        line = raw.strip()
        if not line:
            continue
        where = f'{name}:{n}'
        if eof_line is not None:
            raise HexError(f'{where}: data after the end-of-file record of line {eof_line}')
        if line[0] != ':':
            raise HexError(f"{where}: a record must start with ':'")
        body = line[1:]
        bad = next((c for c in body if c not in '0123456789abcdefABCDEF'), None)
        if bad is not None:
            raise HexError(f'{where}: {bad!r} is not a hex digit')
        if len(body) % 2:
            raise HexError(f'{where}: odd number of hex digits (truncated line?)')
        rec = bytes.fromhex(body)
        if len(rec) < 5:
            raise HexError(f'{where}: record too short ({len(rec)} bytes)')
        count, addr, rtype = rec[0], (rec[1] << 8) | rec[2], rec[3]
        if len(rec) != count + 5:
            raise HexError(f'{where}: length field says {count} data bytes, the record has '
                           f'{len(rec) - 5} (truncated line?)')
        if sum(rec) & 0xFF:
            want = (-sum(rec[:-1])) & 0xFF
            raise HexError(f'{where}: checksum 0x{rec[-1]:02X} is wrong (0x{want:02X} expected)')
        data = rec[4:-1]
        if rtype == 0x00:
            for i, b in enumerate(data):
                a = base + addr + i
                if a in mem and mem[a] != b:
                    raise HexError(f'{where}: byte address 0x{a:X} defined twice with different values')
                mem[a] = b
        elif rtype == 0x01:
            if count != 0:
                raise HexError(f'{where}: end-of-file record with data')
            eof_line = n
        elif rtype == 0x02:
            if count != 2:
                raise HexError(f'{where}: extended segment address record needs 2 bytes')
            base = ((data[0] << 8) | data[1]) << 4
        elif rtype == 0x04:
            if count != 2:
                raise HexError(f'{where}: extended linear address record needs 2 bytes')
            base = ((data[0] << 8) | data[1]) << 16
        elif rtype in (0x03, 0x05):
            pass   # start address: the dsPIC starts at its reset vector
        else:
            raise HexError(f'{where}: unknown record type 0x{rtype:02X}')
    if eof_line is None:
        raise HexError(f'{name}: no end-of-file record (:00000001FF): the file is truncated')
    return mem


def program_words(mem):
    """{byte address: byte} to ({PC: [low, mid, upper]} of program flash,
    notes).  Refuses the bootloader's region and addresses the dsPIC does
    not have."""
    words = {}
    skipped = {'EEPROM': 0, 'configuration': 0}
    for a in sorted(mem):
        pc = (a // 4) * 2
        k = a % 4
        if pc >= CONFIG_START:
            skipped['configuration'] += 1
            continue
        if EEPROM_START <= pc < EEPROM_END:
            skipped['EEPROM'] += 1
            continue
        if BOOT_ROW <= pc < FLASH_END:
            raise HexError(f'refused: the .hex writes program address 0x{pc:05X} (byte address '
                           f'0x{a:X}), inside the bootloader (0x{BOOT_ROW:05X}..0x{FLASH_END - 1:05X}); '
                           'link the program below 0x17F00')
        if pc >= FLASH_END:
            raise HexError(f'refused: byte address 0x{a:X} (program address 0x{pc:X}) is not memory '
                           'of the dsPIC30F6014A')
        if k == 3:
            continue   # phantom byte
        w = words.setdefault(pc, list(ERASED))
        w[k] = mem[a]
    notes = [f'skipped {n} bytes of {what} data: the bootloader writes program flash only'
             for what, n in skipped.items() if n]
    return words, notes


def decode_goto(w0, w1):
    """Target of a GOTO split over two instruction words, or None."""
    word0 = w0[0] | (w0[1] << 8) | (w0[2] << 16)
    word1 = w1[0] | (w1[1] << 8) | (w1[2] << 16)
    if (word0 >> 16) != 0x04 or (word1 & ~0x7F) != 0:
        return None
    return (word0 & 0xFFFE) | ((word1 & 0x7F) << 16)


def encode_goto(target):
    word0 = 0x040000 | (target & 0xFFFE)
    word1 = (target >> 16) & 0x7F
    return ([word0 & 0xFF, (word0 >> 8) & 0xFF, word0 >> 16],
            [word1 & 0xFF, (word1 >> 8) & 0xFF, word1 >> 16])


def build_rows(words, robot_id):
    """The rows to send, in order: {row PC: 96 bytes}.  Relocates the reset
    vector and fills the bootloader's row."""
    if 0 not in words or 2 not in words:
        raise HexError('the .hex has no reset vector (a GOTO at program address 0)')
    target = decode_goto(words[0], words[2])
    if target is None:
        raise HexError('the word at program address 0 is not a GOTO: not an XC16 program image')
    if target >= BOOT_ROW:
        raise HexError(f'the reset vector jumps to 0x{target:X}, inside the bootloader')
    user_goto = (list(words[0]), list(words[2]))
    words = dict(words)
    words[0], words[2] = encode_goto(BOOT_ENTRY)
    rows = {}
    for pc in sorted(words):
        row = pc - pc % ROW_PC
        buf = rows.setdefault(row, bytearray(bytes(ERASED) * ROW_WORDS))
        i = (pc - row) // 2 * 3
        buf[i:i + 3] = bytes(words[pc])
    boot = bytearray(bytes(ERASED) * ROW_WORDS)

    def put(pc, w):
        i = (pc - BOOT_ROW) // 2 * 3
        boot[i:i + 3] = bytes(w)

    if robot_id is not None:
        put(ROBOT_ID_PC, [robot_id & 0xFF, (robot_id >> 8) & 0xFF, 0x00])
    put(USER_RESET, user_goto[0])
    put(USER_RESET + 2, user_goto[1])
    ordered = [(row, bytes(rows[row])) for row in sorted(rows)]
    ordered.append((BOOT_ROW, bytes(boot)))
    return ordered, target


def packet(row_pc, data):
    head = bytes([row_pc & 0xFF, (row_pc >> 8) & 0xFF, (row_pc >> 16) & 0xFF, PACKET_DATA])
    body = head + data
    return body + bytes([(-sum(body)) & 0xFF])


# ------------------------------------------------------------------ serial

class Serial:
    def __init__(self, path):
        try:
            self.fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        except OSError as e:
            raise FlashError(f'cannot open {path}: {e.strerror}') from None
        self.path = path
        try:
            tty.setraw(self.fd)
            attr = termios.tcgetattr(self.fd)
            attr[2] |= termios.CLOCAL | termios.CREAD
            attr[2] &= ~getattr(termios, 'CRTSCTS', 0)
            attr[4] = attr[5] = termios.B115200
            termios.tcsetattr(self.fd, termios.TCSANOW, attr)
            termios.tcflush(self.fd, termios.TCIOFLUSH)
        except termios.error as e:
            os.close(self.fd)
            # termios.error carries (errno, text): say the text, not the tuple
            why = e.args[1] if len(e.args) > 1 else str(e)
            raise FlashError(f'{path} is not a serial device: {why}') from None

    def write(self, data):
        view = memoryview(data)
        deadline = time.monotonic() + 5.0
        while view:
            try:
                n = os.write(self.fd, view)
                view = view[n:]
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise FlashError(f'{self.path}: cannot write (device blocked)') from None
                select.select([], [self.fd], [], 0.1)
            except OSError as e:
                raise FlashError(f'{self.path}: write failed: {e.strerror}') from None

    def read_some(self, timeout, limit=4096):
        """What has arrived (up to `limit` bytes), or b'' after `timeout` s."""
        r, _, _ = select.select([self.fd], [], [], max(timeout, 0.0))
        if not r:
            return b''
        try:
            b = os.read(self.fd, limit)
        except BlockingIOError:
            return b''
        except OSError as e:
            if e.errno == errno.EIO:
                raise FlashError(f'{self.path}: the connection was lost') from None
            raise FlashError(f'{self.path}: read failed: {e.strerror}') from None
        if not b:
            raise FlashError(f'{self.path}: the connection was closed')
        return b

    def read_byte(self, timeout):
        """One byte, or None after `timeout` seconds."""
        r, _, _ = select.select([self.fd], [], [], max(timeout, 0.0))
        if not r:
            return None
        try:
            b = os.read(self.fd, 1)
        except BlockingIOError:
            return None
        except OSError as e:
            if e.errno == errno.EIO:
                raise FlashError(f'{self.path}: the connection was lost') from None
            raise FlashError(f'{self.path}: read failed: {e.strerror}') from None
        if not b:
            raise FlashError(f'{self.path}: the connection was closed')
        return b[0]

    def close(self):
        os.close(self.fd)


def handshake(port, tries, period=0.1, reply_timeout=1.0):
    """Sends 0xC1 every `period` s until 'q' then 'K' come back.  Bytes
    before the 'q' (what the running program was sending) are ignored, read
    in bulk and never past the period's end, so that a robot flooding the
    line does not slow the handshake down."""
    for _ in range(tries):
        port.write(bytes([HANDSHAKE]))
        end = time.monotonic() + period
        while time.monotonic() < end:
            chunk = port.read_some(end - time.monotonic())
            if not chunk:
                break
            q = chunk.rfind(bytes([PIC_TYPE]))
            if q < 0:
                continue
            rest = chunk[q + 1:]
            k = rest[0] if rest else port.read_byte(reply_timeout)
            if k == ord('K'):
                return
            if k is None:
                raise FlashError("the bootloader sent 'q' but no 'K'")
    raise FlashError(f'no answer from the bootloader after {tries} tries '
                     f'({tries * period:.1f} s): reset the robot right after starting the upload, '
                     'and check that nothing else holds the serial port')


class Progress:
    def __init__(self, total, stream=sys.stderr):
        self.total, self.stream, self.last = total, stream, -1
        self.tty = stream.isatty()

    def show(self, done):
        pct = 100 * done // self.total
        if self.tty:
            self.stream.write(f'\rflashing: {done}/{self.total} rows ({pct} %)')
            if done == self.total:
                self.stream.write('\n')
            self.stream.flush()
        elif pct // 10 != self.last // 10 or done == self.total:
            self.stream.write(f'flashing: {done}/{self.total} rows ({pct} %)\n')
        self.last = pct


def send_rows(port, rows, timeout, retries, progress=None):
    for i, (row, data) in enumerate(rows):
        pkt = packet(row, data)
        naks = 0
        while True:
            port.write(pkt)
            r = port.read_byte(timeout)
            if r is None:
                raise FlashError(f'timeout: no reply within {timeout:g} s to the packet of row '
                                 f'0x{row:05X} ({i + 1}/{len(rows)})')
            if r == ord('K'):
                break
            if r == ord('N'):
                naks += 1
                if naks > retries:
                    raise FlashError(f"the bootloader answered 'N' (checksum error) {naks} times to "
                                     f'the packet of row 0x{row:05X}: gave up after {retries} retries')
                continue
            raise FlashError(f'unexpected reply 0x{r:02X} to the packet of row 0x{row:05X}')
        if progress:
            progress.show(i + 1)
    port.write(END_SEQUENCE)


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog='epuck-flash',
        description='Upload an XC16 .hex to an e-puck1 through its serial bootloader.')
    ap.add_argument('hex', metavar='HEX', help='Intel HEX file built by `make firmware`')
    ap.add_argument('device', metavar='DEVICE', help='serial device, e.g. /dev/rfcomm0')
    ap.add_argument('--robot-id', type=int, metavar='N',
                    help='robot id written at program address 0x17F36 (0..65534); without it the '
                         'id word is erased and the robot reports id 0')
    ap.add_argument('--timeout', type=float, default=3.0, metavar='S',
                    help='seconds to wait for each reply of the bootloader (3)')
    ap.add_argument('--retries', type=int, default=5, metavar='N',
                    help="resends of a packet the bootloader answered 'N' (5)")
    ap.add_argument('--handshake-tries', type=int, default=50, metavar='N',
                    help='0xC1 bytes sent, one every 100 ms, while waiting for the bootloader (50)')
    args = ap.parse_args(argv)
    if args.robot_id is not None and not 0 <= args.robot_id <= 0xFFFE:
        ap.error('--robot-id must be 0..65534')
    if args.timeout <= 0 or args.retries < 0 or args.handshake_tries < 1:
        ap.error('--timeout must be > 0, --retries >= 0, --handshake-tries >= 1')

    try:
        with open(args.hex, 'rb') as f:
            raw = f.read()
        try:
            text = raw.decode('ascii')
        except UnicodeDecodeError:
            raise HexError(f'{args.hex}: not a text file (Intel HEX is ASCII)') from None
        mem = parse_hex(text, args.hex)
        words, notes = program_words(mem)
        rows, entry = build_rows(words, args.robot_id)
    except OSError as e:
        print(f'epuck_flash: cannot read {args.hex}: {e.strerror}', file=sys.stderr)
        return 2
    except HexError as e:
        print(f'epuck_flash: {e}', file=sys.stderr)
        return 2
    for note in notes:
        print(f'epuck_flash: note: {note}', file=sys.stderr)
    if args.robot_id is None:
        print('epuck_flash: note: no --robot-id: the id word is erased (the robot reports id 0)',
              file=sys.stderr)
    n_words = len(words)
    print(f'epuck_flash: {args.hex}: {n_words} instructions in {len(rows)} rows, program entry '
          f'0x{entry:05X}', file=sys.stderr)

    port = None
    try:
        port = Serial(args.device)
        print(f'epuck_flash: waiting for the bootloader on {args.device}: reset the robot now',
              file=sys.stderr)
        handshake(port, args.handshake_tries, reply_timeout=args.timeout)
        print('epuck_flash: bootloader found', file=sys.stderr)
        send_rows(port, rows, args.timeout, args.retries, Progress(len(rows)))
    except FlashError as e:
        print(f'epuck_flash: {e}', file=sys.stderr)
        return 1
    finally:
        if port is not None:
            port.close()
    print(f'epuck_flash: done: {len(rows)} rows written; the robot starts the program', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
