"""The gap between two bricks' footprints seen from above (the layout keeps a drawn structure
clear of the spawn spot by it)."""

import math

import pytest

from pyramid_sim.core.poses import Pose
from pyramid_sim.core.zone import footprint, footprint_gap

L, W = 0.192, 0.086


def test_bricks_end_to_end_are_as_far_apart_as_their_ends():
    a, b = footprint(Pose(0, 0, 0, 0), L, W), footprint(Pose(L + 0.05, 0, 0, 0), L, W)
    assert footprint_gap(a, b) == pytest.approx(0.05)


def test_a_turned_brick_comes_nearer_by_its_corner():
    a = footprint(Pose(0, 0, 0, 0), L, W)
    b = footprint(Pose(0, W / 2 + L / 2 + 0.01, 0, math.pi / 2), L, W)  # end-on, 1 cm off
    assert footprint_gap(a, b) == pytest.approx(0.01)
    turned = footprint(Pose(0, W / 2 + L / 2 + 0.01, 0, math.pi / 2 - 0.3), L, W)
    assert footprint_gap(a, turned) < 0.01  # its corner swings nearer


def test_overlapping_and_nested_footprints_touch():
    a = footprint(Pose(0, 0, 0, 0), L, W)
    assert footprint_gap(a, footprint(Pose(0.05, 0.02, 0, 0.4), L, W)) == 0.0
    assert footprint_gap(a, footprint(Pose(0, 0, 0, 0), L / 4, W / 4)) == 0.0
