"""runnable.py - every command the documentation shows as runnable still runs.

A page marks a code block runnable with the line `<!-- runnable -->` right
above its opening fence; each command of such a block (a line, with its
`\\` continuations; `#` comments dropped) must exit 0.  The commands of one
page run in order, in a sandbox of their own: a temporary folder holding a
link to each top-level entry of the repository but `out/` and `build/`,
with `build/` a folder whose entries link to the real build's, so that
whatever a command writes (`out/...`, a new file under `build/`) stays in
the sandbox and the repository is left as it was.  A command that writes
through a link into the repository would change it: such commands are not
marked.  Standard library only.  Usage: runnable.py [PAGE.md ...]
(default: every page of docs/ and README.md).
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
MARK = '<!-- runnable -->'
TIMEOUT_S = 120
SHELLS = ('sh', 'bash', 'shell', 'console', '')


class PageError(Exception):
    """A marked block that is not a shell block, or is not closed."""


def blocks(path):
    """[(line number, [command, ...])] of the page's runnable blocks."""
    with open(path, encoding='utf-8') as f:
        lines = f.read().split('\n')
    found = []
    for i, line in enumerate(lines):
        if line.strip() != MARK:
            continue
        j = i + 1
        fence = lines[j].strip() if j < len(lines) else ''
        m = re.match(r'^(`{3,})\s*([\w-]*)', fence)
        if not m or m.group(2) not in SHELLS:
            raise PageError(f'{os.path.relpath(path, ROOT)}:{i + 1}: {MARK} must stand right above a sh code block')
        end = next((k for k in range(j + 1, len(lines)) if lines[k].strip() == m.group(1)), None)
        if end is None:
            raise PageError(f'{os.path.relpath(path, ROOT)}:{j + 1}: the runnable block is not closed')
        found.append((j + 1, commands(lines[j + 1:end])))
    return found


def commands(body):
    """The block's commands: lines joined at a trailing backslash, comments
    and blank lines dropped (a `#` starts a comment only where the shell's
    own lexer says so)."""
    out, cur = [], ''
    for line in body:
        cur += line.rstrip()
        if cur.endswith('\\'):
            cur = cur[:-1] + ' '
            continue
        lexer = shlex.shlex(cur, posix=True, punctuation_chars=False)
        lexer.whitespace_split = True
        lexer.commenters = '#'
        try:
            has_words = any(True for _ in lexer)
        except ValueError:        # an unclosed quote: let the shell say so
            has_words = True
        if has_words:
            out.append(cur.strip())
        cur = ''
    return out


def sandbox():
    """A folder that looks like the repository, where `out/` and new build
    files are the sandbox's own."""
    box = tempfile.mkdtemp(prefix='docs-runnable-')
    for name in os.listdir(ROOT):
        if name in ('out', 'build'):
            continue
        os.symlink(os.path.join(ROOT, name), os.path.join(box, name))
    os.mkdir(os.path.join(box, 'build'))
    real_build = os.path.join(ROOT, 'build')
    if os.path.isdir(real_build):
        for name in os.listdir(real_build):
            os.symlink(os.path.join(real_build, name), os.path.join(box, 'build', name))
    return box


def run_page(path):
    """(passed, failures) for one page."""
    found = blocks(path)
    if not found:
        return 0, []
    rel = os.path.relpath(path, ROOT)
    box = sandbox()
    passed, failures = 0, []
    try:
        for line, cmds in found:
            for cmd in cmds:
                t0 = time.monotonic()
                try:
                    done = subprocess.run(['bash', '-c', cmd], cwd=box, capture_output=True, text=True,
                                          timeout=TIMEOUT_S, stdin=subprocess.DEVNULL)
                    rc, tail = done.returncode, (done.stderr or done.stdout).strip().splitlines()[-3:]
                except subprocess.TimeoutExpired:
                    rc, tail = 'timeout', [f'still running after {TIMEOUT_S} s']
                secs = time.monotonic() - t0
                if rc == 0:
                    passed += 1
                    print(f'ok   {rel}:{line}: {cmd} ({secs:.1f} s)')
                else:
                    failures.append(f'{rel}:{line}: `{cmd}` exited {rc}: ' + ' / '.join(tail))
                    print(f'FAIL {rel}:{line}: {cmd}')
                    for t in tail:
                        print(f'       {t}')
    finally:
        shutil.rmtree(box, ignore_errors=True)
    return passed, failures


def main(argv):
    pages = argv[1:] or [os.path.join(ROOT, 'README.md')] + sorted(
        glob.glob(os.path.join(ROOT, 'docs', '**', '*.md'), recursive=True))
    passed, failures = 0, []
    for page in pages:
        try:
            p, f = run_page(os.path.abspath(page))
        except PageError as e:
            p, f = 0, [str(e)]
            print(f'FAIL {e}')
        passed += p
        failures += f
    if passed == 0 and not failures:
        failures.append('no page marks a runnable block: the test would test nothing')
    print(f'{passed} passed, {len(failures)} failed')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
