"""A robot's state and commands in lerobot's names and units: the SO-101 pair's motors in
degrees and the gripper 0-100 over the jaw's real range; the Panda pair's unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pyramid_sim.learning.task.lerobot_units import lerobot_units
from pyramid_sim.robots import PRESETS

OURS = tuple(
    f"{arm}/{j}" for arm in ("left", "right") for j in ("a", "b", "c", "d", "e", "gripper")
)


def test_the_so101_pairs_names_and_units_are_lerobots_bimanual_so_followers():
    robot = PRESETS["so101"]
    units = lerobot_units(robot, OURS)
    assert units.robot_type == "bi_so_follower"
    assert units.names[:6] == ("left_shoulder_pan.pos", "left_shoulder_lift.pos",
        "left_elbow_flex.pos", "left_wrist_flex.pos", "left_wrist_roll.pos", "left_gripper.pos")  # fmt: skip
    assert units.names[6] == "right_shoulder_pan.pos"
    (lever,) = robot.finger_gains
    low, high = robot.lerobot_gripper_span
    ours = np.array([math.pi / 2, -0.5, 0, 0, 0, lever * low] + [0, 0, 0, 0, 1.0, lever * high])
    theirs = units.to_lerobot(ours)
    assert theirs[0] == pytest.approx(90.0) and theirs[1] == pytest.approx(-28.6479, abs=1e-3)
    assert theirs[5] == pytest.approx(0.0, abs=1e-4)  # the jaw at its real range's closed end
    assert theirs[11] == pytest.approx(100.0, abs=1e-4)  # and at its open end
    np.testing.assert_allclose(units.from_lerobot(theirs), ours, atol=1e-6)


def test_a_robot_lerobot_has_no_follower_for_keeps_our_names_and_units():
    units = lerobot_units(PRESETS["panda"], OURS)
    assert units.names == OURS and units.robot_type == "panda_bimanual"
    values = np.linspace(-1, 1, 12)
    np.testing.assert_allclose(units.to_lerobot(values), values.astype(np.float32))
