"""After `make run`, every tool the documentation shows works or says in one
line what to run: each console script and each of its subcommands answers
--help (swarm-sweep's ended in a traceback over a '%' in its help), every
`.venv/bin/` program and `make` goal README.md and the site's pages (docs/)
name exists, and a tool
whose generated types, LCM module or matplotlib are missing says what to
run in one line, with no traceback."""
import re
import subprocess
import sys
import tomllib
import unittest
from pathlib import Path

from .helpers import ROOT, TempDir

BIN = Path(sys.executable).parent
# README.md and the site's pages, less the design notes (a record of their time).
README = "\n".join(p.read_text() for p in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
                   if "notes" not in p.relative_to(ROOT).parts)


def scripts():
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]


def run(argv, **kw):
    return subprocess.run(list(map(str, argv)), cwd=ROOT, capture_output=True, text=True, timeout=120, **kw)


class Help(unittest.TestCase):
    def test_every_console_script_and_subcommand(self):
        names = scripts()
        self.assertGreaterEqual(len(names), 7)
        for name in names:
            r = run([BIN / name, "--help"])
            self.assertEqual(r.returncode, 0, f"{name} --help: {r.stderr[-500:]}")
            self.assertNotIn("Traceback", r.stderr, name)
            self.assertIn(f"usage: {name}", r.stdout)
            sub = re.search(r"^  \{([a-z_,-]+)\}$", r.stdout, re.M)      # argparse's list of subcommands
            for command in sub.group(1).split(",") if sub else []:
                r = run([BIN / name, command, "--help"])
                self.assertEqual(r.returncode, 0, f"{name} {command} --help: {r.stderr[-500:]}")
                self.assertIn(f"usage: {name} {command}", r.stdout)


class NamedInTheReadme(unittest.TestCase):
    def test_venv_programs_exist(self):
        named = set(re.findall(r"\.venv/bin/([\w.-]+)", README))
        self.assertIn("swarm-monitor", named)
        for name in sorted(named):
            self.assertTrue((BIN / name).exists(), f"the documentation shows .venv/bin/{name}, which make deps does not install")

    def test_make_goals_exist(self):
        # In code: `make GOAL ...` spans and the lines of code blocks.
        code = re.findall(r"`([^`\n]+)`", README) + re.findall(r"^```\w*\n(.*?)^```", README, re.M | re.S)
        # A goal may be a file the Makefile builds (make build/libswarmsim.so).
        goals = {g.rstrip(".") for text in code for g in re.findall(r"(?:^|\s)make ([a-z][\w./-]*)", text, re.M)}
        self.assertIn("spy", goals)
        self.assertIn("build/libswarmsim.so", goals)
        r = run(["make", "-pq", "--no-print-directory", "help"])
        targets = set(re.findall(r"^([a-z][\w./-]*):", r.stdout, re.M))
        self.assertEqual(sorted(goals - targets), [], "make goals the documentation names but the Makefile lacks")


class TestHalves(unittest.TestCase):
    def test_make_tests_halves_run_every_group_once(self):
        # make test runs run.py's groups in two halves (tools/make/python.mk):
        # a group added to run.py and to neither half would never run there.
        mk = (ROOT / "tools/make/python.mk").read_text()
        halves = [re.search(rf"^{v} = (.*)$", mk, re.M).group(1).split()
                  for v in ("PYTHON_TESTS_1", "PYTHON_TESTS_2")]
        groups = re.search(r"^GROUPS = \((.*)\)$", (ROOT / "tools/tests/run.py").read_text(), re.M).group(1)
        self.assertEqual(sorted(halves[0] + halves[1]), sorted(g.strip(' "') for g in groups.split(",")))


class MissingPieces(TempDir):
    """A module stubbed out through PYTHONPATH (which comes before .venv's
    site-packages) stands for what `make deps` installs."""

    def stub(self, module):
        d = self.tmp / module
        d.mkdir()
        (d / "__init__.py").write_text(f"raise ImportError('no {module} here (a test stub)')\n")
        return {"PYTHONPATH": str(self.tmp), "PATH": str(BIN) + ":/usr/bin:/bin"}

    def check_one_line(self, r, *words):
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertNotIn("Traceback", r.stderr)
        self.assertEqual(len(r.stderr.splitlines()), 1, r.stderr)
        for w in words:
            self.assertIn(w, r.stderr)

    def test_the_generated_types(self):
        env = self.stub("swarmlcm")
        for name in ("swarm-monitor", "swarm-export", "swarm-plot", "swarm-bridge"):
            self.check_one_line(run([BIN / name, "x.lcmlog"], env=env), "swarmlcm", "run `make deps`")

    def test_the_lcm_module(self):
        log = self.tmp / "x.lcmlog"
        log.write_bytes(b"")
        env = self.stub("lcm")
        # (swarm-export reads logs with its own checked reader: it needs no lcm module)
        for argv in (["swarm-monitor", "--log", log], ["swarm-bridge", "/dev/null"]):
            self.check_one_line(run([BIN / argv[0], *argv[1:]], env=env), "`lcm` Python module", "make deps")

    def test_matplotlib(self):
        env = self.stub("matplotlib")
        self.check_one_line(run([BIN / "swarm-plot", "x.lcmlog"], env=env), "matplotlib", "make deps")
