#!/usr/bin/env python3
"""image_gates.py - the portable gates of a platform's firmware images.

A platform (platforms/<p>/) declares its images (images.list, whose mains
tools/make/images.py generates into --gen) and describes its gates in
platform.py's GATES: the targets (compiler, flags, objdump, the bytes of a
return address), its sources and the stubs of its library, what an image's
keys add, the RAM gate.  For every image and every target this compiles
every source warning-free (-std=c99 -pedantic -Wall -Wextra -Werror ...)
with -fstack-usage, links the image against the stubs (a tests/ folder's
sources: they stand for the library) and measures what follows.  A source
is compiled again only when it, a header it includes or its command
changed since its object was made (the object's .d and .cmd files): an
object exists only if its compile passed -Werror.

The images that publish telemetry also link the robot's telemetry
(firmware/telemetry/robot_telemetry.c) and lcm-gen's C code of robot_state_t
and schema_t (--lcm-c-dir, from `make lcm-types`; headers of LCM from
--lcm-cflags), compiled with the same warnings as ours; --gc-sections drops
its decoder (malloc) and its publish/subscribe functions.  Its objects, and
their hash cache, count as ours in the static RAM.

  static RAM   .data + .bss of OUR objects (firmware/, hal/, wire/, the
               platform's), taken from the link map after --gc-sections,
               without the static buffers GATES names ('frames': the camera
               frames) and without the stubs or the C library.  Constant
               data (.rodata) is counted as flash: XC16 keeps const data in
               program memory (PSV).  GATE: GATES['ram_gate'] (on the e-puck1,
               <= 2048 bytes on the avr target: the dsPIC's 8 KB must also
               hold the library's buffers, the camera frames and the stacks).
  frames       the static buffers GATES['frames'] names.
  stack        worst call chain from main, plus the worst chain of each
               interrupt handler GATES['interrupts'] names (it interrupts main
               anywhere): the sum of the frames of the functions on the chain
               (GCC's -fstack-usage .su files; for functions of libgcc/libc,
               which have none, the pushes of their code), plus the return
               address of every call (3 bytes on the atmega2560, 0 on ARM
               where LR is saved inside the frame).  The call graph comes
               from the disassembly of the linked image (direct calls and
               tail jumps); indirect calls are reported.  The images' mains
               call the controller by name (the platform's run loop), so
               there are none on the way.
  flash        .text + .rodata + .data initialisers of our objects, and of
               the whole image (with the stubs, libgcc's software float...).
               AVR code is 8-bit code: the dsPIC's will be smaller.
               GATES: optional 'stack_gate' (the stack estimate) and
               'flash_gate' (our flash), bytes on the RAM gate's target
               (the e-puck2 states both: platforms/epuck2/platform.py).

Prints a table, writes it to BUILD/footprint.md (and, for the platform whose
table the documentation shows, the page's form to footprint_readme.md),
exits 1 when a compile or link fails, the RAM gate is exceeded or the
documentation's table (docs/hardware/footprint.md) is not the measured one.
Standard library only.

usage: image_gates.py --platform platforms/epuck1 --gen DIR [--build DIR] [--jobs N]
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
sys.path.insert(0, os.path.join(ROOT, 'tools', 'make'))
import images as image_decls  # noqa: E402  (tools/make/images.py: the declarations)

WARN = ('-std=c99 -pedantic -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes '
        '-Wmissing-prototypes')
# The layers every platform's images see: the HAL contract, the wire
# protocols, the controllers.
INC = '-Ihal -Iwire -Ifirmware'
COMMON = '-Os -ffunction-sections -fdata-sections -fstack-usage'

# What an image with telemetry links on any platform: the robot's telemetry
# (the simulator runs it too) and lcm-gen's C of the types it sends.
LCM_TYPES_LINKED = ('robot_state_t', 'schema_t')
ROBOT_TELEMETRY_SOURCES = ['firmware/telemetry/robot_telemetry.c']

TARGETS = {}   # the platform's GATES['targets'] (main)


def sh(cmd):
    return subprocess.run(cmd, shell=True, cwd=ROOT, capture_output=True, text=True)


def c_sources(folder):
    """folder/*.c and folder/*/*.c, sorted."""
    out = []
    for d, _dirs, files in sorted(os.walk(os.path.join(ROOT, folder))):
        rel = os.path.relpath(d, ROOT)
        if rel.count(os.sep) - folder.count(os.sep) > 1:
            continue
        out += sorted(os.path.join(rel, f) for f in files if f.endswith('.c'))
    return sorted(out)


def common_sources(gates):
    """Every controller source (firmware/<folder>/*.c), the platform-neutral
    HAL helpers (hal/*.c), the wire protocols (wire/*/*.c) and the
    platform's own sources; --gc-sections keeps what an image uses."""
    out = [s for s in c_sources('firmware') if s.count(os.sep) == 2 and s not in ROBOT_TELEMETRY_SOURCES]
    out += [s for s in c_sources('hal') if s.count(os.sep) == 1]
    out += [s for s in c_sources('wire') if s.count(os.sep) == 2]
    return out + list(gates['sources'])


def image_sources(gates, image):
    """(our sources, stubs) that image's keys add (GATES['when'])."""
    own, stubs = [], []
    for (key, value), (o, st) in gates['when'].items():
        if image.get(key) == value:
            own += o
            stubs += st
    return own, stubs


def obj_path(build, target, src):
    return os.path.join(build, target, 'obj', src[:-2] + '.o')


def up_to_date(obj, cmd):
    """True when `obj` was made by `cmd` (its .cmd file) and is newer than
    its source and every header it read (its .d file, -MMD): the compile
    would give the same object and the same warnings (none: -Werror made
    it), so it is not run again."""
    base = os.path.join(ROOT, obj[:-2])
    try:
        with open(base + '.cmd') as f:
            if f.read() != cmd:
                return False
        with open(base + '.d') as f:
            deps = f.read().replace('\\\n', ' ').split(':', 1)[1].split()
        made = os.path.getmtime(base + '.o')
        return all(os.path.getmtime(os.path.join(ROOT, d)) <= made for d in deps)
    except (OSError, IndexError):
        return False


def compile_one(build, target, src, inc):
    t = TARGETS[target]
    obj = obj_path(build, target, src)
    os.makedirs(os.path.join(ROOT, os.path.dirname(obj)), exist_ok=True)
    dep = obj[:-2] + '.d'
    cmd = (f"{t['cc']} {t['cflags']} {WARN} {inc} {COMMON} -MMD -MF {shlex.quote(dep)} -c {shlex.quote(src)} "
           f"-o {shlex.quote(obj)}")
    if up_to_date(obj, cmd):
        return src, 0, ''
    cmd_file = os.path.join(ROOT, obj[:-2] + '.cmd')
    if os.path.exists(cmd_file):
        os.remove(cmd_file)
    r = sh(cmd)
    if r.returncode == 0:
        with open(cmd_file, 'w') as f:
            f.write(cmd)
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


def is_ours(file, build, target, stub_objs):
    """An object of ours: not a stub (it stands for the platform's library)."""
    prefix = os.path.join(build, target, 'obj') + os.sep
    return file.startswith(prefix) and file not in stub_objs


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

def link_image(build, target, image, column, sources, stub_objs, gates):
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
        if not is_ours(file, build, target, stub_objs):
            continue
        if kind == 'bss' and gates.get('frames') and name.endswith(gates['frames']):
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
    # Interrupt handlers (their names are the run loop's): each can come on
    # top of main's deepest point.
    tick_v, rec2 = 0, []
    for handler in gates.get('interrupts', ()):
        if handler in by_name:
            v, _chain, rec = worst_chain(by_name[handler], edges, cost, t['ret_bytes'])
            tick_v += v
            rec2 += rec
    ours_indirect = sorted(funcs[a][0] for a in indirect
                           if owner(a) and is_ours(owner(a), build, target, stub_objs))
    res = {
        'image': image, 'backend': column, 'target': target,
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


def load_platform(platform_dir):
    """The platform's GATES and its images (tools/make/images.py's
    declarations), or an exit naming what is wrong."""
    try:
        mod = image_decls.load_platform(platform_dir)
        images = image_decls.read_images(image_decls.image_list(platform_dir), mod.IMAGE_KEYS)
    except image_decls.DeclarationError as e:
        sys.exit(f'image_gates: {e}')
    if not hasattr(mod, 'GATES'):
        sys.exit(f'image_gates: {platform_dir}/platform.py has no GATES')
    return mod.GATES, images


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--platform', required=True, help='the platform folder (platforms/<p>)')
    ap.add_argument('--gen', required=True, help="the images' generated mains (tools/make/images.py)")
    ap.add_argument('--build', help='objects and the footprint table (build/firmware/<p>)')
    ap.add_argument('--jobs', type=int, default=os.cpu_count() or 2)
    ap.add_argument('--lcm-c-dir', default='build/lcm_c',
                    help="lcm-gen's C output (make lcm-types)")
    ap.add_argument('--lcm-cflags', default='',
                    help='flags that find <lcm/lcm_coretypes.h> (LCM_CFLAGS of build/config.mk)')
    args = ap.parse_args()
    gates, decls = load_platform(args.platform)
    build = args.build or os.path.join('build', 'firmware', os.path.basename(args.platform))
    TARGETS.clear()
    TARGETS.update(gates['targets'])
    gate_target, ram_gate = gates['ram_gate']
    column_key, column_label = gates['column']
    images = [(im.name, im.get(column_key)) for im in decls]
    mains = {im.name: os.path.join(args.gen, f'{im.name}_main.c') for im in decls}
    for main_c in mains.values():
        if not os.path.exists(os.path.join(ROOT, main_c)):
            sys.exit(f'image_gates: {main_c} not found: the mains are generated by tools/make/images.py '
                     '(make firmware-images)')

    failures = []
    inc = (f"{INC} {' '.join('-I' + d for d in gates['include'])} -I{shlex.quote(args.gen)} "
           f"-I{shlex.quote(args.lcm_c_dir)} {args.lcm_cflags}")
    lcm_srcs = [os.path.join(args.lcm_c_dir, f'swarmlcm_{t}.c') for t in LCM_TYPES_LINKED]
    if any(im.get('telemetry') == 'yes' for im in decls):
        for s in lcm_srcs:
            if not os.path.exists(os.path.join(ROOT, s)):
                sys.exit(f'image_gates: {s} not found: run make lcm-types')
    common = common_sources(gates)
    stubs = list(gates['stubs'])
    per_image = {}
    srcs = set(common + stubs)
    for im in decls:
        own, stub = image_sources(gates, im)
        if im.get('telemetry') == 'yes':
            own = own + ROBOT_TELEMETRY_SOURCES + lcm_srcs
        per_image[im.name] = (own, stub)
        srcs.update(own + stub + [mains[im.name]])
    all_stubs = set(stubs).union(*(set(st) for _o, st in per_image.values()))
    srcs = sorted(srcs)

    results = []
    checks = 0
    for target in TARGETS:
        stub_objs = {obj_path(build, target, s) for s in all_stubs}
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
            outs = list(ex.map(lambda s, t=target: compile_one(build, t, s, inc), srcs))
        bad = [(s, msg) for s, rc, msg in outs if rc != 0]
        checks += len(outs)
        for s, msg in bad:
            failures.append(f'{target}: {s} does not compile warning-free:\n{msg}')
        print(f'{target}: {len(srcs) - len(bad)}/{len(srcs)} sources compile warning-free '
              f"({TARGETS[target]['what']})")
        if bad:
            continue
        for image, column in images:
            own, stub = per_image[image]
            sources = common + own + [mains[image]] + stubs + stub
            res, err = link_image(build, target, image, column, sources, stub_objs, gates)
            checks += 1
            if res is None:
                failures.append(f'{target}: {image} does not link:\n{err}')
                continue
            print(f'{target}: {image} links ({column})')
            if res['recursion']:
                failures.append(f"{target}: {image}: recursion in {', '.join(res['recursion'])}: "
                                'no stack bound')
            if res['indirect']:
                print(f"  note: indirect calls in {', '.join(res['indirect'])} (not followed)")
            results.append(res)

    by = {(r['image'], r['target']): r for r in results}
    others = [t for t in TARGETS if t != gate_target]
    lines = []
    lines.append(f'| image | {column_label} | static RAM (gate <= {ram_gate}) | .data | .bss | '
                 + ('camera frames | ' if gates.get('frames') else '')
                 + 'stack estimate | our RAM total | our flash | image flash |'
                 + ''.join(f" {TARGETS[t]['label']} static RAM / flash |" for t in others))
    lines.append('|---' * (10 + (1 if gates.get('frames') else 0) + len(others) - 1) + '|')
    for image, column in images:
        a = by.get((image, gate_target))
        if a is None:
            continue
        total = a['static'] + a['frames'] + a['stack']
        row = (f"| {image} | {column} | {a['static']} | {a['data']} | {a['bss']} | "
               + (f"{a['frames']} | " if gates.get('frames') else '')
               + (f"{a['stack']} ({a['stack_main']} + tick {a['stack_tick']}) | " if gates.get('interrupts')
                  else f"{a['stack']} | ")
               + f"{total} | {a['flash_ours']} | {a['flash_image']} |")
        for t in others:
            m = by.get((image, t))
            row += f" {m['static']} / {m['flash_ours']} |" if m else ' n/a |'
        lines.append(row)
        checks += 1
        if a['static'] > ram_gate:
            failures.append(f"{image}: our static RAM {a['static']} B exceeds the {ram_gate} B budget")
        if gates.get('stack_gate') is not None and a['stack'] > gates['stack_gate']:
            failures.append(f"{image}: its stack estimate {a['stack']} B exceeds the {gates['stack_gate']} B budget")
        if gates.get('flash_gate') is not None and a['flash_ours'] > gates['flash_gate']:
            failures.append(f"{image}: our flash {a['flash_ours']} B exceeds the {gates['flash_gate']} B budget")
    notes = [''] + list(gates.get('notes', ()))
    for image, _ in images:
        a = by.get((image, gate_target))
        if a:
            notes.append(f"Deepest chain of {image} ({gate_target}): {' > '.join(a['chain'])}.")
    table = '\n'.join(lines + notes) + '\n'
    print()
    print(table)
    out = os.path.join(ROOT, build, 'footprint.md')
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, 'w') as f:
        f.write('# Firmware footprint\n\n' + table)
    print(f'written to {os.path.relpath(out, ROOT)}')
    if gates.get('readme'):
        # The documentation shows the same measurement in its own form:
        # written beside it, and the page's copy must equal it
        # (readme_footprint.py).
        readme_table = readme_footprint.render(images, by, readme_footprint.compiler_versions(TARGETS), ram_gate)
        with open(os.path.join(ROOT, build, 'footprint_readme.md'), 'w') as f:
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
