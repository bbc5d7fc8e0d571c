"""Properties of the sweep-file reader (swarmtools.sweep.spec) and the
expansion (swarmtools.sweep.plan), which every sweep and study goes
through:

- any text, and any document built from a sweep file's own keys with
  values of every YAML kind (tags, anchors and aliases, nested flows,
  huge numbers, line breaks in names), is read or refused with a
  SweepError naming the file (and its line, when one is at fault);
  nothing else is raised, and nothing is expanded past the run cap;
- a file right but for one value (any kind, at any key) or nested
  thousands deep is read or refused the same way, and an accepted name,
  key or metric is one whole word (no trailing line break);
- what is read expands to exactly (combinations x seeds) runs, at most the
  cap, each with its own id, the same ids again in a second expansion;
- run ids hash an unambiguous encoding: two different override lists never
  give the same text to hash.
"""
import math
import os
import tempfile
import unittest
from pathlib import Path

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from swarmtools.sweep import plan, spec

ROOT = Path(__file__).resolve().parents[3]
SCENARIO = ROOT / "tests" / "data" / "scenarios" / "valid_small.yaml"
SEED_MAX = 2**53 - 1
CAP = 5000          # a small cap, so that the properties also meet it
# A document nested 1,000 deep reads slowly: fewer of them (a tenth at length).
DEEP_EXAMPLES = 25 if os.environ.get("SWARM_HYPOTHESIS", "ci") == "ci" else max(25, settings().max_examples // 10)

words = st.sampled_from(["robots.0.count", "arena.width", "a.b", "seed", "scenario", "x", "robots.0.policy",
                         "name", "1", "a.b\n", "..", "k.0.v"])
scalars = st.one_of(
    st.integers(-3, 12).map(str), st.integers().map(str), st.floats(allow_nan=True).map(repr),
    st.sampled_from(["true", "false", "null", "~", "yes", "0x1F", "1e999", "-.inf", ".nan", "2001-12-14",
                     "'quoted'", '"a\\nb"', '"t\\n"', "!foo x", '!!int "ten"', "!!bool 0", "!!timestamp 178",
                     "!!binary aGk=", "!!str 10", "! 10", "&a 1", "*a", "*b", "<<", "drtm", "../x.yaml",
                     str(SCENARIO), "[", "]", "{", "}", ":", "- ", "|", ">", "'", '"', "#", "%TAG", "? x"]),
    st.text(max_size=12))


@st.composite
def values(draw, depth=0):
    """A YAML value in flow style: a scalar, a list or a mapping."""
    kind = draw(st.integers(0, 5 if depth < 3 else 0))
    if kind <= 3:
        return draw(scalars)
    if kind == 4:
        return "[" + ", ".join(draw(st.lists(values(depth + 1), max_size=6))) + "]"
    keys = draw(st.lists(words, max_size=4))
    return "{" + ", ".join(f"{k!r}: {draw(values(depth + 1))}" if "\n" in k else f"{k}: {draw(values(depth + 1))}"
                           for k in keys) + "}"


@st.composite
def axes(draw):
    out = []
    for _ in range(draw(st.integers(0, 3))):
        kind = draw(st.sampled_from(["grid", "zip", "list", "cross"]))
        if kind == "list":
            body = "[" + ", ".join("{" + f"{draw(words)}: {draw(values())}" + "}"
                                   for _ in range(draw(st.integers(0, 4)))) + "]"
        else:
            cols = {draw(words): "[" + ", ".join(draw(st.lists(scalars, max_size=8))) + "]"
                    for _ in range(draw(st.integers(0, 4)))}
            body = "{" + ", ".join(f"{k!r}: {v}" if "\n" in k else f"{k}: {v}" for k, v in cols.items()) + "}"
        out.append(f"  - {kind}: {body}")
    return "axes:\n" + "\n".join(out) if out else draw(st.sampled_from(["", "axes: []", "axes: {}", "axes: 3"]))


@st.composite
def sweep_files(draw):
    """A sweep file's text: its own keys, in any order, some missing, some twice."""
    lines = []
    pool = {
        "scenario": lambda: draw(st.sampled_from([str(SCENARIO), "missing.yaml", "[x]", "!!str " + str(SCENARIO)])),
        "name": lambda: draw(st.one_of(st.sampled_from(["t", "a-b.c", "..", '"t\\n"', "x" * 70]), scalars)),
        "set": lambda: draw(values()),
        "steps": lambda: draw(st.one_of(st.integers(-5, 10**11).map(str), scalars)),
        "repetitions": lambda: draw(st.one_of(st.integers(-1, 10**8).map(str), scalars)),
        "seeds": lambda: draw(st.one_of(values(), st.just("{first: 1, count: 3}"),
                                        st.integers(0, 10**7).map(lambda n: f"{{first: 0, count: {n}}}"))),
        "metrics": lambda: draw(values()),
        "max_attempts": lambda: draw(scalars),
        "run_timeout": lambda: draw(scalars),
        "keep_timeseries": lambda: draw(scalars),
        "extra": lambda: draw(scalars),
    }
    for key in draw(st.lists(st.sampled_from([*pool, "axes"]), max_size=10)):
        lines.append(draw(axes()) if key == "axes" else f"{key}: {pool[key]()}")
    return "\n".join(lines) + "\n"


class SweepFiles(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="fuzz_sweep.")
        self.path = Path(self._tmp.name) / "s.yaml"

    def tearDown(self):
        self._tmp.cleanup()

    def load(self, text):
        self.path.write_text(text, encoding="utf-8", errors="surrogatepass")
        try:
            return spec.load(self.path, SEED_MAX, CAP)
        except spec.SweepError as e:
            self.assertTrue(str(e).startswith(str(self.path)), str(e))
            self.assertRegex(str(e)[len(str(self.path)):], r"^(:\d+)?: ")
            return None

    def check_expansion(self, sw):
        combos = math.prod(len(a.combos) for a in sw.axes)
        self.assertLessEqual(combos * len(sw.seeds), CAP)
        try:
            runs = plan.expand(sw)
        except spec.SweepError as e:          # the same run listed twice
            self.assertIn("are the same run", str(e))
            return
        self.assertEqual(len(runs), combos * len(sw.seeds))
        self.assertEqual(len({r.run_id for r in runs}), len(runs))
        self.assertEqual([r.run_id for r in runs], [r.run_id for r in plan.expand(sw)])
        self.assertTrue(spec.NAME_RE.fullmatch(sw.name))

    @given(st.text(max_size=400))
    def test_any_text_is_read_or_refused_with_its_place(self, text):
        sw = self.load(text.replace("\x00", ""))
        if sw is not None:
            self.check_expansion(sw)

    @given(sweep_files())
    def test_any_sweep_shaped_file_is_read_or_refused_with_its_place(self, text):
        sw = self.load(text)
        if sw is not None:
            self.check_expansion(sw)

    @given(values(), st.sampled_from(["set: {{arena.width: {}}}", "steps: {}", "repetitions: {}", "seeds: {}",
                                      "max_attempts: {}", "run_timeout: {}", "keep_timeseries: {}", "metrics: {}",
                                      "axes: [{{grid: {{arena.width: {}}}}}]", "axes: [{{list: [{{a.b: {}}}]}}]"]))
    def test_any_value_in_an_otherwise_valid_file(self, value, line):
        # The rest of the file is right, so the reader reaches the value
        # (tags, anchors, flows, huge numbers) and must say what is wrong.
        sw = self.load(f"scenario: {SCENARIO}\nrepetitions: 1\n{line.format(value)}\n")
        if sw is not None:
            self.check_expansion(sw)

    @settings(max_examples=DEEP_EXAMPLES)
    @given(st.integers(1, 1500), st.sampled_from(["[", "{a: ", "- "]), st.sampled_from(["set", "axes", "seeds", "x"]))
    def test_deep_nesting_is_refused_not_a_traceback(self, depth, opener, key):
        close = {"[": "]", "{a: ": "}", "- ": ""}[opener]
        body = opener * depth + "1" + close * depth if opener != "- " else "".join(
            "\n" + "  " * k + "- " for k in range(min(depth, 400))) + "1"
        self.load(f"scenario: {SCENARIO}\nrepetitions: 1\n{key}: {body}\n")

    @given(st.text(max_size=20), st.sampled_from(["name", "key", "metric"]))
    def test_an_accepted_name_key_or_metric_is_one_whole_word(self, word, what):
        # Names reach folder names and batch scripts: matched whole, so no
        # trailing line break passes ('$' matches before one).
        quoted = '"' + word.encode("unicode_escape").decode().replace('"', '\\"') + '"'
        line = {"name": f"name: {quoted}", "key": f"set: {{{quoted}: 2}}", "metric": f"metrics: [{quoted}]"}[what]
        sw = self.load(f"scenario: {SCENARIO}\nrepetitions: 1\n{line}\n")
        if sw is not None:
            got = {"name": sw.name, "key": sw.fixed[0][0] if sw.fixed else "", "metric": (sw.metrics or [""])[0]}[what]
            self.assertEqual(got, word)
            self.assertRegex(got, r"\A[A-Za-z0-9_.-]+\Z")

    @given(st.integers(1, 40), st.integers(1, 40), st.integers(1, 10**6))
    def test_the_cap_is_met_before_anything_is_expanded(self, a, b, reps):
        text = (f"scenario: {SCENARIO}\nrepetitions: {reps}\naxes:\n  - grid: {{a.b: {list(range(a))}}}\n"
                f"  - grid: {{c.d: {list(range(b))}}}\n")
        sw = self.load(text)
        self.assertEqual(sw is None, a * b * reps > CAP)


pairs = st.lists(st.tuples(st.text(max_size=8), st.text(max_size=8)), max_size=4)


class RunIds(unittest.TestCase):
    @given(pairs, pairs)
    def test_different_overrides_never_hash_the_same_text(self, one, two):
        assume(one != two)
        a = plan.canonical({"scenario_sha256": "0" * 64, "overrides": [list(p) for p in one]})
        b = plan.canonical({"scenario_sha256": "0" * 64, "overrides": [list(p) for p in two]})
        self.assertNotEqual(a, b)
        self.assertNotEqual(plan.scenario_hash("0" * 64, one), plan.scenario_hash("0" * 64, two))
