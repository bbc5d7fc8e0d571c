"""Sweep files: what to run, read strictly (every error names FILE:LINE).

A sweep file is YAML::

    name: policies_x_food          # optional; default the file name
    scenario: ../sim_host/scenarios/foraging_base.yaml   # relative to this file
    set:                           # overrides for every run (optional)
      duration: 600
    steps: 2000                    # optional; default the scenario's duration
    axes:                          # combined as a Cartesian product, in order
      - grid:                      # every combination of these values
          robots.0.policy: [drtm, artm]
          foraging.food_count: [20, 25]
      - zip:                       # these vary together (equal lengths)
          arena.width: [3, 4]
          arena.height: [3, 4]
      - list:                      # explicit combinations (same keys each)
          - {scenario: ../sim_host/scenarios/foraging_l3.yaml}
          - {scenario: ../sim_host/scenarios/foraging_base.yaml}
    repetitions: 10                # seeds 1..10; or seeds: [3, 7] or
                                   # seeds: {first: 100, count: 10}
    metrics: [food_net, oae_total] # optional; default every summary metric
    max_attempts: 3                # a failed run is retried on a rerun, this
                                   # many attempts in all (default 3)
    run_timeout: 600               # s; a run taking longer fails (0: none)
    keep_timeseries: true          # keep each run's timeseries.csv

Keys under ``set`` and in the axes are the simulator's ``--set`` keys; the key
``scenario`` (axes only) varies the scenario file. Every combination of the
axes runs with the same seeds (common random numbers), as a study compares
conditions on the same seeds.

Values are plain YAML scalars, or for an array key (a controller's weights)
a flat list of numbers, written to the simulator as ``--set key=[v0, v1, ...]``
(a grid of arrays: ``robots.2.params.b_out: [[0, 0, 0], [100, -100, 0]]``).
Explicit tags (``!!int``, ``!foo``) are refused, as are sweeps of more than MAX_RUNS runs (counted before anything
is expanded; ``swarm-sweep --max-runs`` raises the cap).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

TOP_KEYS = ("name", "scenario", "set", "steps", "axes", "seeds", "repetitions",
            "metrics", "max_attempts", "run_timeout", "keep_timeseries")
AXIS_KINDS = ("grid", "zip", "list")
SCENARIO_KEY = "scenario"
Scalar = str | int | float | bool
#: A value of ``set`` or of an axis: a scalar, or an array key's numbers.
Value = Scalar | tuple[int | float, ...]
#: Runs a sweep may have unless the caller raises the cap (swarm-sweep
#: --max-runs): the largest shipped sweep, studies/repatt_gains.yaml, has
#: 540,000; a plan holds about 1 kB a run in memory and in sweep.json.
MAX_RUNS = 1_000_000


class SweepError(Exception):
    """A bad sweep file or argument: one message naming the file and line."""

    exit_code = 2


@dataclass
class Axis:
    """One entry of ``axes``: its combinations, each {key: value}."""

    kind: str
    keys: list[str]
    combos: list[dict[str, Value]]
    line: int


@dataclass
class Sweep:
    path: Path
    name: str
    scenario: Path
    fixed: list[tuple[str, Value]] = field(default_factory=list)
    steps: int | None = None
    axes: list[Axis] = field(default_factory=list)
    seeds: list[int] = field(default_factory=list)
    metrics: list[str] | None = None
    max_attempts: int = 3
    run_timeout: float = 0.0
    keep_timeseries: bool = True
    key_lines: dict[str, int] = field(default_factory=dict)   # --set key -> line

    @property
    def varied_keys(self) -> list[str]:
        return [k for a in self.axes for k in a.keys]


def set_text(value: Value | list) -> str:
    """A value as the simulator's --set reads it (an array as a YAML flow list)."""
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(set_text(v) for v in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


_constructor = yaml.constructor.SafeConstructor()
_resolver = yaml.resolver.Resolver()
# Names become paths and script text: matched whole (re.fullmatch; `$` would
# also match before a final newline).
_KEY_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.([A-Za-z_][A-Za-z0-9_]*|[0-9]+))*")
NAME_RE = re.compile(r"[A-Za-z0-9_.-]{1,64}")
METRIC_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_DEFAULT_TAGS = {yaml.MappingNode: "tag:yaml.org,2002:map", yaml.SequenceNode: "tag:yaml.org,2002:seq"}


def _count(n: int) -> str:
    """A run count as text: 1,000 or, past a million, 10^12."""
    return f"{n:,}" if n < 10**7 else f"about 10^{len(str(n)) - 1}"


class _Reader:
    """Walks the composed YAML nodes, so that every error has a line."""

    def __init__(self, path: Path, max_runs: int = MAX_RUNS):
        self.path = path
        self.max_runs = max_runs

    def fail(self, node: yaml.Node | None, where: str, msg: str) -> SweepError:
        line = f":{node.start_mark.line + 1}" if node is not None else ""
        return SweepError(f"{self.path}{line}: {where}{': ' if where else ''}{msg}")

    def untagged(self, node: yaml.Node, where: str) -> None:
        """Refuses an explicit tag (`!!int "ten"`, `!foo`): a sweep's values
        are what they look like."""
        if isinstance(node, yaml.ScalarNode):
            implied = _resolver.resolve(yaml.ScalarNode, node.value, (node.style is None, False))
        else:
            implied = _DEFAULT_TAGS.get(type(node))
        if node.tag != implied:
            raise self.fail(node, where, f"explicit YAML tag '{node.tag}' refused: write the value "
                                         "plainly (quote it to make it a word)")

    def mapping(self, node: yaml.Node, where: str) -> list[tuple[str, yaml.Node, yaml.Node]]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, where, "expected a mapping (key: value lines)")
        self.untagged(node, where)
        seen: dict[str, int] = {}
        out = []
        for k, v in node.value:
            if not isinstance(k, yaml.ScalarNode):
                raise self.fail(k, where, "a key must be a plain word")
            self.untagged(k, where)
            if k.value in seen:
                raise self.fail(k, where, f"'{k.value}' given twice (first on line {seen[k.value]})")
            seen[k.value] = k.start_mark.line + 1
            out.append((k.value, k, v))
        return out

    def scalar(self, node: yaml.Node, where: str) -> Scalar:
        if not isinstance(node, yaml.ScalarNode):
            raise self.fail(node, where, "expected a single value")
        self.untagged(node, where)
        try:
            value = _constructor.construct_object(node, deep=True)
        except (yaml.YAMLError, ValueError, TypeError, OverflowError) as e:   # a safeguard: tags are refused above
            raise self.fail(node, where, f"cannot read '{node.value}': {e}") from None
        if value is None or not isinstance(value, (str, int, float, bool)):
            raise self.fail(node, where, f"expected a number, a word or true/false, got '{node.value}'")
        return value

    def value(self, node: yaml.Node, where: str) -> Value:
        """A scalar, or a flat non-empty list of numbers (an array key's value)."""
        if not isinstance(node, yaml.SequenceNode):
            return self.scalar(node, where)
        out = []
        for i, item in enumerate(self.sequence(node, where)):
            v = self.scalar(item, f"{where}[{i}]")
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise self.fail(item, f"{where}[{i}]", f"an array holds numbers, got '{item.value}'")
            out.append(v)
        return tuple(out)

    def integer(self, node: yaml.Node, where: str, lo: int, hi: int) -> int:
        v = self.scalar(node, where)
        if isinstance(v, bool) or not isinstance(v, int):
            raise self.fail(node, where, f"expected an integer, got '{node.value}'")
        if not lo <= v <= hi:
            raise self.fail(node, where, f"{v} is out of range [{lo}, {hi}]")
        return v

    def sequence(self, node: yaml.Node, where: str) -> list[yaml.Node]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, where, "expected a list")
        self.untagged(node, where)
        if not node.value:
            raise self.fail(node, where, "expected a non-empty list")
        return list(node.value)

    def set_key(self, knode: yaml.Node, where: str) -> str:
        key = knode.value
        if key == "seed":
            raise self.fail(knode, where, "seeds are not overrides: give them with `seeds:` or `repetitions:`")
        if not _KEY_RE.fullmatch(key):
            raise self.fail(knode, where, f"{key!r} is not a scenario key path (e.g. robots.0.count)")
        return key


def _suggest(word: str, choices: tuple[str, ...]) -> str:
    import difflib
    best = difflib.get_close_matches(word, choices, n=1)
    return f" (did you mean '{best[0]}'?)" if best else ""


def load(path: str | Path, seed_max: int, max_runs: int = MAX_RUNS) -> Sweep:
    """Read and check a sweep file; seeds must lie in [0, seed_max], and it
    may have at most max_runs runs."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SweepError(f"{path}: no such sweep file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise SweepError(f"{path}: cannot read: {e}") from None
    try:
        root = yaml.compose(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        line = f":{mark.line + 1}" if mark is not None else ""
        raise SweepError(f"{path}{line}: YAML syntax error: {getattr(e, 'problem', e)}") from None
    except RecursionError:
        raise SweepError(f"{path}: nested too deeply to be a sweep file") from None
    r = _Reader(path, max_runs)
    if root is None:
        raise SweepError(f"{path}: empty sweep file")
    entries = r.mapping(root, "")
    sw = Sweep(path=path, name=path.stem, scenario=Path())
    have = {}
    for key, knode, vnode in entries:
        if key not in TOP_KEYS:
            raise r.fail(knode, key, f"unknown key '{key}'{_suggest(key, TOP_KEYS)}")
        have[key] = (knode, vnode)
    if "scenario" not in have:
        raise r.fail(root, "scenario", "missing: the base scenario file")
    if "name" in have:
        sw.name = str(r.scalar(have["name"][1], "name"))
        if not isinstance(sw.name, str) or not NAME_RE.fullmatch(sw.name) or sw.name in (".", ".."):
            raise r.fail(have["name"][1], "name", "use 1 to 64 letters, digits, '_', '.' or '-'")
    sw.scenario = _scenario_path(r, have["scenario"][1], "scenario")
    if "set" in have:
        for key, knode, vnode in r.mapping(have["set"][1], "set"):
            if key == SCENARIO_KEY:
                raise r.fail(knode, "set", "the scenario is the top-level `scenario:` (or an axis)")
            sw.fixed.append((r.set_key(knode, "set"), r.value(vnode, f"set.{key}")))
            sw.key_lines[key] = knode.start_mark.line + 1
    if "steps" in have:
        sw.steps = r.integer(have["steps"][1], "steps", 1, 10_000_000_000)
    if "axes" in have:
        for i, anode in enumerate(r.sequence(have["axes"][1], "axes")):
            sw.axes.append(_axis(r, anode, f"axes[{i}]", sw))
    seen: dict[str, str] = {k: "set" for k, _ in sw.fixed}
    for i, axis in enumerate(sw.axes):
        for k in axis.keys:
            if k in seen:
                raise SweepError(f"{path}:{sw.key_lines[k]}: axes[{i}]: '{k}' is already varied or set in {seen[k]}")
            seen[k] = f"axes[{i}]"
    combos = 1
    for axis in sw.axes:
        combos *= len(axis.combos)
    sw.seeds = _seeds(r, have, seed_max, root, combos)
    if "metrics" in have:
        sw.metrics = []
        for j, m in enumerate(r.sequence(have["metrics"][1], "metrics")):
            name = r.scalar(m, f"metrics[{j}]")
            if not isinstance(name, str) or not METRIC_RE.fullmatch(name):
                raise r.fail(m, f"metrics[{j}]", f"{m.value!r} is not a metric name")
            if name in sw.metrics:
                raise r.fail(m, f"metrics[{j}]", f"'{name}' listed twice")
            sw.metrics.append(name)
    if "max_attempts" in have:
        sw.max_attempts = r.integer(have["max_attempts"][1], "max_attempts", 1, 100)
    if "run_timeout" in have:
        v = r.scalar(have["run_timeout"][1], "run_timeout")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 <= v <= 1e7:
            raise r.fail(have["run_timeout"][1], "run_timeout", "expected seconds in [0, 1e7] (0: no limit)")
        sw.run_timeout = float(v)
    if "keep_timeseries" in have:
        v = r.scalar(have["keep_timeseries"][1], "keep_timeseries")
        if not isinstance(v, bool):
            raise r.fail(have["keep_timeseries"][1], "keep_timeseries", "expected true or false")
        sw.keep_timeseries = v
    return sw


def _scenario_path(r: _Reader, node: yaml.Node, where: str) -> Path:
    v = r.scalar(node, where)
    if not isinstance(v, str):
        raise r.fail(node, where, "expected a scenario file path")
    p = resolve_scenario(r.path, v)
    if not p.is_file():
        raise r.fail(node, where, f"no such scenario file: {p}")
    return p


def resolve_scenario(sweep_file: Path, value: str) -> Path:
    """A scenario path as written in a sweep file (relative to that file)."""
    return (sweep_file.parent / value).resolve()


def _axis(r: _Reader, node: yaml.Node, where: str, sw: Sweep) -> Axis:
    entries = r.mapping(node, where)
    if len(entries) != 1 or entries[0][0] not in AXIS_KINDS:
        got = ", ".join(k for k, _, _ in entries)
        raise r.fail(node, where, f"expected one of grid:, zip:, list:, got {got or 'nothing'}")
    kind, _, body = entries[0]
    where = f"{where}.{kind}"
    line = node.start_mark.line + 1
    if kind in ("grid", "zip"):
        columns: list[tuple[str, list[Value]]] = []
        for key, knode, vnode in r.mapping(body, where):
            values = [_axis_value(r, v, f"{where}.{key}", key) for v in r.sequence(vnode, f"{where}.{key}")]
            if key != SCENARIO_KEY:
                r.set_key(knode, where)
            if len(set(map(repr, values))) != len(values):
                raise r.fail(vnode, f"{where}.{key}", "a value is listed twice")
            sw.key_lines[key] = knode.start_mark.line + 1
            columns.append((key, values))
        if not columns:
            raise r.fail(body, where, "no keys")
        keys = [k for k, _ in columns]
        if kind == "zip":
            n = {len(v) for _, v in columns}
            if len(n) != 1:
                lens = ", ".join(f"{k}: {len(v)}" for k, v in columns)
                raise r.fail(body, where, f"zipped lists differ in length ({lens})")
            combos = [dict(zip(keys, vals, strict=True)) for vals in zip(*(v for _, v in columns), strict=True)]
        else:
            import itertools
            import math
            n = math.prod(len(v) for _, v in columns)
            if n > r.max_runs:
                raise r.fail(body, where, f"{' x '.join(str(len(v)) for _, v in columns)} = {_count(n)} "
                                          f"combinations, more than the cap of {r.max_runs:,} runs "
                                          "(swarm-sweep --max-runs N raises it)")
            combos = [dict(zip(keys, vals, strict=True)) for vals in itertools.product(*(v for _, v in columns))]
        return Axis(kind, keys, combos, line)
    combos = []
    keys: list[str] = []
    for j, cnode in enumerate(r.sequence(body, where)):
        combo: dict[str, Value] = {}
        for key, knode, vnode in r.mapping(cnode, f"{where}[{j}]"):
            if key != SCENARIO_KEY:
                r.set_key(knode, f"{where}[{j}]")
            combo[key] = _axis_value(r, vnode, f"{where}[{j}].{key}", key)
            sw.key_lines.setdefault(key, knode.start_mark.line + 1)
        if j == 0:
            keys = list(combo)
        elif list(combo) != keys:
            raise r.fail(cnode, f"{where}[{j}]", f"keys differ from the first entry's ({', '.join(keys)})")
        if combo in combos:
            raise r.fail(cnode, f"{where}[{j}]", "the same combination is listed twice")
        combos.append(combo)
    return Axis(kind, keys, combos, line)


def _axis_value(r: _Reader, node: yaml.Node, where: str, key: str) -> Value:
    if key == SCENARIO_KEY:
        _scenario_path(r, node, where)
        return node.value       # as written: the table shows it so
    return r.value(node, where)


def _seeds(r: _Reader, have: dict[str, Any], seed_max: int, root: yaml.Node, combos: int) -> list[int]:
    """The seeds, refused at once if combos x seeds passes the cap."""
    if ("seeds" in have) == ("repetitions" in have):
        raise r.fail(root, "seeds", "give exactly one of `seeds:` (a list or {first, count}) and `repetitions:`")
    if "repetitions" in have:
        n = r.integer(have["repetitions"][1], "repetitions", 1, 10_000_000)
        first = 1
        node = have["repetitions"][1]
    else:
        node = have["seeds"][1]
        if isinstance(node, yaml.SequenceNode):
            seeds = [r.integer(s, f"seeds[{i}]", 0, seed_max) for i, s in enumerate(r.sequence(node, "seeds"))]
            if len(set(seeds)) != len(seeds):
                raise r.fail(node, "seeds", "a seed is listed twice")
            _cap(r, node, combos, len(seeds))
            return seeds
        fields = {k: v for k, _, v in r.mapping(node, "seeds")}
        extra = set(fields) - {"first", "count"}
        if extra or set(fields) != {"first", "count"}:
            raise r.fail(node, "seeds", "expected {first: N, count: N} or a list of seeds")
        first = r.integer(fields["first"], "seeds.first", 0, seed_max)
        n = r.integer(fields["count"], "seeds.count", 1, 10_000_000)
    if first + n - 1 > seed_max:
        raise r.fail(node, "seeds", f"seeds {first}..{first + n - 1} pass the simulator's seed range [0, {seed_max}]")
    _cap(r, node, combos, n)
    return list(range(first, first + n))


def _cap(r: _Reader, node: yaml.Node, combos: int, seeds: int) -> None:
    if combos * seeds > r.max_runs:
        raise r.fail(node, "", f"{_count(combos)} combinations x {seeds:,} seeds = {_count(combos * seeds)} runs, "
                               f"more than the cap of {r.max_runs:,} (swarm-sweep --max-runs N raises it)")
