#!/usr/bin/env python3
"""images.py - a platform's robot images, declared in platforms/<p>/images.list:
reads the declarations, lists them for make, and writes each image's main.

An image is declared, not written: one entry names the controller it runs and
its build-time parameters.  Its main is generated, a few lines of C that
include the controller's header, state the declaration as IMAGE_* macros and
two small functions, and then include the platform's run loop
(platforms/<p>/run/image_main.h), written once for every controller.  The run
loop calls the controller's functions by name (controller.h's contract, token
pasted from IMAGE_CONTROLLER), so an image's call graph holds only direct
calls and its stack gate follows the whole chain from main.

An entry is a line `image NAME` and the indented `key value` lines under it
('#' starts a comment).  The keys every platform has:

  controller NAME       required: firmware/<folder>/NAME.h, a controller of
                        controller.h's contract (NAME_t, NAME_params_t,
                        NAME_default_params, NAME_init, NAME_step,
                        NAME_state_name; NAME_observables with telemetry)
  telemetry yes|no      the robot's own telemetry (robot_telemetry.h) (no)
  reads_sensors yes|no  its robot_state_t carries the IR and ambient summaries;
                        no for a controller that reads no sensor (yes)
  seed random|id|zero   the controller's seed: the platform's entropy (on the
                        e-puck the robot id mixed with the noise of the first
                        light readings), the robot id, or 0 (random)
  policy C              the controller's policy (an index into its policies,
                        as a C constant), applied by NAME_set_policy
  selector C1 C2 ...    the selector switch picks the policy at power-on:
                        position 1 gives C1, 2 gives C2 ...; every other
                        position gives `policy` (which it needs)
  param FIELD VALUE     params.FIELD = VALUE after NAME_default_params (C)
  storage T[N] F(ARGS)  storage the controller is given before init: a static
                        T array of N, passed as F(&state, array, ARGS)

and the keys of the platform, from platforms/<p>/platform.py's IMAGE_KEYS:
{'choices': (...)} or {'type': 'int'}, and 'required'.  A given platform key
becomes IMAGE_<KEY> (yes/no: 1/0; a number: Nu; another choice: IMAGE_<KEY>_<CHOICE>
defined as 1); a key left out is not defined, and the run loop takes the
platform's default.

`$(NAME)` in a value is the build's constant NAME, given with --set NAME=VALUE
(tools/make/firmware.mk passes every constant it knows; `make firmware
FIRMWARE_N_ROBOTS=30` changes one), and `$(upper NAME)` the same in capitals
(FORAGER_POLICY=artm: TA_$(upper FORAGER_POLICY) is TA_ARTM).  A declaration that is wrong (a key the
platform does not have, a value out of its choices, a missing controller or
constant) is an error naming the file and line; nothing is written then.

usage: images.py list IMAGES.LIST [--platform DIR] [--fields KEY ...]
       images.py generate IMAGES.LIST --out DIR [--platform DIR] [--set NAME=VALUE ...]
       images.py platform-value PLATFORM_DIR NAME

`list` prints one word per image, NAME:VALUE:VALUE... with the values of
--fields (yes/no keys print yes or no).  `platform-value` prints NAME of the
platform's platform.py, one item a line (tests/firmware/hygiene.sh reads
HYGIENE_COMPILERS so).  `generate` writes DIR/<image>_main.c,
replacing a file only when its text changes (make rebuilds nothing else).
Standard library only.
"""
import argparse
import glob
import importlib.util
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))

YES_NO = ('yes', 'no')
SEEDS = ('random', 'id', 'zero')
# The keys of every platform: what their values may be.
COMMON_KEYS = {
    'controller': {'required': True},
    'telemetry': {'choices': YES_NO},
    'reads_sensors': {'choices': YES_NO},
    'seed': {'choices': SEEDS},
    'policy': {},
    'selector': {},
    'param': {'repeat': True},
    'storage': {},
}
DEFAULTS = {'telemetry': 'no', 'reads_sensors': 'yes', 'seed': 'random'}
NAME_RE = re.compile(r'^[a-z][a-z0-9_]*$')
FIELD_RE = re.compile(r'^[A-Za-z_][A-Za-z0-9_.]*$')
STORAGE_RE = re.compile(r'^([A-Za-z_][A-Za-z0-9_]*)\s*\[(.+)\]\s+([A-Za-z_][A-Za-z0-9_]*)\s*\((.*)\)$')
VAR_RE = re.compile(r'\$\((upper )?([A-Za-z_][A-Za-z0-9_]*)\)')


class DeclarationError(Exception):
    pass


class Image:
    """One entry: its name, where it is declared, its keys."""

    def __init__(self, name, path, line):
        self.name, self.path, self.line = name, path, line
        self.keys = {}       # key -> (value, line)
        self.params = []     # (field, value, line)

    def where(self, line=None):
        return f'{self.path}:{line or self.line}'

    def get(self, key):
        if key in self.keys:
            return self.keys[key][0]
        return DEFAULTS.get(key)


def load_platform(platform_dir):
    """The platform's descriptor (platforms/<p>/platform.py) as a module."""
    path = os.path.join(ROOT, platform_dir, 'platform.py')
    if not os.path.exists(path):
        raise DeclarationError(f'{platform_dir}: no platform.py (what its images may declare)')
    spec = importlib.util.spec_from_file_location(f'platform_{os.path.basename(platform_dir)}', path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def expand(value, variables, where):
    """`value` with every $(NAME) replaced by the build's constant NAME;
    `variables` None leaves them as they are."""
    if variables is None:
        return value

    def one(m):
        if m.group(2) not in variables:
            raise DeclarationError(f'{where}: $({m.group(2)}) is not a build constant (known: '
                                   f'{", ".join(sorted(variables)) or "none"})')
        v = variables[m.group(2)]
        return v.upper() if m.group(1) else v
    return VAR_RE.sub(one, value)


def check_value(image, key, spec, value, line):
    where = image.where(line)
    choices = spec.get('choices')
    if choices and value not in choices:
        raise DeclarationError(f'{where}: {key} is {value!r}; it must be one of: {", ".join(choices)}')
    if spec.get('type') == 'int' and not re.fullmatch(r'[0-9]+', value):
        raise DeclarationError(f'{where}: {key} is {value!r}; it must be a whole number')


def read_images(path, platform_keys, variables=None):
    """The entries of an image list, checked; DeclarationError names the
    file and line of the first thing wrong."""
    keys = dict(COMMON_KEYS)
    for k in platform_keys:
        if k in keys:
            raise DeclarationError(f'platform key {k!r} is one of the common keys')
        keys[k] = platform_keys[k]
    rel = os.path.relpath(os.path.join(ROOT, path), ROOT)
    images, seen = [], {}
    cur = None
    with open(os.path.join(ROOT, path), encoding='utf-8') as fh:
        for lineno, raw in enumerate(fh, 1):
            text = raw.split('#', 1)[0].rstrip()
            if not text.strip():
                continue
            words = text.split()
            where = f'{rel}:{lineno}'
            if not raw[0].isspace():
                if words[0] != 'image' or len(words) != 2:
                    raise DeclarationError(f'{where}: expected "image NAME" to start an entry, got: {text.strip()}')
                if not NAME_RE.match(words[1]):
                    raise DeclarationError(f'{where}: image name {words[1]!r}: lower case, digits and _ only')
                if words[1] in seen:
                    raise DeclarationError(f'{where}: image {words[1]} is already declared at {rel}:{seen[words[1]]}')
                seen[words[1]] = lineno
                cur = Image(words[1], rel, lineno)
                images.append(cur)
                continue
            if cur is None:
                raise DeclarationError(f'{where}: a key before the first "image NAME" line')
            key = words[0]
            if key not in keys:
                raise DeclarationError(f'{where}: unknown key {key!r} (keys: {", ".join(sorted(keys))})')
            if len(words) < 2:
                raise DeclarationError(f'{where}: {key} needs a value')
            value = expand(text.strip()[len(key):].strip(), variables, where)
            if key == 'param':
                parts = value.split(None, 1)
                if len(parts) != 2 or not FIELD_RE.match(parts[0]):
                    raise DeclarationError(f'{where}: expected "param FIELD VALUE", got: {text.strip()}')
                if any(f == parts[0] for f, _, _ in cur.params):
                    raise DeclarationError(f'{where}: param {parts[0]} is set twice in image {cur.name}')
                cur.params.append((parts[0], parts[1], lineno))
                continue
            if key in cur.keys:
                raise DeclarationError(f'{where}: {key} is set twice in image {cur.name} '
                                       f'(first at {rel}:{cur.keys[key][1]})')
            if variables is not None or not VAR_RE.search(value):   # unexpanded: checked by generate
                check_value(cur, key, keys[key], value, lineno)
            cur.keys[key] = (value, lineno)
    for im in images:
        for k, spec in keys.items():
            if spec.get('required') and k not in im.keys:
                raise DeclarationError(f'{im.where()}: image {im.name} has no {k}')
        if 'selector' in im.keys and 'policy' not in im.keys:
            raise DeclarationError(f"{im.where(im.keys['selector'][1])}: image {im.name}: a selector "
                                   'needs a policy (what the other positions give)')
        if 'storage' in im.keys and not STORAGE_RE.match(im.keys['storage'][0]):
            raise DeclarationError(f"{im.where(im.keys['storage'][1])}: expected \"storage TYPE[COUNT] "
                                   f"FUNCTION(ARGS)\", got: {im.keys['storage'][0]}")
        if im.get('telemetry') == 'no' and 'reads_sensors' in im.keys:
            raise DeclarationError(f"{im.where(im.keys['reads_sensors'][1])}: image {im.name}: "
                                   'reads_sensors without telemetry')
    return images


def controller_header(image):
    """firmware/<folder>/NAME.h of the image's controller, as included."""
    name = image.get('controller')
    where = image.where(image.keys['controller'][1])
    if not NAME_RE.match(name):
        raise DeclarationError(f'{where}: controller {name!r} is not a controller name')
    found = sorted(glob.glob(os.path.join(ROOT, 'firmware', '*', name + '.h')))
    if len(found) != 1:
        raise DeclarationError(f'{where}: controller {name}: '
                               + ('no firmware/*/' + name + '.h' if not found else
                                  'more than one header: ' + ', '.join(os.path.relpath(f, ROOT) for f in found)))
    return os.path.relpath(found[0], os.path.join(ROOT, 'firmware'))


def c_value(key, value, spec):
    if spec.get('choices') == YES_NO:
        return '1' if value == 'yes' else '0'
    if spec.get('type') == 'int':
        return value + 'u'
    return value


def render(image, platform_dir, platform_keys):
    """The C text of the image's main."""
    ctrl = image.get('controller')
    header = controller_header(image)
    out = []
    w = out.append
    w('/*')
    w(f' * {image.name}_main.c - the {os.path.basename(platform_dir)} image {image.name}, generated by')
    w(f' * tools/make/images.py from {image.where()} (edit that, not this file):')
    w(f' * the controller {ctrl} (firmware/{header}) on the platform\'s run loop,')
    w(f' * {platform_dir}/run/image_main.h.')
    w(' */')
    w('#include <stdint.h>')
    w('')
    w(f'#include "{header}"')
    w('')
    w(f'#define IMAGE_CONTROLLER {ctrl}')
    w(f'#define IMAGE_CONTROLLER_NAME {ctrl.upper()}_NAME')
    w(f"#define IMAGE_TELEMETRY {1 if image.get('telemetry') == 'yes' else 0}")
    if image.get('telemetry') == 'yes':
        w(f"#define IMAGE_READS_SENSORS {1 if image.get('reads_sensors') == 'yes' else 0}u")
    w(f"#define IMAGE_SEED_{image.get('seed').upper()} 1")
    for key, spec in platform_keys.items():
        if key not in image.keys:
            continue
        value = image.keys[key][0]
        if spec.get('choices') and spec['choices'] != YES_NO:
            w(f'#define IMAGE_{key.upper()}_{value.upper()} 1')
        else:
            w(f'#define IMAGE_{key.upper()} {c_value(key, value, spec)}')
    if 'storage' in image.keys:
        t, n, fn, args = STORAGE_RE.match(image.get('storage')).groups()
        w(f'#define IMAGE_STORAGE_TYPE {t}')
        w(f'#define IMAGE_STORAGE_COUNT ({n})')
        extra = f', {args}' if args.strip() else ''
        w(f'#define IMAGE_STORAGE_ATTACH(state, storage) {fn}((state), (storage){extra})')
    if 'selector' in image.keys:
        positions = image.get('selector').split()
        w('#define IMAGE_SELECTOR 1')
        w('')
        w('/* The policy the selector switch picks at power-on. */')
        w('static uint8_t app_policy(uint8_t selector)')
        w('{')
        w('    switch (selector) {')
        for i, p in enumerate(positions, 1):
            w(f'    case {i}u: return (uint8_t){p};')
        w(f"    default: return (uint8_t){image.get('policy')};")
        w('    }')
        w('}')
    elif 'policy' in image.keys:
        w(f"#define IMAGE_POLICY ((uint8_t){image.get('policy')})")
    w('')
    w('/* The build-time parameters, over the controller\'s defaults. */')
    w(f'static void app_params({ctrl}_params_t *params)')
    w('{')
    if not image.params:
        w('    (void)params;')
    for field, value, _ in image.params:
        w(f'    params->{field} = {value};')
    w('}')
    w('')
    w('#include "image_main.h"')
    return '\n'.join(out) + '\n'


def write_if_changed(path, text):
    try:
        with open(path, encoding='utf-8') as fh:
            if fh.read() == text:
                return False
    except FileNotFoundError:
        pass
    tmp = path + '.tmp'
    with open(tmp, 'w', encoding='utf-8') as fh:
        fh.write(text)
    os.replace(tmp, path)
    return True


def platform_value(platform_dir, name):
    value = getattr(load_platform(platform_dir), name, None)
    if value is None:
        raise DeclarationError(f'{platform_dir}/platform.py has no {name}')
    return value if isinstance(value, (list, tuple)) else [value]


def main(argv=None):
    if argv is None:
        argv = sys.argv[1:]
    if argv[:1] == ['platform-value']:
        if len(argv) != 3:
            print('usage: images.py platform-value PLATFORM_DIR NAME', file=sys.stderr)
            return 2
        try:
            print('\n'.join(str(v) for v in platform_value(argv[1], argv[2])))
        except DeclarationError as e:
            print(f'images.py: {e}', file=sys.stderr)
            return 1
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('action', choices=('list', 'generate'))
    ap.add_argument('images', help='the image list (platforms/<p>/images.list)')
    ap.add_argument('--platform', help='the platform folder (default: the image list\'s)')
    ap.add_argument('--fields', nargs='*', default=[], help='list: the keys to print after the name')
    ap.add_argument('--out', help='generate: the folder of the mains')
    ap.add_argument('--set', action='append', default=[], metavar='NAME=VALUE', help="a build constant")
    args = ap.parse_args(argv)
    platform_dir = args.platform or os.path.dirname(args.images)
    try:
        platform_keys = load_platform(platform_dir).IMAGE_KEYS
        if args.action == 'list':
            images = read_images(args.images, platform_keys)
            print(' '.join(':'.join([im.name] + [im.get(f) or '' for f in args.fields]) for im in images))
            return 0
        if not args.out:
            ap.error('generate needs --out')
        variables = {}
        for s in args.set:
            name, eq, value = s.partition('=')
            if not eq:
                ap.error(f'--set {s}: expected NAME=VALUE')
            variables[name] = value
        images = read_images(args.images, platform_keys, variables)
        texts = {im.name: render(im, platform_dir, platform_keys) for im in images}
    except DeclarationError as e:
        print(f'images.py: {e}', file=sys.stderr)
        return 1
    os.makedirs(args.out, exist_ok=True)
    for name, text in texts.items():
        write_if_changed(os.path.join(args.out, f'{name}_main.c'), text)
    # A main whose image is no longer declared goes.
    for old in glob.glob(os.path.join(args.out, '*_main.c')):
        if os.path.basename(old)[:-len('_main.c')] not in texts:
            os.remove(old)
    return 0


if __name__ == '__main__':
    sys.exit(main())
