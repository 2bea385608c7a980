"""DE NIRO's pyramids as resting targets: pure geometry, no MuJoCo.

`create_coordinates` and `create_coordinates_new` are DE NIRO's generators (its
pick_and_place.py) kept number for number, 0.03 m release gap and 4-decimal rounding included;
`pyramid` and `pyramid_even` turn their layouts into resting targets (the gap is a separate
release clearance in MotionConfig).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..config import BrickConfig, check_count
from .poses import Pose

SEED_START = (0.49, 0.01, 0.11)  # xs, ys, zs: DE NIRO's spawn spot and bottom brick centre
SEED_GAP = 0.03  # gap between neighbouring bricks across the face, and DE NIRO's drop height
SEED_X_GAP = 0.05  # the structure stands this far beyond one brick length past the spawn
MAX_LAYERS = 12


@dataclass(frozen=True)
class BrickTarget:
    """Where one brick must come to rest, and its layer (0 = bottom)."""

    pose: Pose
    layer: int


def create_coordinates(layer: int) -> tuple[list[list[float]], list[float]]:
    """DE NIRO's `create_coordinates`: layers of n, n-1, ..., 1 bricks, top layer first,
    odd and even layers offset by half a pitch. Returns (lay, s) as DE NIRO's does."""
    xs, ys, zs = SEED_START
    xb, yb, zb = 0.192, 0.086, 0.062
    sc = 1
    lay: list[list[float]] = []
    x_structure = round(xs + xb + sc * 0.05, 4)
    for j in range(layer):
        z_structure = zs + (layer - j - 1) * zb + 0.03
        total_list: list[float] | list[int]
        if (j + 1) % 2 == 0:
            init_list = [i + 0.5 for i in range(int((j + 1) / 2))]
            rev_list = [-(i + 0.5) for i in range(int((j + 1) / 2))]
            rev_list.reverse()
            total_list = rev_list + init_list
        else:
            pos_list = list(range(int((j + 2) / 2)))
            neg_list = list(range(int(-(j / 2)), 0))
            total_list = neg_list + pos_list
        for item in total_list:
            y_structure = ys + item * (yb + 0.03)
            lay.append([round(x_structure, 4), round(y_structure, 4), round(z_structure, 4)])
    return lay, [xs, ys, zs]


def create_coordinates_new(layer: int) -> tuple[list[list[float]], list[float]]:
    """DE NIRO's `create_coordinates_new`: layers of 2n, 2n-2, ..., 2 bricks, bottom first."""
    xs, ys, zs = SEED_START
    xb, yb, zb = 0.192, 0.086, 0.062
    sc = 1
    m = [d * 2 for d in range(layer, 0, -1)]
    lay: list[list[float]] = []
    x_structure = round(xs + xb + sc * 0.05, 4)
    for i in m:
        z_structure = zs + (layer - (i / 2)) * zb + 0.03
        tot_list = list(range(int(-(i / 2)), 0)) + list(range(int(i / 2)))
        for item in [x + 0.5 for x in tot_list]:
            y_structure = ys + item * (yb + 0.03)
            lay.append([round(x_structure, 4), round(y_structure, 4), round(z_structure, 4)])
    return lay, [xs, ys, zs]


def check_layers(layers: int) -> None:
    check_count("layers", layers, 1, MAX_LAYERS)


Gaps = tuple[float, float]  # m between bricks across the face, and beyond the spot's brick
SEED_GAPS: Gaps = (SEED_GAP, SEED_X_GAP)


def _layout(
    slots_per_layer: list[list[float]],
    brick: BrickConfig,
    start: tuple[float, float, float],
    gaps: Gaps,
) -> tuple[BrickTarget, ...]:
    """Targets from slot numbers (in brick pitches across the face), bottom layer first."""
    xs, ys, zs = start
    x = xs + brick.length + gaps[1]
    pitch = brick.width + gaps[0]
    return tuple(
        BrickTarget(Pose(x, ys + slot * pitch, zs + layer * brick.height, 0.0), layer)
        for layer, slots in enumerate(slots_per_layer)
        for slot in slots
    )


def pyramid(
    layers: int = 4,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    gaps: Gaps = SEED_GAPS,
) -> tuple[BrickTarget, ...]:
    """DE NIRO's `create_coordinates` pyramid: n, n-1, ..., 1 bricks, each layer offset by half
    a pitch from the one below, long axes pointing away from the robots (yaw 0)."""
    check_layers(layers)
    slots = [[k - (n - 1) / 2 for k in range(n)] for n in range(layers, 0, -1)]
    return _layout(slots, brick, start, gaps)


def pyramid_even(
    layers: int = 4,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    gaps: Gaps = SEED_GAPS,
) -> tuple[BrickTarget, ...]:
    """DE NIRO's `create_coordinates_new` pyramid: 2n, 2n-2, ..., 2 bricks in columns."""
    check_layers(layers)
    slots = [[k - (n - 1) / 2 for k in range(n)] for n in range(2 * layers, 0, -2)]
    return _layout(slots, brick, start, gaps)
