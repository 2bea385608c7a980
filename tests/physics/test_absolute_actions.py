"""`action_mode="absolute"`: each hand's pose in the world, bounded as a delta is from where
the hand is measured. The target is the action cut to a step and a half of travel; the
expert's label is that bounded target; the expert builds in it, and a recording in it is
labelled with places near the hand, not changes."""

import numpy as np

import pyramid_sim
from pyramid_sim.learning.action_modes.delta import to_delta, to_waypoint

TOOLS = np.array([[0.5, 0.3, 0.2, 0.1], [0.5, -0.3, 0.2, -3.1]])


def test_a_far_target_is_cut_to_the_bound_and_a_near_one_kept():
    far = np.array([0.8, 0.3, 0.2, 0.1, 0.08, 0.502, -0.299, 0.2, -3.1, 0.0])
    bounded = to_waypoint(to_delta(far, TOOLS, reach=0.09, turn=0.2), TOOLS)
    np.testing.assert_allclose(bounded[:3], [0.59, 0.3, 0.2], atol=1e-7)  # 9 cm of 30
    np.testing.assert_allclose(bounded[5:8], far[5:8], atol=1e-7)  # 2 mm away: there


def test_the_expert_builds_with_absolute_actions():
    evaluation = pyramid_sim.evaluate(
        "expert", "pyramid-even", layers=1, episodes=2, fps=10, action_mode="absolute"
    )
    assert evaluation.scores["successes"] == 2


def test_an_absolute_recording_labels_each_frame_with_a_place_near_the_hand(tmp_path):
    """The labels are world positions (tens of centimetres off the origin, not changes of
    millimetres), one a step's move from the last: the hand goes a step at a time."""
    import pyarrow.parquet as pq

    root = tmp_path / "d"
    recorded = pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, fps=10, cameras=(), linger=0.0,
        action_mode="absolute",
    )  # fmt: skip
    assert recorded.failed == ()
    table = pq.read_table(root / "data/chunk-000/file-000.parquet")
    actions = np.array(table["action"].to_pylist())
    assert np.abs(actions[:, 0]).max() > 0.2  # a place in the world, not a change
    steps = np.linalg.norm(np.diff(actions[:, :3], axis=0), axis=1)
    assert steps.max() < 0.2 and steps.max() > 0.01  # it moves, a step at a time
    assert actions.shape[1] == 10
