#!/usr/bin/env python3
"""Parameter sweep: `pyramid-sim sweep` with the same options, e.g.

python3 scripts/sweep.py --friction 0.3:1.5:5 --brick-mass 0.2:1.5:5 --workers 2 --out runs/sweep
"""

import sys

from pyramid_sim.cli import main

if __name__ == "__main__":
    sys.exit(main(["sweep", *sys.argv[1:]]))
