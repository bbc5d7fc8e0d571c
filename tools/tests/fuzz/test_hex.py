"""Properties of the flasher's .hex reading (swarmtools.flash.epuck), the
one parser of a file a user hands the robot:

- any text is parsed or refused with a HexError that names the file (and
  the line, when a line is at fault); nothing else is raised;
- an Intel HEX file written here (records of any length, extended linear
  address records where needed and where not, lower-case digits, CRLF,
  blank lines, start-address records) reads back to exactly its bytes;
- one hex digit changed, anywhere, is refused, naming its line; a file cut
  before the end of its end-of-file record is refused;
- for a program image, the rows sent are whole packets that sum to 0, and
  written in order into a model of the bootloader's memory they give the
  program with its reset vector moved and the robot id in place;
- the command line ends with exit status 2 (bad .hex) or 1 (the device)
  for any file, never with a traceback.
"""
import contextlib
import io
import tempfile
import unittest
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

import swarmtools.flash.epuck as ef

NAME = "prog.hex"


def record(rtype, addr, data=b""):
    body = bytes([len(data), (addr >> 8) & 0xFF, addr & 0xFF, rtype]) + bytes(data)
    return ":" + (body + bytes([(-sum(body)) & 0xFF])).hex().upper()


@st.composite
def hex_files(draw, mem_strategy=None):
    """(text, {byte address: byte}) of a well-formed file in varied forms."""
    mem = draw(mem_strategy if mem_strategy is not None else memories())
    lines, upper = [], None
    addrs = sorted(mem)
    i = 0
    while i < len(addrs):
        a = addrs[i]
        if a >> 16 != upper or draw(st.integers(0, 15)) == 0:   # sometimes needlessly
            upper = a >> 16
            lines.append(record(0x04, 0, bytes([upper >> 8, upper & 0xFF])))
        size = draw(st.integers(1, 32))
        run = [a]
        while (len(run) < size and i + len(run) < len(addrs) and addrs[i + len(run)] == a + len(run)
               and (a + len(run)) >> 16 == upper):
            run.append(a + len(run))
        lines.append(record(0x00, a & 0xFFFF, bytes(mem[x] for x in run)))
        i += len(run)
    if draw(st.booleans()):
        lines.append(record(0x05, 0, b"\x00\x00\x01\x00"))
    lines.append(record(0x01, 0))
    if draw(st.booleans()):
        lines = [ln.lower() for ln in lines]
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines) - 1)), "")
    eol = draw(st.sampled_from(["\n", "\r\n"]))
    return eol.join(lines) + draw(st.sampled_from(["", eol])), mem


def memories():
    """Bytes at addresses below and above 64 KB, in runs, as a linker writes them."""
    run = st.tuples(st.integers(0, 0x2FFFF), st.binary(min_size=1, max_size=80))
    return st.lists(run, max_size=6).map(
        lambda runs: {a + k: b for a, data in runs for k, b in enumerate(data) if a + k < 0x30000})


def line_of(text, index):
    return text.count("\n", 0, index) + 1


class Parse(unittest.TestCase):
    @given(st.text(alphabet=st.sampled_from(":0123456789ABCDEFabcdefg \r\n\t"), max_size=300))
    def test_any_text_is_parsed_or_refused_by_name(self, text):
        try:
            mem = ef.parse_hex(text, NAME)
        except ef.HexError as e:
            self.assertTrue(str(e).startswith(NAME + ":"), str(e))
            return
        self.assertIsInstance(mem, dict)

    @given(st.text(max_size=200))
    def test_any_unicode_is_parsed_or_refused(self, text):
        with contextlib.suppress(ef.HexError):
            ef.parse_hex(text, NAME)

    @given(hex_files())
    def test_round_trip(self, file):
        text, mem = file
        self.assertEqual(ef.parse_hex(text, NAME), mem)

    @given(hex_files(), st.data())
    def test_one_digit_changed_is_refused_at_its_line(self, file, data):
        text, _ = file
        digits = [i for i, c in enumerate(text) if c in "0123456789abcdefABCDEF"]
        i = data.draw(st.sampled_from(digits))
        new = data.draw(st.sampled_from([c for c in "0123456789ABCDEF" if c != text[i].upper()]))
        bad = text[:i] + new + text[i + 1:]
        with self.assertRaises(ef.HexError) as cm:
            ef.parse_hex(bad, NAME)
        self.assertTrue(str(cm.exception).startswith(f"{NAME}:{line_of(text, i)}:"), str(cm.exception))

    @given(hex_files(), st.data())
    def test_cut_short_is_refused(self, file, data):
        text, _ = file
        end = text.rstrip("\r\n").__len__()     # the end of the end-of-file record
        cut = data.draw(st.integers(0, end - 1))
        with self.assertRaises(ef.HexError):
            ef.parse_hex(text[:cut], NAME)


@st.composite
def programs(draw):
    """{PC: 24-bit word} of a program image: a reset GOTO at 0 into the
    program, words anywhere below the bootloader's row."""
    target = draw(st.integers(0x100, ef.BOOT_ROW - 2)) & ~1
    goto0, goto1 = ef.encode_goto(target)
    words = {0: goto0[0] | goto0[1] << 8 | goto0[2] << 16, 2: goto1[0] | goto1[1] << 8 | goto1[2] << 16}
    for pc in draw(st.lists(st.integers(2, ef.BOOT_ROW // 2 - 1), max_size=40)):
        words[2 * pc] = draw(st.integers(0, 0xFFFFFF))
    return words, target


def image(words):
    """The {byte address: byte} XC16 writes for `words` (phantom byte 0)."""
    mem = {}
    for pc, w in words.items():
        mem.update({2 * pc: w & 0xFF, 2 * pc + 1: (w >> 8) & 0xFF, 2 * pc + 2: w >> 16, 2 * pc + 3: 0})
    return mem


class Rows(unittest.TestCase):
    @given(programs(), st.one_of(st.none(), st.integers(0, 0xFFFE)))
    def test_rows_write_the_program_and_the_bootloader_row(self, prog, robot_id):
        words, target = prog
        pw, notes = ef.program_words(image(words))
        rows, entry = ef.build_rows(pw, robot_id)
        self.assertEqual((entry, notes), (target, []))
        flash = {}
        for k, (row, data) in enumerate(rows):
            self.assertEqual(len(data), ef.PACKET_DATA)
            self.assertEqual(sum(ef.packet(row, data)) & 0xFF, 0)
            self.assertEqual(row % ef.ROW_PC, 0)
            self.assertTrue(row < ef.BOOT_ROW or (row == ef.BOOT_ROW and k == len(rows) - 1))
            for i in range(ef.ROW_WORDS):
                flash[row + 2 * i] = int.from_bytes(data[3 * i:3 * i + 3], "little")
        self.assertEqual(rows[-1][0], ef.BOOT_ROW)
        boot = ef.encode_goto(ef.BOOT_ENTRY)
        self.assertEqual((flash[0], flash[2]), tuple(int.from_bytes(bytes(w), "little") for w in boot))
        self.assertEqual((flash[ef.USER_RESET], flash[ef.USER_RESET + 2]), (words[0], words[2]))
        self.assertEqual(flash[ef.ROBOT_ID_PC], 0xFFFFFF if robot_id is None else robot_id)
        for pc, w in words.items():
            if pc not in (0, 2):
                self.assertEqual(flash[pc], w)

    @given(programs(), st.integers(ef.BOOT_ROW, ef.FLASH_END - 2))
    def test_a_word_in_the_bootloader_is_refused(self, prog, pc):
        words, _ = prog
        words[pc & ~1] = 0
        with self.assertRaises(ef.HexError) as cm:
            ef.build_rows(ef.program_words(image(words))[0], None)
        self.assertIn("bootloader", str(cm.exception))


class CommandLine(unittest.TestCase):
    @given(st.one_of(st.binary(max_size=300), hex_files(memories()).map(lambda f: f[0].encode())))
    def test_any_file_ends_with_status_1_or_2(self, content):
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / NAME
            path.write_bytes(content)
            err = io.StringIO()
            with contextlib.redirect_stderr(err):
                rc = ef.main([str(path), str(Path(tmp) / "no-such-device"), "--handshake-tries", "1"])
        self.assertIn(rc, (1, 2), err.getvalue())
        self.assertNotIn("Traceback", err.getvalue())
        if rc == 1:
            self.assertIn("cannot open", err.getvalue())


if __name__ == "__main__":
    unittest.main()
