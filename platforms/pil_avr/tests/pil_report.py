#!/usr/bin/env python3
"""pil_report.py - the emulated ATmega2560's measured cycles and stack, per
image, beside today's estimates (make pil-avr-compare writes it to
build/firmware/pil_avr/cpu.md; docs/hardware/footprint.md shows it).

    pil_report.py MEASURE_DIR [--cpu build/firmware/cpu.md]
                  [--footprint build/firmware/epuck1/footprint.md]
                  [--page docs/hardware/footprint.md] [--m4 M4_MEASURE_DIR]

It prints the report; with --page it writes it into PAGE between the two
marker lines PAGE_BEGIN and PAGE_END instead (make readme-pil-cpu), the
page replaced whole or not at all.

MEASURE_DIR holds what pil_tests.sh measured: <image>_<robot>.json and
<image>_frames_<robot>.json from pil_compare --json (each image beside its
host build over a scripted world), detect_blobs.csv, detect_tones.csv and
detect_<robot>.json from the detector image (tests/detect_main.c).  The
figures:

  controller step   cycles between the run loop's two marks: the
                    controller's step and the HAL calls it makes, the PIL
                    requests' own frames included (a CRC-16 a byte at a
                    time: about 100 cycles a byte), not the STEP and ACT
                    frames nor the image's telemetry;
  whole step        every cycle from STEP to ACT: that, the frames and the
                    telemetry (a robot_state_t every 10 steps);
  + detectors       the controller step's max, plus what the e-puck1's HAL
                    runs for it each step: the blob detector over one 40 x 20
                    frame (images with a camera) and the tone detector over
                    96 samples of 3 microphones (images with sound), each
                    measured on its own by the detector image;
  stack             the high-water mark by painting over the run, with
                    blobs from the simulator, and with frames (blob_detect
                    on the MCU) where measured;
  estimates         the footprint table's stack estimate (its call graph,
                    -fstack-usage frames) and the CPU report's dsPIC cycles
                    (3 x x86 instructions under callgrind, plus software
                    float).

With --m4, two more columns from the emulated Cortex-M4F (QEMU, the
e-puck2's core: platforms/pil_m4/, make pil-m4-compare): the controller
step's instructions between the same two marks (SysTick under
`-icount shift=0`: QEMU counts instructions, not cycles: it models no flash
wait states or pipeline) and its stack by painting.

The AVR is an 8-bit core: 16- and 32-bit arithmetic costs it 2 to 4 times a
dsPIC's cycles (more for the tone detector's 32-bit products), so these
figures bound the dsPIC's from above; they are no gate.
"""
import argparse
import csv
import glob
import json
import os
import re
import sys
import tempfile

HZ = 16_000_000
PAGE_BEGIN = '<!-- pil-cpu: measured by make pil-avr-compare; make readme-pil-cpu writes it -->'
PAGE_END = '<!-- /pil-cpu -->'
# Which of the CPU report's rows (build/firmware/cpu.md) estimates each
# controller's step.
CPU_ROW = {'forager': 'forager', 'nest_beacon': 'nest_beacon', 'random_walk': 'random_walk', 'repatt': 'repatt'}


def num(text):
    return int(text.replace(',', '').strip())


def read_table(path, key_col, want):
    """{first column: {column name: cell}} of the first markdown table in path."""
    if not path or not os.path.exists(path):
        return {}
    rows, head = {}, None
    with open(path, encoding='utf-8') as fh:
        for line in fh:
            if not line.startswith('|'):
                if head:
                    break
                continue
            cells = [c.strip() for c in line.strip().strip('|').split('|')]
            if head is None:
                head = cells
            elif not set(line.strip()) <= set('|-: '):
                rows[cells[key_col]] = {h: c for h, c in zip(head, cells, strict=False) if any(w in h for w in want)}
    return rows


def load(measure):
    out = {}
    for path in sorted(glob.glob(os.path.join(measure, '*.json'))):
        if os.path.basename(path).startswith('detect_'):
            continue
        with open(path, encoding='utf-8') as fh:
            m = json.load(fh)
        frames = m.get('frames', 0)
        slot = out.setdefault(m['image'], {'controller': m['controller'], 'blobs': [], 'frames': []})
        slot['frames' if frames else 'blobs'].append(m)
    return out


def detector(measure, name):
    """(mean of the detector's steps minus the idle steps', max, stack) from its CSV and JSON."""
    path = os.path.join(measure, f'detect_{name}.csv')
    if not os.path.exists(path):
        return None
    idle, busy = [], []
    with open(path, encoding='utf-8') as fh:
        for row in csv.DictReader(fh):
            (idle if int(row['step']) % 3 == 0 else busy).append(int(row['control_cycles']))
    busy = [b for b in busy if b > max(idle) * 4] or busy
    base = sum(idle) / len(idle)
    with open(os.path.join(measure, f'detect_{name}.json'), encoding='utf-8') as fh:
        stack = json.load(fh)['stack_bytes']
    return round(max(busy) - base), stack


def fmt(n):
    return f'{n:,.0f}'


def ms(cycles):
    return f'{cycles / HZ * 1000:.2f}'


def render(args, images, page=False, m4=None):
    """The report's lines, without its title (for a page, without the
    closing paragraph on the method: the page says it)."""
    lines = []
    blob = detector(args.measure, 'blobs')
    tone = detector(args.measure, 'tones')
    cpu = read_table(args.cpu, 0, ('dsPIC',))
    foot = read_table(args.footprint, 0, ('stack',))
    flags = {}
    decl = os.path.join(os.path.dirname(__file__), '..', '..', 'epuck1', 'images.list')
    cur = None
    with open(decl, encoding='utf-8') as fh:
        for line in fh:
            m = re.match(r'^image (\w+)', line)
            if m:
                cur = m.group(1)
                flags[cur] = set()
            elif cur and re.match(r'^\s+(camera|sound)\s+yes', line):
                flags[cur].add(line.split()[0])
    w = lines.append
    w('| image | AVR controller step, cycles mean / max | AVR whole step max (frames, telemetry) | '
      'AVR + detectors, max (ms at 16 MHz) | AVR stack by painting | stack estimate | '
      + ('M4 controller step, instructions mean / max | M4 stack by painting | ' if m4 else '')
      + 'dsPIC estimate, max |')
    w('|---|---|---|---|---|---|---|' + ('---|---|' if m4 else ''))
    for name, m in images.items():
        runs = m['blobs'] or m['frames']
        cmean = sum(r['control_mean'] for r in runs) / len(runs)
        cmax = max(r['control_max'] for r in runs)
        whole = max(r['cycles_max'] for r in runs)
        stack = max(r['stack_bytes'] for r in m['blobs']) if m['blobs'] else None
        fstack = max(r['stack_bytes'] for r in m['frames']) if m['frames'] else None
        extra, parts = cmax, []
        if 'camera' in flags.get(name, ()) and blob:
            extra += blob[0]
            parts.append('blobs')
        if 'sound' in flags.get(name, ()) and tone:
            extra += tone[0]
            parts.append('tones')
        with_det = f'{fmt(extra)} ({ms(extra)}; {" + ".join(parts)})' if parts else '-'
        st = f'{stack}' + (f' ({fstack} with frames)' if fstack else '')
        est = foot.get(name, {})
        est_stack = next(iter(est.values()), '-')
        ds = cpu.get(CPU_ROW.get(m['controller'], ''), {})
        ds = next((v for k, v in ds.items() if 'max' in k), '-') if ds else '-'
        m4_cells = ''
        if m4 is not None:
            mm = m4.get(name)
            if mm:
                mruns = mm['blobs'] or mm['frames']
                mmean = sum(r['control_mean'] for r in mruns) / len(mruns)
                mmax = max(r['control_max'] for r in mruns)
                mstack = max(r['stack_bytes'] for r in mm['blobs']) if mm['blobs'] else None
                mfstack = max(r['stack_bytes'] for r in mm['frames']) if mm['frames'] else None
                mst = f'{mstack}' + (f' ({mfstack} with frames)' if mfstack else '')
                m4_cells = f'{fmt(mmean)} / {fmt(mmax)} | {mst} | '
            else:
                m4_cells = '- | - | '
        w(f'| {name} | {fmt(cmean)} / {fmt(cmax)} ({ms(cmax)} ms) | {fmt(whole)} | {with_det} | {st} | '
          f'{est_stack} | {m4_cells}{ds} |')
    w('')
    if blob and tone:
        w(f'Detectors alone: the blob detector over a 40 x 20 RGB565 frame, {fmt(blob[0])} cycles '
          f'({ms(blob[0])} ms at 16 MHz), stack {blob[1]} bytes with the PIL run loop; the tone detector over '
          f'96 samples of each of 3 microphones, {fmt(tone[0])} cycles ({ms(tone[0])} ms), stack {tone[1]} bytes. '
          '(The CPU report\'s dsPIC estimates: blob_detect and tone_detect rows.)')
    if page:
        return lines
    w('')
    w('Measured by simavr\'s cycle counter (exact for the AVR) over each image\'s run beside its host build '
      '(pil_compare, a scripted world; frames: RGB565 camera frames, blob_detect on the MCU); stack by '
      'painting RAM above the static data before reset.  An upper bound for the dsPIC (the AVR is an 8-bit '
      'core), not a gate.')
    return lines


def write_page(page, lines):
    """Put lines between the page's markers, atomically."""
    with open(page, encoding='utf-8') as fh:
        text = fh.read()
    a, b = text.find(PAGE_BEGIN), text.find(PAGE_END)
    if a < 0 or b < a:
        sys.exit(f'pil_report.py: {page}: no lines {PAGE_BEGIN} and {PAGE_END} to write between')
    body = text[:a] + PAGE_BEGIN + '\n' + '\n'.join(lines) + '\n' + text[b:]
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(page)), prefix='.pil_report.')
    with os.fdopen(fd, 'w', encoding='utf-8') as fh:
        fh.write(body)
    os.chmod(tmp, 0o644)
    os.replace(tmp, page)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('measure')
    ap.add_argument('--cpu', default='build/firmware/cpu.md')
    ap.add_argument('--footprint', default='build/firmware/epuck1/footprint.md')
    ap.add_argument('--page', help='write the report into this page, between its markers')
    ap.add_argument('--m4', help="the emulated Cortex-M4F's measurements (pil-m4-compare's measure folder)")
    args = ap.parse_args(argv)
    images = load(args.measure)
    if not images:
        print(f'pil_report.py: {args.measure}: no measurements', file=sys.stderr)
        return 1
    m4 = load(args.m4) if args.m4 else None
    if args.m4 and not m4:
        print(f'pil_report.py: {args.m4}: no measurements', file=sys.stderr)
        return 1
    lines = render(args, images, page=bool(args.page), m4=m4)
    if args.page:
        write_page(args.page, lines)
        print(f'pil_report.py: {args.page}: {len(images)} images')
    else:
        print('# PIL: measured cycles and stack on the emulated ATmega2560\n')
        print('\n'.join(lines))
    return 0


if __name__ == '__main__':
    sys.exit(main())
