#!/usr/bin/env python3
"""Render a whole build to MP4 headless (EGL, else OSMesa): `pyramid-sim build --video` with
a default path. Any `pyramid-sim build` option may follow, e.g. --camera front --shadows."""

import sys

from pyramid_sim.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--video" not in args:
        args += ["--video", "runs/pyramid/build.mp4"]
    if "--out" not in args:
        args += ["--out", "runs/pyramid"]
    sys.exit(main(["build", *args]))
