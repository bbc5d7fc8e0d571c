#!/usr/bin/env python3
"""test_image_decls.py - tools/make/images.py, the reader of the platforms'
image declarations and the writer of their mains: every mistake in a
declaration is an error naming its file and line (and nothing is written);
a good one gives the main the run loop expects; mains are rewritten only
when their text changes.  Standard library only (unittest)."""
import contextlib
import io
import os
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tools', 'make'))
import images  # noqa: E402

KEYS = {
    'ir': {'choices': ('randb', 'libircom'), 'required': True},
    'camera': {'choices': ('yes', 'no')},
    'period_ms': {'type': 'int'},
}
GOOD = """# a comment
image walker
    controller  random_walk
    ir          libircom     # trailing comment
image beacon
    controller  nest_beacon
    ir          randb
    camera      no
    period_ms   25
    telemetry   yes
    reads_sensors no
    seed        zero
    param n_robots   $(N)u
    param t2_steps   $(L)u / 10u
image forager
    controller  forager
    ir          randb
    selector    TA_DRTM TA_ARTM
    policy      TA_$(upper POLICY)
    storage     uint32_t[8u] some_attach(8u)
"""
VARS = {'N': '20', 'L': '4000', 'POLICY': 'artm'}


class Declarations(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def write(self, text):
        path = os.path.join(self.tmp.name, 'images.list')
        with open(path, 'w', encoding='utf-8') as fh:
            fh.write(text)
        return path

    def refused(self, text, line, words, variables=None):
        """The declaration is refused with an error at `line` that says `words`."""
        path = self.write(text)
        with self.assertRaises(images.DeclarationError) as cm:
            decls = images.read_images(path, KEYS, VARS if variables is None else variables)
            for im in decls:
                images.controller_header(im)
        msg = str(cm.exception)
        self.assertIn(f'images.list:{line}:', msg)
        for w in words:
            self.assertIn(w, msg)

    def test_good_declarations_read_as_written(self):
        decls = images.read_images(self.write(GOOD), KEYS, VARS)
        self.assertEqual([im.name for im in decls], ['walker', 'beacon', 'forager'])
        walker, beacon, forager = decls
        self.assertEqual(walker.get('ir'), 'libircom')
        self.assertEqual(walker.get('telemetry'), 'no')     # the defaults
        self.assertEqual(walker.get('seed'), 'random')
        self.assertEqual(beacon.params, [('n_robots', '20u', 13), ('t2_steps', '4000u / 10u', 14)])
        self.assertEqual(forager.get('policy'), 'TA_ARTM')
        self.assertEqual(walker.line, 2)

    def test_the_main_states_the_declaration(self):
        decls = images.read_images(self.write(GOOD), KEYS, VARS)
        beacon = images.render(decls[1], 'platforms/x', KEYS)
        for want in ('#include "foraging/nest_beacon.h"', '#define IMAGE_CONTROLLER nest_beacon',
                     '#define IMAGE_CONTROLLER_NAME NEST_BEACON_NAME', '#define IMAGE_TELEMETRY 1',
                     '#define IMAGE_READS_SENSORS 0u', '#define IMAGE_SEED_ZERO 1',
                     '#define IMAGE_IR_RANDB 1', '#define IMAGE_CAMERA 0', '#define IMAGE_PERIOD_MS 25u',
                     '    params->n_robots = 20u;', '    params->t2_steps = 4000u / 10u;',
                     '#include "image_main.h"'):
            self.assertIn(want, beacon)
        walker = images.render(decls[0], 'platforms/x', KEYS)
        # A platform key left out is not defined: the run loop's default.
        self.assertNotIn('IMAGE_CAMERA', walker)
        self.assertNotIn('IMAGE_PERIOD_MS', walker)
        self.assertIn('    (void)params;', walker)
        forager = images.render(decls[2], 'platforms/x', KEYS)
        for want in ('case 1u: return (uint8_t)TA_DRTM;', 'case 2u: return (uint8_t)TA_ARTM;',
                     'default: return (uint8_t)TA_ARTM;', '#define IMAGE_SELECTOR 1',
                     '#define IMAGE_STORAGE_TYPE uint32_t', '#define IMAGE_STORAGE_COUNT (8u)',
                     '#define IMAGE_STORAGE_ATTACH(state, storage) some_attach((state), (storage), 8u)'):
            self.assertIn(want, forager)

    def test_mistakes_name_their_line(self):
        head = 'image a\n    controller random_walk\n'
        self.refused(head + '    ir randb\n    colour red\n', 4, ["unknown key 'colour'"])
        self.refused(head + '    ir ircom\n', 3, ['ir', "'ircom'", 'randb, libircom'])
        self.refused(head + '    ir randb\n    period_ms 2.5\n', 4, ['whole number'])
        self.refused(head, 1, ['image a has no ir'])
        self.refused(head + '    ir randb\n    ir randb\n', 4, ['ir is set twice', ':3'])
        self.refused(head + '    ir randb\nimage a\n    controller random_walk\n    ir randb\n', 4,
                     ['image a is already declared', ':1'])
        self.refused('    controller random_walk\n', 1, ['before the first "image NAME"'])
        self.refused('image A-1\n', 1, ['image name'])
        self.refused('imag a\n', 1, ['expected "image NAME"'])
        self.refused(head + '    ir randb\n    param n $(NOPE)\n', 4, ['$(NOPE) is not a build constant'])
        self.refused(head + '    ir randb\n    param n\n', 4, ['expected "param FIELD VALUE"'])
        self.refused(head + '    ir randb\n    param n 1\n    param n 2\n', 5, ['param n is set twice'])
        self.refused(head + '    ir randb\n    selector A B\n', 4, ['selector needs a policy'])
        self.refused(head + '    ir randb\n    storage lots\n', 4, ['storage TYPE[COUNT]'])
        self.refused(head + '    ir randb\n    reads_sensors no\n', 4, ['reads_sensors without telemetry'])
        self.refused(head + '    ir randb\n    seed often\n', 4, ['random, id, zero'])
        self.refused(head + '    ir\n', 3, ['ir needs a value'])
        self.refused('image a\n    controller no_such_controller\n    ir randb\n', 2,
                     ['no firmware/*/no_such_controller.h'])

    def test_a_refused_list_writes_nothing(self):
        out = os.path.join(self.tmp.name, 'gen')
        path = self.write('image a\n    controller random_walk\n    ir serial\n')
        plat = os.path.join(ROOT, 'platforms', 'epuck1')
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = images.main(['generate', path, '--platform', plat, '--out', out])
        self.assertEqual(rc, 1)
        self.assertIn("images.list:3: ir is 'serial'", err.getvalue())
        self.assertFalse(os.path.exists(out))

    def test_mains_are_rewritten_only_when_they_change(self):
        out = os.path.join(self.tmp.name, 'gen')
        plat = os.path.join(ROOT, 'platforms', 'epuck1')
        path = self.write('image a\n    controller random_walk\n    ir randb\n'
                          'image b\n    controller phototaxis\n    ir libircom\n')
        self.assertEqual(images.main(['generate', path, '--platform', plat, '--out', out]), 0)
        a = os.path.join(out, 'a_main.c')
        os.utime(a, (1, 1))
        self.assertEqual(images.main(['generate', path, '--platform', plat, '--out', out]), 0)
        self.assertEqual(os.stat(a).st_mtime, 1)          # same text: untouched
        # b is no longer declared: its main goes; a changes: rewritten.
        self.write('image a\n    controller random_walk\n    ir libircom\n')
        self.assertEqual(images.main(['generate', path, '--platform', plat, '--out', out]), 0)
        self.assertNotEqual(os.stat(a).st_mtime, 1)
        self.assertEqual(sorted(os.listdir(out)), ['a_main.c'])

    def test_every_platform_list_reads(self):
        with open(os.path.join(ROOT, 'platforms', 'platforms.list'), encoding='utf-8') as fh:
            names = [ln.split('#', 1)[0].strip() for ln in fh]
        names = [n for n in names if n]
        self.assertIn('epuck1', names)
        for p in names:
            lst = os.path.join('platforms', p, 'images.list')
            self.assertTrue(os.path.isdir(os.path.join(ROOT, 'platforms', p)), p)
            self.assertTrue(os.path.exists(os.path.join(ROOT, 'platforms', p, 'platform.mk')), p)
            if not os.path.exists(os.path.join(ROOT, lst)):
                continue
            keys = images.load_platform(os.path.join('platforms', p)).IMAGE_KEYS
            decls = images.read_images(lst, keys)
            self.assertTrue(decls)
            for im in decls:
                images.controller_header(im)


if __name__ == '__main__':
    unittest.main()
