"""gen_hal.py - the HAL reference, read from hal/hal.h at every docs build so
that the contract is written once: the header's opening comment, then each
banner section with every declaration (functions, constants, types) beside
its `/** ... */` comment, and an overview table of the calls.

The MkDocs hook (hooks.py) puts it where a page says `<!-- generated: hal.h -->`;
run by hand to see it:  python tools/docs/gen_hal.py
"""

import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HEADER = os.path.join(ROOT, 'hal', 'hal.h')
MARK = '<!-- generated: hal.h -->'

_BANNER = re.compile(r'^/\* -{10,} \*/$')
_TITLE = re.compile(r'^/\* (.*\S)\s*\*/$')
_FUNCTION = re.compile(r'\b(hal_[a-z0-9_]+)\s*\(')


class HalHeaderError(RuntimeError):
    """hal.h is not in the shape this page is made from."""


def _comment_text(lines):
    """The text of a /* */ or /** */ comment's lines, without the stars."""
    out = []
    for line in lines:
        s = line.strip()
        s = re.sub(r'^/\*\*?', '', s)
        s = re.sub(r'\*/$', '', s)
        s = re.sub(r'^\* ?', '', s.strip())
        out.append(s.rstrip())
    while out and not out[0]:
        out.pop(0)
    while out and not out[-1]:
        out.pop()
    return out


def parse(text):
    """(opening comment lines, [(section title, [(doc, code lines)])])."""
    lines = text.splitlines()
    if not lines or not lines[0].startswith('/*'):
        raise HalHeaderError('hal.h does not open with its comment')
    end = next((i for i, ln in enumerate(lines) if ln.rstrip().endswith('*/')), None)
    if end is None:
        raise HalHeaderError('hal.h: the opening comment never ends')
    intro = _comment_text(lines[:end + 1])
    sections = [('Status and types', [])]
    i = end + 1
    doc = None
    while i < len(lines):
        line = lines[i].rstrip()
        if (_BANNER.match(line) and i + 2 < len(lines) and _TITLE.match(lines[i + 1].rstrip())
                and _BANNER.match(lines[i + 2].rstrip())):
            sections.append((_TITLE.match(lines[i + 1].rstrip()).group(1), []))
            i += 3
            continue
        if line.lstrip().startswith('/**') and not line.lstrip().startswith('/**<'):
            j = i
            while not lines[j].rstrip().endswith('*/'):
                j += 1
            doc = re.sub(r'\s+', ' ', ' '.join(_comment_text(lines[i:j + 1]))).strip()
            i = j + 1
            continue
        if not line or line in ('#ifndef HAL_H', '#define HAL_H') or line.startswith(('#endif', '#include')):
            i += 1
            continue
        code = []
        depth = 0
        while i < len(lines):
            ln = lines[i].rstrip()
            code.append(ln)
            depth += ln.count('{') - ln.count('}')
            i += 1
            if depth == 0 and (ln.endswith(';') or ln.startswith('#define')):
                break
        if doc is None and sections[-1][1]:
            sections[-1][1][-1][1].extend(code)    # an undocumented line joins the one above
        else:
            sections[-1][1].append((doc or '', code))
        doc = None
    if len(sections) < 2:
        raise HalHeaderError('hal.h has no banner sections')
    return intro, sections


def _anchor(title):
    return re.sub(r'[^a-z0-9]+', '-', title.lower()).strip('-')


def page(text=None):
    if text is None:
        with open(HEADER, encoding='utf-8') as f:
            text = f.read()
    intro, sections = parse(text)
    out = ['<!-- Generated at every docs build by tools/docs/gen_hal.py from `hal/hal.h`; '
           'edit the header, not this page. -->', '']
    for k, ln in enumerate(intro[1:]):        # the first line names the file: the page's title does
        if ln.lstrip().startswith('- ') and k and not intro[k].lstrip().startswith('- '):
            out.append('')                    # a list needs a blank line before it
        out.append(ln.lstrip() if ln.lstrip().startswith('- ') else ln)
    out += ['', '## The calls at a glance', '', '| call | section | what it gives |', '|---|---|---|']
    for title, items in sections:
        for doc, code in items:
            names = _FUNCTION.findall(' '.join(code))
            if names and code[0].split('(')[0].strip().split()[-1].lstrip('*') == names[0]:
                first = re.split(r'(?<=\.)\s(?=[A-Z(])', doc, maxsplit=1)[0].replace('|', '\\|')
                out.append(f'| `{names[0]}` | [{title}](#{_anchor(title)}) | {first} |')
    out.append('')
    for title, items in sections:
        out += [f'## {title}', '']
        for doc, code in items:
            out += ['```c', *code, '```', '']
            if doc:
                out += [doc, '']
    return '\n'.join(out)


if __name__ == '__main__':
    try:
        sys.stdout.write(page())
    except (OSError, HalHeaderError) as e:
        sys.exit(f'gen_hal: {e}')
