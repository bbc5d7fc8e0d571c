"""readme_footprint.py - the documentation's footprint table, made from what
the image gates measured (tests/firmware/image_gates.py), so that it cannot
drift from the measurement (it once was 16 B off).

The table sits in its page, PAGE (docs/hardware/footprint.md), between the
two marker lines below.  The gates
compare it with the measurement and fail when it differs; `make
readme-footprint` writes the measured table there.  Sizes depend on the
compilers, so the table names the versions it was measured with, and a
machine with other versions only notes the difference (its sizes are its
own, not wrong).

usage: readme_footprint.py --update [--page docs/hardware/footprint.md] [--table build/firmware/footprint_readme.md]
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
#: The page that holds the table.
PAGE = os.path.join(ROOT, 'docs', 'hardware', 'footprint.md')
BEGIN = '<!-- footprint: measured by make firmware-check, which fails when this differs; make readme-footprint writes it -->'
END = '<!-- /footprint -->'
#: How the page names the IR backends of images.list.
BACKEND_NAMES = {'randb': 'turret', 'libircom': 'libIrcom'}


def compiler_versions(targets):
    """'avr-gcc 5.4.0, arm-none-eabi-gcc 12.2.1': the compilers of the gates."""
    out = []
    for t in targets.values():
        r = subprocess.run([t['cc'], '-dumpversion'], capture_output=True, text=True)
        out.append(f"{t['cc']} {r.stdout.strip() or '?'}")
    return ', '.join(out)


def n(v):
    return f'{v:,}'


def render(images, by, versions, gate):
    """The page's table (between the markers) from the gates' results
    `by[(image, target)]`."""
    lines = [BEGIN,
             f'| image | IR | static RAM (gate <= {n(gate)}) | camera frames | stack estimate | our RAM total '
             '| our flash | image flash | Cortex-M4F static RAM / flash |',
             '|---|---|---|---|---|---|---|---|---|']
    for image, backend in images:
        a, m = by.get((image, 'avr')), by.get((image, 'arm'))
        if a is None:
            continue
        arm = f"{n(m['static'])} / {n(m['flash_ours'])}" if m else 'n/a'
        lines.append(f"| {image} | {BACKEND_NAMES.get(backend, backend)} | {n(a['static'])} | {n(a['frames'])} "
                     f"| {n(a['stack'])} | {n(a['static'] + a['frames'] + a['stack'])} | {n(a['flash_ours'])} "
                     f"| {n(a['flash_image'])} | {arm} |")
    lines += ['', f'Measured with {versions}.', END]
    return '\n'.join(lines) + '\n'


def readme_block(text):
    """(start, end) of the marked table in the page's text, or None."""
    start = text.find(BEGIN)
    end = text.find(END, start)
    if start < 0 or end < 0:
        return None
    return start, end + len(END) + 1


def compare(readme, table):
    """None when the page's table is the measured one; else why not (a
    failure), or a note starting with 'note:' when other compilers made it."""
    with open(readme, encoding='utf-8') as fh:
        text = fh.read()
    span = readme_block(text)
    if span is None:
        return f'{os.path.relpath(readme, ROOT)} has no footprint table between the markers (see {__file__})'
    theirs = text[span[0]:span[1]]
    if theirs == table:
        return None
    measured_with = [ln for ln in table.splitlines() if ln.startswith('Measured with')]
    if measured_with and measured_with[0] not in theirs:
        return (f"note: {os.path.relpath(readme, ROOT)}'s footprint table was not measured with this machine's compilers "
                f"({measured_with[0][len('Measured with '):-1]}): not compared")
    ours, measured = theirs.splitlines(), table.splitlines()
    k = next((i for i, (a, b) in enumerate(zip(ours, measured, strict=False)) if a != b), min(len(ours), len(measured)))
    readme_line = ours[k] if k < len(ours) else '(nothing)'
    measured_line = measured[k] if k < len(measured) else '(nothing)'
    return (f"{os.path.relpath(readme, ROOT)}'s footprint table differs from the measurement: the page "
            f"{readme_line!r}, measured {measured_line!r}; `make readme-footprint` writes the measured table there")


def update(readme, table_path):
    with open(table_path, encoding='utf-8') as fh:
        table = fh.read()
    with open(readme, encoding='utf-8') as fh:
        text = fh.read()
    span = readme_block(text)
    if span is None:
        sys.exit(f'readme_footprint: {readme}: no footprint markers')
    with open(readme, 'w', encoding='utf-8') as fh:
        fh.write(text[:span[0]] + table + text[span[1]:])
    print(f'readme_footprint: {os.path.relpath(readme, ROOT)}: footprint table written from {table_path}')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--update', action='store_true', help='write the measured table into the page')
    ap.add_argument('--page', '--readme', dest='readme', default=PAGE)
    ap.add_argument('--table', default=os.path.join(ROOT, 'build', 'firmware', 'footprint_readme.md'))
    args = ap.parse_args()
    if not args.update:
        ap.error('--update is the only action (the gates compare)')
    if not os.path.exists(args.table):
        sys.exit(f'readme_footprint: {args.table}: not measured yet: run make firmware-gates')
    update(args.readme, args.table)
    return 0


if __name__ == '__main__':
    sys.exit(main())
