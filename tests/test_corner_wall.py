"""The corner wall of the Brick Manager's own loop (upstream goal_manager_server2), checked
against numbers worked out by hand from that loop for two sizes, and laid out where both arms
and one can build it. Brick 0.192 x 0.086 x 0.062 m, 20 mm joints along a leg: pitch
P = 0.212 m; in the corner's frame the leg running through the corner starts at Lb/2 = 0.096 m,
the other a 4 mm corner joint past its side at W + 0.004 + Lb/2 = 0.186 m."""

import itertools
import math

import pytest

from pyramid_sim import ConfigError, plan
from pyramid_sim.config import BrickConfig
from pyramid_sim.core.corner_wall import CORNER_AHEAD, corner_courses, corner_wall
from pyramid_sim.core.structures import StructureSpec

B = BrickConfig()


def _close(got, want):
    assert len(got) == len(want)
    for (u, v, leg), (wu, wv, wleg) in zip(got, want):
        assert (round(u, 6), round(v, 6), leg) == (round(wu, 6), round(wv, 6), wleg)


def test_the_seeds_size_is_two_courses_of_six_and_one_of_three():
    """15 bricks, width 5: legs of width // 2 + 1 = 3 and 3; the third course only leg 0."""
    courses = corner_courses(15, 5, B)
    assert [len(c) for c in courses] == [6, 6, 3]
    # Course 0: leg 0 runs through the corner, leg 1 starts a joint past its side.
    _close(
        courses[0],
        [
            (-0.096, -0.043, 0),
            (-0.308, -0.043, 0),
            (-0.520, -0.043, 0),
            (-0.043, -0.186, 1),
            (-0.043, -0.398, 1),
            (-0.043, -0.610, 1),
        ],
    )
    # Course 1: leg 1 runs through, each leg shifted by a brick width and the joint (0.090 m).
    _close(
        courses[1],
        [
            (-0.186, -0.043, 0),
            (-0.398, -0.043, 0),
            (-0.610, -0.043, 0),
            (-0.043, -0.096, 1),
            (-0.043, -0.308, 1),
            (-0.043, -0.520, 1),
        ],
    )
    _close(courses[2], courses[0][:3])


def test_width_two_has_legs_of_two_and_one():
    """10 bricks, width 2: courses of 3 (two along leg 0, one turned), the last course of 1."""
    courses = corner_courses(10, 2, B)
    assert [len(c) for c in courses] == [3, 3, 3, 1]
    _close(courses[0], [(-0.096, -0.043, 0), (-0.308, -0.043, 0), (-0.043, -0.186, 1)])
    _close(courses[1], [(-0.186, -0.043, 0), (-0.398, -0.043, 0), (-0.043, -0.096, 1)])
    _close(courses[3], [(-0.186, -0.043, 0)])


def _footprint(t):
    """Corners of a brick's rectangle seen from above."""
    c, s = math.cos(t.pose.yaw), math.sin(t.pose.yaw)
    return [
        (t.pose.x + c * dx - s * dy, t.pose.y + s * dx + c * dy)
        for dx in (-B.length / 2, B.length / 2)
        for dy in (-B.width / 2, B.width / 2)
    ]


def _overlap(a, b):
    """Separating axes of two rectangles: True if they overlap by more than 1 mm."""
    for t in (a, b):
        for yaw in (t.pose.yaw, t.pose.yaw + math.pi / 2):
            axis = (math.cos(yaw), math.sin(yaw))
            pa = [x * axis[0] + y * axis[1] for x, y in _footprint(a)]
            pb = [x * axis[0] + y * axis[1] for x, y in _footprint(b)]
            if min(max(pa), max(pb)) - max(min(pa), min(pb)) < 0.001:
                return False
    return True


@pytest.mark.parametrize("bricks, width", [(15, 5), (10, 2), (24, 7)])
def test_no_two_bricks_of_a_course_overlap_and_courses_interlock(bricks, width):
    targets = corner_wall(bricks, width)
    for a, b in itertools.combinations(targets, 2):
        if a.layer == b.layer:
            assert not _overlap(a, b), (a, b)
    # the corner is bonded: each course's first brick of leg 0 lies on the course below's
    # corner bricks, of both legs
    by_course = {}
    for t in targets:
        by_course.setdefault(t.layer, []).append(t)
    for lower, upper in zip(by_course.values(), list(by_course.values())[1:]):
        assert sum(_overlap(upper[0], t) for t in lower) >= 1
    assert {round(t.pose.yaw, 4) for t in targets} == {
        round(-math.pi / 4, 4),
        round(math.pi / 4, 4),
    }


def test_the_corner_stands_ahead_of_the_spawn_spot_which_lies_inside_it():
    p = plan("corner-wall")
    corner = (p.spawn.x + CORNER_AHEAD, p.spawn.y)
    for b in p.bricks:
        # every brick lies behind the corner, on the robots' side, within 45 degrees
        dx, dy = b.target.pose.x - corner[0], b.target.pose.y - corner[1]
        assert dx < 0 and abs(dy) <= -dx + 1e-9
    # the spot lies 0.19 m inside either leg's inner face (the outer face runs through the
    # corner's vertex, the inner one a brick width in)
    for leg_yaw in (-math.pi / 4, math.pi / 4):
        nx, ny = -math.sin(leg_yaw), math.cos(leg_yaw)
        outer = abs((p.spawn.x - corner[0]) * nx + (p.spawn.y - corner[1]) * ny)
        assert outer - B.width == pytest.approx(0.19, abs=0.002)


def test_a_free_end_keeps_its_centre_of_mass_over_the_course_below():
    """Each leg moves by a brick width and the corner joint between courses: the end brick
    overhangs by that much, less than half its length."""
    courses = corner_courses(15, 5, B)
    for lower, upper in zip(courses, courses[1:]):
        for leg, axis in ((0, 0), (1, 1)):
            if not any(p[2] == leg for p in upper):
                continue
            low_end = min(p[axis] for p in lower if p[2] == leg) - B.length / 2
            up_centre = min(p[axis] for p in upper if p[2] == leg)
            assert up_centre - low_end >= 0.005  # the centre stays 5 mm or more inside


def test_one_arm_builds_the_same_corner_in_the_same_place():
    both, left = plan("corner-wall"), plan("corner-wall", arms="left")
    assert sorted((b.target.pose.x, b.target.pose.y) for b in both.bricks) == sorted(
        (b.target.pose.x, b.target.pose.y) for b in left.bricks
    )
    assert {b.arm for b in left.bricks} == {"left"}


def test_sizes_are_checked():
    with pytest.raises(ConfigError, match="wall width"):
        StructureSpec("corner-wall", width=0)
    with pytest.raises(ConfigError, match="not an option of corner-wall"):
        StructureSpec("corner-wall", layers=2)
