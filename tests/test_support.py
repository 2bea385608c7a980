"""Whether bricks can stand where a plan puts them: overlaps by the separating axis test,
floating and tipping bricks, goal files refused naming the row, and every built-in structure
passing the same checks."""

import math

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim import ConfigError
from pyramid_sim.config import BrickConfig, SimConfig
from pyramid_sim.core.goals import load_goals
from pyramid_sim.core.plan import make_plan
from pyramid_sim.core.poses import Pose
from pyramid_sim.core.seed_pyramids import MAX_LAYERS, SEED_START
from pyramid_sim.core.structures import MAX_BRICKS, MAX_COURSE, StructureSpec
from pyramid_sim.core.support import (
    clip_convex,
    convex_hull,
    first_fault,
    footprint,
    overlap_depth,
    polygon_area,
)
from pyramid_sim.resources import GOALS

BRICK = BrickConfig()
REST = SEED_START[2]  # the centre height of a brick on the table
UP = REST + BRICK.height


def test_a_footprint_is_the_brick_turned_by_its_yaw():
    corners = footprint(Pose(1.0, 2.0, REST, math.pi / 2), BRICK)
    assert corners[:, 0].max() - corners[:, 0].min() == pytest.approx(BRICK.width)
    assert corners[:, 1].max() - corners[:, 1].min() == pytest.approx(BRICK.length)
    assert polygon_area(corners) == pytest.approx(BRICK.length * BRICK.width)


@pytest.mark.parametrize(
    "b, depth_mm",
    [
        (Pose(0.0, 0.0, REST), 62.0),  # the same place: as deep as the brick is tall
        (Pose(0.0, 0.086, REST), 0.0),  # side by side, touching
        (Pose(0.0, 0.0855, REST), 0.5),  # half a millimetre in
        (Pose(0.0, 0.0, UP), 0.0),  # stacked: faces touch
        (Pose(0.0, 0.12, REST, math.pi / 2), 19.0),  # turned: its end 19 mm into the first
        (Pose(0.2, 0.2, REST, 0.3), None),  # far apart
    ],
)
def test_overlap_depth_is_the_separating_axis_test_in_xy_and_z(b, depth_mm):
    depth = overlap_depth(Pose(0.0, 0.0, REST), b, BRICK) * 1000
    if depth_mm is None:
        assert depth < 0
    else:
        assert depth == pytest.approx(depth_mm, abs=1e-6)


def test_a_turned_brick_corner_to_corner_overlaps_only_where_the_rectangles_do():
    """45 degrees: an axis-aligned test would call these apart or overlapping wrongly."""
    a = Pose(0.0, 0.0, REST, math.pi / 4)
    reach = (BRICK.length + BRICK.width) / 2 / math.sqrt(2)  # a's extent along x
    assert overlap_depth(a, Pose(reach + BRICK.length / 2 + 0.001, 0.0, REST), BRICK) < 0
    assert overlap_depth(a, Pose(reach + BRICK.length / 2 - 0.005, 0.0, REST), BRICK) > 0.004


def test_the_contact_of_two_crossed_bricks_is_their_common_square():
    a = footprint(Pose(0.0, 0.0, REST), BRICK)
    b = footprint(Pose(0.0, 0.0, UP, math.pi / 2), BRICK)
    assert polygon_area(clip_convex(a, b)) == pytest.approx(BRICK.width**2)
    apart = footprint(Pose(1.0, 0.0, REST), BRICK)
    assert len(clip_convex(apart, b)) == 0


def test_the_hull_of_points_drops_the_inner_ones():
    hull = convex_hull(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5], [0.5, 0]]))
    assert len(hull) == 4 and polygon_area(hull) == pytest.approx(1.0)


def _describe(poses):
    fault = first_fault(poses, BRICK, REST)
    return None if fault is None else fault.describe(lambda i: f"row {i + 1}")


def test_a_brick_bridging_a_gap_stands_though_its_centre_is_over_the_gap():
    """The pyramid's rule: the centre lies between its two supports, over neither (a union of
    footprints would refuse it; the hull of the contacts does not)."""
    below = [Pose(0.7, -0.058, REST), Pose(0.7, 0.058, REST)]
    assert _describe([*below, Pose(0.7, 0.0, UP, math.pi / 2)]) is None
    assert (
        "row 3: the brick would tip, its centre 39.0 mm outside its support on row 2"
        in _describe([*below, Pose(0.7, 0.14, UP, math.pi / 2)])
    )


@pytest.mark.parametrize(
    "poses, words",
    [
        ([Pose(0.7, 0, UP)], "row 1: the brick floats, 62 mm above the table"),
        ([Pose(0.7, 0, REST), Pose(0.7, 0.3, UP)], "row 2: the brick floats"),
        ([Pose(0.7, 0, REST), Pose(0.7, 0.087, UP)], "row 2: the brick floats"),  # edge only
        ([Pose(0.7, 0, REST), Pose(0.8, 0, UP)], "row 2: the brick would tip, its centre 4.0 mm"),
        (
            [Pose(0.7, 0, REST), Pose(0.75, 0.05, REST)],
            "row 1 and row 2: the bricks overlap by 36.0",
        ),
        ([Pose(0.7, 0, REST), Pose(0.7, 0, UP), Pose(0.7, 0.02, UP, 0.1)], "row 2 and row 3"),
    ],
)
def test_each_fault_names_the_brick_and_the_rule(poses, words):
    assert words in _describe(poses)


def test_a_brick_on_the_edge_of_its_support_or_a_hair_into_a_neighbour_stands():
    assert _describe([Pose(0.7, 0, REST), Pose(0.796, 0, UP)]) is None  # centre over the edge
    assert _describe([Pose(0.7, 0, REST), Pose(0.7, 0.0855, REST)]) is None  # 0.5 mm: rounding


def _max_size(name: str) -> dict:
    return {
        "pyramid": {"layers": MAX_LAYERS},
        "pyramid-even": {"layers": MAX_LAYERS},
        "wall": {"bricks": MAX_BRICKS, "width": MAX_COURSE},
        "corner-wall": {"bricks": MAX_BRICKS, "width": MAX_COURSE},
        "wall-pyramid": {"width": MAX_COURSE, "layers": MAX_COURSE},
        "towers": {"towers": MAX_COURSE, "layers": MAX_LAYERS},
    }[name]


@pytest.mark.parametrize(
    "name", ["pyramid", "pyramid-even", "wall", "corner-wall", "wall-pyramid", "towers"]
)
@pytest.mark.parametrize("size", ["default", "max"])
def test_every_built_in_structure_passes_the_goal_checks(name, size):
    """In its own order and in each plan's build order, at its default and largest size."""
    spec = StructureSpec(name, **(_max_size(name) if size == "max" else {}))
    orders = [[t.pose for t in spec.targets(BRICK, SEED_START)]]
    config = SimConfig()
    rest = config.layout.table_top_z + config.brick.height / 2
    for arms in ("both", "left", "right"):
        orders.append([b.target.pose for b in make_plan(spec, config, arms).bricks])
    for poses in orders:
        assert first_fault(poses, config.brick, rest) is None


def test_the_seeds_five_goals_pass():
    assert len(load_goals(GOALS / "seed_five.json", BRICK, REST)) == 5


def _goals(tmp_path, text: str, name: str = "g.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "text, words",
    [
        (
            "x,y,z\n0.7,0,0.11\n0.7,0.3,0.172\n",
            "g.csv row 2: the brick floats, 62 mm above the table",
        ),
        ("x,y,z\n0.7,0,0.172\n", "g.csv row 1: the brick floats"),
        ("x,y,z\n0.7,0,0.11\n0.8,0,0.172\n", "g.csv row 2: the brick would tip"),
        ("x,y,z\n0.7,0,0.125\n", "row 1: z 0.125 is not a resting height"),  # 15 mm up
        (
            "x,y,z,yaw\n0.7,0,0.11,0\n0.7,0.12,0.11,1.5708\n",
            "row 1 and row 2: the bricks overlap by 19.0",
        ),
    ],
)
def test_goals_that_float_tip_or_overlap_are_refused_naming_the_row(tmp_path, text, words):
    with pytest.raises(ConfigError, match=words):
        load_goals(_goals(tmp_path, text), BRICK, REST)


def test_rows_are_checked_course_by_course_as_every_plan_builds_them(tmp_path):
    """The top row first in the file: the plan lays the course under it first, so it stands;
    the fault names the file's rows."""
    assert len(load_goals(_goals(tmp_path, "x,y,z\n0.7,0,0.172\n0.7,0,0.11\n"), BRICK, REST)) == 2
    with pytest.raises(ConfigError, match="row 1: the brick would tip"):
        load_goals(_goals(tmp_path, "x,y,z\n0.8,0,0.172\n0.7,0,0.11\n"), BRICK, REST)


def test_the_python_plan_refuses_a_floating_goal(tmp_path):
    path = _goals(tmp_path, "x,y,z\n0.7,0,0.11\n0.7,0.3,0.172\n")
    with pytest.raises(ConfigError, match="row 2: the brick floats"):
        pyramid_sim.plan("list", goals=path)


def test_the_command_line_refuses_a_floating_goal_in_one_line(tmp_path, refused):
    path = _goals(tmp_path, "x,y,z\n0.7,0,0.11\n0.7,0.3,0.172\n")
    err = refused(["plan", "--structure", "list", "--goals", str(path)])
    assert "g.csv row 2: the brick floats" in err and "accepted" in err
