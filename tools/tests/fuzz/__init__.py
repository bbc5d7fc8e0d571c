"""Property tests (hypothesis) of the host tools' parsers of untrusted input:
the flasher's .hex parser, the telemetry frame decoder, the LCM log reader
and the CSV export's file names, sweep files and run ids, and what the live
view takes from pages and telemetry.

Two profiles: "ci" (the default: 300 examples a property, derandomized, so
that `make test` is repeatable) and "long" (SWARM_HYPOTHESIS=long, random,
SWARM_HYPOTHESIS_EXAMPLES a property, 20,000 by default; `make fuzz` runs
it).  No example database is written into the tree.
"""
import os

from hypothesis import HealthCheck, settings

settings.register_profile("ci", max_examples=300, derandomize=True, deadline=None, database=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=int(os.environ.get("SWARM_HYPOTHESIS_EXAMPLES", "20000")),
                          deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("SWARM_HYPOTHESIS", "ci"))
