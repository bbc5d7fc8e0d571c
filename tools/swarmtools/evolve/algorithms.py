"""The search: CMA-ES (the `cma` package) or a genetic algorithm of the kind
Sperati et al. ran (DEAP's operators: truncation selection of the elite, each
parent copied into population / elite offspring, all but the first mutated
by Gaussian noise), both over the unit cube of the genome's ranges.

Each is deterministic given the evolution's seed and the generation: the
randomness of generation g comes from a generator seeded with (seed, g), so
a resumed evolution replays the finished generations (asking the same
genomes, telling the recorded fitnesses) and goes on exactly as an
uninterrupted one.  Both maximise: CMA-ES is told the negated fitness.
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np


def _rng(seed: int, generation: int) -> np.random.Generator:
    return np.random.default_rng([seed, generation, 0x5EED])


class _Normal:
    """cma's `randn` option: normal draws from the generation's generator."""

    def __init__(self) -> None:
        self.gen = np.random.default_rng(0)

    def __call__(self, *shape: int) -> np.ndarray:
        return self.gen.standard_normal(shape)


class CMAES:
    def __init__(self, dimension: int, settings: dict[str, Any], seed: int):
        import cma

        self.seed = seed
        self.normal = _Normal()
        opts = {"bounds": [0.0, 1.0], "popsize": int(settings["population"]), "seed": np.nan,
                "randn": self.normal, "verbose": -9, "verb_log": 0, "verb_disp": 0, "CMA_diagonal": False,
                "tolfun": 0, "tolflatfitness": 10**9, "tolstagnation": 10**9, "tolx": 0}
        self.es = cma.CMAEvolutionStrategy(np.full(dimension, 0.5), float(settings["sigma"]), opts)

    def ask(self, generation: int) -> list[list[float]]:
        self.normal.gen = _rng(self.seed, generation)
        return [list(map(float, x)) for x in self.es.ask()]

    def tell(self, genomes: list[list[float]], fitness: list[float]) -> None:
        self.es.tell([np.array(g) for g in genomes], [-f for f in fitness])


class GA:
    def __init__(self, dimension: int, settings: dict[str, Any], seed: int):
        self.seed = seed
        self.n = dimension
        self.size = int(settings["population"])
        self.elite = int(settings["elite"])
        self.sd = float(settings["mutation_sd"])
        self.rate = float(settings["mutation_rate"])
        self.pop: list[list[float]] | None = None

    def ask(self, generation: int) -> list[list[float]]:
        from deap import tools

        r = random.Random(int(_rng(self.seed, generation).integers(2**62)))
        state = random.getstate()          # DEAP's operators draw from the module `random`
        random.seed(r.random())
        try:
            if self.pop is None:           # generation 0: uniform over the cube
                return [[random.random() for _ in range(self.n)] for _ in range(self.size)]
            out: list[list[float]] = []
            per = -(-self.size // self.elite)
            for parent in self.pop[: self.elite]:
                for c in range(per):
                    if len(out) == self.size:
                        break
                    child = list(parent)
                    if c > 0:
                        (child,) = tools.mutGaussian(child, mu=0.0, sigma=self.sd, indpb=self.rate)
                    out.append([min(1.0, max(0.0, v)) for v in child])
            return out
        finally:
            random.setstate(state)

    def tell(self, genomes: list[list[float]], fitness: list[float]) -> None:
        from deap import base, creator, tools

        if not hasattr(creator, "SwarmEvolveFitness"):
            creator.create("SwarmEvolveFitness", base.Fitness, weights=(1.0,))
            creator.create("SwarmEvolveGenome", list, fitness=creator.SwarmEvolveFitness)
        inds = []
        for g, f in zip(genomes, fitness, strict=True):
            ind = creator.SwarmEvolveGenome(g)
            ind.fitness.values = (f,)
            inds.append(ind)
        # selBest is stable: among equal fitnesses the earlier genome comes first.
        self.pop = [list(i) for i in tools.selBest(inds, self.elite)]


def make(name: str, dimension: int, settings: dict[str, Any], seed: int) -> CMAES | GA:
    return {"cmaes": CMAES, "ga": GA}[name](dimension, settings, seed)
