"""`action_mode="relative"`: each joint's action is its change from where the joint is
measured at the step's start (the finger gaps as in joint mode). The same targets reach the
motion generator as in joint mode, the expert builds with it, `record --action-mode relative`
writes its actions so and a replay of them builds, and `evaluate` scores a policy in it."""

import json

import gymnasium
import numpy as np
import pyarrow.parquet as pq
import pytest

import pyramid_sim
from pyramid_sim.learning.action_modes.relative import LEAD, led

pytestmark = pytest.mark.physics
TASK = {"structure": "pyramid-even", "layers": 1}


def _env(mode: str, variation: str = "fixed"):
    return gymnasium.make(
        pyramid_sim.ENV_ID, action_mode=mode, variation=variation, **TASK
    ).unwrapped


def _joints(env) -> np.ndarray:
    return env.layout.joints


def test_a_relative_action_is_the_joint_target_less_where_the_joints_are():
    relative, joint = _env("relative"), _env("joint")
    first, _ = relative.reset(seed=0)
    joint.reset(seed=0)
    joints = _joints(joint)
    wanted = joint.expert_action().astype(np.float64)
    wanted[joints] -= first["state"][joints]
    np.testing.assert_allclose(relative.expert_action(), wanted, atol=1e-6)
    # Each joint may move its range's span either way; a gap is a gap, as in joint mode.
    space = relative.action_space
    span = joint.action_space.high - joint.action_space.low
    np.testing.assert_allclose(space.high[joints], span[joints])
    np.testing.assert_allclose(space.low[joints], -span[joints])
    assert np.array_equal(space.high[~joints], joint.action_space.high[~joints])
    # The same command, so the same motion (to float32's rounding of the change).
    after_relative = relative.step(relative.expert_action())[0]["state"]
    after_joint = joint.step(joint.expert_action())[0]["state"]
    np.testing.assert_allclose(after_relative, after_joint, atol=1e-6)


def test_no_change_holds_the_arms_where_they_are():
    env = _env("relative")
    observation, _ = env.reset(seed=0)
    start = observation["state"].copy()
    joints = _joints(env)
    hold = np.where(joints, 0.0, start).astype(np.float32)  # the gaps as they are
    for _ in range(25):  # a second
        observation, _, terminated, truncated, _ = env.step(hold)
        assert not (terminated or truncated)
    assert np.abs(observation["state"] - start)[joints].max() < 1e-3


def test_a_change_past_a_joints_range_stops_at_its_end():
    env = _env("relative")
    observation, _ = env.reset(seed=0)
    joints = _joints(env)
    push = np.where(joints, env.action_space.high, observation["state"]).astype(np.float32)
    env.step(push)
    np.testing.assert_array_equal(env.generator._target[joints], env.layout.high[joints])


def test_the_expert_builds_in_relative_mode():
    env = _env("relative", variation="layout")
    env.reset(seed=3)
    while True:
        _, _, terminated, truncated, info = env.step(env.expert_action())
        if terminated or truncated:
            break
    assert terminated and info["is_success"] and info["result"]["bricks_placed"] == 2


def test_a_relative_recording_replays_into_its_build_and_keeps_its_mode(tmp_path, replay):
    root = tmp_path / "d"
    recorded = pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, cameras=(), action_mode="relative"
    )
    assert recorded.failed == ()
    doc = json.loads((root / "meta/pyramid_sim/dataset.json").read_text())
    assert doc["action_mode"] == "relative"
    frames = pq.read_table(root / "data/chunk-000/file-000.parquet").to_pydict()
    states, actions = np.array(frames["observation.state"]), np.array(frames["action"])
    env = _env("relative", variation="layout")
    joints = _joints(env)
    # A relative action is small beside the posture it changes.
    assert np.median(np.abs(actions[:, joints])) < 0.05 < 0.5 < np.median(np.abs(states[:, joints]))
    terminated, info = replay(env, actions)
    assert terminated and info["is_success"]
    with pytest.raises(pyramid_sim.ConfigError, match='action_mode "relative", this run "joint"'):
        pyramid_sim.record("pyramid-even", out=root, layers=1, episodes=2, cameras=())


def test_evaluate_scores_a_policy_in_its_action_mode(tmp_path):
    scored = pyramid_sim.evaluate(
        "expert", "pyramid-even", layers=1, out=tmp_path / "e", episodes=1, action_mode="relative"
    )
    assert scored.success_rate == 1.0
    written = json.loads((tmp_path / "e/evaluation.json").read_text())
    assert written["task"]["action_mode"] == "relative" and written["successes"] == 1
    with pytest.raises(
        pyramid_sim.ConfigError,
        match="accepted joint, relative, waypoint, anchored, delta or absolute",
    ):
        pyramid_sim.record(
            "pyramid-even", out=tmp_path / "r", layers=1, cameras=(), action_mode="ee"
        )
    assert not (tmp_path / "r").exists()


def test_a_target_far_ahead_is_brought_within_the_lead_along_its_way():
    env = _env("relative")
    observation, _ = env.reset(seed=0)
    state, joints = observation["state"], _joints(env)
    far = state.copy()
    far[joints] += np.linspace(-0.5, 1.0, joints.sum())
    far[~joints] = 0.01  # the gaps: not an arm's lead
    near = led(far, state, env.layout, 0.2)
    change = near[joints] - state[joints]
    assert np.abs(change).max() == pytest.approx(0.2)
    np.testing.assert_allclose(change / 0.2, (far - state)[joints] / 1.0)  # the same way
    assert np.array_equal(near[~joints], far[~joints])
    within = state.copy()
    within[joints] += 0.05
    assert np.array_equal(led(within, state, env.layout, 0.2), within)


def test_the_experts_relative_actions_never_lead_the_arm_by_more_than_its_lead():
    env = _env("relative", "layout")
    observation, _ = env.reset(seed=3)
    joints, ahead, asked = _joints(env), 0.0, 0.0
    expert = env._expert
    while True:
        action = env.expert_action()
        asked = max(asked, np.abs(action[joints]).max())
        ahead = max(ahead, np.abs(expert._last - observation["state"])[joints].max())
        observation, _, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            break
    assert info["is_success"]
    assert ahead > 2 * LEAD  # the IK ran ahead of the arm ...
    assert asked <= LEAD + 1e-5  # ... and the actions asked for did not
