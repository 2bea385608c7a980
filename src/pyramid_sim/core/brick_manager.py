"""The Brick Manager's structures as resting targets: pure geometry, no MuJoCo."""

from __future__ import annotations

import math

from ..config import BrickConfig, check_count
from .poses import Pose
from .seed_pyramids import SEED_GAPS, SEED_START, BrickTarget, Gaps, check_layers

MAX_COURSE = 12  # bricks a course, towers side by side
MAX_BRICKS = 200
SEED_WALL_TOLERANCE = 0.02  # the Brick Manager's `tol`: gap between bricks end to end


def _wall_line(
    start: tuple[float, float, float], brick: BrickConfig, gaps: Gaps
) -> tuple[float, float]:
    """x of the wall's centre line and the z of its bottom course: the pyramids' line."""
    xs, _, zs = start
    return xs + brick.length + gaps[1], zs


def wall(
    bricks: int = 13,
    width: int = 4,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    gaps: Gaps = SEED_GAPS,
) -> tuple[BrickTarget, ...]:
    """The Brick Manager's `goal_manager_server2` wall: `bricks` bricks in courses along y, `width`
    stretchers (yaw pi/2) a course, `tol` apart; every second course is offset by half a brick
    and closed at both ends by a header turned 90 degrees (its `angle`), whose outer face
    is flush with the wall's end: `shift2` = (length - width) / 2 in from the end stretcher's
    centre, `shift1` = (length + width) / 2 from its neighbour's. Courses bottom first; the last
    course may be partial."""
    check_count("wall width", width, 1, MAX_COURSE)
    check_count("bricks", bricks, 1, MAX_BRICKS)
    x, z0 = _wall_line(start, brick, gaps)
    pitch = brick.length + SEED_WALL_TOLERANCE
    y0 = start[1] - (width - 1) * pitch / 2  # centred on the spawn spot's y, as the pyramids
    shift2 = (brick.length - brick.width) / 2
    targets: list[BrickTarget] = []
    course = 0
    while len(targets) < bricks:
        z = z0 + course * brick.height
        if course % 2 == 0:
            row = [(y0 + i * pitch, math.pi / 2) for i in range(width)]
        else:
            row = [(y0 - shift2, 0.0)]
            row += [(y0 + (i + 0.5) * pitch, math.pi / 2) for i in range(width - 1)]
            row += [(y0 + (width - 1) * pitch + shift2, 0.0)]
        for y, yaw in row[: bricks - len(targets)]:
            targets.append(BrickTarget(Pose(x, y, z, yaw), course))
        course += 1
    return tuple(targets)


def wall_pyramid(
    width: int = 5,
    layers: int = 3,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    gaps: Gaps = SEED_GAPS,
) -> tuple[BrickTarget, ...]:
    """The Brick Manager's `goal_manager_server3`: stretchers end to end along y (yaw pi/2),
    `width` in the bottom course, each course above one shorter and shifted by half a brick,
    `layers` courses (at most `width`)."""
    check_count("wall width", width, 1, MAX_COURSE)
    check_count("layers", layers, 1, width)  # a course of `width` carries at most `width`
    x, z0 = _wall_line(start, brick, gaps)
    pitch = brick.length + SEED_WALL_TOLERANCE
    y0 = start[1] - (width - 1) * pitch / 2
    return tuple(
        BrickTarget(
            Pose(x, y0 + (i + course / 2) * pitch, z0 + course * brick.height, math.pi / 2), course
        )
        for course in range(layers)
        for i in range(width - course)
    )


def towers(
    towers: int = 4,
    layers: int = 3,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    gaps: Gaps = SEED_GAPS,
    pickup_y: float | None = None,
) -> tuple[BrickTarget, ...]:
    """The Brick Manager's `generate_simple_wall` helper: `towers` columns of `layers` bricks
    side by side (yaw 0, the pyramids' gap between them), begun at the end away from the
    pick-up spot (as there: pick-up at y >= 0, first tower at negative y). Tower by tower."""
    check_count("towers", towers, 1, MAX_COURSE)
    check_layers(layers)
    x, z0 = _wall_line(start, brick, gaps)
    pitch = brick.width + gaps[0]
    pickup = start[1] if pickup_y is None else pickup_y
    direction = 1.0 if pickup >= start[1] else -1.0
    first = start[1] - direction * (towers - 1) * pitch / 2
    return tuple(
        BrickTarget(Pose(x, first + direction * t * pitch, z0 + k * brick.height, 0.0), k)
        for t in range(towers)
        for k in range(layers)
    )


# name -> (generator, its size options with their defaults). Every generator takes its size
# options as keywords, then the brick and the spawn spot the layout starts from; a goal list
