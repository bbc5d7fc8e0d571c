"""What each study costs, and what its --quick smoke run is: facts written
once, printed by each study before it starts and shown on the site's
Studies page (docs/studies/index.md, generated from COSTS).

A full study's core-hours and wall time are measurements: the simulator's
CPU time summed over its runs, and the wall time of the whole command on
the 2-core machine of the benchmarks (docs/development/benchmarks.md),
while other work shared it where `shared` says so.  Its number of runs is
counted from its sweep files when it starts (`runs` here is what the
measurement ran)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Cost:
    """A full study as measured."""
    study: str              # what it is, as the Studies page names it
    command: str            # how to run it
    runs: int
    core_hours: float
    wall: str               # wall time on 2 cores
    note: str = ""          # how the wall time was taken ("shared": other work ran)


@dataclass(frozen=True)
class Quick:
    """A --quick smoke run: at most `seeds` seeds a cell and every run cut at
    `steps` control steps (the run length, not only the seeds, so that the
    slowest cell is bounded too)."""
    seeds: int
    steps: int
    note: str = ""          # what else it narrows


#: Each study's --quick: under a minute on 2 cores, into out/<study>_quick/.
QUICK: dict[str, Quick] = {
    "drtm": Quick(2, 1000),
    "faults": Quick(2, 1000),
    "repatt": Quick(1, 800, "ALNS plans of 500 iterations (with --figures alns)"),
    "gains": Quick(1, 800, "8 of the 900 combinations screened, 3 confirmed on 1 more seed, 2 raced on 2 seeds"),
    "eaipp": Quick(1, 600),
}

COSTS: dict[str, Cost] = {
    "drtm": Cost("seed 000 (DRTM), with the speed rows", "make study-drtm", 1600, 0.193, "6 min 1 s", "shared"),
    "faults": Cost("seed 000 under faults", "make study-faults", 100, 0.009, "26 s", "shared"),
    "example": Cost("the example sweep", "make sweep SWEEP=studies/example_swarm_size.yaml", 100, 0.013, "25 s"),
    "repatt": Cost("seed 002 (RepAtt): worlds, slotted, scale", "make study-repatt", 3180, 1.94, "58 min", "shared"),
    "alns": Cost("seed 002, ALNS: 5 plans, then the routes", 'make study-repatt STUDY_ARGS="--figures worlds,alns"',
                 300, 0.02, "27 min", "shared; plus the plans, 97 s each on a quiet core"),
    "gains": Cost("seed 002's gains, reduced: screen, confirm, race", "make study-gains", 3000, 3.5, "100 min",
                  "shared"),
    "gains_full": Cost("seed 002's full gains sweep (measured from 150 runs)",
                       ".venv/bin/swarm-sweep run studies/repatt_gains.yaml --backend slurm", 540000, 150.0,
                       "(a cluster)"),
    "eaipp": Cost("seed 003 (EAIPP): eight sweeps, with NNEA's rows", "make study-eaipp", 10500, 1.18, "36 min", "shared"),
}
