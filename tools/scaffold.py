"""scaffold.py - a new controller or task, copied from the tutorials' examples
with its names changed, ready to build and run (`make new-controller
NAME=foo`, `make new-task NAME=bar`, which then build and run its scenario).

    controller NAME  firmware/NAME/{NAME.h, NAME.c, NAME_def.c} from
                     firmware/examples/phototaxis*, and the scenario
                     sim_host/scenarios/NAME.yaml (the example's world, its
                     robots running NAME)
    task NAME        sim_host/tasks/NAME/{NAME.h, NAME.c} from
                     sim_host/tasks/gather/, and sim_host/scenarios/NAME.yaml
                     (the example's world with a NAME: section)

Nothing existing is overwritten: a name already taken (a file, a folder, a
registered controller or task) is an error, exit 2, with nothing written.
--root DIR writes into another copy of the repository (the tests).  Prints
the files it wrote, one a line, then the scenario to run.  Standard library only.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: C keywords and names the build already uses for other things.
RESERVED = {'auto', 'break', 'case', 'char', 'const', 'continue', 'default', 'do', 'double', 'else', 'enum',
            'extern', 'float', 'for', 'goto', 'if', 'inline', 'int', 'long', 'register', 'restrict', 'return',
            'short', 'signed', 'sizeof', 'static', 'struct', 'switch', 'typedef', 'union', 'unsigned', 'void',
            'volatile', 'while', 'common', 'apps', 'core', 'hal', 'sim', 'main', 'registry', 'idle', 'test'}
EXAMPLE_CONTROLLER = ('firmware/examples', 'phototaxis', ('phototaxis.h', 'phototaxis.c', 'phototaxis_def.c'))
EXAMPLE_TASK = ('sim_host/tasks/gather', 'gather', ('gather.h', 'gather.c'))
EXAMPLE_SCENARIO = 'sim_host/scenarios/phototaxis_gather.yaml'


class ScaffoldError(Exception):
    pass


def renamed(text, old, new):
    """The example's text with its name changed, in every case it is written."""
    for a, b in ((old.upper(), new.upper()), (old.capitalize(), new.capitalize()), (old, new)):
        text = text.replace(a, b)
    return text


def taken(root, name):
    """Why NAME cannot be used, or None."""
    if not re.fullmatch(r'[a-z][a-z0-9_]{0,23}', name):
        return 'a name is a lower-case C identifier of at most 24 characters: a-z, 0-9 and _, starting with a letter'
    if name in RESERVED:
        return f'{name} is a C keyword or a name the build uses'
    for d in sorted(os.listdir(os.path.join(root, 'firmware'))) + [None]:
        if d and os.path.exists(os.path.join(root, 'firmware', d, f'{name}.c')):
            return f'firmware/{d}/{name}.c exists: a controller (or module) of that name is there'
    for path in (f'firmware/{name}', f'sim_host/tasks/{name}', f'sim_host/scenarios/{name}.yaml'):
        if os.path.exists(os.path.join(root, path)):
            return f'{path} exists'
    # a registered name written elsewhere (`.name = "foo"` or a NAME define)
    for dirpath, _, files in os.walk(os.path.join(root, 'firmware')):
        for f in files:
            if f.endswith(('.c', '.h')):
                with open(os.path.join(dirpath, f), encoding='utf-8', errors='replace') as fh:
                    if re.search(r'(\.name\s*=|_NAME)\s+"' + re.escape(name) + '"', fh.read()):
                        return f'a controller is registered as {name} ({os.path.relpath(os.path.join(dirpath, f), root)})'
    return None


def write_all(root, files):
    """Writes {path: text} (relative to root), refusing to replace anything."""
    for path in files:
        if os.path.exists(os.path.join(root, path)):
            raise ScaffoldError(f'{path} exists; nothing written')
    for path, text in files.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, 'x', encoding='utf-8') as f:
            f.write(text)
        print(path)


def read(root, path):
    with open(os.path.join(root, path), encoding='utf-8') as f:
        return f.read()


def scenario_for_controller(text, name):
    """The example scenario with its robots running NAME."""
    out, n = re.subn(r'controller:\s*phototaxis\b', f'controller: {name}', text)
    if n == 0:
        raise ScaffoldError(f'{EXAMPLE_SCENARIO} has no `controller: phototaxis` to change')
    return (f'# {name}: made by `make new-controller NAME={name}` from {EXAMPLE_SCENARIO}; '
            f'its robots run {name}.\n' + re.sub(r'^name:.*$', f'name: {name}', out, count=1, flags=re.M))


def scenario_for_task(text, name):
    """The example scenario with its task section named NAME."""
    out, n = re.subn(r'^gather:', f'{name}:', text, flags=re.M)
    if n != 1:
        raise ScaffoldError(f'{EXAMPLE_SCENARIO} has no top-level `gather:` section to rename')
    return (f'# {name}: made by `make new-task NAME={name}` from {EXAMPLE_SCENARIO}; the world\'s task is {name}.\n'
            + re.sub(r'^name:.*$', f'name: {name}', out, count=1, flags=re.M))


def scaffold(kind, name, root):
    why = taken(root, name)
    if why:
        raise ScaffoldError(f'{kind} {name!r}: {why}; nothing written')
    folder, old, sources = EXAMPLE_CONTROLLER if kind == 'controller' else EXAMPLE_TASK
    dest = f'firmware/{name}' if kind == 'controller' else f'sim_host/tasks/{name}'
    def moved(text):   # the example's name, and its folder in includes and comments
        return renamed(text, old, name).replace(f'{folder}/', f'{dest}/').replace(
            f'"{os.path.basename(folder)}/', f'"{os.path.basename(dest)}/')
    files = {f'{dest}/{renamed(src, old, name)}': moved(read(root, f'{folder}/{src}')) for src in sources}
    scenario = read(root, EXAMPLE_SCENARIO)
    files[f'sim_host/scenarios/{name}.yaml'] = (scenario_for_controller(scenario, name) if kind == 'controller'
                                                else scenario_for_task(scenario, name))
    write_all(root, files)
    return f'sim_host/scenarios/{name}.yaml'


def main(argv):
    ap = argparse.ArgumentParser(prog='scaffold.py', description=__doc__.split('\n\n')[0])
    ap.add_argument('kind', choices=('controller', 'task'))
    ap.add_argument('name')
    ap.add_argument('--root', default=ROOT, help='the repository to write into (default this one)')
    a = ap.parse_args(argv)
    try:
        scenario = scaffold(a.kind, a.name, os.path.abspath(a.root))
    except ScaffoldError as e:
        print(f'scaffold: {e}', file=sys.stderr)
        return 2
    except OSError as e:
        print(f'scaffold: {e.filename}: {e.strerror}', file=sys.stderr)
        return 2
    print(f'scenario: {scenario}')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
