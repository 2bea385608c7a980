"""`python -m pyramid_sim.cli`: the same as `pyramid-sim`."""

import sys

from . import main

sys.exit(main())
