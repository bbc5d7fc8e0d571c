"""Logs as untrusted input (issue 12's defects): a corrupt length field, a
channel name that is not UTF-8, and channel names that try to leave the
export folder. Each tool ends with one clear line (exit 1), never a signal
or a traceback, and nothing is written outside the folder it was given."""

import os
import struct
import subprocess
import sys

from swarmtools.telemetry import logfile

from .helpers import ROOT, TempDir, robot_state

SYNC = 0xEDA1DA01


def raw_event(num, channel: bytes, data: bytes, data_len=None):
    n = len(data) if data_len is None else data_len
    return struct.pack(">Iqqii", SYNC, num, 1000 * num, len(channel), n) + channel + data


def run_tool(module, *args, cwd=None):
    return subprocess.run([sys.executable, "-m", f"swarmtools.telemetry.{module}", *map(str, args)],
                          capture_output=True, text=True, timeout=120, cwd=cwd or ROOT, check=False)


class HostileLogs(TempDir):
    def good(self, robot_id=1):
        return robot_state(robot_id=robot_id, values=()).encode()

    def test_huge_length_is_an_error_naming_the_offset(self):
        path = self.tmp / "bad.lcmlog"
        first = raw_event(0, b"ROBOT_STATE", self.good())
        path.write_bytes(first + raw_event(1, b"ROBOT_STATE", b"", data_len=0x7FFFFFFF))
        with self.assertRaisesRegex(logfile.LogError, f"corrupt event at byte {len(first)}: .*2147483647"):
            list(logfile.events(path))
        for module, args in (("export_csv", (path,)), ("plot_run", (path, "-o", self.tmp / "plots")),
                             ("monitor", ("--log", path, "--plain", "--exit-idle", "1"))):
            with self.subTest(tool=module):
                r = run_tool(module, *args)
                self.assertGreater(r.returncode, 0, r.stderr)     # an exit status, not a signal
                self.assertIn(f"corrupt event at byte {len(first)}", r.stderr)
                self.assertNotIn("Traceback", r.stderr)

    def test_garbage_and_truncated_files(self):
        for name, data, want in (("garbage", b"\x00" * 64, "not an LCM log"),
                                 ("cut", raw_event(0, b"ROBOT_STATE", self.good())[:30], "not an LCM log"),
                                 ("negative", raw_event(0, b"X", b"", data_len=-5), "not an LCM log")):
            with self.subTest(name):
                path = self.tmp / f"{name}.lcmlog"
                path.write_bytes(data)
                r = run_tool("export_csv", path)
                self.assertEqual(r.returncode, 1, r.stderr)
                self.assertIn(want, r.stderr)
                self.assertNotIn("Traceback", r.stderr)

    def test_channel_that_is_not_utf8(self):
        path = self.tmp / "names.lcmlog"
        path.write_bytes(raw_event(0, b"\xff\xfeROBOT_STATE", self.good()))
        self.assertEqual([e.channel for e in logfile.events(path)], ["\\xff\\xfeROBOT_STATE"])
        out = self.tmp / "csv"
        r = run_tool("export_csv", path, "-o", f"{out}/")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("Traceback", r.stderr)
        files = os.listdir(out)
        self.assertEqual(len(files), 1)
        self.assertRegex(files[0], r"^[A-Za-z0-9_.-]+\.csv$")
        r = run_tool("plot_run", path, "-o", self.tmp / "plots")
        self.assertNotIn("Traceback", r.stderr)

    def test_channel_names_cannot_leave_the_export_folder(self):
        path = self.tmp / "escape.lcmlog"
        path.write_bytes(raw_event(0, b"../../escROBOT_STATE", self.good(1))
                         + raw_event(1, b"A/BROBOT_STATE", self.good(2))
                         + raw_event(2, b"ROBOT_STATE", self.good(3)))
        work = self.tmp / "deep" / "cwd"
        work.mkdir(parents=True)
        r = run_tool("export_csv", path, "-o", "out/", cwd=work)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("Traceback", r.stderr)
        written = sorted(p.relative_to(self.tmp) for p in self.tmp.rglob("*.csv"))
        self.assertEqual(len(written), 3, written)
        for p in written:
            self.assertEqual(p.parent.as_posix(), "deep/cwd/out", written)
        self.assertIn("deep/cwd/out/ROBOT_STATE.csv", [p.as_posix() for p in written])

    def test_a_raw_name_and_its_escaped_text_stay_two_channels(self):
        # Before: b"X\xff" read as "X\\xff", which is also what the plain
        # name "X\xff" (a backslash, x, f, f) reads as: one file held both.
        path = self.tmp / "twins.lcmlog"
        path.write_bytes(raw_event(0, b"X\xffROBOT_STATE", self.good(1))
                         + raw_event(1, b"X\\xffROBOT_STATE", self.good(2))
                         + raw_event(2, b"X\\xffROBOT_STATE", self.good(2)))
        names = [e.channel for e in logfile.events(path)]
        self.assertEqual(names, ["X\\xffROBOT_STATE", "X\\\\xffROBOT_STATE", "X\\\\xffROBOT_STATE"])
        out = self.tmp / "csv"
        r = run_tool("export_csv", path, "-o", f"{out}/")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = {}
        for f in out.iterdir():
            lines = f.read_text().splitlines()
            col = lines[0].split(",").index("robot_id")
            rows[f.name] = sorted(line.split(",")[col] for line in lines[1:])
        self.assertEqual(sorted(rows.values()), [["1"], ["2", "2"]], rows)
