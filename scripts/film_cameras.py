#!/usr/bin/env python3
"""A still from each camera of a finished two-layer pyramid, for docs/cameras/.

    python3 scripts/film_cameras.py [--out docs/cameras]

Writes panda_overview.png, panda_front.png, panda_top.png and baxter_overview.png (640x480),
each from its own build (a build films one camera).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pyramid_sim

SHOTS = (("panda", "overview"), ("panda", "front"), ("panda", "top"), ("baxter", "overview"))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--out", type=Path, default=Path(__file__).resolve().parents[1] / "docs/cameras"
    )
    out = parser.parse_args().out
    for robot, camera in SHOTS:
        path = out / f"{robot}_{camera}.png"
        result = pyramid_sim.build(
            "pyramid-even",
            layers=2,
            robot=robot,
            snapshot=path,
            video_config=pyramid_sim.VideoConfig(camera=camera),
        )
        print(f"{path}: {result.bricks_placed}/{result.bricks_total} bricks in place")


if __name__ == "__main__":
    main()
