import sys

from swarmtools.live.server import main

sys.exit(main())
