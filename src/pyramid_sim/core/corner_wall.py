"""The Brick Manager's corner wall, as its authors' loop builds it (de3-robo/brick_manager,
`goal_manager_server2` in scripts/brick_manager_server.py): pure geometry, no MuJoCo.

The Brick Manager's server shows only that function's set-up (a cornerstone, 15 bricks,
"width" 5, 20 mm added to the brick's length and height); its loop makes a corner: each course
has width + 1 bricks, the first width // 2 + 1 laid end to end along one leg from the corner,
the rest turned 90 degrees and laid along the other leg, and every second course shifts each
leg by one brick width so the courses interlock at the corner, as a mason bonds one.

Two things differ from the loop's numbers, and why:
- the loop places the turned leg (L - W) / 2 from the corner in both parities, which in every
  second course puts its first brick 80 mm into the cornerstone; here the leg that does not run
  through the corner starts a 4 mm joint past the other leg's side, in every course, so each
  leg moves by a brick width (and that joint) between courses, as the loop's legs do;
- the 20 mm the loop adds to the height is a drop gap, not a joint: courses rest on each other.
"""

from __future__ import annotations

import math

from ..config import BrickConfig, check_count
from .brick_manager import MAX_BRICKS, MAX_COURSE, SEED_WALL_TOLERANCE
from .poses import Pose
from .seed_pyramids import SEED_START, BrickTarget

# The corner's outer vertex stands this far straight ahead of the spawn spot, and the legs come
# back towards the robots at 45 degrees either side: the spot lies inside the corner, 0.19 m
# from each leg, and each leg's far end stays within the arms' reach.
CORNER_AHEAD = 0.39  # m
# The joint at the corner, between one leg's side and the other's first brick. Each leg moves by
# a brick width and this joint between courses, so a leg's free end overhangs the course below
# by as much: a 20 mm joint there would put the end brick's centre of mass 10 mm past its
# support. The loop itself shifts by exactly a brick width.
CORNER_JOINT = 0.004  # m
# The corner frame's u and v axes in the world: the legs run back along -u and -v.
U_AXIS = (math.cos(-math.pi / 4), math.sin(-math.pi / 4))
V_AXIS = (math.cos(math.pi / 4), math.sin(math.pi / 4))


def corner_courses(
    bricks: int, width: int, brick: BrickConfig
) -> list[list[tuple[float, float, int]]]:
    """The courses as (u, v, leg) in the corner's own frame: the outer vertex at the origin,
    leg 0 running along -u (its outer face on v = 0), leg 1 along -v (outer face on u = 0).
    Bottom course first; within a course leg 0 then leg 1, each from the corner outwards."""
    check_count("wall width", width, 1, MAX_COURSE)
    check_count("bricks", bricks, 1, MAX_BRICKS)
    pitch = brick.length + SEED_WALL_TOLERANCE
    through = brick.length / 2  # centre of the first brick of the leg running through the corner
    beside = brick.width + CORNER_JOINT + brick.length / 2  # ... of the other leg's
    first_leg = width // 2 + 1
    courses = []
    laid = 0
    course = 0
    while laid < bricks:
        a0, b0 = (through, beside) if course % 2 == 0 else (beside, through)
        row = [(-(a0 + k * pitch), -brick.width / 2, 0) for k in range(first_leg)]
        row += [(-brick.width / 2, -(b0 + k * pitch), 1) for k in range(width + 1 - first_leg)]
        row = row[: bricks - laid]
        courses.append(row)
        laid += len(row)
        course += 1
    return courses


def corner_wall(
    bricks: int = 15,
    width: int = 5,
    brick: BrickConfig = BrickConfig(),
    start: tuple[float, float, float] = SEED_START,
    pickup_y: float | None = None,
) -> tuple[BrickTarget, ...]:
    """`bricks` bricks in courses of `width` + 1 round a corner straight ahead of the spawn
    spot (at y `pickup_y`, also when one arm builds alone: the corner needs the spot inside
    it); leg 0's bricks turned -45 degrees, leg 1's +45."""
    xs, ys, zs = start
    vx, vy = xs + CORNER_AHEAD, ys if pickup_y is None else pickup_y
    yaws = (-math.pi / 4, math.pi / 4)
    targets = []
    for course, row in enumerate(corner_courses(bricks, width, brick)):
        for u, v, leg in row:
            x = vx + u * U_AXIS[0] + v * V_AXIS[0]
            y = vy + u * U_AXIS[1] + v * V_AXIS[1]
            targets.append(BrickTarget(Pose(x, y, zs + course * brick.height, yaws[leg]), course))
    return tuple(targets)
