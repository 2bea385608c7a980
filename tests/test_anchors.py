"""The anchored action mode's frames (learning/task/anchors.py): pure, no MuJoCo."""

import numpy as np
import pytest

from pyramid_sim.learning.task.anchors import (
    DEAD,
    RADIUS,
    anchor_poses,
    frame_at,
    next_targets,
    to_anchored,
    to_world,
)

PICK = np.array([0.48, 0.01, 0.11, 1.37])
CLEARS = np.array([[0.3, 0.62, 0.4, 0.0], [0.3, -0.62, 0.4, 0.0]])
GOALS = np.array([[0.75, 0.02, 0.11, -0.1], [0.74, -0.09, 0.11, -0.1], [0.745, -0.03, 0.17, -0.1]])


def test_an_arms_next_target_is_its_first_unplaced_then_its_last_and_none_for_an_idle_arm():
    orders = [[0, 2], [1], []]
    np.testing.assert_array_equal(next_targets(orders, GOALS, ())[:2], GOALS[[0, 1]])
    np.testing.assert_array_equal(next_targets(orders, GOALS, {0})[0], GOALS[2])
    done = next_targets(orders, GOALS, {0, 1, 2})
    np.testing.assert_array_equal(done[:2], GOALS[[2, 1]])  # the last, once all are placed
    np.testing.assert_array_equal(done[2], np.zeros(4))  # an arm that places none


def test_an_arm_whose_hand_is_over_the_target_it_placed_last_works_on_it_yet():
    """Its release and its rise off the brick are given from that target: within RADIUS
    across the table of it (at any height) the arm's next is still it; once the hand has
    left, the next unplaced one (the tools' x and y are all that count)."""
    orders = [[0, 2], [1]]
    over = np.array([[*(GOALS[0][:2] + [RADIUS * 0.9, 0.0]), 0.4, 0.0], CLEARS[1]])
    rows = next_targets(orders, GOALS, {0}, over)
    np.testing.assert_array_equal(rows[0], GOALS[0])
    np.testing.assert_array_equal(rows[1], GOALS[1])  # the right arm has placed none yet
    left = np.array([[*(GOALS[0][:2] + [RADIUS * 1.1, 0.0]), 0.11, 0.0], CLEARS[1]])
    np.testing.assert_array_equal(next_targets(orders, GOALS, {0}, left)[0], GOALS[2])
    # every target placed: the last, wherever the hand is
    np.testing.assert_array_equal(next_targets(orders, GOALS, {0, 2}, over)[0], GOALS[2])


def _anchors():
    return anchor_poses(PICK, CLEARS, next_targets([[0], [1]], GOALS, ()))


def test_a_waypoint_over_the_pick_or_the_target_is_given_from_it_and_elsewhere_from_clear():
    hover_pick = [*(PICK[:3] + [0.002, -0.001, 0.1]), PICK[3] + 0.05, 0.08]
    hover_goal = [*(GOALS[1][:3] + [0.0, 0.0, 0.1]), GOALS[1][3], 0.0]
    action = to_anchored(np.array(hover_pick + hover_goal), _anchors())
    np.testing.assert_allclose(action[:6], [0, 0.002, -0.001, 0.1, 0.05, 0.08], atol=1e-6)
    np.testing.assert_allclose(action[6:], [2, 0, 0, 0.1, 0, 0], atol=1e-6)
    near_clear = [0.31, 0.6, 0.4, 0.2, 0.08]
    far = [GOALS[1][0] + RADIUS * 1.01, *GOALS[1][1:], 0]
    action = to_anchored(np.array(near_clear + far), _anchors())
    np.testing.assert_allclose(action[:6], [1, 0.01, -0.02, 0.0, 0.2, 0.08], atol=1e-6)
    assert action[6] == 1  # just outside the radius of the arm's target: from its clear pose


@pytest.mark.parametrize("seed", range(5))
def test_an_anchored_action_turns_back_into_the_waypoint_it_was_made_from(seed):
    rng = np.random.default_rng(seed)
    anchors = _anchors()
    world = np.concatenate(
        [[*(PICK[:3] + rng.normal(0, 0.01, 3)), rng.uniform(-3, 3), 0.08],
         [*rng.uniform(0.2, 0.8, 3), rng.uniform(-3, 3), 0.0]]
    )  # fmt: skip
    back = to_world(to_anchored(world, anchors), anchors)
    keep = [0, 1, 2, 4, 5, 6, 7, 9]
    np.testing.assert_allclose(back[keep], world[keep], atol=1e-6)
    for yaw in (3, 8):  # the same heading, a turn apart at most
        assert abs(np.remainder(back[yaw] - world[yaw] + np.pi, 2 * np.pi) - np.pi) < 1e-6


def test_a_hand_carrying_a_brick_works_on_its_next_target_over_the_one_it_placed_last():
    """The 20-brick pyramid's top bricks stand over the ones each arm placed just before:
    carried down there within RADIUS of the target below, the hand was given that one, and
    the policy set its brick a layer low (seed 100021)."""
    orders = [[0, 2], [1]]
    above = np.array([[*GOALS[0][:2], 0.3, 0.0], CLEARS[1]])
    np.testing.assert_array_equal(next_targets(orders, GOALS, {0}, above)[0], GOALS[0])
    carrying = next_targets(orders, GOALS, {0}, above, carrying=(True, False))
    np.testing.assert_array_equal(carrying[0], GOALS[2])
    np.testing.assert_array_equal(carrying[1], GOALS[1])
    let_go = next_targets(orders, GOALS, {0}, above, carrying=(False, False))
    np.testing.assert_array_equal(let_go[0], GOALS[0])  # its rise off the brick let go


def test_an_anchor_near_an_integer_is_that_frame_and_between_two_slides_from_one_to_the_next():
    frames = _anchors()[0]
    for anchor, frame in ((0.1, 0), (0.9, 1), (1.0 + DEAD, 1), (1.9, 2), (7.0, 2), (-3.0, 0)):
        np.testing.assert_allclose(frame_at(anchor, frames), frames[frame])
    np.testing.assert_allclose(frame_at(1.5, frames), (frames[1] + frames[2]) / 2)
    np.testing.assert_allclose(frame_at(0.5, frames), (frames[0] + frames[1]) / 2)
    quarter = frame_at(DEAD + 0.25 * (1 - 2 * DEAD), frames)
    np.testing.assert_allclose(quarter, 0.75 * frames[0] + 0.25 * frames[1])
    world = to_world(np.array([1.5, 0, 0, 0.1, 0, 0.0] * 2), _anchors())
    np.testing.assert_allclose(world[:3], (frames[1][:3] + frames[2][:3]) / 2 + [0, 0, 0.1])


def test_a_hand_turned_half_round_from_its_target_is_labelled_one_way_every_time():
    """The SO-101 pair's right arm sets its brick down with the hand turned half round from
    the brick's yaw, its clear pose at 135 degrees: a hand a hair either side of the half
    turn is labelled near +pi both times (wrapped to a half turn either way it was +pi and
    -pi by turns), and the waypoint it asks for is the hand's yaw again, within a turn."""
    clears = np.array([[0.3, 0.6, 0.4, 0.79], [0.3, -0.6, 0.4, 2.36]])
    anchors = anchor_poses(PICK, clears, next_targets([[0], [1]], GOALS, ()))
    target = GOALS[1]
    labels = []
    for hair in (-1e-3, 1e-3):
        yaw = target[3] + np.pi + hair
        hand = [*PICK[:3], PICK[3], 0.08, *target[:3], yaw, 0.0]
        action = to_anchored(np.array(hand), anchors)
        labels.append(action[10])
        world = to_world(action, anchors)
        assert abs(np.remainder(world[8] - yaw + np.pi, 2 * np.pi) - np.pi) < 1e-6
    assert labels[0] == pytest.approx(np.pi - 1e-3, abs=1e-6)
    assert labels[1] == pytest.approx(np.pi + 1e-3, abs=1e-6)
