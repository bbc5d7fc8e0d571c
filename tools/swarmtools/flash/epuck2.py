#!/usr/bin/env python3
"""epuck2-flash (swarmtools.flash.epuck2) - loads an e-puck2 image (an .elf of
`make epuck2-firmware`) through the robot's on-board programmer, a GDB server
over USB that speaks the Black Magic Probe's protocol, with gdb-multiarch.

    .venv/bin/epuck2-flash build/firmware/epuck2/real/forager.elf /dev/ttyACM0
    (or make epuck2-flash ELF=... PORT=/dev/ttyACM0)

What it runs, in GDB's batch mode: `target extended-remote PORT`, `monitor
swdp_scan` and `attach 1` (the probe finds the STM32F407 and attaches to
it), `load` (writes the image's sections to flash), `compare-sections`
(reads them back), then `kill`, which makes the probe reset the robot: the
image runs.  PORT is the programmer's serial device, or HOST:PORT for a GDB
server over TCP; with --no-scan and --start jump it drives any GDB server
that takes `load` (QEMU's gdbstub, which the tests use: there the image is
started by setting SP and PC from its vector table and detaching).  A
server that refuses `monitor swdp_scan` is named as not a probe and left
as it was (GDB disconnects before `attach 1`, which would kill it).

Before GDB starts, the image is checked: an ELF file for 32-bit ARM whose
loadable sections all lie in the STM32F407's flash (0x08000000, 1 MB), so an
e-puck1 .hex, an AVR image or an image linked elsewhere is refused with
nothing written; and so is a port that does not exist.  A HOST:PORT is
connected to first: nothing listening there fails at once, as "no GDB
server".

Exit codes: 0 flashed and verified; 1 the programmer or the transfer failed
(no GDB server at PORT, no target found, load error, a section that does
not match); 2 bad arguments, a wrong image, a missing port or no GDB (then
nothing is sent).  Standard library only.
"""
import argparse
import os
import re
import shutil
import socket
import struct
import subprocess
import sys

PROG = 'epuck2_flash'
#: The STM32F407's flash: where every loadable byte of an e-puck2 image goes.
FLASH_START = 0x08000000
FLASH_BYTES = 1024 * 1024
EM_ARM = 40
PT_LOAD = 1
#: What `make deps` installs for it (tools/deps.sh).
GDB_PACKAGE = 'gdb-multiarch'
#: How long a HOST:PORT may take to accept the connection tried before GDB
#: starts (GDB itself retries a refused one for about 12 s).
CONNECT_TIMEOUT_S = 5.0
#: What the Python of SCAN prints when the server refused the probe's scan.
NOT_A_PROBE = 'epuck2-flash: not a probe'
#: `monitor swdp_scan` and what follows it, as GDB's Python.  A server that is
#: not a probe (QEMU's gdbstub, OpenOCD) refuses the command and has a halted
#: CPU attached already: `attach 1` would then ask "Kill it?", which batch
#: mode answers yes, and the server would die.  So on a refusal GDB leaves
#: the server as it found it (disconnect, not detach, which would resume it)
#: and stops before attach, with nothing written.
SCAN = rf"""
import re
try:
    said = gdb.execute('monitor swdp_scan', to_string=True)
except gdb.error as e:  # no monitor commands at all: an error, not output
    said = str(e)
print(said, end='')
if re.search(r"unknown command|invalid command|Target does not support this command|Protocol error with Rcmd", said, re.I):
    print('{NOT_A_PROBE}: it does not know monitor swdp_scan')
    gdb.execute('disconnect')
    gdb.execute('quit 3')
"""


class ImageError(Exception):
    """The file is not an e-puck2 image."""


def check_image(path):
    """The loadable segments (address, size) of the ELF at `path`, or
    ImageError saying why it is not an image for the e-puck2's flash."""
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as e:
        raise ImageError(f'{path}: cannot read it: {e.strerror}') from None
    if data[:4] != b'\x7fELF':
        hint = ' (an Intel HEX: the e-puck1 is flashed with epuck-flash)' if data[:1] == b':' else ''
        raise ImageError(f'{path}: not an ELF file{hint}')
    if len(data) < 52 or data[4] != 1 or data[5] != 1:
        raise ImageError(f'{path}: not a 32-bit little-endian ELF (the STM32F407 is one)')
    machine, = struct.unpack_from('<H', data, 18)
    if machine != EM_ARM:
        raise ImageError(f'{path}: an ELF for machine {machine}, not ARM ({EM_ARM}): not an e-puck2 image')
    phoff, = struct.unpack_from('<I', data, 28)
    phentsize, phnum = struct.unpack_from('<HH', data, 42)
    segments = []
    for k in range(phnum):
        off = phoff + k * phentsize
        if off + 32 > len(data):
            raise ImageError(f'{path}: truncated (program header {k})')
        p_type, _off, _vaddr, paddr, filesz = struct.unpack_from('<IIIII', data, off)
        if p_type != PT_LOAD or filesz == 0:
            continue
        if not (FLASH_START <= paddr and paddr + filesz <= FLASH_START + FLASH_BYTES):
            raise ImageError(f'{path}: loads {filesz} B at 0x{paddr:08X}, outside the STM32F407\'s flash '
                             f'(0x{FLASH_START:08X}, 1 MB): not linked for the e-puck2')
        segments.append((paddr, filesz))
    if not segments:
        raise ImageError(f'{path}: nothing to load')
    return segments


def gdb_commands(port, scan, start):
    cmds = [f'target extended-remote {port}']
    if scan:
        cmds += [f'python exec({SCAN!r})', 'attach 1']
    cmds += ['load', 'compare-sections']
    if start == 'reset':
        cmds.append('kill')
    else:
        cmds += ['set $sp = *(unsigned int *)0x08000000', 'set $pc = *(unsigned int *)0x08000004', 'detach']
    return cmds


def diagnose(rc, out, port, scan):
    """None when GDB's transcript says the image is loaded and verified,
    else what went wrong."""
    if scan and NOT_A_PROBE in out:
        return (f'the GDB server at {port} is not a probe (it does not know `monitor swdp_scan`), and it was '
                'left as it was: for QEMU\'s gdbstub or another plain GDB server use --no-scan --start jump')
    if 'Python scripting is not supported' in out:
        return f'this GDB has no Python, which the probe\'s scan needs: use {GDB_PACKAGE} (make deps installs it)'
    if re.search(r'MIS-MATCHED', out):
        bad = re.findall(r'Section (\S+), range .*MIS-MATCHED', out)
        return f'verify failed: {", ".join(bad) or "a section"} does not match what was loaded'
    if re.search(r'(Connection refused|No such file or directory|could not connect|Connection timed out|'
                 r'Remote communication error|not responding)', out, re.I) and 'Loading section' not in out:
        return f'no GDB server at {port}: is the robot on and its USB cable in, and is {port} its programmer\'s port?'
    if scan and re.search(r'(SW-DP scan failed|No usable targets found|Attaching to Remote target failed|'
                          r'Don\'t know how to attach)', out):
        return 'the programmer found no target (monitor swdp_scan / attach 1): is the robot switched on?'
    if re.search(r'(Load failed|Error erasing flash|Error writing data to flash|Memory access error)', out):
        return 'the load failed: ' + next(ln for ln in out.splitlines()
                                          if re.search(r'Load failed|Error|Memory access', ln)).strip()
    if rc != 0 or 'matched' not in out:
        tail = ' / '.join(ln.strip() for ln in out.strip().splitlines()[-3:])
        return f'GDB did not load and verify the image (exit {rc}): {tail}'
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(prog='epuck2-flash',
                                 description="Load an e-puck2 .elf through its on-board programmer (GDB).")
    ap.add_argument('elf', metavar='ELF', help='image built by make epuck2-firmware (build/firmware/epuck2/real/*.elf)')
    ap.add_argument('port', metavar='PORT', help="the programmer's serial device (/dev/ttyACM0), or HOST:PORT")
    ap.add_argument('--gdb', default=GDB_PACKAGE, help='the GDB to run (gdb-multiarch)')
    ap.add_argument('--no-scan', action='store_true',
                    help='skip monitor swdp_scan and attach 1 (a GDB server that is not a probe: '
                         'QEMU\'s gdbstub takes --no-scan --start jump)')
    ap.add_argument('--start', choices=('reset', 'jump'), default='reset',
                    help='how the image starts: the probe resets the robot (reset), or SP and PC are set '
                         'from its vector table (jump: QEMU)')
    ap.add_argument('--timeout', type=float, default=120.0, metavar='S', help='seconds GDB may take (120)')
    args = ap.parse_args(argv)
    if args.timeout <= 0:
        ap.error('--timeout must be > 0')

    try:
        segments = check_image(args.elf)
    except ImageError as e:
        print(f'{PROG}: {e}', file=sys.stderr)
        return 2
    tcp = re.fullmatch(r'([\w.-]*):(\d+)', args.port)
    if tcp and not 0 < int(tcp[2]) < 65536:
        print(f'{PROG}: {args.port}: port {tcp[2]} is not a TCP port (1 to 65535)', file=sys.stderr)
        return 2
    if not tcp and not os.path.exists(args.port):
        print(f'{PROG}: {args.port}: no such port: plug the robot in by USB and switch it on '
              '(ls /dev/serial/by-id/ shows its two serial ports: the programmer is one of them)', file=sys.stderr)
        return 2
    gdb = shutil.which(args.gdb)
    if gdb is None:
        print(f'{PROG}: {args.gdb} not found: install {GDB_PACKAGE} (make deps does)', file=sys.stderr)
        return 2

    if tcp:
        # Nothing listening fails here at once, the same whatever --timeout
        # (GDB would retry for 12 s, or run into a shorter --timeout).
        host = tcp[1] or 'localhost'
        try:
            socket.create_connection((host, int(tcp[2])), timeout=CONNECT_TIMEOUT_S).close()
        except socket.gaierror:
            print(f'{PROG}: {args.port}: no such host {host}', file=sys.stderr)
            return 2
        except OSError as e:
            why = 'nothing answered' if isinstance(e, socket.timeout) else (e.strerror or str(e))
            print(f'{PROG}: no GDB server at {args.port} ({why}): is the GDB server running there '
                  '(for QEMU: -gdb tcp:HOST:PORT)?', file=sys.stderr)
            return 1
    cmd = [gdb, '-nx', '--batch']
    for c in gdb_commands(args.port, not args.no_scan, args.start):
        cmd += ['-ex', c]
    cmd.append(args.elf)
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        print(f'{PROG}: GDB did not finish within {args.timeout:g} s (is {args.port} a GDB server?)', file=sys.stderr)
        return 1
    out = r.stdout + r.stderr
    why = diagnose(r.returncode, out, args.port, not args.no_scan)
    if why:
        print(f'{PROG}: {why}', file=sys.stderr)
        return 1
    total = sum(n for _a, n in segments)
    print(f'{PROG}: {args.elf}: {total} B in {len(segments)} segment(s) loaded and verified through {args.port}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
