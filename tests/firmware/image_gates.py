#!/usr/bin/env python3
"""image_gates.py - the portable gates of the e-puck firmware images.

For every image (firmware/apps/*_main.c with hal/epuck and its IR backend)
and every target:

  avr  avr-gcc -mmcu=atmega2560: 16-bit int and pointers, 32-bit double, the
       data model of XC16 on the dsPIC30F6014A, and 8 KB of RAM like it;
  arm  arm-none-eabi-gcc for a Cortex-M4F (the e-puck2's STM32F407 class),

it compiles every source warning-free (-std=c99 -pedantic -Wall -Wextra
-Werror ...) with -fstack-usage, links the image against the stubs of the
e-puck library functions (tests/firmware/stubs/) and measures:

The images that publish telemetry (telemetry_images) also link lcm-gen's C
code of robot_state_t (--lcm-c-dir, from `make lcm-types`; headers of LCM
from --lcm-cflags), compiled with the same warnings as ours; --gc-sections
drops its decoder (malloc) and its publish/subscribe functions.  Its
objects, and their hash cache, count as ours in the static RAM.

  static RAM   .data + .bss of OUR objects (firmware/, hal/), taken from the
               link map after --gc-sections, without the camera frames and
               without the stubs (they stand for the library) or the C
               library.  Constant data (.rodata) is counted as flash: XC16
               keeps const data in program memory (PSV).  GATE on the avr
               target: <= 2048 bytes (the dsPIC's 8 KB must also hold the
               library's buffers, the camera frames and the stacks).
  frames       the camera's two frames (static `camera_frames` of an app).
  stack        worst call chain from main, plus the worst chain of the
               timer-2 agenda callback (it interrupts main anywhere): the
               sum of the frames of the functions on the chain (GCC's
               -fstack-usage .su files; for functions of libgcc/libc, which
               have none, the pushes of their code), plus the return
               address of every call (3 bytes on the atmega2560, 0 on ARM
               where LR is saved inside the frame).  The call graph comes
               from the disassembly of the linked image (direct calls and
               tail jumps); indirect calls are reported.
  flash        .text + .rodata + .data initialisers of our objects, and of
               the whole image (with the stubs, libgcc's software float...).
               AVR code is 8-bit code: the dsPIC's will be smaller.

Prints a table, writes it to build/firmware/footprint.md (and the
documentation's form of it to footprint_readme.md), exits 1 when a compile
or link fails, the RAM gate is exceeded or the documentation's table
(docs/hardware/footprint.md) is not the measured one.  Standard library only.

usage: image_gates.py [--build DIR] [--jobs N] IMAGE:BACKEND ...
"""
import argparse
import concurrent.futures
import os
import re
import shlex
import subprocess
import sys

import readme_footprint

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
RAM_GATE = 2048

WARN = ('-std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes '
        '-Wmissing-prototypes')
INC = '-Ihal -Ifirmware -Ihal/epuck -Itests/firmware/stubs'
COMMON = '-Os -ffunction-sections -fdata-sections -fstack-usage'

TARGETS = {
    'avr': {
        'cc': 'avr-gcc',
        'cflags': '-mmcu=atmega2560',
        'ldflags': '-mmcu=atmega2560 -Wl,--gc-sections',
        'objdump': 'avr-objdump',
        'ret_bytes': 3,
        'what': 'avr-gcc atmega2560 (16-bit int, XC16 data model, 8 KB RAM)',
    },
    'arm': {
        'cc': 'arm-none-eabi-gcc',
        'cflags': '-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16',
        'ldflags': ('-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 '
                    '--specs=nano.specs --specs=nosys.specs -Wl,--gc-sections'),
        'objdump': 'arm-none-eabi-objdump',
        'ret_bytes': 0,
        'what': 'arm-none-eabi-gcc Cortex-M4F (e-puck2 class)',
    },
}

BACKEND_SOURCES = {
    'randb': (['hal/epuck/ircom_randb.c'],
              ['tests/firmware/stubs/adscan_stubs.c', 'tests/firmware/stubs/randb_stubs.c']),
    'libircom': (['hal/epuck/ircom_libircom.c'], ['tests/firmware/stubs/ircom_stubs.c']),
}


# The generated sources an image with telemetry links, and its own: the
# robot's telemetry (portable, the simulator runs it too) and the e-puck's
# platform values for it.
LCM_TYPES_LINKED = ('robot_state_t', 'schema_t')
TELEMETRY_APP_SOURCES = ['firmware/telemetry/robot_telemetry.c', 'firmware/apps/app_telemetry.c']


def read_images(path):
    """(image, backend) pairs and the set of images with telemetry, from the
    image list; exits with the file and line of a bad entry."""
    images, telemetry = [], set()
    with open(os.path.join(ROOT, path), encoding='utf-8') as fh:
        for lineno, line in enumerate(fh, 1):
            words = line.split('#', 1)[0].split()
            if not words:
                continue
            if len(words) != 3 or words[1] not in BACKEND_SOURCES or words[2] not in ('yes', 'no'):
                sys.exit(f'image_gates: {path}:{lineno}: expected "IMAGE BACKEND yes|no" with a backend '
                         f'in {", ".join(BACKEND_SOURCES)}, got: {line.strip()}')
            if not os.path.exists(os.path.join(ROOT, 'firmware', 'apps', f'{words[0]}_main.c')):
                sys.exit(f'image_gates: {path}:{lineno}: firmware/apps/{words[0]}_main.c not found')
            images.append((words[0], words[1]))
            if words[2] == 'yes':
                telemetry.add(words[0])
    return images, telemetry


def sh(cmd):
    return subprocess.run(cmd, shell=True, cwd=ROOT, capture_output=True, text=True)


def common_sources():
    """Every controller source (firmware/<folder>/*.c but the apps) and the
    platform-neutral HAL helpers; --gc-sections keeps what an image uses."""
    out = []
    fw = os.path.join(ROOT, 'firmware')
    for d in sorted(os.listdir(fw)):
        if d != 'apps' and os.path.isdir(os.path.join(fw, d)):
            out += sorted(os.path.join('firmware', d, f) for f in os.listdir(os.path.join(fw, d))
                          if f.endswith('.c') and os.path.join('firmware', d, f) not in TELEMETRY_APP_SOURCES)
    out += sorted(os.path.join('hal', f) for f in os.listdir(os.path.join(ROOT, 'hal'))
                  if f.endswith('.c'))
    return out + ['hal/epuck/hal_epuck.c', 'hal/epuck/host_link.c']


def obj_path(build, target, src):
    return os.path.join(build, target, 'obj', src[:-2] + '.o')


def compile_one(build, target, src, inc=INC):
    t = TARGETS[target]
    obj = obj_path(build, target, src)
    os.makedirs(os.path.join(ROOT, os.path.dirname(obj)), exist_ok=True)
    cmd = f"{t['cc']} {t['cflags']} {WARN} {inc} {COMMON} -c {shlex.quote(src)} -o {shlex.quote(obj)}"
    r = sh(cmd)
    return src, r.returncode, (r.stdout + r.stderr).strip()


# ------------------------------------------------------------------ map

SECTION_RE = re.compile(r'^ (\S+)?\s+0x([0-9a-fA-F]+)\s+0x([0-9a-fA-F]+)\s+(\S.*)$')
NAME_ONLY_RE = re.compile(r'^ (\S+)$')


def parse_map(path):
    """Input sections kept in the link: (section, address, size, file)."""
    rows = []
    with open(path) as f:
        lines = f.read().split('\n')
    try:
        start = next(i for i, line in enumerate(lines) if line.startswith('Linker script and memory map'))
    except StopIteration:
        return rows
    pending = None
    for line in lines[start:]:
        m = NAME_ONLY_RE.match(line)
        if m and not line.startswith('  '):
            pending = m.group(1)
            continue
        m = SECTION_RE.match(line)
        if m and (m.group(1) or pending):
            name = m.group(1) or pending
            pending = None
            size = int(m.group(3), 16)
            file = m.group(4).strip()
            if size == 0 or name.startswith('*') or ' ' in file and '(' not in file:
                continue
            rows.append((name, int(m.group(2), 16), size, file))
        else:
            pending = None
    return rows


def classify(section):
    s = section
    if s.startswith('.bss') or s == 'COMMON':
        return 'bss'
    if s.startswith('.data'):
        return 'data'
    if s.startswith('.rodata') or s.startswith('.progmem'):
        return 'rodata'
    if s.startswith('.text') or s.startswith('.init') or s.startswith('.fini') \
            or s.startswith('.vectors') or s.startswith('.trampolines'):
        return 'text'
    return None


def is_ours(file, build, target):
    prefix = os.path.join(build, target, 'obj') + os.sep
    return file.startswith(prefix) and not file.startswith(prefix + 'tests' + os.sep)


# ------------------------------------------------------------------ stack

def read_su(objs):
    """{(object, function): bytes} from the .su files next to the objects."""
    frames = {}
    for obj in objs:
        su = os.path.join(ROOT, obj[:-2] + '.su')
        if not os.path.exists(su):
            continue
        with open(su) as f:
            for line in f:
                parts = line.rstrip('\n').split('\t')
                if len(parts) < 2:
                    continue
                name = parts[0].rsplit(':', 1)[-1]
                frames[(obj, name)] = int(parts[1])
    return frames


FUNC_RE = re.compile(r'^([0-9a-fA-F]+) <([^>]+)>:$')
INSN_RE = re.compile(r'^\s*([0-9a-fA-F]+):\s+(?:[0-9a-fA-F]{2,8}\s)+\s*(\S+)\s*(.*)$')
TARGET_RE = re.compile(r'(?:0x)?([0-9a-fA-F]+)\s+<([^>+]+)(\+0x[0-9a-fA-F]+)?>')


def disassemble(target, elf):
    """{function start: (name, [instructions (mnemonic, operands)])}."""
    r = sh(f"{TARGETS[target]['objdump']} -d {shlex.quote(elf)}")
    funcs = {}
    cur = None
    for line in r.stdout.split('\n'):
        m = FUNC_RE.match(line)
        if m:
            cur = int(m.group(1), 16)
            funcs[cur] = (m.group(2), [])
            continue
        m = INSN_RE.match(line)
        if m and cur is not None:
            funcs[cur][1].append((m.group(2), m.group(3)))
    return funcs


def push_bytes(target, insns):
    """Stack a function without a .su entry uses: its pushes (and, on ARM,
    explicit sp decrements)."""
    n = 0
    for mn, ops in insns:
        if target == 'avr':
            if mn == 'push':
                n += 1
        else:
            if mn.startswith('push') or mn.startswith('stmdb'):
                n += 4 * (ops.count(',') + 1)
            elif mn.startswith('vpush'):
                regs = ops.count(',') + 1
                n += 8 * regs if 'd' in ops else 4 * regs
            elif mn.startswith('sub') and 'sp' in ops.split(',')[0]:
                m = re.search(r'#(\d+)', ops)
                if m:
                    n += int(m.group(1))
    return n


def call_edges(target, funcs, starts):
    """{caller start: set(callee starts)}, and callers with indirect calls."""
    edges = {}
    indirect = set()
    for addr, (_name, insns) in funcs.items():
        out = set()
        for mn, ops in insns:
            if target == 'avr':
                is_call = mn in ('call', 'rcall')
                is_jump = mn in ('jmp', 'rjmp')
                if mn in ('icall', 'eicall', 'ijmp', 'eijmp'):
                    indirect.add(addr)
            else:
                base = mn.split('.')[0]
                is_call = base in ('bl', 'blx') and '<' in ops
                is_jump = base == 'b' and '<' in ops
                if base == 'blx' and '<' not in ops:
                    indirect.add(addr)
            if not (is_call or is_jump):
                continue
            m = TARGET_RE.search(ops)
            if not m:
                continue
            dest = int(m.group(1), 16)
            if m.group(3):   # into the middle of a function: a local jump
                continue
            if dest in starts and dest != addr and (is_call or dest in starts):
                out.add(dest)
        edges[addr] = out
    return edges, indirect


def worst_chain(root, edges, cost, ret_bytes):
    """Largest sum of frames (+ return addresses) over the call chains from
    `root`; flags recursion."""
    memo = {}
    recursion = []

    def visit(a, stack):
        if a in memo:
            return memo[a]
        if a in stack:
            recursion.append(a)
            return (0, [])
        stack.add(a)
        best = (0, [])
        for b in edges.get(a, ()):
            v, chain = visit(b, stack)
            if v + ret_bytes > best[0]:
                best = (v + ret_bytes, chain)
        stack.discard(a)
        memo[a] = (cost(a) + best[0], [a] + best[1])
        return memo[a]

    v, chain = visit(root, set())
    return v, chain, recursion


# ------------------------------------------------------------------ image

def link_image(build, target, image, backend, sources):
    t = TARGETS[target]
    objs = [obj_path(build, target, s) for s in sources]
    elf = os.path.join(build, target, image + '.elf')
    mapf = os.path.join(build, target, image + '.map')
    r = sh(f"{t['cc']} {t['ldflags']} -Wl,-Map={shlex.quote(mapf)} -o {shlex.quote(elf)} "
           + ' '.join(shlex.quote(o) for o in objs))
    if r.returncode != 0:
        return None, (r.stdout + r.stderr).strip()

    rows = parse_map(os.path.join(ROOT, mapf))
    acc = {k: 0 for k in ('data', 'bss', 'frames', 'rodata', 'text',
                          'all_text', 'all_rodata', 'all_data', 'all_bss')}
    sect_owner = []   # (start, end, object, function name) of .text sections
    for name, addr, size, file in rows:
        kind = classify(name)
        if kind is None:
            continue
        acc['all_' + ('text' if kind == 'text' else kind)] += size
        if kind == 'text':
            fn = name[len('.text.'):] if name.startswith('.text.') else None
            sect_owner.append((addr, addr + size, file, fn))
        if not is_ours(file, build, target):
            continue
        if kind == 'bss' and name.endswith('camera_frames'):
            acc['frames'] += size
        else:
            acc[kind] += size

    funcs = disassemble(target, os.path.join(ROOT, elf))
    starts = set(funcs)
    edges, indirect = call_edges(target, funcs, starts)
    frames = read_su(objs)
    by_name = {v[0]: a for a, v in funcs.items()}

    def owner(a):
        for lo, hi, file, _fn in sect_owner:
            if lo <= a < hi:
                return file
        return None

    def cost(a):
        name, insns = funcs[a]
        base = name.split('.')[0]   # GCC clones: foo.constprop.0
        f = owner(a)
        if f is not None and (f, base) in frames:
            return frames[(f, base)]
        if f is not None and (f, name) in frames:
            return frames[(f, name)]
        return push_bytes(target, insns)

    main_v, main_chain, rec1 = worst_chain(by_name['main'], edges, cost, t['ret_bytes'])
    tick = by_name.get('app_tick')
    tick_v, tick_chain, rec2 = (worst_chain(tick, edges, cost, t['ret_bytes'])
                                if tick is not None else (0, [], []))
    ours_indirect = sorted(funcs[a][0] for a in indirect
                           if owner(a) and is_ours(owner(a), build, target))
    res = {
        'image': image, 'backend': backend, 'target': target,
        'data': acc['data'], 'bss': acc['bss'], 'static': acc['data'] + acc['bss'],
        'frames': acc['frames'],
        'stack': main_v + tick_v,
        'stack_main': main_v, 'stack_tick': tick_v,
        'chain': [funcs[a][0] for a in main_chain],
        'recursion': sorted(set(funcs[a][0] for a in rec1 + rec2)),
        'indirect': ours_indirect,
        'flash_ours': acc['text'] + acc['rodata'] + acc['data'],
        'flash_image': acc['all_text'] + acc['all_rodata'] + acc['all_data'],
        'ram_image': acc['all_data'] + acc['all_bss'],
    }
    return res, ''


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--build', default='build/firmware')
    ap.add_argument('--jobs', type=int, default=os.cpu_count() or 2)
    ap.add_argument('--lcm-c-dir', default='build/lcm_c',
                    help="lcm-gen's C output (make lcm-types)")
    ap.add_argument('--lcm-cflags', default='',
                    help='flags that find <lcm/lcm_coretypes.h> (LCM_CFLAGS of build/config.mk)')
    ap.add_argument('--images', default='firmware/apps/images.list',
                    help='the image list (firmware/apps/images.list)')
    args = ap.parse_args()

    images, telemetry_images = read_images(args.images)

    failures = []
    inc = f"{INC} -I{shlex.quote(args.lcm_c_dir)} {args.lcm_cflags}"
    lcm_srcs = [os.path.join(args.lcm_c_dir, f'swarmlcm_{t}.c') for t in LCM_TYPES_LINKED]
    if any(i in telemetry_images for i, _ in images):
        for s in lcm_srcs:
            if not os.path.exists(os.path.join(ROOT, s)):
                sys.exit(f'image_gates: {s} not found: run make lcm-types')
    common = common_sources()
    stubs = ['tests/firmware/stubs/epuck_lib_stubs.c']
    srcs = set(common + stubs)
    for image, backend in images:
        srcs.add(f'firmware/apps/{image}_main.c')
        srcs.update(BACKEND_SOURCES[backend][0] + BACKEND_SOURCES[backend][1])
        if image in telemetry_images:
            srcs.update(lcm_srcs + TELEMETRY_APP_SOURCES)
    srcs = sorted(srcs)

    results = []
    checks = 0
    for target in TARGETS:
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
            outs = list(ex.map(lambda s, t=target: compile_one(args.build, t, s, inc), srcs))
        bad = [(s, msg) for s, rc, msg in outs if rc != 0]
        checks += len(outs)
        for s, msg in bad:
            failures.append(f'{target}: {s} does not compile warning-free:\n{msg}')
        print(f'{target}: {len(srcs) - len(bad)}/{len(srcs)} sources compile warning-free '
              f"({TARGETS[target]['what']})")
        if bad:
            continue
        for image, backend in images:
            own, stub = BACKEND_SOURCES[backend]
            sources = common + own + [f'firmware/apps/{image}_main.c'] + stubs + stub
            if image in telemetry_images:
                sources += lcm_srcs + TELEMETRY_APP_SOURCES
            res, err = link_image(args.build, target, image, backend, sources)
            checks += 1
            if res is None:
                failures.append(f'{target}: {image} does not link:\n{err}')
                continue
            print(f'{target}: {image} links ({backend})')
            if res['recursion']:
                failures.append(f"{target}: {image}: recursion in {', '.join(res['recursion'])}: "
                                'no stack bound')
            if res['indirect']:
                print(f"  note: indirect calls in {', '.join(res['indirect'])} (not followed)")
            results.append(res)

    by = {(r['image'], r['target']): r for r in results}
    lines = []
    lines.append(f'| image | IR backend | static RAM (gate <= {RAM_GATE}) | .data | .bss | camera frames '
                 '| stack estimate | our RAM total | our flash | image flash | Cortex-M4F static RAM / flash |')
    lines.append('|---|---|---|---|---|---|---|---|---|---|---|')
    for image, backend in images:
        a = by.get((image, 'avr'))
        m = by.get((image, 'arm'))
        if a is None:
            continue
        total = a['static'] + a['frames'] + a['stack']
        arm = f"{m['static']} / {m['flash_ours']}" if m else 'n/a'
        lines.append(f"| {image} | {backend} | {a['static']} | {a['data']} | {a['bss']} | {a['frames']} "
                     f"| {a['stack']} ({a['stack_main']} + tick {a['stack_tick']}) | {total} "
                     f"| {a['flash_ours']} | {a['flash_image']} | {arm} |")
        checks += 1
        if a['static'] > RAM_GATE:
            failures.append(f"{image}: our static RAM {a['static']} B exceeds the {RAM_GATE} B budget")
    notes = [
        '',
        'Bytes, measured with avr-gcc -Os for the atmega2560 (16-bit int and pointers, 32-bit '
        'double: the data model of XC16 on the dsPIC30F6014A) unless marked Cortex-M4F.',
        'Static RAM: .data + .bss of our objects after --gc-sections, without the camera frames, '
        'the library (stubs) and the C library; const data is counted as flash (XC16 keeps it in '
        'program memory). Stack estimate: the worst call chain from main plus that of the timer '
        'agenda callback (frames from -fstack-usage, return addresses of 3 bytes).  Flash: our '
        '.text + .rodata + .data initialisers; "image flash" adds the stubs, libgcc and libc '
        '(8-bit AVR code: the dsPIC\'s is smaller).',
    ]
    for image, _ in images:
        a = by.get((image, 'avr'))
        if a:
            notes.append(f"Deepest chain of {image} (avr): {' > '.join(a['chain'])}.")
    table = '\n'.join(lines + notes) + '\n'
    print()
    print(table)
    out = os.path.join(ROOT, args.build, 'footprint.md')
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, 'w') as f:
        f.write('# Firmware footprint\n\n' + table)
    print(f'written to {os.path.relpath(out, ROOT)}')
    # The documentation shows the same measurement in its own form: written
    # beside it, and the page's copy must equal it (readme_footprint.py).
    readme_table = readme_footprint.render(images, by, readme_footprint.compiler_versions(TARGETS), RAM_GATE)
    with open(os.path.join(ROOT, args.build, 'footprint_readme.md'), 'w') as f:
        f.write(readme_table)
    why = readme_footprint.compare(readme_footprint.PAGE, readme_table)
    checks += 1
    if why and why.startswith('note:'):
        print(why)
    elif why:
        failures.append(why)
    for msg in failures:
        print('FAIL: ' + msg)
    print(f'image gates: {checks - len(failures)} passed, {len(failures)} failed')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
