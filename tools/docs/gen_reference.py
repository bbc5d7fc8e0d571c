"""gen_reference.py - the site's generated reference pages, made from the
programs themselves so that they cannot drift: the swarmsim command line and
every scenario key from `swarmsim --help`, and each Python tool's `--help`.

The MkDocs hook (hooks.py) calls these on every build; run by hand to see a
page:  python tools/docs/gen_reference.py cli|scenario-keys|python-tools
"""

import os
import re
import subprocess
import sys
import tomllib
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
#: Where the simulator's help begins each part of the pages.
KEYS_HEADING = 'Scenario keys'
CONTROLLERS_HEADING = 'controllers ('
GENERATED = ('<!-- Generated at every docs build by tools/docs/gen_reference.py from {what}; '
             'edit the program, not this page. -->\n\n')


class HelpError(RuntimeError):
    """A program's --help could not be had or read."""


def run_help(argv, cwd=ROOT):
    """The standard output of `argv` (a --help call), at a fixed width."""
    env = dict(os.environ, COLUMNS='100', LC_ALL='C.UTF-8')
    try:
        done = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise HelpError(f'{" ".join(argv)}: {e}') from None
    if done.returncode != 0:
        raise HelpError(f'{" ".join(argv)} exited {done.returncode}: {done.stderr.strip()[-300:]}')
    return done.stdout


def swarmsim_help(sim):
    if not os.path.isfile(sim):
        raise HelpError(f'{sim} is not built: run `make` first (`make docs` builds it)')
    return run_help([sim, '--help'])


def split_help(text):
    """(options part, controllers-and-tasks part, scenario-keys part) of the help."""
    k = text.find('\n' + KEYS_HEADING)
    if k < 0:
        raise HelpError(f'swarmsim --help has no "{KEYS_HEADING}" section')
    c = text.find('\n' + CONTROLLERS_HEADING)
    if c < 0 or c > k:
        c = k
    return text[:c].strip('\n'), text[c:k].strip('\n'), text[k:].strip('\n')


def fence(text):
    return '```text\n' + text.rstrip() + '\n```\n'


def cli_page(sim):
    options, registry, _ = split_help(swarmsim_help(sim))
    return ('# The swarmsim command line\n\n' + GENERATED.format(what='`swarmsim --help`') +
            'Every option of `build/swarmsim`, as `swarmsim --help` gives it. Every scenario key is on '
            '[Scenario keys](scenario-keys.md); what a scenario holds and what a run writes, on '
            '[Scenarios](scenarios.md).\n\n' + fence(options) +
            '\n## Controllers and tasks\n\nWhat this build registers (the build finds them in the sources):\n\n' +
            fence(registry))


# One row of the keys table: key, type, default, range, meaning.  The range
# may hold spaces ("[0, 1]", "<= 63 chars"), so it is matched by its forms.
_ROW = re.compile(r'^  (\S+)\s+(\S+)\s+(\S+)\s+(\[[^\]]*\](?:\|\S+)?|<= \d+(?: chars)?|\S+)\s+(.*)$')
_GROUP = re.compile(r'^  (\S+) when (controller is \S+|task is \S+)(?: \((.*)\))?:\s*$')
_NONE = re.compile(r'^  (\S+): none when (.*)$')


def _cell(s):
    return s.replace('|', '\\|').strip()


def _section_of(key):
    """The page section a top-level key goes to: its first path component."""
    return re.split(r'[.\[]', key, maxsplit=1)[0]


def keys_page(sim):
    _, _, keys = split_help(swarmsim_help(sim))
    lines = keys.split('\n')
    head, rows = lines[0], lines[1:]
    sections, groups, notes, verbatim = {}, [], [], []
    group = None                 # (prefix, title, doc, rows) of a controller's params
    for line in rows:
        if not line.strip() or re.match(r'^\s+key\s+type\s+default', line):
            continue
        g, n, r = _GROUP.match(line), _NONE.match(line), _ROW.match(line)
        if g:
            group = (g.group(1), g.group(2), g.group(3), [])
            groups.append(group)
        elif n:
            groups.append((n.group(1), n.group(2), None, []))
            group = None
        elif r:
            key = r.group(1)
            if group and key.startswith(group[0] + '.'):
                group[3].append(r.groups())
            else:
                group = None
                sections.setdefault(_section_of(key), []).append(r.groups())
        elif line.startswith('  '):
            verbatim.append(line)
        else:
            notes.append(line.strip())
    out = ['# Scenario keys', '', GENERATED.format(what='`swarmsim --help`').rstrip(), '',
           f'{head.rstrip(":")}. ' + ' '.join(notes), '']

    def table(rows):
        out.extend(['| key | type | default | range | meaning |', '|---|---|---|---|---|'])
        for key, typ, default, rng, doc in rows:
            out.append(f'| `{_cell(key)}` | {typ} | `{_cell(default)}` | {_cell(rng)} | {_cell(doc)} |')
        out.append('')

    singles = [rows[0] for rows in sections.values() if len(rows) == 1]
    if singles:
        out.extend(['## The run', ''])
        table(singles)
    for name, rows in sections.items():
        if len(rows) > 1:
            out.extend([f'## `{name}`', ''])
            table(rows)
    for prefix, when, doc, rows in groups:
        out.extend([f'## `{prefix}` when {when.replace(" is ", " is `")}`', ''])
        if doc:
            out.extend([_cell(doc) + '.', ''])
        if rows:
            table(rows)
        else:
            out.extend(['No parameters.', ''])
    if verbatim:   # lines of a form this page does not know: shown as they are
        out.extend(['## Other lines of the help', '', fence('\n'.join(verbatim))])
    return '\n'.join(out).rstrip() + '\n'


def console_scripts():
    """[(name, module)] of pyproject.toml's [project.scripts]."""
    with open(os.path.join(ROOT, 'pyproject.toml'), 'rb') as f:
        return sorted(tomllib.load(f)['project']['scripts'].items())


def module_tools():
    """swarmtools modules run with `python -m` (they end in a __main__ guard)
    that no console script names."""
    scripted = {m.split(':')[0] for _, m in console_scripts()}
    found = []
    base = os.path.join(ROOT, 'tools')
    for dirpath, _, files in os.walk(os.path.join(base, 'swarmtools')):
        for name in sorted(files):
            if not name.endswith('.py') or name == '__main__.py':
                continue
            path = os.path.join(dirpath, name)
            with open(path, encoding='utf-8') as f:
                if not re.search(r'^if __name__ == .__main__.:', f.read(), re.M):
                    continue
            module = os.path.relpath(path, base)[:-3].replace(os.sep, '.')
            if module not in scripted:
                found.append(module)
    return sorted(found)


def subcommands(help_text):
    """The sub-commands an argparse help lists as {a,b,c}, if any."""
    m = re.search(r'^positional arguments:\n  \{([\w,-]+)\}', help_text, re.M)
    return m.group(1).split(',') if m else []


def python_tools_page(venv):
    py = os.path.join(venv, 'bin', 'python')
    tools = [(name, [os.path.join(venv, 'bin', name)]) for name, _ in console_scripts()]
    tools += [(f'python -m {m}', [py, '-m', m]) for m in module_tools()]
    with ThreadPoolExecutor(max_workers=4) as pool:
        helps = list(pool.map(lambda t: run_help(t[1] + ['--help']), tools))
        subs = [[(s, t[1] + [s]) for s in subcommands(h)] for t, h in zip(tools, helps, strict=True)]
        sub_helps = [list(pool.map(lambda s: run_help(s[1] + ['--help']), ss)) for ss in subs]
    out = ['# The Python tools', '', GENERATED.format(what="each tool's `--help`").rstrip(), '',
           'The host tools are one package, `swarmtools` (`tools/swarmtools/`), installed into `.venv` by '
           '`make deps`. Each console script is in `.venv/bin/`; the other tools run as '
           '`.venv/bin/python -m MODULE`. What each prints for `--help`:', '']
    for (name, _), h, ss, shs in zip(tools, helps, subs, sub_helps, strict=True):
        out.extend([f'## `{name}`', '', fence(h)])
        for (s, _), sh in zip(ss, shs, strict=True):
            out.extend([f'### `{name} {s}`', '', fence(sh)])
    return '\n'.join(out)


PAGES = {
    'reference/cli.md': lambda sim, venv: cli_page(sim),
    'reference/scenario-keys.md': lambda sim, venv: keys_page(sim),
    'reference/python-tools.md': lambda sim, venv: python_tools_page(venv),
}


def main(argv):
    sim = os.environ.get('SWARMSIM', os.path.join(ROOT, 'build', 'swarmsim'))
    venv = os.environ.get('VENV', os.path.join(ROOT, '.venv'))
    if len(argv) != 2 or f'reference/{argv[1]}.md' not in PAGES:
        sys.exit(f'usage: {argv[0]} ' + '|'.join(p[10:-3] for p in PAGES))
    try:
        sys.stdout.write(PAGES[f'reference/{argv[1]}.md'](sim, venv))
    except HelpError as e:
        sys.exit(f'gen_reference: {e}')


if __name__ == '__main__':
    main(sys.argv)
