"""The anchored action mode's frames (learning/task/anchors.py): pure, no MuJoCo."""

import numpy as np
import pytest

from pyramid_sim.learning.task.anchors import (
    RADIUS,
    anchor_poses,
    next_targets,
    to_anchored,
    to_world,
)

PICK = np.array([0.48, 0.01, 0.11, 1.37])
GOALS = np.array([[0.75, 0.02, 0.11, -0.1], [0.74, -0.09, 0.11, -0.1], [0.745, -0.03, 0.17, -0.1]])


def test_an_arms_next_target_is_its_first_unplaced_then_its_last_and_none_for_an_idle_arm():
    orders = [[0, 2], [1], []]
    np.testing.assert_array_equal(next_targets(orders, GOALS, ())[:2], GOALS[[0, 1]])
    np.testing.assert_array_equal(next_targets(orders, GOALS, {0})[0], GOALS[2])
    done = next_targets(orders, GOALS, {0, 1, 2})
    np.testing.assert_array_equal(done[:2], GOALS[[2, 1]])  # the last, once all are placed
    np.testing.assert_array_equal(done[2], np.zeros(4))  # an arm that places none


def _anchors():
    return anchor_poses(PICK, next_targets([[0], [1]], GOALS, ()))


def test_a_waypoint_over_the_pick_or_the_target_is_given_from_it_and_elsewhere_from_the_table():
    hover_pick = [*(PICK[:3] + [0.002, -0.001, 0.1]), PICK[3] + 0.05, 0.08]
    hover_goal = [*(GOALS[1][:3] + [0.0, 0.0, 0.1]), GOALS[1][3], 0.0]
    action = to_anchored(np.array(hover_pick + hover_goal), _anchors())
    np.testing.assert_allclose(action[:6], [1, 0.002, -0.001, 0.1, 0.05, 0.08], atol=1e-6)
    np.testing.assert_allclose(action[6:], [2, 0, 0, 0.1, 0, 0], atol=1e-6)
    clear = [0.3, 0.62, 0.4, 0.2, 0.08]
    far = to_anchored(np.array(clear + [GOALS[1][0] + RADIUS * 1.01, *GOALS[1][1:], 0]), _anchors())
    np.testing.assert_allclose(far[:6], [0, *clear], atol=1e-6)  # the table: as in the world
    assert far[6] == 0  # just outside the radius of the arm's target


@pytest.mark.parametrize("seed", range(5))
def test_an_anchored_action_turns_back_into_the_waypoint_it_was_made_from(seed):
    rng = np.random.default_rng(seed)
    anchors = _anchors()
    world = np.concatenate(
        [[*(PICK[:3] + rng.normal(0, 0.01, 3)), rng.uniform(-3, 3), 0.08],
         [*rng.uniform(0.2, 0.8, 3), rng.uniform(-3, 3), 0.0]]
    )  # fmt: skip
    back = to_world(to_anchored(world, anchors), anchors)
    np.testing.assert_allclose(
        back[[0, 1, 2, 4, 5, 6, 7, 9]], world[[0, 1, 2, 4, 5, 6, 7, 9]], atol=1e-6
    )
    for yaw in (3, 8):  # the same heading, a turn apart at most
        assert abs(np.remainder(back[yaw] - world[yaw] + np.pi, 2 * np.pi) - np.pi) < 1e-6


def test_an_anchor_between_frames_is_rounded_and_one_out_of_range_clipped():
    anchors = _anchors()
    for anchor, frame in ((0.4, 0), (0.6, 1), (1.7, 2), (7.0, 2), (-3.0, 0)):
        world = to_world(np.array([anchor, 0, 0, 0.1, 0, 0.0] * 2), anchors)
        np.testing.assert_allclose(world[:3], anchors[0, frame, :3] + [0, 0, 0.1])
