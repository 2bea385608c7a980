#!/usr/bin/env python3
"""Render a whole build to MP4 headless (EGL, else OSMesa): `pyramid-sim build --video` with
its own default folder, runs/render/, so it never writes over the README's main command's
video. Any `pyramid-sim build` option may follow, e.g. --camera front --shadows."""

import sys
from pathlib import Path

from pyramid_sim.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "runs/render"]
    if "--video" not in args:
        video = Path(args[args.index("--out") + 1]) / "build.mp4"
        args += ["--video", str(video)]
        if video.exists():
            print(f"render_mp4.py: {video} exists and will be replaced", file=sys.stderr)
    sys.exit(main(["build", *args]))
