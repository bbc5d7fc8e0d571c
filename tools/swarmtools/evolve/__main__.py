import sys

from swarmtools.evolve.cli import main

sys.exit(main())
