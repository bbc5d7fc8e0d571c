"""swarm-evolve: evolve a controller's parameters, each generation's runs
through the sweep engine (here on local cores, or as SLURM job arrays).

    swarm-evolve EVOLVE.yaml [--out DIR] [--jobs N] [--backend local|slurm ...]
                 [--sim PATH] [--stop-after N] [--quiet]

The file (spec.py) names the scenario(s), the genome (a group's params with
their ranges), the fitness (fitness.py), the trials, the algorithm and the
budget; before anything runs or is written the simulator checks the genome
against the controller's keys and the fitness against the runs' metrics.
DIR (default out/evolve/<name>) gets, after every generation, all of them
written whole (atomically):

  checkpoint.pkl       the finished generations' genomes and fitnesses: a
                       rerun of the same command resumes after the last one
                       (the search replays them: deterministic given the seed)
  generations.csv      per generation: best, mean, sd, worst fitness, the
  generations.parquet  runs so far, the best so far and the generation's best
                       genome (JSON)
  evaluations.csv      every genome of every generation with its fitness
  fitness.png          best, mean +- sd and best-so-far over the generations
  best_params.yaml     the best genome so far as the group's `params:` mapping
  best_params.h        the same as C initialisers (PREFIX_KEY { ... }) for an
                       image's defaults (firmware/nnea/nnea_evolved.h is one)
  best_scenario.yaml   the first scenario with the best genome written in: a
                       scenario file that runs it; its header names the seeds
                       and --steps that measured the fitness
  evals/               the sweep folder of every run (records, frozen simulator)

A generation's runs are one sweep (its unique genomes x scenarios x trial
seeds); an interrupted generation resumes with its finished runs kept.  One
progress line per generation on stderr.

Exit status: 0 the budget is spent (or --stop-after reached); 1 a run failed
or a fitness could not be computed; 2 a bad file or argument; 130
interrupted (rerun to resume).
"""

from __future__ import annotations

import argparse
import json
import math
import pickle
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from swarmtools.evolve import algorithms
from swarmtools.evolve.fitness import Fitness, FitnessError
from swarmtools.evolve.spec import EvolveError, Spec, check_with_simulator, load, set_args
from swarmtools.sweep import cli as sweep_cli
from swarmtools.sweep import plan as planmod
from swarmtools.sweep.plan import file_sha256
from swarmtools.sweep.spec import SCENARIO_KEY, Axis, Sweep, SweepError, set_text
from swarmtools.sweep.store import Store, atomic_write

REPO_ROOT = Path(__file__).resolve().parents[3]
FORMAT = 1
TAG = "swarm-evolve"


# ------------------------------------------------------------------ the runs
def generation_sweep(sp: Spec, genomes: list[dict[str, Any]], generation: int) -> Sweep:
    """The sweep of one generation: its unique genomes (a list axis) x the
    scenarios x the generation's trial seeds."""
    keys = list(genomes[0])
    axes = [Axis("list", keys, genomes, 0)]
    if len(sp.scenarios) > 1:
        axes.insert(0, Axis("list", [SCENARIO_KEY], [{SCENARIO_KEY: str(s)} for s in sp.scenarios], 0))
    return Sweep(path=sp.path, name=f"{sp.name}_gen{generation:05d}", scenario=sp.scenarios[0],
                 fixed=list(sp.fixed), steps=sp.steps, axes=axes, seeds=sp.trial_seeds(generation),
                 metrics=None, max_attempts=1, run_timeout=0.0, keep_timeseries=False)


def evaluate(sp: Spec, fit: Fitness, X: list[list[float]], generation: int, a: argparse.Namespace,
             sim: Path, out: Path) -> tuple[list[float], int]:
    """Every genome's fitness (the mean over scenarios and trials) and the
    runs made.  Raises Interrupted-like exits as EvolveError with a code."""
    decoded = [sp.decode(x) for x in X]
    unique: list[dict[str, Any]] = []
    index: dict[str, int] = {}
    for d in decoded:
        k = json.dumps({key: set_text(v) for key, v in d.items()}, sort_keys=True)
        if k not in index:
            index[k] = len(unique)
            unique.append(d)
    sw = generation_sweep(sp, unique, generation)
    ns = argparse.Namespace(**{**vars(a), "out": str(out / "evals"), "quiet": True})
    rc = sweep_cli.run_sweep(sw, ns, sim)
    if rc in (130, 143):
        raise Stop(rc, f"interrupted in generation {generation}: its finished runs are kept; "
                       "rerun the same command to resume")
    store = Store(out / "evals")
    runs = planmod.expand(sw)
    sums = [0.0] * len(unique)
    counts = [0] * len(unique)
    for r in runs:
        rec = store.record(r.run_id)
        if rec is None or rec.get("status") != "ok":
            err = (rec or {}).get("error", "not run")
            raise Stop(1, f"generation {generation}: run {r.run_id} (seed {r.seed}) failed: {err}; its record is "
                          f"in {store.records}/ (rerun to retry)")
        k = json.dumps({key: set_text(v) for key, v in r.params.items() if key != SCENARIO_KEY}, sort_keys=True)
        try:
            f = fit(rec.get("metrics", {}))
        except FitnessError as e:
            raise Stop(1, f"{sp.path}: fitness: {e}") from None
        if not math.isfinite(f):
            raise Stop(1, f"{sp.path}: fitness: {f} for run {r.run_id} (seed {r.seed}): not a finite number")
        sums[index[k]] += f
        counts[index[k]] += 1
    per_unique = [s / c for s, c in zip(sums, counts, strict=True)]
    mean = [per_unique[index[json.dumps({key: set_text(v) for key, v in d.items()}, sort_keys=True)]]
            for d in decoded]
    return mean, len(runs)


class Stop(Exception):
    def __init__(self, code: int, message: str):
        super().__init__(message)
        self.code = code


# ------------------------------------------------------------------ the state
def identity(sp: Spec) -> dict[str, Any]:
    """What a checkpoint must agree with to be resumed: everything but the
    budget (which a rerun may raise to go on)."""
    return {"format": FORMAT, "scenarios": [file_sha256(s) for s in sp.scenarios],
            "set": [[k, set_text(v)] for k, v in sp.fixed], "steps": sp.steps, "group": sp.group,
            "genes": [[g.key, g.size, g.lo, g.hi, g.integer] for g in sp.genes], "fitness": sp.fitness,
            "maximise": sp.maximise, "trials": sp.trials, "seed": sp.seed, "fixed_seeds": sp.fixed_seeds,
            "algorithm": sp.algorithm, "settings": sp.settings}


def read_checkpoint(path: Path, sp: Spec) -> list[dict[str, Any]]:
    if not path.exists():
        return []
    try:
        state = pickle.loads(path.read_bytes())
    except Exception as e:   # a checkpoint is only ever written whole; anything else is not ours
        raise EvolveError(f"{path}: not a readable checkpoint ({type(e).__name__}); give a new --out") from None
    if not isinstance(state, dict) or state.get("identity") != identity(sp):
        raise EvolveError(f"{path}: made by another evolution (its scenarios, genome, fitness, trials, seed or "
                          "algorithm differ; only the budget may change): give a new --out")
    return list(state["history"])


def write_checkpoint(path: Path, sp: Spec, history: list[dict[str, Any]]) -> None:
    # pickle shares objects by identity (a string met twice is written once),
    # so the same content pickles to other bytes when a resumed run's history
    # holds the unpickled strings beside fresh ones.  Rebuilt through JSON
    # (exact for floats; dict keys shared by json's memo) the sharing, and so
    # the bytes, depend on the content alone: a resumed evolution writes the
    # uninterrupted one's checkpoint byte for byte.
    state = json.loads(json.dumps({"identity": identity(sp), "history": history}))
    atomic_write(path, pickle.dumps(state, protocol=4))


# ------------------------------------------------------------------ outputs
def _sd(v: list[float]) -> float:
    m = sum(v) / len(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else 0.0


def write_outputs(sp: Spec, history: list[dict[str, Any]], out: Path, sim: Path) -> dict[str, Any]:
    import pandas as pd

    sign = 1.0 if sp.maximise else -1.0
    rows, evals = [], []
    best_ever, best_x, best_gen, runs = -math.inf, None, -1, 0
    for h in history:
        f = [sign * v for v in h["fitness"]]     # in the goal's own sense
        scored = [v * sign for v in f]           # larger is better
        i = max(range(len(scored)), key=lambda j: (scored[j], -j))
        runs += h["runs"]
        if scored[i] > best_ever:
            best_ever, best_x, best_gen = scored[i], h["genomes"][i], h["generation"]
        rows.append({"generation": h["generation"], "runs": runs, "best": f[i],
                     "mean": sum(f) / len(f), "sd": _sd(f), "worst": f[min(range(len(scored)), key=scored.__getitem__)],
                     "best_so_far": sign * best_ever, "genome": json.dumps(sp.params(h["genomes"][i]))})
        for j, (x, v) in enumerate(zip(h["genomes"], f, strict=True)):
            evals.append({"generation": h["generation"], "index": j, "fitness": v, "genome": json.dumps(sp.params(x))})
    df = pd.DataFrame(rows)
    atomic_write(out / "generations.csv", df.to_csv(index=False))
    _parquet(df, out / "generations.parquet")
    atomic_write(out / "evaluations.csv", pd.DataFrame(evals).to_csv(index=False))
    _plot(sp, df, out / "fitness.png")
    best = {"generation": best_gen, "fitness": sign * best_ever, "params": sp.params(best_x)}
    _best_files(sp, best, out, sim)
    return best


def _parquet(df: Any, path: Path) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    import os
    os.close(fd)
    try:
        df.to_parquet(tmp, engine="pyarrow", index=False)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _plot(sp: Spec, df: Any, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110)
    g = df["generation"]
    ax.fill_between(g, df["mean"] - df["sd"], df["mean"] + df["sd"], color="tab:blue", alpha=0.2, lw=0,
                    label="mean ± sd")
    ax.plot(g, df["mean"], color="tab:blue", lw=1)
    ax.plot(g, df["best"], color="tab:red", lw=1, marker=".", label="generation's best")
    ax.plot(g, df["best_so_far"], color="k", lw=1, ls="--", label="best so far")
    ax.set_xlabel("generation")
    ax.set_ylabel(f"fitness ({'max' if sp.maximise else 'min'}imised)")
    ax.set_title(f"{sp.name}: {sp.fitness}", fontsize=9)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fd, tmp = tempfile.mkstemp(prefix=".fitness.", suffix=".png", dir=path.parent)
    import os
    os.close(fd)
    try:
        fig.savefig(tmp, metadata={"Software": None})
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        Path(tmp).unlink(missing_ok=True)


def _best_files(sp: Spec, best: dict[str, Any], out: Path, sim: Path) -> None:
    head = (f"# {TAG} {sp.name}: the best genome so far (generation {best['generation']}, fitness "
            f"{best['fitness']!r}: {sp.fitness}), the params of robots[{sp.group}]")
    lines = [head, "params:"]
    for k, v in best["params"].items():
        lines.append(f"  {k}: {json.dumps(v)}")
    atomic_write(out / "best_params.yaml", "\n".join(lines) + "\n")
    ctrl = _controller_of(sp)
    prefix = f"{ctrl.upper()}_EVOLVED"
    guard = f"{prefix}_GENOME_H"
    c = ["/*", f" * {TAG} {sp.name}: the best genome (generation {best['generation']}, fitness {best['fitness']!r}),",
         f" * the defaults of {ctrl}'s genome keys as C initialisers.  Generated: do not edit.", " */",
         f"#ifndef {guard}", f"#define {guard}", ""]
    for k, v in best["params"].items():
        text = f"{{ {', '.join(str(x) for x in v)} }}" if isinstance(v, list) else str(v)
        c.append(f"#define {prefix}_{k.upper()} {text}")
    c += ["", "#endif"]
    atomic_write(out / "best_params.h", "\n".join(c) + "\n")
    # A scenario that runs the genome: the simulator's own effective scenario.
    with tempfile.TemporaryDirectory(prefix=".best.", dir=out) as tmp:
        cmd = [str(sim), str(sp.scenarios[0]), "--steps", "1", "--lcm", "off", "--quiet", "--out", tmp, "--replace",
               *set_args([*sp.fixed, *sp.decode_params(best["params"]).items()])]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)
        copies = sorted(Path(tmp).glob("run_*/scenario.yaml"))
        if p.returncode != 0 or not copies:
            raise Stop(1, f"writing best_scenario.yaml: {p.stderr.strip() or 'no scenario copy'}")
        atomic_write(out / "best_scenario.yaml", f"{head}\n{_measured(sp, best)}\n" + copies[0].read_text())


def _measured(sp: Spec, best: dict[str, Any]) -> str:
    """The header line saying how to rerun what the fitness measured.  A
    scenario file cannot hold a step count (its `duration` is no substitute:
    tasks check their budgets against it, and faults draw their onsets over
    it), so the evolution's `steps:` is given as the --steps to pass."""
    seeds = sp.trial_seeds(best["generation"])
    steps = f" --steps {sp.steps}" if sp.steps is not None else ""
    length = f"{sp.steps}-step runs (the evolution's steps:; without --steps a run lasts the scenario's duration)" \
        if sp.steps is not None else "runs of the scenario's duration"
    return (f"# measured in {length}, the mean over seeds {', '.join(map(str, seeds))}"
            f"{' and the scenarios' if len(sp.scenarios) > 1 else ''}: "
            f"swarmsim best_scenario.yaml{steps} --seed {seeds[0]} reruns the first")


def _controller_of(sp: Spec) -> str:
    import yaml
    try:
        doc = yaml.safe_load(sp.scenarios[0].read_text())
        return str(doc["robots"][sp.group]["controller"])
    except (OSError, yaml.YAMLError, KeyError, IndexError, TypeError):
        return "genome"


# ------------------------------------------------------------------ main
def run(sp: Spec, a: argparse.Namespace) -> int:
    sim = Path(a.sim) if a.sim else sweep_cli.default_sim()
    out = Path(a.out) if a.out else REPO_ROOT / "out" / "evolve" / sp.name
    check_with_simulator(sp, sim)      # a bad genome or fitness found now, at its line, with nothing written
    out.mkdir(parents=True, exist_ok=True)
    marker = out / ".swarm-evolve"
    if any(p.name != marker.name for p in out.iterdir()) and not marker.exists():
        raise EvolveError(f"{out}: not empty and not an evolution's folder; give a new --out")
    marker.touch()
    fit = Fitness(sp.fitness)
    ckpt = out / "checkpoint.pkl"
    history = read_checkpoint(ckpt, sp)
    algo = algorithms.make(sp.algorithm, sp.dimension, sp.settings, sp.seed)
    sign = 1.0 if sp.maximise else -1.0
    for h in history:                  # replay: the search asks what it asked then
        X = algo.ask(h["generation"])
        if X != h["genomes"]:
            raise EvolveError(f"{ckpt}: generation {h['generation']} asks other genomes than it did (another "
                              "version of cma or DEAP?): give a new --out")
        algo.tell(X, h["fitness"])
    runs = sum(h["runs"] for h in history)
    done_now = 0
    if history and not a.quiet:
        print(f"{TAG}: {sp.name}: resuming after generation {history[-1]['generation']} ({runs} runs) in {out}",
              file=sys.stderr)
    t0 = time.monotonic()
    g = len(history)
    while g < sp.generations and (sp.max_evaluations == 0 or runs < sp.max_evaluations):
        if a.stop_after is not None and done_now >= a.stop_after:
            break
        X = algo.ask(g)
        f, n = evaluate(sp, fit, X, g, a, sim, out)
        scored = [sign * v for v in f]
        algo.tell(X, scored)
        history.append({"generation": g, "genomes": X, "fitness": scored, "runs": n})
        write_checkpoint(ckpt, sp, history)
        best = write_outputs(sp, history, out, sim)
        runs += n
        done_now += 1
        if not a.quiet:
            el = time.monotonic() - t0
            left = (sp.generations - g - 1) * el / done_now
            print(f"{TAG}: {sp.name}: generation {g} ({g + 1}/{sp.generations}): best "
                  f"{max(f) if sp.maximise else min(f):.6g}, mean {sum(f) / len(f):.6g}, sd {_sd(f):.3g}; best so "
                  f"far {best['fitness']:.6g} (generation {best['generation']}); {runs} runs; {el:.0f} s, about "
                  f"{left:.0f} s left",
                  file=sys.stderr)
        g += 1
    if not history:
        return 0
    if not a.quiet:
        print(f"{TAG}: {sp.name}: {len(history)} generations, {runs} runs; best genome: {out / 'best_params.yaml'}",
              file=sys.stderr)
    return 0


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog=TAG, description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file", help="the evolution file (YAML)")
    ap.add_argument("--out", help="the evolution's folder (default out/evolve/<name>)")
    ap.add_argument("--jobs", type=int, default=0, help="local: runs at a time (default 0: one per CPU)")
    ap.add_argument("--sim", help="simulator binary (default build/swarmsim)")
    ap.add_argument("--stop-after", type=int, help="stop after this many generations in this invocation "
                                                   "(a rerun resumes)")
    ap.add_argument("--quiet", action="store_true")
    sweep_cli.add_max_runs(ap)
    sweep_cli.add_backend_options(ap)
    return ap


def main(argv: Sequence[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        sweep_cli.check_args(a)
        if a.no_wait:
            raise EvolveError("--no-wait: an evolution needs each generation's results before the next")
        if a.stop_after is not None and a.stop_after < 1:
            raise EvolveError(f"--stop-after must be at least 1 (got {a.stop_after}): the generations to run "
                              "in this invocation")
        return run(load(a.file), a)
    except Stop as e:
        print(f"{TAG}: {e}", file=sys.stderr)
        return e.code
    except SweepError as e:
        print(f"{TAG}: {e}", file=sys.stderr)
        return e.exit_code
    except KeyboardInterrupt:
        print(f"{TAG}: interrupted; rerun the same command to resume", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
