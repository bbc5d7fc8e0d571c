"""hal_page.py - the generated HAL reference (tools/docs/gen_hal.py) holds the
whole contract: every call and constant hal/hal.h declares is on the built
page, and a header out of shape is an error, not a silent short page.
Run by `make docs-tests` after the build."""

import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, 'tools', 'docs'))
import gen_hal  # noqa: E402

with open(gen_hal.HEADER, encoding='utf-8') as f:
    header = f.read()
calls = re.findall(r'^[a-z][\w ]*?\b(hal_\w+)\(', header, re.M)
constants = [c for c in re.findall(r'^#define (HAL_\w+)', header, re.M) if c != 'HAL_H']
assert len(calls) >= 20 and len(constants) >= 10, (calls, constants)

md = gen_hal.page(header)
glance = md[md.index('## The calls at a glance'):md.index('## Status and types')]
missing = [c for c in calls if f'`{c}`' not in glance]
assert not missing, f'calls missing from the overview table: {missing}'
body = md[md.index('## Status and types'):]
missing = [c for c in calls + constants if c not in body]
assert not missing, f'declarations missing from the page: {missing}'

site = os.path.join(ROOT, 'build', 'site', 'reference', 'hal.html')
with open(site, encoding='utf-8') as f:
    html = f.read()
assert gen_hal.MARK not in html, 'the page kept its marker: the hook did not run'
missing = [c for c in calls if c not in html]
assert not missing, f'{site}: calls missing: {missing}'

# A new call under its own banner shows up; a header without banners is refused.
extra = header.replace('#endif /* HAL_H */', '/* ' + '-' * 66 + ' */\n/* Extra */\n/* ' + '-' * 66 +
                       ' */\n\n/** A probe call. */\nvoid hal_probe(hal_t *hal);\n\n#endif /* HAL_H */')
assert '`hal_probe`' in gen_hal.page(extra) and '## Extra' in gen_hal.page(extra)
try:
    gen_hal.page('/* x */\nvoid hal_x(void);\n')
except gen_hal.HalHeaderError:
    pass
else:
    raise AssertionError('a header without banner sections was accepted')
print(f'hal page: {len(calls)} calls and {len(constants)} constants of hal/hal.h on the page')
