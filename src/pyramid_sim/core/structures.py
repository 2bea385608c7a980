"""Brick structures as resting poses: pure geometry, no MuJoCo.

`create_coordinates` and `create_coordinates_new` are the seed's generators (DE NIRO's
pick_and_place.py) kept number for number, 0.03 m release gap and 4-decimal rounding included;
`pyramid` and `pyramid_even` turn their layouts into resting targets (the gap is a separate
release clearance in MotionConfig).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from ..config import BrickConfig, check_count
from ..errors import ConfigError
from .poses import Pose

SEED_START = (0.49, 0.01, 0.11)  # xs, ys, zs: the seed's spawn spot and bottom brick centre
SEED_GAP = 0.03  # gap between neighbouring bricks across the face, and the seed's drop height
SEED_X_GAP = 0.05  # the structure stands this far beyond one brick length past the spawn
MAX_LAYERS = 12
MAX_COURSE = 12  # bricks a course, towers side by side
MAX_BRICKS = 200


@dataclass(frozen=True)
class BrickTarget:
    """Where one brick must come to rest, and its layer (0 = bottom)."""

    pose: Pose
    layer: int


def create_coordinates(layer: int) -> tuple[list[list[float]], list[float]]:
    """The seed's `create_coordinates`: layers of n, n-1, ..., 1 bricks, top layer first,
    odd and even layers offset by half a pitch. Returns (lay, s) as the seed does."""
    xs, ys, zs = SEED_START
    xb, yb, zb = 0.192, 0.086, 0.062
    sc = 1
    lay: list[list[float]] = []
    x_structure = round(xs + xb + sc * 0.05, 4)
    for j in range(layer):
        z_structure = zs + (layer - j - 1) * zb + 0.03
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
    """The seed's `create_coordinates_new`: layers of 2n, 2n-2, ..., 2 bricks, bottom first."""
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


def _check_layers(layers: int) -> None:
    check_count("layers", layers, 1, MAX_LAYERS)


def _layout(
    slots_per_layer: list[list[float]], brick: BrickConfig, start: tuple[float, float, float]
) -> tuple[BrickTarget, ...]:
    """Targets from slot numbers (in brick pitches across the face), bottom layer first."""
    xs, ys, zs = start
    x = xs + brick.length + SEED_X_GAP
    pitch = brick.width + SEED_GAP
    return tuple(
        BrickTarget(Pose(x, ys + slot * pitch, zs + layer * brick.height, 0.0), layer)
        for layer, slots in enumerate(slots_per_layer)
        for slot in slots
    )


def pyramid(
    layers: int = 4, brick: BrickConfig = BrickConfig(), start: tuple[float, float, float] = SEED_START
) -> tuple[BrickTarget, ...]:
    """The seed's `create_coordinates` pyramid: n, n-1, ..., 1 bricks, each layer offset by half
    a pitch from the one below, long axes pointing away from the robots (yaw 0)."""
    _check_layers(layers)
    slots = [[k - (n - 1) / 2 for k in range(n)] for n in range(layers, 0, -1)]
    return _layout(slots, brick, start)


def pyramid_even(
    layers: int = 4, brick: BrickConfig = BrickConfig(), start: tuple[float, float, float] = SEED_START
) -> tuple[BrickTarget, ...]:
    """The seed's `create_coordinates_new` pyramid: 2n, 2n-2, ..., 2 bricks in columns."""
    _check_layers(layers)
    slots = [[k - (n - 1) / 2 for k in range(n)] for n in range(2 * layers, 0, -2)]
    return _layout(slots, brick, start)


# --- the Brick Manager's structures (seed 000) ----------------------------------------------

SEED_WALL_TOLERANCE = 0.02  # the seed's `tol`: gap between bricks end to end


def goal_manager_server3(wall_base_width: int, wall_height: int) -> list[list[float]]:
    """The seed's `goal_manager_server3` wall pyramid, its own numbers: a parallelogram of
    bricks end to end along x (pitch blength + tol, courses bheight + tol apart, each course
    shifted by half a brick), with the overhanging ends of each course peeled away. The seed
    spelled out heights 1 to 5 by hand; this follows the same rule for any height (the loop's
    length, not shown in the seed, is one course per height)."""
    bstart = [1, -0.8, 0.116, 0, 0, math.pi / 2]
    blength, bheight = 0.2 + SEED_WALL_TOLERANCE, 0.06 + SEED_WALL_TOLERANCE
    square_number = wall_base_width * wall_height
    pyramid_seperate = []
    xnos = znos = offset = 0
    for _ in range(0, square_number):
        pyramid_seperate.append([
            round(bstart[0] + xnos * blength + offset * (blength / 2), 3), bstart[1],
            round(bstart[2] + znos * bheight, 3), bstart[3], bstart[4], bstart[5],
        ])
        if xnos < wall_base_width - 1:
            xnos += 1
        else:
            xnos = 0
            znos += 1
            offset += 1
    if wall_height == 1:
        return pyramid_seperate
    # The seed's peel, generalised: the first slice keeps the base course and the first brick
    # of the next (its `[:(w*2)-1]`), each later slice the k-th course minus its last k bricks.
    pos_final = pyramid_seperate[: (wall_base_width * 2) - 1]
    for k in range(2, wall_height):
        pos_final += pyramid_seperate[wall_base_width * k : wall_base_width * (k + 1) - k]
    return pos_final


def _wall_line(start: tuple[float, float, float], brick: BrickConfig) -> tuple[float, float]:
    """x of the wall's centre line and the z of its bottom course: the pyramids' line."""
    xs, _, zs = start
    return xs + brick.length + SEED_X_GAP, zs


def wall(
    bricks: int = 13,
    width: int = 4,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
) -> tuple[BrickTarget, ...]:
    """The seed's `goal_manager_server2` wall: `bricks` bricks in courses along y, `width`
    stretchers (yaw pi/2) a course, `tol` apart; every second course is offset by half a brick
    and closed at both ends by a header turned 90 degrees (the seed's `angle`), whose outer face
    is flush with the wall's end: `shift2` = (length - width) / 2 in from the end stretcher's
    centre, `shift1` = (length + width) / 2 from its neighbour's. Courses bottom first; the last
    course may be partial."""
    check_count("wall width", width, 1, MAX_COURSE)
    check_count("bricks", bricks, 1, MAX_BRICKS)
    x, z0 = _wall_line(start, brick)
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
) -> tuple[BrickTarget, ...]:
    """The seed's `goal_manager_server3`: stretchers end to end along y (yaw pi/2), `width` in
    the bottom course, each course above one shorter and shifted by half a brick, `layers`
    courses (at most `width`)."""
    check_count("wall width", width, 1, MAX_COURSE)
    check_count("layers", layers, 1, width)  # a course of `width` carries at most `width`
    x, z0 = _wall_line(start, brick)
    pitch = brick.length + SEED_WALL_TOLERANCE
    y0 = start[1] - (width - 1) * pitch / 2
    return tuple(
        BrickTarget(Pose(x, y0 + (i + course / 2) * pitch, z0 + course * brick.height, math.pi / 2), course)
        for course in range(layers)
        for i in range(width - course)
    )


def towers(
    towers: int = 4,
    layers: int = 3,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    pickup_y: float | None = None,
) -> tuple[BrickTarget, ...]:
    """The seed's `generate_simple_wall` helper: `towers` columns of `layers` bricks side by
    side (yaw 0, the pyramids' gap between them), begun at the end away from the pick-up spot
    (the seed: pick-up at y >= 0, first tower at negative y). Tower by tower."""
    check_count("towers", towers, 1, MAX_COURSE)
    _check_layers(layers)
    x, z0 = _wall_line(start, brick)
    pitch = brick.width + SEED_GAP
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
# has no generator (its targets are the goals).
STRUCTURES: dict[str, tuple[Callable[..., tuple[BrickTarget, ...]] | None, dict[str, int]]] = {
    "pyramid": (pyramid, {"layers": 4}),
    "pyramid-even": (pyramid_even, {"layers": 4}),
    "wall": (wall, {"bricks": 13, "width": 4}),  # the seed's 15 x 5: both arms only
    "wall-pyramid": (wall_pyramid, {"width": 5, "layers": 3}),
    "towers": (towers, {"towers": 4, "layers": 3}),
    "list": (None, {}),
}
SIZE_OPTIONS = ("layers", "bricks", "width", "towers")
# The option `reach` grows to find the largest buildable size.
SIZE_KNOB = {
    "pyramid": "layers", "pyramid-even": "layers", "wall": "width", "wall-pyramid": "width",
    "towers": "towers",
}


@dataclass(frozen=True)
class StructureSpec:
    """A structure and its size: options left None take the structure's defaults; an option
    the structure has no use for is refused (ConfigError), as is a size it cannot have."""

    name: str = "pyramid-even"
    layers: int | None = None
    bricks: int | None = None
    width: int | None = None
    towers: int | None = None
    goals: tuple[BrickTarget, ...] | None = None  # `list`: targets read from a goals file
    goals_source: str = ""  # the goals file, as named in messages and the CSV

    def __post_init__(self) -> None:
        if self.name not in STRUCTURES:
            raise ConfigError(
                f"structure: unknown {self.name!r}; accepted {', '.join(sorted(STRUCTURES))}"
            )
        defaults = STRUCTURES[self.name][1]
        for option in SIZE_OPTIONS:
            value = getattr(self, option)
            if option in defaults:
                if value is None:
                    object.__setattr__(self, option, defaults[option])
            elif value is not None:
                users = [n for n, (_, d) in STRUCTURES.items() if option in d]
                raise ConfigError(
                    f"{option}: not an option of {self.name}; accepted with {', '.join(users)}"
                )
        if (self.name == "list") != (self.goals is not None):
            raise ConfigError(
                "goals: a goals file is needed by the list structure, and only by it; "
                "accepted --structure list --goals FILE"
            )
        if self.name == "list" and not self.goals:
            raise ConfigError(f"goals: {self.goals_source or 'the file'} holds no goals")
        self.targets(BrickConfig(), SEED_START)  # the generator refuses an impossible size

    @property
    def size(self) -> dict[str, int]:
        """The size options of this structure and their values."""
        if self.name == "list":
            assert self.goals is not None
            return {"goals": len(self.goals)}
        return {o: getattr(self, o) for o in STRUCTURES[self.name][1]}

    def size_text(self) -> str:
        if self.name == "list":
            return f"goals={self.goals_source}:{self.size['goals']}"
        return " ".join(f"{k}={v}" for k, v in self.size.items())

    def targets(
        self,
        brick: BrickConfig,
        start: tuple[float, float, float],
        pickup_y: float | None = None,
    ) -> tuple[BrickTarget, ...]:
        """The resting targets, laid out from `start` (the spawn spot's x and z, the
        structure's centre y); goals are absolute and ignore it."""
        generator, defaults = STRUCTURES[self.name]
        if generator is None:
            assert self.goals is not None
            return self.goals
        options: dict = {o: getattr(self, o) for o in defaults}
        if self.name == "towers":
            options["pickup_y"] = start[1] if pickup_y is None else pickup_y
        return generator(**options, brick=brick, start=start)


def make_structure(
    spec: StructureSpec | str,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
) -> tuple[BrickTarget, ...]:
    """Targets of a structure (or a structure's name at its default size), laid out from the
    spawn spot `start` as the seed does."""
    if isinstance(spec, str):
        spec = StructureSpec(spec)
    return spec.targets(brick, start)
