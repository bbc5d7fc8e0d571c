#!/usr/bin/env python3
"""state_map.py - where each field of an image's controller state lies on the
emulated ATmega2560 and on this PC, from the DWARF of both builds, so that the
simulator can mirror the MCU's state into its own struct after every step
(sim_host/models/pil/pil_mirror.h): the world-side logic that reads a
controller's state (a task's token ledger, the summary's counters, the
simulator's telemetry) then reads the machine code's state, not a host copy.

    state_map.py AVR.elf HOST_EXE OUT.map [--symbol app_ctrl]

Both programs are the same image (its generated main, build/firmware/pil_avr/
avr/<image>.elf and host/<image>); the two type trees of `app_ctrl` are walked
side by side, member by member (same names, same order: one source), down to
the scalars:

  integers and enums  copied, sign- or zero-extended when their sizes differ
                      (an enum is 2 bytes on the AVR, 4 on the PC)
  float               copied (IEEE-754 single on both)
  double              widened (32-bit on the AVR, 64-bit on the PC)
  pointers            left alone: the host's point into its own memory
  bit-fields, unions of different sizes   refused (none in the controllers)

Adjacent scalars that are copied as they are merge into one run.  The map is
text, a line each:

  pil-state-map 1 AVR_SIZE HOST_SIZE TYPE
  copy AVR_OFFSET HOST_OFFSET BYTES
  int AVR_OFFSET HOST_OFFSET AVR_BYTES HOST_BYTES SIGNED
  double AVR_OFFSET HOST_OFFSET
  skip AVR_OFFSET HOST_OFFSET WHAT       (a pointer, for the reader)
"""
import argparse
import os
import sys

from elftools.elf.elffile import ELFFile


class MapError(Exception):
    pass


def find_var(path, name):
    """The DIE of global variable `name` in the ELF at `path`."""
    with open(path, 'rb') as fh:
        elf = ELFFile(fh)
        if not elf.has_dwarf_info():
            raise MapError(f'{path}: no DWARF (build it with -g)')
        dw = elf.get_dwarf_info()
        for cu in dw.iter_CUs():
            for die in cu.iter_DIEs():
                if die.tag == 'DW_TAG_variable' and die.attributes.get('DW_AT_name') \
                        and die.attributes['DW_AT_name'].value.decode() == name and 'DW_AT_type' in die.attributes:
                    return Tree(die)
    raise MapError(f'{path}: no variable {name}')


class Tree:
    """A DIE with what walking its type needs."""

    def __init__(self, die):
        self.die = die

    def type(self):
        t = self.die.get_DIE_from_attribute('DW_AT_type')
        while t.tag in ('DW_TAG_typedef', 'DW_TAG_const_type', 'DW_TAG_volatile_type'):
            t = t.get_DIE_from_attribute('DW_AT_type')
        return t


def strip(t):
    while t.tag in ('DW_TAG_typedef', 'DW_TAG_const_type', 'DW_TAG_volatile_type'):
        t = t.get_DIE_from_attribute('DW_AT_type')
    return t


def name_of(die):
    a = die.attributes.get('DW_AT_name')
    return a.value.decode() if a else '?'


def size_of(t):
    t = strip(t)
    if 'DW_AT_byte_size' in t.attributes:
        return t.attributes['DW_AT_byte_size'].value
    if t.tag == 'DW_TAG_array_type':
        return size_of(t.get_DIE_from_attribute('DW_AT_type')) * count_of(t)
    raise MapError(f'no size for {t.tag} {name_of(t)}')


def count_of(arr):
    n = 1
    for sub in arr.iter_children():
        if sub.tag != 'DW_TAG_subrange_type':
            continue
        if 'DW_AT_count' in sub.attributes:
            n *= sub.attributes['DW_AT_count'].value
        elif 'DW_AT_upper_bound' in sub.attributes:
            n *= sub.attributes['DW_AT_upper_bound'].value + 1
        else:
            raise MapError('an array without bounds')
    return n


def member_offset(m):
    a = m.attributes.get('DW_AT_data_member_location')
    if a is None:
        return 0
    if isinstance(a.value, int):
        return a.value
    # DW_OP_plus_uconst N (older compilers)
    v = a.value
    if len(v) >= 2 and v[0] == 0x23:
        n, shift = 0, 0
        for b in v[1:]:
            n |= (b & 0x7F) << shift
            shift += 7
            if not b & 0x80:
                break
        return n
    raise MapError(f'member {name_of(m)}: a location this reader does not know')


def scalar_kind(t):
    """('int', signed) / ('float',) / ('double',) / ('ptr',) for a scalar type."""
    t = strip(t)
    if t.tag == 'DW_TAG_pointer_type':
        return ('ptr',)
    if t.tag == 'DW_TAG_enumeration_type':
        signed = any(c.attributes['DW_AT_const_value'].value < 0 for c in t.iter_children()
                     if c.tag == 'DW_TAG_enumerator' and 'DW_AT_const_value' in c.attributes)
        return ('int', signed)
    if t.tag == 'DW_TAG_base_type':
        enc = t.attributes['DW_AT_encoding'].value
        if enc == 0x04:   # DW_ATE_float
            return ('float',) if size_of(t) == 4 else ('double',)
        if enc in (0x05, 0x06):   # signed, signed_char
            return ('int', True)
        if enc in (0x02, 0x07, 0x08):   # boolean, unsigned, unsigned_char
            return ('int', False)
    raise MapError(f'a {t.tag} ({name_of(t)}) this reader does not map')


def walk(a, h, ao, ho, path, out):
    """Leaves of types a (AVR) and h (host) at offsets ao, ho."""
    a, h = strip(a), strip(h)
    if a.tag != h.tag:
        raise MapError(f'{path}: {a.tag} on the AVR, {h.tag} on the host')
    if a.tag in ('DW_TAG_structure_type', 'DW_TAG_union_type'):
        am = [m for m in a.iter_children() if m.tag == 'DW_TAG_member']
        hm = [m for m in h.iter_children() if m.tag == 'DW_TAG_member']
        if [name_of(m) for m in am] != [name_of(m) for m in hm]:
            raise MapError(f'{path}: the members differ')
        if a.tag == 'DW_TAG_union_type':
            if size_of(a) != size_of(h):
                raise MapError(f'{path}: a union of {size_of(a)} bytes on the AVR, {size_of(h)} on the host')
            out.append(('copy', ao, ho, size_of(a), path))
            return
        for x, y in zip(am, hm, strict=True):
            if 'DW_AT_bit_size' in x.attributes:
                raise MapError(f'{path}.{name_of(x)}: a bit-field')
            walk(x.get_DIE_from_attribute('DW_AT_type'), y.get_DIE_from_attribute('DW_AT_type'),
                 ao + member_offset(x), ho + member_offset(y), f'{path}.{name_of(x)}', out)
        return
    if a.tag == 'DW_TAG_array_type':
        n = count_of(a)
        if n != count_of(h):
            raise MapError(f'{path}: {n} elements on the AVR, {count_of(h)} on the host')
        ae, he = a.get_DIE_from_attribute('DW_AT_type'), h.get_DIE_from_attribute('DW_AT_type')
        asz, hsz = size_of(ae), size_of(he)
        for k in range(n):
            walk(ae, he, ao + k * asz, ho + k * hsz, f'{path}[{k}]', out)
        return
    ka, kh = scalar_kind(a), scalar_kind(h)
    if ka[0] == 'ptr' or kh[0] == 'ptr':
        out.append(('skip', ao, ho, 'pointer', path))
        return
    sa, sh = size_of(a), size_of(h)
    if ka == ('float',) and kh == ('double',):
        out.append(('double', ao, ho, path))
    elif ka[0] == 'int' and kh[0] == 'int':
        if sa == sh:
            out.append(('copy', ao, ho, sa, path))
        else:
            out.append(('int', ao, ho, sa, sh, 1 if ka[1] else 0, path))
    elif ka == kh and sa == sh:
        out.append(('copy', ao, ho, sa, path))
    else:
        raise MapError(f'{path}: {ka} of {sa} bytes on the AVR, {kh} of {sh} on the host')


def merge(leaves):
    """Adjacent copies that are contiguous on both sides, as one."""
    out = []
    for leaf in leaves:
        if (leaf[0] == 'copy' and out and out[-1][0] == 'copy' and out[-1][1] + out[-1][3] == leaf[1]
                and out[-1][2] + out[-1][3] == leaf[2]):
            prev = out[-1]
            out[-1] = ('copy', prev[1], prev[2], prev[3] + leaf[3], prev[4])
        else:
            out.append(leaf)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('avr')
    ap.add_argument('host')
    ap.add_argument('out')
    ap.add_argument('--symbol', default='app_ctrl')
    args = ap.parse_args(argv)
    try:
        a = find_var(args.avr, args.symbol).type()
        h = find_var(args.host, args.symbol).type()
        leaves = []
        walk(a, h, 0, 0, args.symbol, leaves)
        lines = [f'pil-state-map 1 {size_of(a)} {size_of(h)} {name_of(a)}']
        for leaf in merge(leaves):
            lines.append(' '.join(str(x) for x in leaf[:-1]))
    except MapError as e:
        print(f'state_map.py: {e}', file=sys.stderr)
        return 1
    tmp = args.out + '.tmp'
    with open(tmp, 'w', encoding='utf-8') as fh:
        fh.write('\n'.join(lines) + '\n')
    os.replace(tmp, args.out)
    return 0


if __name__ == '__main__':
    sys.exit(main())
