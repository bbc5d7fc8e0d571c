#!/usr/bin/env python3
"""test_epuck2.py - the e-puck2 flasher (swarmtools.flash.epuck2).

End to end against a real GDB server: QEMU's gdbstub (netduinoplus2, the
e-puck2's Cortex-M4F, started halted with -S) takes the e-puck2 PIL image
(make epuck2-pil: build/firmware/epuck2/pil/phototaxis.elf) by `load` and
`compare-sections`; started (--start jump) it runs, and its UART's bytes
decode to telemetry frames of robot 5 (the image stops QEMU itself after
3 s of emulated time).  The probe's own commands (monitor swdp_scan, attach
1) and its failures are covered by a scripted fake GDB that prints what
gdb-multiarch prints for them; the wrong image, missing port and missing
GDB cases by the flasher's checks before anything is sent.

The cases before GDB and against the fake run the flasher's main() in this
process (a Python start-up each would cost more than the cases); the end
to end case runs it as `python -m swarmtools.flash.epuck2`, as a user does.

Run: .venv/bin/python -m tools.tests.flash.test_epuck2 ELF  (unittest; prints "N passed, M failed")
"""
import contextlib
import io
import os
import socket
import stat
import struct
import subprocess
import sys
import tempfile
import unittest

import swarmtools.flash.epuck2 as ef
from swarmtools.telemetry import frames

from ..telemetry.helpers import wait_for

ELF = None           # the PIL image (argv[1])
TIMEOUT_S = 120      # a bound only a hang reaches


def run_flasher(*args):
    """The flasher's main() in this process: (exit code, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = ef.main(list(args))
        except SystemExit as e:      # argparse's errors
            rc = e.code
    return rc, out.getvalue(), err.getvalue()


def run_flasher_command(*args):
    """The flasher as a user runs it (python -m swarmtools.flash.epuck2)."""
    r = subprocess.run([sys.executable, '-m', 'swarmtools.flash.epuck2', *args],
                       capture_output=True, text=True, timeout=TIMEOUT_S)
    return r.returncode, r.stdout, r.stderr


def minimal_elf(machine=ef.EM_ARM, paddr=0x08000000, size=16):
    """An ELF header and one PT_LOAD program header, nothing else."""
    head = b'\x7fELF' + bytes([1, 1, 1]) + bytes(9)
    head += struct.pack('<HHIIIIIHHHHHH', 2, machine, 1, paddr, 52, 0, 0, 52, 32, 1, 40, 0, 0)
    ph = struct.pack('<IIIIIIII', ef.PT_LOAD, 84, paddr, paddr, size, size, 5, 4)
    return head + ph + bytes(size)


class Checks(unittest.TestCase):
    """Refused before GDB runs: exit 2, the reason named."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def write(self, name, data):
        path = os.path.join(self.tmp.name, name)
        with open(path, 'wb') as f:
            f.write(data)
        return path

    def test_wrong_images(self):
        cases = [
            (self.write('a.hex', b':020000040000FA\n'), 'not an ELF file (an Intel HEX'),
            (self.write('avr.elf', minimal_elf(machine=83)), 'machine 83, not ARM'),
            (self.write('ram.elf', minimal_elf(paddr=0x20000000)), "outside the STM32F407's flash"),
            (self.write('empty.elf', minimal_elf(size=0)), 'nothing to load'),
            (os.path.join(self.tmp.name, 'none.elf'), 'cannot read it'),
        ]
        for path, why in cases:
            rc, _out, err = run_flasher(path, '127.0.0.1:1')
            self.assertEqual(rc, 2, err)
            self.assertIn(why, err)
            self.assertIn(path, err)

    def test_missing_port_and_gdb(self):
        good = self.write('good.elf', minimal_elf())
        rc, _out, err = run_flasher(good, '/dev/no-such-programmer')
        self.assertEqual(rc, 2)
        self.assertIn('/dev/no-such-programmer: no such port', err)
        rc, _out, err = run_flasher(good, '127.0.0.1:1', '--gdb', '/no/such/gdb')
        self.assertEqual(rc, 2)
        self.assertIn('install gdb-multiarch', err)

    def test_commands(self):
        cmds = ef.gdb_commands('/dev/ttyACM0', True, 'reset')
        self.assertEqual(cmds[:1] + cmds[2:], ['target extended-remote /dev/ttyACM0', 'attach 1', 'load',
                                               'compare-sections', 'kill'])
        self.assertIn("monitor swdp_scan", cmds[1])      # in GDB's Python, which stops on a refusal
        self.assertEqual(ef.gdb_commands('h:1', False, 'jump')[-1], 'detach')
        self.assertNotIn('swdp_scan', ' '.join(ef.gdb_commands('h:1', False, 'jump')))

    def test_bad_tcp_port_and_host(self):
        good = self.write('good.elf', minimal_elf())
        rc, _out, err = run_flasher(good, '127.0.0.1:70000')
        self.assertEqual(rc, 2)
        self.assertIn('port 70000 is not a TCP port', err)
        rc, _out, err = run_flasher(good, 'no-such-host.invalid:3333')
        self.assertEqual(rc, 2)
        self.assertIn('no such host no-such-host.invalid', err)


FAKE_GDB = r'''#!/bin/sh
# A scripted gdb-multiarch: prints what GDB and a Black Magic Probe print
# for the case in FAKE_CASE; records its arguments.
printf '%s\n' "$@" > "$FAKE_ARGS"
case "$FAKE_CASE" in
ok) cat <<EOF
Target voltage: 3.3V
Available Targets:
No. Att Driver
 1      STM32F40x M4
Loading section .text, size 0x1e708 lma 0x8000000
Section .text, range 0x8000000 -- 0x801e708: matched.
[Inferior 1 (Remote target) killed]
EOF
;;
noscan) echo 'SW-DP scan failed!'; echo "Don't know how to attach.  Try \"help target\"." >&2; exit 1;;
mismatch) echo 'Loading section .text, size 0x10 lma 0x8000000'; echo 'Section .text, range 0x8000000 -- 0x8000010: MIS-MATCHED!';;
refused) echo '/dev/ttyACM0: No such file or directory.' >&2; exit 1;;
erase) echo 'Loading section .text, size 0x10 lma 0x8000000'; echo 'Error erasing flash with vFlashErase packet' >&2; exit 1;;
notprobe) echo "unknown command: 'swdp_scan'"; echo 'epuck2-flash: not a probe: it does not know monitor swdp_scan'; exit 3;;
esac
'''


class ProbeReplies(unittest.TestCase):
    """The probe's replies, scripted: what each failure exits with and says."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.gdb = os.path.join(self.tmp.name, 'gdb-multiarch')
        with open(self.gdb, 'w') as f:
            f.write(FAKE_GDB)
        os.chmod(self.gdb, os.stat(self.gdb).st_mode | stat.S_IEXEC)
        self.elf = os.path.join(self.tmp.name, 'x.elf')
        with open(self.elf, 'wb') as f:
            f.write(minimal_elf())
        self.port = os.path.join(self.tmp.name, 'ttyACM0')   # a file standing for the device
        open(self.port, 'w').close()
        self.args = os.path.join(self.tmp.name, 'args')

    def flash(self, case):
        os.environ['FAKE_CASE'] = case
        os.environ['FAKE_ARGS'] = self.args
        return run_flasher(self.elf, self.port, '--gdb', self.gdb)

    def test_ok_scans_attaches_loads_verifies_resets(self):
        rc, out, err = self.flash('ok')
        self.assertEqual(rc, 0, err)
        self.assertIn('loaded and verified', out)
        with open(self.args) as f:
            args = f.read().split('\n')
        want = [f'target extended-remote {self.port}', 'attach 1', 'load', 'compare-sections', 'kill']
        self.assertEqual([a for a in args if a in want], want)
        self.assertIn('monitor swdp_scan', args[args.index('attach 1') - 2])
        self.assertEqual(args[-2], self.elf)

    def test_failures(self):
        for case, why in [('noscan', 'found no target'), ('mismatch', 'verify failed: .text'),
                          ('refused', 'no GDB server at'), ('erase', 'the load failed: Error erasing flash'),
                          ('notprobe', 'is not a probe (it does not know `monitor swdp_scan`)')]:
            rc, _out, err = self.flash(case)
            self.assertEqual(rc, 1, (case, err))
            self.assertIn(why, err, case)

    def test_nothing_listening_fails_before_gdb(self):
        # The same answer at once whatever --timeout: GDB is not even started.
        port = free_port()
        os.environ['FAKE_CASE'] = 'ok'
        os.environ['FAKE_ARGS'] = self.args
        for extra in ([], ['--timeout', '5'], ['--timeout', '0.5']):
            with self.subTest(extra=extra):
                rc, _out, err = run_flasher(self.elf, f'127.0.0.1:{port}', '--gdb', self.gdb, *extra)
                self.assertEqual(rc, 1, err)
                self.assertIn(f'no GDB server at 127.0.0.1:{port} (Connection refused)', err)
                self.assertFalse(os.path.exists(self.args), 'GDB was started')


def free_port():
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


class QemuGdbServer(unittest.TestCase):
    """Refused as a probe, then load and compare-sections through QEMU's
    gdbstub, and the image runs."""

    def test_load_verify_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            uart = os.path.join(tmp, 'uart.bin')
            port = free_port()
            qemu = subprocess.Popen(['qemu-system-arm', '-M', 'netduinoplus2', '-nodefaults', '-display', 'none',
                                     '-monitor', 'none', '-serial', f'file:{uart}',
                                     '-semihosting-config', 'enable=on,target=native',
                                     '-S', '-gdb', f'tcp:127.0.0.1:{port}'],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            try:
                # The gdbstub listens once QEMU is up: wait for it.
                def listening():
                    if qemu.poll() is not None:
                        self.fail('QEMU did not start its gdbstub: ' + qemu.stderr.read().decode())
                    try:
                        socket.create_connection(('127.0.0.1', port), timeout=1).close()
                        return True
                    except OSError:
                        return False
                wait_for(listening, "QEMU's gdbstub", timeout=TIMEOUT_S, every=0.05)
                # As a probe (the defaults): refused by name, and QEMU is left
                # running, halted, for the right command.
                rc, _out, err = run_flasher_command(ELF, f'127.0.0.1:{port}')
                self.assertEqual(rc, 1, err)
                self.assertIn(f'the GDB server at 127.0.0.1:{port} is not a probe', err)
                self.assertIn('--no-scan --start jump', err)
                self.assertIsNone(qemu.poll(), 'QEMU was killed')
                rc, out, err = run_flasher_command(ELF, f'127.0.0.1:{port}', '--no-scan', '--start', 'jump')
                self.assertEqual(rc, 0, err)
                self.assertIn('loaded and verified', out)
                # It runs: it stops QEMU itself after 3 s of emulated time.
                qemu.wait(TIMEOUT_S)
            finally:
                if qemu.poll() is None:
                    qemu.kill()
                    qemu.wait()
            self.assertEqual(qemu.returncode, 0)
            with open(uart, 'rb') as f:
                got = frames.FrameDecoder().feed(f.read())
            self.assertGreaterEqual(len(got), 3)
            self.assertEqual({fr.robot_id for fr in got}, {5})


class Summary(unittest.TextTestResult):
    pass


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit('usage: python -m tools.tests.flash.test_epuck2 PIL_ELF (build/firmware/epuck2/pil/phototaxis.elf)')
    ELF = sys.argv.pop(1)
    runner = unittest.TextTestRunner(verbosity=1, resultclass=Summary)
    result = runner.run(unittest.defaultTestLoader.loadTestsFromModule(sys.modules[__name__]))
    failed = len(result.failures) + len(result.errors)
    print(f'e-puck2 flasher tests: {result.testsRun - failed} passed, {failed} failed')
    sys.exit(0 if result.wasSuccessful() else 1)
