#!/usr/bin/env python3
"""Render a whole build to MP4 headless (EGL, else OSMesa): `pyramid-sim build --video` with
its own default folder, runs/render/, so it never writes over the README's main command's
video. Any `pyramid-sim build` option may follow, e.g. --camera front --shadows; a film already
there is kept unless it is the same build's or --overwrite is given (as `build` keeps it)."""

import sys
from pathlib import Path

from pyramid_sim.cli import main
from pyramid_sim.cli.args import Parser


def build_args(args: list[str]) -> tuple[list[str], Path | None]:
    """The `build` command line for these options, and the video it will write when this
    script chose the path. Only --out and --video are read here (in any of argparse's
    spellings); build checks the rest."""
    paths = Parser(prog="render_mp4.py", add_help=False)
    paths.add_argument("--out", default="runs/render")
    paths.add_argument("--video")
    known, _ = paths.parse_known_args(args)
    if known.video is not None:
        return ["build", "--out", known.out, *args], None
    video = Path(known.out) / "build.mp4"
    return ["build", "--out", known.out, "--video", str(video), *args], video


if __name__ == "__main__":
    argv = sys.argv[1:]
    command, _ = build_args(argv)
    sys.exit(main(command))
