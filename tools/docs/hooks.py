"""hooks.py - MkDocs hooks of the site (mkdocs.yml `hooks:`): adds the pages
that are generated from the programs and sources at every build, so that
they are never typed twice (gen_reference.py), and the LCM types page from
lcm_types/; and writes the studies' costs (swarmtools.study.costs) where a
page says `<!-- generated: study costs -->`.  SWARMSIM and VENV name the simulator and the virtualenv
(default build/swarmsim and .venv, as `make docs` sets them)."""

import glob
import os
import sys

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gen_reference  # noqa: E402  (beside this file)


def lcm_types_page():
    """lcm_types/README.md and every .lcm definition, as they are."""
    root = gen_reference.ROOT
    with open(os.path.join(root, 'lcm_types', 'README.md'), encoding='utf-8') as f:
        text = f.read()
    parts = [gen_reference.GENERATED.format(what='`lcm_types/README.md` and `lcm_types/*.lcm`'), text.rstrip(),
             '', '## The definitions', '']
    for path in sorted(glob.glob(os.path.join(root, 'lcm_types', '*.lcm'))):
        with open(path, encoding='utf-8') as f:
            parts += [f'### `{os.path.basename(path)}`', '', '```c', f.read().rstrip(), '```', '']
    return '\n'.join(parts)


COSTS_MARK = '<!-- generated: study costs -->'


def study_costs_table():
    """The full studies' measured costs and the --quick smoke runs, from
    swarmtools.study.costs (what each study prints before it starts)."""
    from swarmtools.study.costs import COSTS, QUICK
    rows = ['| study | command | runs | core-hours | wall time on 2 cores | `--quick` |',
            '|---|---|---:|---:|---|---|']
    for key, c in COSTS.items():
        q = QUICK.get(key)
        quick = (f'{q.seeds} seed{"s" if q.seeds != 1 else ""} a cell, runs cut at {q.steps:,} steps'
                 + (f'; {q.note}' if q.note else '')) if q else '-'
        wall = c.wall + (f' ({c.note})' if c.note else '')
        rows.append(f'| {c.study} | `{c.command}` | {c.runs:,} | {c.core_hours:g} | {wall} | {quick} |')
    return '\n'.join(rows) + '\n'


def on_page_markdown(markdown, page, config, files):
    if COSTS_MARK in markdown:
        markdown = markdown.replace(COSTS_MARK, study_costs_table())
    return markdown


def on_files(files, config):
    sim = os.environ.get('SWARMSIM', os.path.join(gen_reference.ROOT, 'build', 'swarmsim'))
    venv = os.environ.get('VENV', os.path.join(gen_reference.ROOT, '.venv'))
    pages = {path: make for path, make in gen_reference.PAGES.items()}
    pages['reference/lcm-types.md'] = lambda sim, venv: lcm_types_page()
    for path, make in pages.items():
        if files.get_file_from_path(path) is not None:
            raise PluginError(f'docs/{path} is generated at every build: delete the file (edit the program instead)')
        try:
            content = make(sim, venv)
        except gen_reference.HelpError as e:
            raise PluginError(f'cannot generate {path}: {e}') from None
        files.append(File.generated(config, path, content=content))
    return files
