"""The Brick Manager's structures: wall, wall pyramid, towers, goal lists."""

import json
import math

import pytest

from pyramid_sim import ConfigError
from pyramid_sim.config import BrickConfig
from pyramid_sim.core.brick_manager import (
    SEED_WALL_TOLERANCE,
    towers,
    wall,
    wall_pyramid,
)
from pyramid_sim.core.goals import load_goals
from pyramid_sim.core.seed_pyramids import SEED_START
from pyramid_sim.core.structures import StructureSpec
from pyramid_sim.resources import GOALS

BRICK_MANAGER_BRICK = BrickConfig(
    length=0.2, width=0.09, height=0.06
)  # goal_manager_server2/3's brick
TABLE_Z = 0.11


# The Brick Manager's own function, as its authors wrote it: the reference `wall_pyramid` is
# held to.
def goal_manager_server3(wall_base_width: int, wall_height: int) -> list[list[float]]:
    """The Brick Manager's `goal_manager_server3` wall pyramid, its own numbers: a
    parallelogram of bricks end to end along x (pitch blength + tol, courses bheight + tol
    apart, each course shifted by half a brick), with the overhanging ends of each course peeled
    away. The Brick Manager spelled out heights 1 to 5 by hand; this follows the same rule for
    any height (the loop's length, not shown there, is one course per height)."""
    bstart = [1, -0.8, 0.116, 0, 0, math.pi / 2]
    blength, bheight = 0.2 + SEED_WALL_TOLERANCE, 0.06 + SEED_WALL_TOLERANCE
    square_number = wall_base_width * wall_height
    pyramid_seperate = []
    xnos = znos = offset = 0
    for _ in range(0, square_number):
        pyramid_seperate.append(
            [
                round(bstart[0] + xnos * blength + offset * (blength / 2), 3),
                bstart[1],
                round(bstart[2] + znos * bheight, 3),
                bstart[3],
                bstart[4],
                bstart[5],
            ]
        )
        if xnos < wall_base_width - 1:
            xnos += 1
        else:
            xnos = 0
            znos += 1
            offset += 1
    if wall_height == 1:
        return pyramid_seperate
    # The Brick Manager's peel, generalised: the first slice keeps the base course and the first
    # brick of the next (its `[:(w*2)-1]`), each later slice the k-th course minus its last k
    # bricks.
    pos_final = pyramid_seperate[: (wall_base_width * 2) - 1]
    for k in range(2, wall_height):
        pos_final += pyramid_seperate[wall_base_width * k : wall_base_width * (k + 1) - k]
    return pos_final


def _brick_manager_peel(w: int, h: int) -> list:
    """The Brick Manager's own if-chain for heights 1 to 5, as printed: the oracle for our loop."""
    square = []
    blength, bheight = 0.22, 0.08
    xnos = znos = offset = 0
    for _ in range(w * h):
        square.append(
            [
                round(1 + xnos * blength + offset * (blength / 2), 3),
                -0.8,
                round(0.116 + znos * bheight, 3),
                0,
                0,
                math.pi / 2,
            ]
        )
        if xnos < w - 1:
            xnos += 1
        else:
            xnos, znos, offset = 0, znos + 1, offset + 1
    if h == 1:
        return square
    if h == 2:
        return square[: (w * 2) - 1]
    if h == 3:
        return square[: (w * 2) - 1] + square[(w * 2) : (w * 3) - 2]
    if h == 4:
        return square[: (w * 2) - 1] + square[(w * 2) : (w * 3) - 2] + square[(w * 3) : (w * 4) - 3]
    return (
        square[: (w * 2) - 1]
        + square[(w * 2) : (w * 3) - 2]
        + square[(w * 3) : (w * 4) - 3]
        + square[(w * 4) : (w * 5) - 4]
    )


@pytest.mark.parametrize("h", [1, 2, 3, 4, 5])
def test_goal_manager_server3_is_the_brick_managers_peel(h):
    assert goal_manager_server3(5, h) == _brick_manager_peel(5, h)


def test_goal_manager_server3_numbers_by_hand():
    p = goal_manager_server3(5, 3)
    assert [q[0] for q in p[:5]] == [1.0, 1.22, 1.44, 1.66, 1.88]  # blength + tol = 0.22
    assert [q[0] for q in p[5:9]] == [1.11, 1.33, 1.55, 1.77]  # shifted half a brick
    assert [q[2] for q in (p[0], p[5], p[9])] == [0.116, 0.196, 0.276]  # bheight + tol = 0.08


@pytest.mark.parametrize("width, layers", [(5, 1), (5, 3), (5, 5), (3, 2)])
def test_wall_pyramid_lays_the_brick_managers_pattern_along_the_wall(width, layers):
    """Same offsets along the wall as the Brick Manager, resting heights (its + tol was a drop)."""
    theirs = goal_manager_server3(width, layers)
    mine = wall_pyramid(width, layers, BRICK_MANAGER_BRICK)
    assert len(mine) == len(theirs) == sum(width - c for c in range(layers))
    y0 = min(t.pose.y for t in mine if t.layer == 0)
    assert sorted(round(t.pose.y - y0, 3) for t in mine) == sorted(
        round(q[0] - 1.0, 3) for q in theirs
    )
    assert {round(t.pose.z - SEED_START[2], 4) for t in mine} == {
        round(c * 0.06, 4) for c in range(layers)
    }
    assert all(t.pose.yaw == pytest.approx(math.pi / 2) for t in mine)


def test_wall_of_the_brick_managers_15_bricks_5_wide():
    targets = wall(15, 5, BRICK_MANAGER_BRICK)
    per_course = [sum(t.layer == c for t in targets) for c in range(3)]
    assert per_course == [5, 6, 4]  # full, closed by two turned ends, partial
    second = sorted((t for t in targets if t.layer == 1), key=lambda t: t.pose.y)
    first = sorted((t for t in targets if t.layer == 0), key=lambda t: t.pose.y)
    assert second[0].pose.yaw == 0.0 and second[-1].pose.yaw == 0.0  # the Brick Manager's `angle`
    shift1 = (BRICK_MANAGER_BRICK.length + BRICK_MANAGER_BRICK.width) / 2
    shift2 = (BRICK_MANAGER_BRICK.length - BRICK_MANAGER_BRICK.width) / 2
    # The turned end sits shift2 in from the end stretcher below: flush outer faces.
    assert first[0].pose.y - second[0].pose.y == pytest.approx(shift2)
    assert second[-1].pose.y - first[-1].pose.y == pytest.approx(shift2)
    # ... and shift1 plus the Brick Manager's tolerance from its neighbour in the course.
    assert second[1].pose.y - second[0].pose.y == pytest.approx(shift1 + SEED_WALL_TOLERANCE)
    # Stretchers of the offset course sit half a pitch along.
    pitch = BRICK_MANAGER_BRICK.length + SEED_WALL_TOLERANCE
    assert second[1].pose.y - first[0].pose.y == pytest.approx(pitch / 2)


def test_towers_begin_away_from_the_pick_up_spot():
    brick = BrickConfig()
    high_side = towers(3, 2, brick, (0.49, 0.01, 0.11))  # spot at y >= 0: start negative
    assert high_side[0].pose.y < high_side[-1].pose.y
    other = towers(3, 2, brick, (0.49, 0.25, 0.11), pickup_y=0.01)  # spot on the low side
    assert other[0].pose.y > other[-1].pose.y
    assert [t.layer for t in high_side] == [0, 1, 0, 1, 0, 1]  # tower by tower


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"name": "wall", "layers": 3}, "not an option of wall"),
        ({"name": "wall-pyramid", "width": 2, "layers": 3}, "accepted 1 to 2"),
        ({"name": "wall", "width": 0}, "width"),
        ({"name": "towers", "towers": 13}, "towers"),
        ({"name": "list"}, "goals"),
        ({"name": "pyramid", "goals": ()}, "goals"),
        ({"name": "arch"}, "structure"),
    ],
)
def test_impossible_sizes_are_refused(kwargs, words):
    with pytest.raises(ConfigError, match=words):
        StructureSpec(**kwargs)


def test_the_brick_managers_five_goals_ship_as_an_example():
    goals = load_goals(GOALS / "seed_five.json", BrickConfig(), TABLE_Z)
    assert [round(g.pose.y, 3) for g in goals] == [0.01, -0.24, 0.26, -0.17, 0.19]
    assert [g.layer for g in goals] == [0, 0, 0, 1, 1]
    assert all(g.pose.yaw == pytest.approx(1.5708) for g in goals)


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "name, text, words",
    [
        ("g.csv", "x,y,z,yaw,colour\n0.7,0,0.11,0,red\n", "row 1: unknown column 'colour'"),
        ("g.csv", "x,y,z\n0.7,0,0.11\n0.7,0.3,abc\n", "row 2: z 'abc' is not a number"),
        (
            "g.csv",
            "x,y,z,yaw\n0.7,0,0.11,0\n0.75,0.05,0.11,0\n",
            "row 1 and row 2: the bricks overlap",
        ),
        ("g.csv", "x,y,z\n0.7,0,0.14\n", "row 1: z 0.14 is not a resting height"),
        ("g.csv", "x,y,z\n0.7,0,0.05\n", "row 1: z 0.05 is not a resting height"),
        ("g.csv", "x,y,z\n", "holds no goals"),
        ("g.json", '[{"x": 0.7, "y": 0, "z": 0.11}, {"x": 0.7, "y": 0.3}]', "row 2: no z"),
        ("g.json", '{"goals": [1, 2]}', "list of"),
        ("g.json", "{oops", "not JSON"),
        (
            "g.json",
            '[{"x": 0.7, "y": "inf", "z": 0.11}]',
            "y 'inf' is a string; accepted a JSON number",  # JSON's numbers are numbers
        ),
        (
            "g.csv",
            "x,y,z\n0.7,inf,0.11\n",
            r"y inf is out of range; accepted \[-10, 10\] m",
        ),
    ],
)
def test_bad_goal_files_name_the_row(tmp_path, name, text, words):
    with pytest.raises(ConfigError, match=words):
        load_goals(_write(tmp_path, name, text), BrickConfig(), TABLE_Z)


def test_goals_keep_their_order_and_find_their_course(tmp_path):
    path = _write(
        tmp_path, "g.csv", "x,y,z,yaw\n0.73,0.05,0.11,0\n0.73,-0.1,0.11,1.5708\n0.73,0,0.172,0\n"
    )
    goals = load_goals(path, BrickConfig(), TABLE_Z)
    assert [(g.pose.y, g.layer) for g in goals] == [(0.05, 0), (-0.1, 0), (0.0, 1)]
    assert json.loads(json.dumps([g.pose.z for g in goals])) == [0.11, 0.11, 0.172]
