#!/usr/bin/env python3
"""test_flash.py - tests of epuck_flash.py against a simulated e-puck1
bootloader on a pseudo-terminal pair.

The simulator plays the dsPIC Tiny Bootloader byte by byte: it expects
0xC1, answers 'q' 'K', then reads 4-byte headers and 97 more bytes per
packet, answers 'N' when the 101 bytes do not sum to 0 and 'K' after
"erasing and writing" the row into its model of program memory, and stops
at a header whose count byte is 0xFF.  It records every deviation it sees
(a byte other than 0xC1 before its answer, a count byte other than 0x60, a
row address not on a row boundary or inside the bootloader's code, an end
sequence other than 95 00 00 FF, anything sent after it) and the tests
check that there is none and that program memory ends up as expected.

Run: .venv/bin/python tools/tests/flash/test_epuck.py  (unittest; prints "N passed, M failed")
"""
import os
import pty
import subprocess
import sys
import tempfile
import threading
import time
import tty
import unittest

import swarmtools.fake_epuck.bootloader as fake_boot
import swarmtools.flash.epuck as ef

# The flasher as a user runs it (python -m, from the installed package).
FLASHER_CMD = [sys.executable, '-m', 'swarmtools.flash.epuck']
#: Seconds the flasher and the simulated bootloader wait for each other's
#: answer where one comes (in milliseconds): only a hang reaches it.
LONG = 120

ROW = 64          # PC units per row
BOOT_CODE = 0x17F40


# ------------------------------------------------------------------ .hex maker

def record(rtype, addr, data=b''):
    body = bytes([len(data), (addr >> 8) & 0xFF, addr & 0xFF, rtype]) + bytes(data)
    return ':' + (body + bytes([(-sum(body)) & 0xFF])).hex().upper()


def make_hex(words, extra=None):
    """INHX32 text of {PC: 24-bit word} the way XC16 writes it: 4 bytes per
    instruction at byte address 2 * PC, phantom byte 0.  `extra`:
    {byte address: bytes} added as is (EEPROM, configuration)."""
    mem = {}
    for pc, w in words.items():
        a = 2 * pc
        mem[a], mem[a + 1], mem[a + 2], mem[a + 3] = w & 0xFF, (w >> 8) & 0xFF, w >> 16, 0
    for a, data in (extra or {}).items():
        for i, b in enumerate(data):
            mem[a + i] = b
    lines, upper = [], None
    addrs = sorted(mem)
    i = 0
    while i < len(addrs):
        a = addrs[i]
        if a >> 16 != upper:
            upper = a >> 16
            lines.append(record(4, 0, bytes([upper >> 8, upper & 0xFF])))
        chunk = [mem[a]]
        while (i + len(chunk) < len(addrs) and addrs[i + len(chunk)] == a + len(chunk)
               and len(chunk) < 16 and (a + len(chunk)) >> 16 == upper):
            chunk.append(mem[a + len(chunk)])
        lines.append(record(0, a & 0xFFFF, bytes(chunk)))
        i += len(chunk)
    lines.append(record(1, 0))
    return '\n'.join(lines) + '\n'


def goto_words(target):
    return 0x040000 | (target & 0xFFFE), (target >> 16) & 0x7F


def sample_program():
    """Reset GOTO to 0x200, an interrupt vector, code spread over 4 rows,
    one of them partial and one starting mid-row."""
    w0, w1 = goto_words(0x200)
    words = {0: w0, 2: w1, 0x14: 0x000200}
    for i in range(40):                      # 0x200.. : rows 0x200 and 0x240 (partly)
        words[0x200 + 2 * i] = 0x780000 + i
    for i in range(5):                       # mid-row at 0x1000 + 0x20
        words[0x1020 + 2 * i] = 0xEB0000 | i
    words[0x17EFE] = 0x123456                # last word below the bootloader's row
    return words


# ------------------------------------------------------------------ simulator

class Bootloader(threading.Thread):
    """swarm-fake-epuck's Tiny Bootloader (swarmtools.fake_epuck.bootloader)
    on the master side of a pty: the robot is reset when the flasher's
    first byte arrives (as the handshake presses reset on a fake robot),
    so its listening window starts then."""

    def __init__(self, master, answer_after=1, noise=b'', nak=None, stop_after=None,
                 silent=False, initial=None, flood=False):
        super().__init__(daemon=True)
        self.fd = master
        self.silent = silent
        self.flash = dict(initial or {})    # PC -> (lo, mid, up)
        faults = fake_boot.Faults(answer_after=answer_after, silent=silent, nak=dict(nak or {}),
                                  stop_after=stop_after, noise=noise, flood=flood)
        self.boot = fake_boot.Bootloader(self.flash, faults, now=0.0)
        self.stop = threading.Event()

    # What the tests read: the bootloader's record of the session.
    errors = property(lambda self: self.boot.deviations)
    rows = property(lambda self: self.boot.rows)
    receptions = property(lambda self: self.boot.receptions)
    ended = property(lambda self: self.boot.state == "ended")
    extra = property(lambda self: self.boot.after_end)

    def run(self):
        import select
        reset_at = None
        while not self.stop.is_set():
            now = 0.0 if reset_at is None else time.monotonic() - reset_at
            out = self.boot.poll(now)
            r, _, _ = select.select([self.fd], [], [], 0.01 if self.boot.faults.flood else 0.05)
            if r:
                try:
                    data = os.read(self.fd, 4096)
                except OSError:
                    return
                if reset_at is None:
                    reset_at = time.monotonic()
                out += self.boot.feed(data, time.monotonic() - reset_at)
            if out:
                try:
                    os.write(self.fd, out)
                except OSError:
                    return
            b = self.boot
            if b.state == "gone" or b.state == "ended" and now - b.ended_at >= fake_boot.END_GRACE_S:
                return                      # nothing more to answer: the session is over


def unread(fd):
    """Bytes waiting to be read on a descriptor (FIONREAD)."""
    import fcntl
    import struct
    import termios
    return struct.unpack('i', fcntl.ioctl(fd, termios.FIONREAD, b'\0' * 4))[0]


def word_of(t):
    return t[0] | (t[1] << 8) | (t[2] << 16)


class PtyCase(unittest.TestCase):
    def setUp(self):
        self.master, self.slave = pty.openpty()
        tty.setraw(self.slave)
        self.device = os.ttyname(self.slave)
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        if getattr(self, 'boot', None) is not None:
            self.boot.stop.set()
            self.boot.join(2)
        os.close(self.master)
        os.close(self.slave)
        self.tmp.cleanup()

    def hexfile(self, text, name='prog.hex'):
        path = os.path.join(self.tmp.name, name)
        with open(path, 'w') as f:
            f.write(text)
        return path

    def flash(self, hex_path, *args, boot=None, device=None):
        self.boot = boot
        if boot is not None:
            boot.start()
        r = subprocess.run([*FLASHER_CMD, hex_path, device or self.device,
                            '--timeout', str(LONG), *args],
                           capture_output=True, text=True, timeout=4 * LONG)
        if boot is not None:
            # Once it has read all the flasher sent, the bootloader may stop.
            end = time.monotonic() + LONG
            while boot.is_alive() and unread(self.master) and time.monotonic() < end:
                time.sleep(0.01)
            boot.stop.set()
            boot.join(LONG)
        return r


class TestFlashing(PtyCase):
    def test_flashes_relocates_and_writes_id(self):
        words = sample_program()
        boot = Bootloader(self.master, initial={0x17F40: (1, 2, 3)})
        r = self.flash(self.hexfile(make_hex(words)), '--robot-id', '1234', boot=boot)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])
        self.assertTrue(boot.ended)
        rows = boot.rows
        self.assertEqual(rows, sorted(rows[:-1]) + [0x17F00], 'rows ascending, boot row last')
        self.assertEqual(set(rows), {0x0, 0x200, 0x240, 0x1000, 0x17EC0, 0x17F00})
        f = boot.flash
        # every word of the program, but the reset vector, is as in the .hex
        for pc, w in words.items():
            if pc not in (0, 2):
                self.assertEqual(word_of(f[pc]), w, hex(pc))
        # undefined words of a written row are erased
        self.assertEqual(f[0x1000], (0xFF, 0xFF, 0xFF))
        self.assertEqual(f[0x4], (0xFF, 0xFF, 0xFF))
        # reset vector -> bootloader; program's GOTO at 0x17F38; id at 0x17F36
        self.assertEqual((word_of(f[0]), word_of(f[2])), goto_words(0x17F40))
        self.assertEqual((word_of(f[0x17F38]), word_of(f[0x17F3A])), goto_words(0x200))
        self.assertEqual(word_of(f[0x17F36]), 1234)
        self.assertEqual(f[0x17F00], (0xFF, 0xFF, 0xFF))
        self.assertEqual(f[0x17F40], (1, 2, 3), 'bootloader code untouched')
        self.assertIn('100 %', r.stderr)

    def test_without_robot_id_the_id_word_is_erased(self):
        boot = Bootloader(self.master)
        r = self.flash(self.hexfile(make_hex(sample_program())), boot=boot)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])
        self.assertEqual(boot.flash[0x17F36], (0xFF, 0xFF, 0xFF))
        self.assertIn('no --robot-id', r.stderr)

    def test_waits_for_reset_and_ignores_program_output(self):
        boot = Bootloader(self.master, answer_after=4, noise=b'\x00telemetry q\x00K')
        r = self.flash(self.hexfile(make_hex(sample_program())), boot=boot)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])
        self.assertTrue(boot.ended)

    def test_retries_a_packet_answered_n(self):
        boot = Bootloader(self.master, nak={1: 2, 3: 1})
        r = self.flash(self.hexfile(make_hex(sample_program())), boot=boot)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])
        self.assertEqual(boot.receptions[1], 3)
        self.assertEqual(boot.receptions[3], 2)
        self.assertEqual(boot.receptions[0], 1)
        self.assertTrue(boot.ended)

    def test_gives_up_after_too_many_n(self):
        boot = Bootloader(self.master, nak={2: 100})
        r = self.flash(self.hexfile(make_hex(sample_program())), '--retries', '3', boot=boot)
        self.assertEqual(r.returncode, 1)
        self.assertIn("answered 'N'", r.stderr)
        self.assertIn('gave up after 3 retries', r.stderr)
        self.assertEqual(boot.receptions[2], 4)
        self.assertFalse(boot.ended)

    def test_timeout_when_the_robot_stops_answering(self):
        boot = Bootloader(self.master, stop_after=2)
        r = self.flash(self.hexfile(make_hex(sample_program())), '--timeout', '0.5', boot=boot)
        self.assertEqual(r.returncode, 1)
        self.assertIn('timeout: no reply within 0.5 s', r.stderr)
        self.assertIn('(3/6)', r.stderr)

    def test_no_bootloader(self):
        boot = Bootloader(self.master, silent=True)
        r = self.flash(self.hexfile(make_hex(sample_program())), '--handshake-tries', '3', boot=boot)
        self.assertEqual(r.returncode, 1)
        self.assertIn('no answer from the bootloader after 3 tries', r.stderr)
        self.assertEqual(boot.errors, [])

    def test_skips_eeprom_and_configuration(self):
        extra = {2 * 0x7FFC00: bytes([1, 2, 0, 0]), 2 * 0xF80000: bytes([0x3F, 0xC7, 0, 0])}
        boot = Bootloader(self.master)
        r = self.flash(self.hexfile(make_hex(sample_program(), extra)), boot=boot)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])
        self.assertIn('EEPROM', r.stderr)
        self.assertIn('configuration', r.stderr)
        self.assertTrue(all(pc < 0x18000 for pc in boot.flash))

    def test_handshake_keeps_its_pace_under_a_flood(self):
        """The robot's program floods the line: each try still ends on time,
        so the 5th 0xC1 arrives within the 50 tries (a try used to last as
        long as the flood, which lasts until the answer: never)."""
        boot = Bootloader(self.master, answer_after=5, flood=True)
        r = self.flash(self.hexfile(make_hex(sample_program())), boot=boot)    # 50 tries
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(boot.errors, [])

    def test_each_handshake_try_ends_while_bytes_never_stop(self):
        """A port that always has bytes to read (never a 'q'): every try must
        still end after its period, so 3 tries send 3 handshakes and give up
        (a try used to read until the line fell silent: forever here)."""
        class EndlessPort:
            def __init__(self):
                self.written = b''

            def write(self, data):
                self.written += data

            def read_some(self, timeout, limit=4096):
                return b'x' * 64

            def read_byte(self, timeout):
                return ord('x')

        port = EndlessPort()
        outcome = []

        def run():
            try:
                ef.handshake(port, 3, period=0.05)
                outcome.append('answered')
            except ef.FlashError as e:
                outcome.append(str(e))
        t = threading.Thread(target=run, daemon=True)
        t.start()
        t.join(LONG)
        self.assertFalse(t.is_alive(), 'the handshake never ended')
        self.assertEqual(port.written, bytes([0xC1]) * 3)
        self.assertIn('no answer from the bootloader after 3 tries', outcome[0])

    def test_not_a_serial_device_says_why_in_words(self):
        r = self.flash(self.hexfile(make_hex(sample_program())), device='/dev/null')
        self.assertEqual(r.returncode, 1)
        self.assertIn('/dev/null is not a serial device: Inappropriate ioctl for device', r.stderr)
        self.assertNotIn('(25,', r.stderr)

    def test_missing_device(self):
        r = self.flash(self.hexfile(make_hex(sample_program())),
                       device=os.path.join(self.tmp.name, 'rfcomm9'))
        self.assertEqual(r.returncode, 1)
        self.assertIn('cannot open', r.stderr)


class TestBadHex(PtyCase):
    """Every one of these exits 2 before touching the device: the device
    path given does not exist, and the message is about the .hex."""

    def check(self, text, *expected, args=()):
        path = self.hexfile(text)
        r = self.flash(path, *args, device=os.path.join(self.tmp.name, 'never-opened'))
        self.assertEqual(r.returncode, 2, r.stderr)
        for e in expected:
            self.assertIn(e, r.stderr)
        self.assertNotIn('cannot open', r.stderr)
        return r

    def good_lines(self):
        return make_hex(sample_program()).splitlines()

    def test_bad_checksum_names_the_line(self):
        lines = self.good_lines()
        rec = lines[3]
        lines[3] = rec[:-2] + '%02X' % ((int(rec[-2:], 16) + 1) & 0xFF)
        self.check('\n'.join(lines) + '\n', 'prog.hex:4:', 'checksum')

    def test_corrupted_data_byte(self):
        lines = self.good_lines()
        rec = lines[2]
        lines[2] = rec[:9] + ('0' if rec[9] != '0' else '1') + rec[10:]
        self.check('\n'.join(lines) + '\n', 'prog.hex:3:', 'checksum')

    def test_not_hex_digits(self):
        lines = self.good_lines()
        lines[1] = lines[1][:5] + 'ZZ' + lines[1][7:]
        self.check('\n'.join(lines) + '\n', 'prog.hex:2:', "'Z' is not a hex digit")

    def test_missing_colon(self):
        lines = self.good_lines()
        lines[2] = lines[2][1:]
        self.check('\n'.join(lines) + '\n', 'prog.hex:3:', "start with ':'")

    def test_length_mismatch(self):
        lines = self.good_lines()
        lines[2] = lines[2][:-6] + lines[2][-2:]
        self.check('\n'.join(lines) + '\n', 'prog.hex:3:')

    def test_unknown_record_type(self):
        lines = self.good_lines()
        lines.insert(1, record(7, 0, b'\x01'))
        self.check('\n'.join(lines) + '\n', 'prog.hex:2:', 'unknown record type 0x07')

    def test_truncated_file(self):
        text = make_hex(sample_program())
        self.check(text[:len(text) // 2], 'prog.hex')
        lines = self.good_lines()
        self.check('\n'.join(lines[:-1]) + '\n', 'no end-of-file record', 'truncated')

    def test_data_after_end_of_file(self):
        lines = self.good_lines()
        lines.append(lines[1])
        self.check('\n'.join(lines) + '\n', 'after the end-of-file record')

    def test_empty_and_binary_files(self):
        self.check('', 'no end-of-file record')
        path = os.path.join(self.tmp.name, 'bin.hex')
        with open(path, 'wb') as f:
            f.write(b'\xff\xfe\x00garbage')
        r = self.flash(path, device=os.path.join(self.tmp.name, 'never-opened'))
        self.assertEqual(r.returncode, 2)
        self.assertIn('not a text file', r.stderr)

    def test_refuses_bootloader_region(self):
        for pc in (0x17F00, 0x17F38, 0x17F40, 0x17FFE):
            words = sample_program()
            words[pc] = 0x000000
            self.check(make_hex(words), 'refused', 'bootloader', f'0x{pc:05X}')

    def test_refuses_memory_the_dspic_lacks(self):
        words = sample_program()
        words[0x20000] = 1
        self.check(make_hex(words), 'refused', 'not memory of the dsPIC30F6014A')

    def test_needs_a_reset_goto(self):
        words = sample_program()
        del words[0], words[2]
        self.check(make_hex(words), 'no reset vector')
        words = sample_program()
        words[0] = 0x123456
        self.check(make_hex(words), 'not a GOTO')
        words = sample_program()
        words[0], words[2] = goto_words(0x17F40)
        self.check(make_hex(words), 'inside the bootloader')

    def test_bad_arguments(self):
        path = self.hexfile(make_hex(sample_program()))
        r = self.flash(path, '--robot-id', '70000', device=os.path.join(self.tmp.name, 'x'))
        self.assertEqual(r.returncode, 2)
        self.assertIn('--robot-id', r.stderr)


class TestPackets(unittest.TestCase):
    def test_packet_layout(self):
        data = bytes(range(96))
        p = ef.packet(0x12340, data)
        self.assertEqual(len(p), 101)
        self.assertEqual(p[:4], bytes([0x40, 0x23, 0x01, 0x60]))
        self.assertEqual(p[4:100], data)
        self.assertEqual(sum(p) & 0xFF, 0)

    def test_goto_round_trip(self):
        for t in (0, 0x200, 0x17F40, 0x17EFE):
            w0, w1 = ef.encode_goto(t)
            self.assertEqual(ef.decode_goto(w0, w1), t)
        self.assertEqual(ef.encode_goto(0x17F40), ([0x40, 0x7F, 0x04], [0x01, 0x00, 0x00]))

    def test_parse_extended_segment(self):
        text = record(2, 0, b'\x10\x00') + '\n' + record(0, 0x10, b'\xAA') + '\n' + record(1, 0) + '\n'
        self.assertEqual(ef.parse_hex(text), {0x10010: 0xAA})


class Summary(unittest.TextTestResult):
    pass


if __name__ == '__main__':
    runner = unittest.TextTestRunner(verbosity=1, resultclass=Summary)
    result = runner.run(unittest.defaultTestLoader.loadTestsFromModule(sys.modules[__name__]))
    failed = len(result.failures) + len(result.errors)
    print(f'flasher tests: {result.testsRun - failed} passed, {failed} failed')
    sys.exit(0 if result.wasSuccessful() else 1)
