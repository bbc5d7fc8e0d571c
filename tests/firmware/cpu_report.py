#!/usr/bin/env python3
"""cpu_report.py - instructions per control step of each controller, measured
on the host with valgrind --tool=callgrind, and an estimate for the e-puck1's
dsPIC30F6014A (14.7456 MIPS, no FPU).

Runs tests/firmware/cpu_harness (built by `make firmware-cpu`) under
callgrind; the harness dumps the cost of every single step, so the mean and
the maximum over the steps come straight from the dumps.

The dsPIC figure is an ESTIMATE, not a measurement.  Assumptions:
  - k = 3 dsPIC instructions per x86-64 instruction for our integer code:
    the dsPIC's ALU is 16-bit, so the 32-bit additions, shifts and
    comparisons of the controllers take 2-4 instructions each, and it has
    16 working registers against x86-64's richer addressing; a typical
    dsPIC instruction takes one cycle (branches 2, a 32/16 division 18);
  - plus software floating point: x86-64 does a float operation in one
    SSE instruction, XC16's library in ~100-400 cycles.  Only the
    forager's decision step (every T1 = 50 steps) uses floats: ~35
    operations (eqs 2-7 and the roulette, counted in firmware/foraging/forager.c
    and firmware/foraging/task_alloc.c), budgeted at 200 cycles each = 7,000 cycles
    on its maximum.
  - NOT covered by k: a 32-bit division (or %), one x86-64 instruction, is a
    call of XC16's software routine (hundreds of cycles; the dsPIC's own
    DIV.UD/DIV.U divide 32 or 16 by 16 bits in 19 cycles, but C's 32-bit '/'
    does not use them).  Code measured here should divide in 16 bits in its
    per-step paths; hal/blob_detect.c does (its pixel loop, two table
    lookups a pixel, is 18 x86-64 instructions = 54 estimated cycles, about
    24 by a hand count in dsPIC instructions: k is cautious there).
Camera: on the robot a step that asks for blobs also runs blob_detect on
the 40 x 20 frame; the "forager + camera" row adds its maximum.
Sound: a step that reads the microphones (hal_mic_level, hal/tone_detect.c)
copies and analyses 96 samples per microphone: the "tone_detect" row is 3
microphones x 3 bands.  The RepAtt image (25 ms period) runs its controller,
the camera's blob_detect and the detector in one step: the "repatt + camera
+ sound" row adds the three maxima, and must stay under the period minus
the microphones' 6 ms window (19 ms), or the tail of the robot's own tone
reaches its next reading.  The last column is each row's share of its
image's period (100 ms; 25 ms for the RepAtt rows).
Its inner loop is 16 x 16 -> 32-bit products (one dsPIC instruction each)
and 32-bit additions, which the factor k covers.

usage: cpu_report.py HARNESS [STEPS] [--out build/firmware/cpu.md]
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

MIPS = 14.7456e6
K = 3
FLOAT_CYCLES = 35 * 200
PERIOD_MS = 100.0
#: The control period of the RepAtt image (seed 002), which listens.
SOUND_PERIOD_MS = 25.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('harness')
    ap.add_argument('steps', nargs='?', type=int, default=2000)
    ap.add_argument('--out', default='build/firmware/cpu.md')
    args = ap.parse_args()
    if shutil.which('valgrind') is None:
        print('cpu report: valgrind is not installed (apt-get install valgrind): skipped')
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        base = os.path.join(tmp, 'cg.out')
        r = subprocess.run(['valgrind', '--tool=callgrind', f'--callgrind-out-file={base}',
                            '--dump-instr=no', '--compress-strings=no', '--compress-pos=no',
                            os.path.abspath(args.harness), str(args.steps)],
                           capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stdout + r.stderr)
            print('cpu report: the harness failed under valgrind')
            return 1
        print(r.stdout.strip())
        costs = {}
        trig = re.compile(r'^desc: Trigger: Client Request: (\S+)$', re.M)
        summ = re.compile(r'^summary: (\d+)$', re.M)
        for path in glob.glob(base + '.*'):
            with open(path) as f:
                text = f.read()
            t, s = trig.search(text), summ.search(text)
            if t and s:
                costs.setdefault(t.group(1), []).append(int(s.group(1)))

    def est(x86, float_cycles=0):
        cycles = K * x86 + float_cycles
        ms = cycles / MIPS * 1000.0
        return cycles, ms

    rows = []
    order = ['forager', 'nest_beacon', 'random_walk', 'repatt', 'blob_detect', 'tone_detect']
    period = {'repatt': SOUND_PERIOD_MS, 'tone_detect': SOUND_PERIOD_MS}
    for name in order:
        c = costs.get(name)
        if not c:
            print(f'cpu report: no measurements of {name}')
            return 1
        mean = sum(c) / len(c)
        fl = FLOAT_CYCLES if name == 'forager' else 0
        cyc, ms = est(max(c), fl)
        rows.append((name, len(c), mean, max(c), cyc, ms, period.get(name, PERIOD_MS)))
    f = costs['forager']
    b = costs['blob_detect']
    cyc, ms = est(max(f) + max(b), FLOAT_CYCLES)
    rows.append(('forager + camera (robot step)', len(f), sum(f) / len(f) + sum(b) / len(b),
                 max(f) + max(b), cyc, ms, PERIOD_MS))
    r, t = costs['repatt'], costs['tone_detect']
    r_cyc, r_ms = est(max(r) + max(b) + max(t))
    rows.append(('repatt + camera + sound (robot step)', len(r),
                 sum(r) / len(r) + sum(b) / len(b) + sum(t) / len(t), max(r) + max(b) + max(t),
                 r_cyc, r_ms, SOUND_PERIOD_MS))

    lines = ['| step | steps measured | x86-64 instructions, mean | x86-64 max | dsPIC cycles '
             '(estimate, max) | ms at 14.7456 MIPS | share of its period |',
             '|---|---|---|---|---|---|---|']
    for name, n, mean, mx, cyc, ms, per in rows:
        lines.append(f'| {name} | {n} | {mean:,.0f} | {mx:,} | {cyc:,.0f} | {ms:.2f} | '
                     f'{ms / per * 100:.1f} % of {per:.0f} ms |')
    lines += ['',
              f'Measured with valgrind --tool=callgrind (gcc -O2, x86-64), one dump per step. '
              f'dsPIC estimate = {K} x x86 instructions (16-bit ALU) + {FLOAT_CYCLES:,} cycles of '
              'software float in the forager\'s decision step (~35 float operations x ~200 cycles); '
              'an estimate, not a measurement on the robot.']
    t = costs['tone_detect']
    t_cyc, t_ms = est(max(t))
    sound_line = (f'Sound: tone_detect (3 microphones x 3 bands, one 96-sample block each) takes at most '
                  f'{t_cyc:,.0f} dsPIC cycles (estimate) = {t_ms:.2f} ms, '
                  f'{t_ms / SOUND_PERIOD_MS * 100:.1f} % of the RepAtt image\'s '
                  f'{SOUND_PERIOD_MS:.0f} ms control period.')
    sound_line += (f' The RepAtt robot step (controller + camera + sound) takes at most {r_ms:.2f} ms '
                   f'of {SOUND_PERIOD_MS:.0f} ms (limit {SOUND_PERIOD_MS - 6:.0f} ms).')
    lines += ['', sound_line]
    table = '\n'.join(lines) + '\n'
    print()
    print(table)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, 'w') as fo:
        fo.write('# Controller CPU per step\n\n' + table)
    print(f'written to {args.out}')
    worst = max(ms for *_, ms, per in rows if per == PERIOD_MS)
    ok = worst < PERIOD_MS / 2 and t_ms < SOUND_PERIOD_MS / 4 and r_ms < SOUND_PERIOD_MS - 6
    print(f'cpu report: worst step {worst:.2f} ms of {PERIOD_MS:.0f} ms; RepAtt {r_ms:.2f} ms of '
          f'{SOUND_PERIOD_MS:.0f} ms: '
          + ('fits inside the periods' if ok else 'TOO SLOW (more than half a 100 ms period, the '
                                                  'detector above a quarter of 25 ms, or RepAtt\'s '
                                                  'step above 19 ms)'))
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
