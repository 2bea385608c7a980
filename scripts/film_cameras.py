#!/usr/bin/env python3
"""A still from each camera of a finished two-layer pyramid, for docs/cameras/.

    python3 scripts/film_cameras.py [--out docs/cameras]

Writes panda_overview.png, panda_front.png, panda_top.png, baxter_overview.png and
so101_overview.png (640x480), each from its own build (a build films one camera; the SO-101
pair's three-layer even pyramid, its largest); and each robot's wrist cameras as the
environment films them, at the moment each hand first closes on a brick
(<robot>_left_wrist.png, <robot>_right_wrist.png, 320x240).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import gymnasium
import imageio.v3 as iio

import pyramid_sim

SHOTS = (
    ("panda", "overview"),
    ("panda", "front"),
    ("panda", "top"),
    ("baxter", "overview"),
    ("so101", "overview"),
)
LAYERS = {"so101": 3}  # each robot's pyramid-even: two layers, or its own largest


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
            layers=LAYERS.get(robot, 2),
            robot=robot,
            snapshot=path,
            video_config=pyramid_sim.VideoConfig(camera=camera),
        )
        print(f"{path}: {result.bricks_placed}/{result.bricks_total} bricks in place")
    for robot in ("panda", "baxter", "so101"):
        film_wrists(robot, out)


def film_wrists(robot: str, out: Path) -> None:
    """Each wrist camera's view as its hand first grips, in the expert's rollout."""
    cameras = ("left_wrist", "right_wrist")
    env = gymnasium.make(
        pyramid_sim.ENV_ID, structure="pyramid-even", layers=2, robot=robot, image_size=(240, 320)
    ).unwrapped
    env.reset(seed=0)
    todo = {"left": cameras[0], "right": cameras[1]}
    while todo:
        *_, terminated, truncated, _ = env.step(env.expert_action())
        for arm in list(todo):
            step = env.loop.step_of(arm)
            if step is not None and step.name == "grip":
                path = out / f"{robot}_{todo.pop(arm)}.png"
                iio.imwrite(path, env.images((f"{arm}_wrist",))[f"{arm}_wrist"])
                print(f"{path}: the {arm} hand gripping")
        if terminated or truncated:
            break
    env.close()


if __name__ == "__main__":
    main()
