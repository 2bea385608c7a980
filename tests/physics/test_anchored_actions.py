"""action_mode="anchored": the waypoint mode's poses given from the pick location or each arm's
next target, turned into the waypoint with the anchors the step's observation showed."""

import json

import gymnasium
import numpy as np
import pyarrow.parquet as pq
from gymnasium.utils.env_checker import check_env

import pyramid_sim
from pyramid_sim.learning.recording.episode import JointNoise

ENV = pyramid_sim.ENV_ID


def _env(**options):
    return gymnasium.make(
        ENV, structure="pyramid-even", layers=1, variation="layout", action_mode="anchored",
        **options,
    ).unwrapped  # fmt: skip


def test_the_experts_anchored_actions_build_from_all_three_frames():
    env = _env()
    assert env.action_space.shape == (12,)
    assert env.action_units.names[:6] == (
        "left/anchor", "left/x", "left/y", "left/z", "left/yaw", "left/gripper"
    )  # fmt: skip
    check_env(env, skip_render_check=True)
    env.reset(seed=3)
    anchors, placing = set(), set()
    while True:
        action = env.expert_action()
        anchors |= {float(action[0]), float(action[6])}
        if env.loop.dispatch.runners["left"].current is not None:
            if env.loop.dispatch.runners["left"].current.name == "servo" and action[5] == 0:
                placing.add(float(action[0]))  # the left setting its brick down
        _, _, terminated, truncated, info = env.step(action)
        if terminated or truncated:
            break
    assert terminated and info["is_success"], info["failure"]
    assert anchors == {0.0, 1.0, 2.0} and placing == {2.0}
    env.close()


def test_an_offset_from_the_next_target_takes_the_hand_over_that_target():
    """The anchor reaches the physics: the hand's tool site comes to rest 10 cm above the
    target the observation names as the left arm's next, in an episode of its own layout."""
    env = _env()
    for seed in (1, 2):
        obs, _ = env.reset(seed=seed)
        held = env.held_command()
        action = held.copy()
        action[:6] = [2, 0.0, 0.0, 0.1, 0.0, held[5]]
        for _ in range(60):
            obs, _, terminated, truncated, info = env.step(action)
            assert not (terminated or truncated), info["failure"]
        tool = env.loop.data.site_xpos[env.loop.handles.tcp_site["left"]]
        np.testing.assert_allclose(tool, obs["next"][0][:3] + [0, 0, 0.1], atol=0.005)
        assert np.linalg.norm(tool[:2] - obs["pick"][:2]) > 0.1  # not the pick's frame
    env.close()


def test_darts_noise_on_anchored_actions_moves_the_offsets_only():
    env = _env()
    env.reset(seed=0)
    moved = JointNoise(env, 0, 0.01)(env.expert_action()) - env.expert_action()
    assert np.all(moved[[1, 2, 3, 7, 8, 9]] != 0)  # each hand's x, y, z offset
    assert np.all(moved[[0, 4, 5, 6, 10, 11]] == 0)  # not the anchor, yaw or fingers
    env.close()


def test_an_anchored_recording_names_its_actions_and_replays_into_its_build(tmp_path, replay):
    root = tmp_path / "d"
    recorded = pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, cameras=(), action_mode="anchored",
        variation="layout",
    )  # fmt: skip
    assert recorded.failed == ()
    info = json.loads((root / "meta/info.json").read_text())
    assert info["features"]["action"]["names"][6:10] == [
        "right/anchor", "right/x", "right/y", "right/z"
    ]  # fmt: skip
    names = info["features"]["observation.environment_state"]["names"]
    assert "left_next.x" in names and "right_next.yaw" in names
    frames = pq.read_table(root / "data/chunk-000/file-000.parquet").to_pydict()
    actions = np.array(frames["action"])
    assert set(actions[:, 0]) == {0.0, 1.0, 2.0}
    env = _env()
    terminated, info = replay(env, actions)
    assert terminated and info["is_success"]
    loop = env.unwrapped.loop
    spares = loop.handles.brick_body[len(loop.plan.bricks) :]
    assert len(spares) and np.all(loop.data.xpos[spares][:, 2] < 0)  # none fed: none needed
    env.close()
