"""`action_mode="delta"`: each hand's bounded pose change from where it is measured, the
continuous track's end-effector mode. The waypoint it asks for is the observed tools plus the
change; the expert's label is its waypoint less the tools, bounded; the expert builds in it,
and a recording in it replays."""

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.learning.action_modes.delta import to_delta, to_waypoint

TOOLS = np.array([[0.5, 0.3, 0.2, 0.1], [0.5, -0.3, 0.2, -3.1]])


def test_a_change_is_the_way_to_the_waypoint_bounded_and_given_back():
    far = np.array([0.8, 0.3, 0.2, 0.1, 0.08, 0.502, -0.299, 0.2, 3.1, 0.0])
    delta = to_delta(far, TOOLS, reach=0.09, turn=0.2)
    np.testing.assert_allclose(delta[:5], [0.09, 0, 0, 0, 0.08], atol=1e-7)  # saturated
    # near: the millimetres left, and a yaw across the half turn the short way round
    np.testing.assert_allclose(delta[5:], [0.002, 0.001, 0, 6.2 - 2 * np.pi, 0.0], atol=1e-6)
    back = to_waypoint(delta, TOOLS)
    np.testing.assert_allclose(back[5:8], far[5:8], atol=1e-6)
    assert abs(np.remainder(back[8] - far[8] + np.pi, 2 * np.pi) - np.pi) < 1e-6


def test_the_expert_builds_with_delta_actions():
    evaluation = pyramid_sim.evaluate(
        "expert", "pyramid-even", layers=1, episodes=2, fps=10, action_mode="delta"
    )
    assert evaluation.scores["successes"] == 2


def test_a_delta_recording_labels_each_frame_with_a_bounded_change(tmp_path):
    """The expert's led labels, given back as changes from the tools of their frame: the bound
    reached in the moves, never passed, and near zero while a hand holds still."""
    import pyarrow.parquet as pq

    root = tmp_path / "d"
    recorded = pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, fps=10, cameras=(), linger=0.0,
        action_mode="delta",
    )  # fmt: skip
    assert recorded.failed == ()
    table = pq.read_table(root / "data/chunk-000/file-000.parquet")
    actions = np.array(table["action"].to_pylist())
    reach = np.linalg.norm(actions[:, [0, 1, 2]], axis=1)
    assert reach.max() == pytest.approx(0.09, abs=1e-6)  # m: a step and a half at 0.6 m/s
    assert reach.min() < 0.002  # still, at a grip or a release
