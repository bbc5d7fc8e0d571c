"""Evolution files: what to evolve, read strictly (every error names FILE:LINE);
check_with_simulator then checks the genome and the fitness against what the
simulator's controllers and tasks declare, before anything runs.

An evolution file is YAML::

    name: nnea_d18                 # optional; default the file name
    scenarios:                     # one or more, relative to this file: every
      - ../sim_host/scenarios/nnea_square.yaml    # genome is tried in each
    set: {paths.hold: 1.0}         # overrides for every run (optional)
    steps: 3000                    # control steps per run (default the scenario's)
    genome:
      group: swarm                 # the robot group (name or index) whose
                                   # controller's params are the genome
      params:                      # each: a key of its params, its length
        - {key: w_in, size: 56, range: [-2047, 2047], integer: true}
        - {key: tau, size: 4, range: [0, 255], integer: true}
    fitness: trips_per_robot + 10 * success   # a metric, or an expression (fitness.py)
    goal: maximise                 # or minimise (default maximise)
    trials: 3                      # seeds per genome and scenario
    seed: 1                        # the evolution's seed: genomes and trial seeds
    trial_seeds: per_generation    # new seeds each generation, or `fixed`
    algorithm:
      name: cmaes                  # cmaes (cma) or ga (DEAP's operators)
      population: 16
      sigma: 0.25                  # cmaes: first step, in the unit cube of the ranges
      # ga: elite: 4, mutation_sd: 0.1, mutation_rate: 0.1
    generations: 50                # the budget
    max_evaluations: 0             # another budget: runs (0: none)

A genome is a point of the unit cube, one coordinate per gene; gene i of key k
is range_lo + x (range_hi - range_lo), rounded when `integer`.  The runs are
the sweep engine's: a key of size 1 is a scalar (`--set
robots.G.params.KEY=V`), a longer one an array (`=[v0, v1, ...]`).
"""

from __future__ import annotations

import difflib
import hashlib
import json
import re
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from swarmtools.sweep.spec import NAME_RE, SweepError, Value, _Reader, resolve_scenario, set_text

TOP_KEYS = ("name", "scenarios", "set", "steps", "genome", "fitness", "goal", "trials", "seed",
            "trial_seeds", "algorithm", "generations", "max_evaluations")
ALGORITHMS = {
    "cmaes": {"population": (int, 2, 100_000), "sigma": (float, 1e-6, 1.0)},
    "ga": {"population": (int, 2, 100_000), "elite": (int, 1, 100_000), "mutation_sd": (float, 0.0, 1.0),
           "mutation_rate": (float, 0.0, 1.0)},
}
DEFAULTS = {"cmaes": {"population": 16, "sigma": 0.25},
            "ga": {"population": 20, "elite": 4, "mutation_sd": 0.1, "mutation_rate": 0.1}}
MAX_GENES = 10_000
SEED_MAX = 2**31 - 1


class EvolveError(SweepError):
    """A bad evolution file or argument: one message naming the file and line."""


@dataclass
class Gene:
    key: str                 # the params key
    size: int
    lo: float
    hi: float
    integer: bool

    def values(self, x: list[float]) -> list[int | float]:
        out: list[int | float] = []
        for u in x:
            u = min(1.0, max(0.0, float(u)))
            v = self.lo + u * (self.hi - self.lo)
            out.append(int(round(v)) if self.integer else float(v))
        return out


@dataclass
class Spec:
    path: Path
    name: str
    scenarios: list[Path]
    fixed: list[tuple[str, Value]] = field(default_factory=list)
    steps: int | None = None
    group: int = 0
    genes: list[Gene] = field(default_factory=list)
    fitness: str = ""
    maximise: bool = True
    trials: int = 1
    seed: int = 1
    fixed_seeds: bool = False
    algorithm: str = "cmaes"
    settings: dict[str, Any] = field(default_factory=dict)
    generations: int = 1
    max_evaluations: int = 0
    sha256: str = ""
    lines: dict[str, int] = field(default_factory=dict)   # the file's line of each key path read

    @property
    def dimension(self) -> int:
        return sum(g.size for g in self.genes)

    def key_path(self, gene: Gene) -> str:
        return f"robots.{self.group}.params.{gene.key}"

    def decode(self, x: list[float]) -> dict[str, Value]:
        """The genome's --set values, by key path."""
        out: dict[str, Value] = {}
        i = 0
        for g in self.genes:
            vals = g.values(list(x[i:i + g.size]))
            i += g.size
            out[self.key_path(g)] = vals[0] if g.size == 1 else tuple(vals)
        return out

    def params(self, x: list[float]) -> dict[str, Any]:
        """The genome as the group's params mapping (key: value or list)."""
        return {g.key: (v if not isinstance(v, tuple) else list(v))
                for g, v in zip(self.genes, self.decode(x).values(), strict=True)}

    def decode_params(self, params: dict[str, Any]) -> dict[str, Value]:
        """A params mapping (best_params.yaml's) as --set values, by key path."""
        return {self.key_path(g): (tuple(params[g.key]) if isinstance(params[g.key], list) else params[g.key])
                for g in self.genes}

    def trial_seeds(self, generation: int) -> list[int]:
        base = self.seed * 1_000_003 % 1_000_000_007
        g = 0 if self.fixed_seeds else generation
        return [1 + (base + g * self.trials + k) % SEED_MAX for k in range(self.trials)]


def load(path: str | Path) -> Spec:
    """Read and check an evolution file (EvolveError naming FILE:LINE)."""
    try:
        return _load(Path(path))
    except EvolveError:
        raise
    except SweepError as e:        # the sweep reader's own messages, with their lines
        raise EvolveError(str(e)) from None


def _load(path: Path) -> Spec:
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise EvolveError(f"{path}: no such evolution file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise EvolveError(f"{path}: cannot read: {e}") from None
    try:
        root = yaml.compose(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        line = f":{mark.line + 1}" if mark is not None else ""
        raise EvolveError(f"{path}{line}: YAML syntax error: {getattr(e, 'problem', e)}") from None
    except RecursionError:
        raise EvolveError(f"{path}: nested too deeply to be an evolution file") from None
    if root is None:
        raise EvolveError(f"{path}: empty evolution file")
    r = _Reader(path)
    have: dict[str, tuple[yaml.Node, yaml.Node]] = {}
    for key, knode, vnode in r.mapping(root, ""):
        if key not in TOP_KEYS:
            best = difflib.get_close_matches(key, TOP_KEYS, n=1)
            hint = f" (did you mean '{best[0]}'?)" if best else f" (valid: {', '.join(TOP_KEYS)})"
            raise _err(r.fail(knode, key, f"unknown key '{key}'{hint}"))
        have[key] = (knode, vnode)
    for need in ("scenarios", "genome", "fitness", "generations"):
        if need not in have:
            raise _err(r.fail(root, need, "missing"))
    sp = Spec(path=path, name=path.stem, scenarios=[], sha256=hashlib.sha256(text.encode()).hexdigest())
    sp.lines = {k: _line(v) for k, (_, v) in have.items()}
    if "name" in have:
        sp.name = str(r.scalar(have["name"][1], "name"))
        if not NAME_RE.fullmatch(sp.name) or sp.name in (".", ".."):
            raise _err(r.fail(have["name"][1], "name", "use 1 to 64 letters, digits, '_', '.' or '-'"))
    for i, node in enumerate(r.sequence(have["scenarios"][1], "scenarios")):
        v = r.scalar(node, f"scenarios[{i}]")
        p = resolve_scenario(path, str(v)) if isinstance(v, str) else None
        if p is None or not p.is_file():
            raise _err(r.fail(node, f"scenarios[{i}]", f"no such scenario file: {p or v}"))
        sp.scenarios.append(p)
        sp.lines[f"scenarios[{i}]"] = _line(node)
    if "set" in have:
        for key, knode, vnode in r.mapping(have["set"][1], "set"):
            sp.fixed.append((r.set_key(knode, "set"), r.value(vnode, f"set.{key}")))
            sp.lines[f"set.{sp.fixed[-1][0]}"] = _line(knode)
    if "steps" in have:
        sp.steps = r.integer(have["steps"][1], "steps", 1, 10_000_000_000)
    _genome(r, have["genome"][1], sp)
    from swarmtools.evolve.fitness import Fitness, FitnessError
    fnode = have["fitness"][1]
    ftext = r.scalar(fnode, "fitness")
    try:
        Fitness(str(ftext))
    except FitnessError as e:
        raise _err(r.fail(fnode, "fitness", str(e))) from None
    sp.fitness = str(ftext)
    if "goal" in have:
        g = r.scalar(have["goal"][1], "goal")
        if g not in ("maximise", "minimise"):
            raise _err(r.fail(have["goal"][1], "goal", f"expected maximise or minimise, got '{g}'"))
        sp.maximise = g == "maximise"
    if "trials" in have:
        sp.trials = r.integer(have["trials"][1], "trials", 1, 100_000)
    if "seed" in have:
        sp.seed = r.integer(have["seed"][1], "seed", 0, SEED_MAX)
    if "trial_seeds" in have:
        v = r.scalar(have["trial_seeds"][1], "trial_seeds")
        if v not in ("per_generation", "fixed"):
            raise _err(r.fail(have["trial_seeds"][1], "trial_seeds", f"expected per_generation or fixed, got '{v}'"))
        sp.fixed_seeds = v == "fixed"
    if "algorithm" in have:
        _algorithm(r, have["algorithm"][1], sp)
    else:
        sp.settings = dict(DEFAULTS["cmaes"])
    sp.generations = r.integer(have["generations"][1], "generations", 1, 10_000_000)
    if "max_evaluations" in have:
        sp.max_evaluations = r.integer(have["max_evaluations"][1], "max_evaluations", 0, 10**12)
    if sp.algorithm == "ga" and sp.settings["elite"] > sp.settings["population"]:
        raise _err(r.fail(have["algorithm"][1], "algorithm.elite",
                          f"{sp.settings['elite']} is more than the population ({sp.settings['population']})"))
    return sp


def _err(e: SweepError) -> EvolveError:
    return EvolveError(str(e))


def _line(node: yaml.Node) -> int:
    return node.start_mark.line + 1


def _genome(r: _Reader, node: yaml.Node, sp: Spec) -> None:
    fields = {k: (kn, v) for k, kn, v in r.mapping(node, "genome")}
    for k, (kn, _) in fields.items():
        if k not in ("group", "params"):
            raise _err(r.fail(kn, f"genome.{k}", f"unknown key '{k}' (valid: group, params)"))
    if "params" not in fields:
        raise _err(r.fail(node, "genome.params", "missing: the params that are the genome"))
    if "group" in fields:
        g = r.scalar(fields["group"][1], "genome.group")
        sp.lines["genome.group"] = _line(fields["group"][1])
        sp.group = _group_index(r, fields["group"][1], g, sp.scenarios)
    seen: dict[str, int] = {}
    for i, item in enumerate(r.sequence(fields["params"][1], "genome.params")):
        where = f"genome.params[{i}]"
        f = {k: (kn, v) for k, kn, v in r.mapping(item, where)}
        for k, (kn, _) in f.items():
            if k not in ("key", "size", "range", "integer"):
                raise _err(r.fail(kn, f"{where}.{k}", f"unknown key '{k}' (valid: key, size, range, integer)"))
        for need in ("key", "range"):
            if need not in f:
                raise _err(r.fail(item, f"{where}.{need}", "missing"))
        key = r.scalar(f["key"][1], f"{where}.key")
        if not isinstance(key, str) or not key.replace("_", "a").isalnum() or not key[0].isalpha():
            raise _err(r.fail(f["key"][1], f"{where}.key", f"'{key}' is not a params key"))
        if key in seen:
            raise _err(r.fail(f["key"][1], f"{where}.key", f"'{key}' listed twice (first in genome.params[{seen[key]}])"))
        seen[key] = i
        size = r.integer(f["size"][1], f"{where}.size", 1, MAX_GENES) if "size" in f else 1
        rng = r.sequence(f["range"][1], f"{where}.range")
        if len(rng) != 2:
            raise _err(r.fail(f["range"][1], f"{where}.range", "expected [low, high]"))
        lo, hi = (r.scalar(n, f"{where}.range") for n in rng)
        if any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in (lo, hi)) or not lo < hi:
            raise _err(r.fail(f["range"][1], f"{where}.range", "expected two numbers, low < high"))
        integer = False
        if "integer" in f:
            integer = r.scalar(f["integer"][1], f"{where}.integer")
            if not isinstance(integer, bool):
                raise _err(r.fail(f["integer"][1], f"{where}.integer", "expected true or false"))
        sp.genes.append(Gene(str(key), size, float(lo), float(hi), integer))
        sp.lines[where] = _line(item)
        sp.lines.update({f"{where}.{k}": _line(v) for k, (_, v) in f.items()})
    if sp.dimension > MAX_GENES:
        raise _err(r.fail(fields["params"][1], "genome.params", f"{sp.dimension} genes: at most {MAX_GENES}"))


def _group_index(r: _Reader, node: yaml.Node, g: object, scenarios: list[Path]) -> int:
    """A group named in every scenario at the same index, or an index."""
    if isinstance(g, int) and not isinstance(g, bool):
        if not 0 <= g < 10_000:
            raise _err(r.fail(node, "genome.group", f"{g} is not a group index"))
        return g
    found: set[int] = set()
    for s in scenarios:
        try:
            doc = yaml.safe_load(s.read_text()) or {}
            names = [grp.get("name") for grp in doc.get("robots", [])]
        except (OSError, yaml.YAMLError, AttributeError, TypeError):
            raise _err(r.fail(node, "genome.group", f"cannot read the groups of {s}")) from None
        if g not in names:
            raise _err(r.fail(node, "genome.group", f"{s.name} has no group named '{g}' (its groups: "
                                                    f"{', '.join(str(n) for n in names)})"))
        found.add(names.index(g))
    if len(found) != 1:
        raise _err(r.fail(node, "genome.group", f"group '{g}' is at different indices in the scenarios"))
    return found.pop()


def _algorithm(r: _Reader, node: yaml.Node, sp: Spec) -> None:
    fields = {k: (kn, v) for k, kn, v in r.mapping(node, "algorithm")}
    if "name" not in fields:
        raise _err(r.fail(node, "algorithm.name", f"missing: one of {', '.join(ALGORITHMS)}"))
    name = r.scalar(fields["name"][1], "algorithm.name")
    if name not in ALGORITHMS:
        raise _err(r.fail(fields["name"][1], "algorithm.name", f"unknown algorithm '{name}' (valid: "
                                                                f"{', '.join(ALGORITHMS)})"))
    sp.algorithm = str(name)
    sp.settings = dict(DEFAULTS[sp.algorithm])
    for k, (kn, v) in fields.items():
        if k == "name":
            continue
        if k not in ALGORITHMS[sp.algorithm]:
            raise _err(r.fail(kn, f"algorithm.{k}", f"unknown setting '{k}' of {sp.algorithm} (valid: "
                                                    f"{', '.join(ALGORITHMS[sp.algorithm])})"))
        kind, lo, hi = ALGORITHMS[sp.algorithm][k]
        if kind is int:
            sp.settings[k] = r.integer(v, f"algorithm.{k}", lo, hi)
        else:
            x = r.scalar(v, f"algorithm.{k}")
            if isinstance(x, bool) or not isinstance(x, (int, float)) or not lo <= x <= hi:
                raise _err(r.fail(v, f"algorithm.{k}", f"expected a number in [{lo:g}, {hi:g}], got '{v.value}'"))
            sp.settings[k] = float(x)


# ------------------------------------------------------------------ against the simulator
def set_args(pairs) -> list[str]:
    """swarmsim's `--set KEY=VALUE` arguments of (key, value) pairs."""
    return [a for k, v in pairs for a in ("--set", f"{k}={set_text(v)}")]


def check_with_simulator(sp: Spec, sim: Path) -> None:
    """What only the simulator knows, checked before anything runs or is
    written: each scenario loads with the `set:` overrides, and with the
    genome at both ends of its ranges and at a point between (which an
    integer key refuses when `integer: true` is missing): the controller's
    own descriptors judge the keys, sizes and ranges.  A one-step run of each
    scenario lists the metrics its runs report, which the fitness must read.
    Each refusal is an EvolveError naming the evolution file's line."""
    from swarmtools.evolve.fitness import Fitness
    fixed = set_args(sp.fixed)
    for i, scenario in enumerate(sp.scenarios):
        def check(*args: str, scenario: Path = scenario, i: int = i) -> None:
            p = _simulate(sim, [str(scenario), "--check", "--quiet", *fixed, *args])
            if p.returncode != 0:
                raise _blame(sp, i, _last_line(p))
        check()
        for x in (0.0, 1.0, 0.37):    # 0.37: no range's end, and not a whole number of most ranges
            check(*set_args(sp.decode([x] * sp.dimension).items()))
        with tempfile.TemporaryDirectory(prefix="swarm-evolve-check.") as tmp:
            p = _simulate(sim, [str(scenario), "--steps", "1", "--lcm", "off", "--quiet", "--out", f"{tmp}/o", *fixed])
            if p.returncode != 0:
                raise _blame(sp, i, _last_line(p))
            try:
                summary = next(Path(tmp, "o").glob("run_*/summary.json"))
                metrics = sorted(json.loads(summary.read_text())["metrics"])
            except (StopIteration, OSError, ValueError, KeyError, TypeError):
                raise EvolveError(f"{sim}: a one-step run of {scenario} wrote no readable summary.json "
                                  "(is it swarmsim?)") from None
        for name in Fitness(sp.fitness).names:
            if name not in metrics:
                best = difflib.get_close_matches(name, metrics, n=1)
                hint = f"did you mean '{best[0]}'? " if best else ""
                raise EvolveError(f"{sp.path}:{sp.lines['fitness']}: fitness: {scenario.name}'s runs report no metric "
                                  f"'{name}' ({hint}they report: {', '.join(metrics)})")


def _simulate(sim: Path, args: list[str]) -> subprocess.CompletedProcess:
    try:
        return subprocess.run([str(sim), *args], capture_output=True, text=True, timeout=120, check=False)
    except OSError as e:
        raise EvolveError(f"{sim}: cannot run the simulator: {e.strerror or e}") from None
    except subprocess.TimeoutExpired:
        raise EvolveError(f"{sim}: the simulator did not load {args[0]} within 120 s") from None


def _last_line(p: subprocess.CompletedProcess) -> str:
    lines = p.stderr.strip().splitlines()
    return lines[-1] if lines else f"exit status {p.returncode}"


def _blame(sp: Spec, scenario: int, msg: str) -> EvolveError:
    """The simulator's refusal as an error at the line of the evolution
    file's key that caused it: its --set key is a gene's or a `set:` one;
    otherwise the scenario itself is at fault."""
    name = sp.scenarios[scenario].name
    m = re.match(r"swarmsim: --set ([^=\s]+)=.*?: (robots\[.*|[a-z_][\w.\[\]]*: .*)$", msg)
    if m is None:                       # not an override's fault: the scenario's (or the simulator's)
        return EvolveError(f"{sp.path}:{sp.lines[f'scenarios[{scenario}]']}: scenarios[{scenario}]: {msg}")
    key, reason = m.group(1), m.group(2)
    if f"set.{key}" in sp.lines:
        return EvolveError(f"{sp.path}:{sp.lines[f'set.{key}']}: set.{key}: {name} refuses it: {reason}")
    genes = {sp.key_path(g): i for i, g in enumerate(sp.genes)}
    if key not in genes:
        return EvolveError(f"{sp.path}:{sp.lines['genome']}: genome: {name} refuses it: {reason}")
    i, g = genes[key], sp.genes[genes[key]]
    where = f"genome.params[{i}]"
    if reason.startswith(f"robots[{sp.group}]:"):        # no such group: the index is wrong
        field, what = "genome.group", f"{name} has no group {sp.group}"
    elif "unknown key" in reason:
        field, what = f"{where}.key", f"'{g.key}' is not a param of the group's controller in {name}"
    elif "out of range" in reason:
        field, what = f"{where}.range", f"[{g.lo:g}, {g.hi:g}] goes beyond what {name}'s controller takes"
    elif "expected an integer" in reason and not g.integer:
        field, what = f"{where}.integer", f"'{g.key}' holds integers: add `integer: true`"
    elif "exactly" in reason or "sequence" in reason:
        field, what = f"{where}.size", f"size {g.size} is not the length of '{g.key}' in {name}"
    else:
        field, what = f"{where}.key", f"{name} refuses '{g.key}'"
    line = sp.lines.get(field) or sp.lines.get(where) or sp.lines["genome"]
    return EvolveError(f"{sp.path}:{line}: {field}: {what} (swarmsim: {reason})")
