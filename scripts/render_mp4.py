#!/usr/bin/env python3
"""Render a whole build to MP4 headless (EGL, else OSMesa): `pyramid-sim build --video` with
its own default folder, runs/render/, so it never writes over the README's main command's
video. Any `pyramid-sim build` option may follow, e.g. --camera front --shadows."""

import sys
from pathlib import Path

from pyramid_sim.cli import main
from pyramid_sim.cli.args import Parser

if __name__ == "__main__":
    args = sys.argv[1:]
    # Only --out and --video are read here (in any of argparse's spellings); build checks the rest.
    paths = Parser(prog="render_mp4.py", add_help=False)
    paths.add_argument("--out", default="runs/render")
    paths.add_argument("--video")
    known, _ = paths.parse_known_args(args)
    if known.video is None:
        video = Path(known.out) / "build.mp4"
        if not {"-h", "--help"} & set(args) and video.exists():
            print(f"render_mp4.py: {video} exists and will be replaced", file=sys.stderr)
        args = ["--video", str(video), *args]
    sys.exit(main(["build", "--out", known.out, *args]))
