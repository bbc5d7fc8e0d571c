"""defaults_documented.py - every default a document states is the default
the descriptors give (`swarmsim --help`, which prints them from the tables):

- the comments of the parameter and config structs, `/**< ... (700) */`:
  every controller's params (the struct its *_def.c describes), every
  task's config and every model's config;
- the tables of the README and of docs/ whose header is `| key | default |`:
  full key paths (`ground.white`, `robots[].ground_sensors`), or bare keys
  under a sentence that names their section (`` each a key of the `sound:`
  section``).

A documented default that differs is a failure naming both; a check that
found almost nothing to compare fails too (it would prove nothing).

usage: python3 tests/cli/defaults_documented.py build/swarmsim
"""
import glob
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))


def help_defaults(sim):
    """{(context, key): default}: context is the controller for
    robots[].params keys, '' for every other key."""
    out = subprocess.run([sim, '--help'], capture_output=True, text=True, check=True).stdout
    keys, context = {}, ''
    for line in out.splitlines():
        m = re.match(r'  robots\[\]\.params when controller is (\w+)', line)
        if m:
            context = m.group(1)
            continue
        m = re.match(r'  (\S+)\s+(bool|int|number|angle|string|enum|list|map)\s+(\S+)', line)
        if m:
            key = m.group(1)
            keys[(context if key.startswith('robots[].params.') else '', key)] = m.group(3)
    return keys


def same(doc, default):
    """A documented value and --help's agree (numbers compare as numbers, a
    boolean as 1 or 0)."""
    default = {'true': '1', 'false': '0'}.get(default, default) if doc in ('0', '1') else default
    try:
        return abs(float(doc) - float(default)) <= 1e-9 * max(1.0, abs(float(default)))
    except ValueError:
        return doc.strip('`') == default


def struct_fields(header, type_name):
    """{field: documented default} of struct `type_name` in `header`."""
    text = open(header).read()
    m = re.search(r'typedef struct \w*\s*\{(.*?)\}\s*' + re.escape(type_name) + r'\s*;', text, re.S)
    if not m:
        return {}
    fields = {}
    for f in re.finditer(r'\b(\w+)(?:\[[^\]]*\])?;\s*/\*\*<[^*]*?\((?:default )?(-?[0-9][0-9.]*)\)\s*\*/', m.group(1)):
        fields[f.group(1)] = f.group(2)
    return fields


def header_of(type_name, folders):
    for h in sorted(sum((glob.glob(os.path.join(ROOT, d, '*.h')) for d in folders), [])):
        if re.search(r'\}\s*' + re.escape(type_name) + r'\s*;', open(h).read()):
            return h
    return None


def check_structs(keys, fail):
    compared = 0
    # Controllers: the params struct their *_def.c describes.
    for defc in sorted(glob.glob(os.path.join(ROOT, 'firmware', '*', '*_def.c'))):
        text = open(defc).read()
        name = re.search(r'^    \.name = (?:"(\w+)"|(\w+)_NAME)', text, re.M)
        ptype = re.search(r'PARAM_\w*FIELD\((\w+),', text)
        if not name or not ptype:
            continue
        alias = re.search(r'#define ' + ptype.group(1) + r' (\w+)', text)   # #define FP forager_params_t
        ptype = alias or ptype
        ctrl = name.group(1) or re.search(r'#define ' + name.group(2) + r'_NAME "(\w+)"',
                                          open(header_of_name(name.group(2))).read()).group(1)
        header = header_of(ptype.group(1), ['firmware/' + os.path.basename(os.path.dirname(defc)), 'firmware/common'])
        for field, doc in struct_fields(header, ptype.group(1)).items() if header else []:
            key = (ctrl, 'robots[].params.' + field)
            if key in keys:
                compared += 1
                if not same(doc, keys[key]):
                    fail(f'{os.path.relpath(header, ROOT)}: {field} documented ({doc}), but '
                         f'{ctrl}\'s default is {keys[key]} (swarmsim --help)')
    # Tasks and models: their config structs, keys by the field's name.
    for header in sorted(glob.glob(os.path.join(ROOT, 'sim_host', 'tasks', '*', '*.h'))
                         + glob.glob(os.path.join(ROOT, 'sim_host', 'models', '*', '*.h'))):
        text = open(header).read()
        for t in re.findall(r'\}\s*(\w+_config_t)\s*;', text):
            for field, doc in struct_fields(header, t).items():
                matches = [k for (c, k) in keys if c == '' and k.split('.')[-1] == field]
                if len(matches) > 1:   # the same name in several sections: the folder's
                    folder = os.path.basename(os.path.dirname(header))
                    matches = [k for k in matches if k.split('.')[0] == folder]
                if len(matches) == 1:
                    compared += 1
                    if not same(doc, keys[('', matches[0])]):
                        fail(f'{os.path.relpath(header, ROOT)}: {field} documented ({doc}), but '
                             f'{matches[0]} defaults to {keys[("", matches[0])]} (swarmsim --help)')
    return compared


def header_of_name(macro):
    for h in glob.glob(os.path.join(ROOT, 'firmware', '*', '*.h')):
        if re.search(r'#define ' + macro + r'_NAME ', open(h).read()):
            return h
    raise SystemExit(f'defaults_documented: no header defines {macro}_NAME')


def check_tables(keys, fail):
    compared = 0
    docs = [os.path.join(ROOT, 'README.md')] + sorted(glob.glob(os.path.join(ROOT, 'docs', '**', '*.md'),
                                                               recursive=True))
    for path in docs:
        lines = open(path).read().splitlines()
        for i, line in enumerate(lines):
            if not re.match(r'\|\s*key\s*\|\s*default\s*\|', line):
                continue
            section = ''
            for back in lines[max(0, i - 3):i]:
                m = re.search(r'`(\w+):` section', back)
                if m:
                    section = m.group(1)
            for row in lines[i + 2:]:
                if not row.startswith('|'):
                    break
                cells = [c.strip() for c in row.strip('|').split('|')]
                names = re.findall(r'`([\w\[\].]+)`', cells[0])
                values = [v.strip() for v in cells[1].split(',')]
                if not names or len(values) != len(names):
                    continue
                for name, value in zip(names, values, strict=True):
                    key = name if '.' in name else (section + '.' + name if section else name)
                    if ('', key) not in keys:
                        if '.' in name or section:
                            fail(f'{os.path.relpath(path, ROOT)}:{lines.index(row) + 1}: `{key}` is not a '
                                 f'scenario key (swarmsim --help)')
                        continue
                    if value in ('none', '-', ''):
                        continue
                    compared += 1
                    if not same(value, keys[('', key)]):
                        fail(f'{os.path.relpath(path, ROOT)}:{lines.index(row) + 1}: `{key}` documented as '
                             f'{value}, but its default is {keys[("", key)]} (swarmsim --help)')
    return compared


def main():
    keys = help_defaults(sys.argv[1] if len(sys.argv) > 1 else 'build/swarmsim')
    failures = []
    structs = check_structs(keys, failures.append)
    tables = check_tables(keys, failures.append)
    for f in failures:
        print('FAIL:', f)
    if structs < 40 or tables < 10:
        print(f'FAIL: compared only {structs} struct comments and {tables} table rows: the parsers found too '
              'little to prove anything')
        failures.append('too little')
    print(f'{structs} struct comments and {tables} table rows compared with swarmsim --help; '
          f'{len(failures)} failed')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
