"""`brick_poses=False` (`record --no-brick-poses`): a policy that sees the bricks through its
cameras alone. Its observation holds neither the bricks' poses nor the goals' fill (judged
from them); the physics is the same; a recording says so, its width is its own, a run with
poses is refused on resuming it, and a checkpoint trained on one is evaluated without them."""

import json

import gymnasium
import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.learning.lerobot_plugin.checkpoint_inputs import checkpoint_views
from pyramid_sim.learning.task.spaces import environment_state

TASK = dict(structure="pyramid-even", layers=1, fps=10, action_mode="anchored")


def test_the_observation_holds_no_brick_pose_and_the_physics_is_the_same():
    seen = gymnasium.make("pyramid_sim/Build-v0", **TASK).unwrapped
    blind = gymnasium.make("pyramid_sim/Build-v0", brick_poses=False, **TASK).unwrapped
    assert set(seen.observation_space.spaces) - set(blind.observation_space.spaces) == {
        "bricks",
        "placed",
    }
    obs_seen, _ = seen.reset(seed=100000)
    obs_blind, _ = blind.reset(seed=100000)
    for _ in range(30):
        action = seen.expert_action()
        assert np.array_equal(action, blind.expert_action())
        obs_seen, *_ = seen.step(action)
        obs_blind, *_ = blind.step(action)
    assert blind.observation_space.contains(obs_blind)
    assert np.array_equal(seen.loop.data.qpos, blind.loop.data.qpos)
    names = pyramid_sim.environment_names(seen.layout.bricks, 2, brick_poses=False)
    assert len(environment_state(obs_blind)) == len(names)
    assert not [n for n in names if n.startswith("brick") or n.endswith(".placed")]
    assert len(environment_state(obs_seen)) - len(names) == seen.layout.bricks * 7 + 2


@pytest.fixture(scope="module")
def blind_recording(tmp_path_factory):
    root = tmp_path_factory.mktemp("blind") / "d"
    pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, fps=10, cameras=(), linger=0.0,
        action_mode="anchored", brick_poses=False,
    )  # fmt: skip
    return root


def test_a_recording_without_brick_poses_says_so_and_has_its_own_width(blind_recording):
    root = blind_recording
    info = json.loads((root / "meta/info.json").read_text())
    names = info["features"]["observation.environment_state"]["names"]
    assert not [n for n in names if n.startswith("brick")] and "pick.x" in names
    assert json.loads((root / "meta/pyramid_sim/dataset.json").read_text())["brick_poses"] is False
    record = json.loads((root / "meta/pyramid_sim/episode_000000.json").read_text())
    assert record["config"]["brick_poses"] is False
    with pytest.raises(pyramid_sim.ConfigError, match="brick_poses false, this run true"):
        pyramid_sim.record(
            "pyramid-even", out=root, layers=1, episodes=2, fps=10, cameras=(), linger=0.0,
            action_mode="anchored",
        )  # fmt: skip


def test_a_default_recording_says_nothing_of_brick_poses(tmp_path):
    """The default, which every recording before the option held: their files stay as they
    were, byte for byte."""
    root = tmp_path / "d"
    pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, fps=10, cameras=(), linger=0.0,
        action_mode="anchored",
    )  # fmt: skip
    assert "brick_poses" not in (root / "meta/pyramid_sim/dataset.json").read_text()
    assert "brick_poses" not in (root / "meta/pyramid_sim/episode_000000.json").read_text()


def test_a_checkpoint_trained_without_brick_poses_is_evaluated_without_them(
    blind_recording, tmp_path
):
    folder = tmp_path / "ckpt"
    folder.mkdir()
    (folder / "config.json").write_text(json.dumps({"input_features": {}}))
    train = {"dataset": {"root": str(blind_recording)}, "output_dir": str(tmp_path / "t")}
    (folder / "train_config.json").write_text(json.dumps(train))
    assert checkpoint_views(str(folder)) == {"brick_poses": False}


def test_with_each_arms_next_goal_alone_every_size_is_observed_alike(tmp_path):
    """`all_goals=False` (`record --next-goals-only`): neither every goal nor their fill, so
    the observation's width is the same for the 2-, 6- and 20-brick pyramids; a recording
    says so."""
    widths = set()
    for layers in (1, 2, 4):
        env = gymnasium.make(
            "pyramid_sim/Build-v0", structure="pyramid-even", layers=layers, fps=10,
            action_mode="anchored", brick_poses=False, all_goals=False,
        ).unwrapped  # fmt: skip
        observation, _ = env.reset(seed=100000)
        assert set(observation) == {"state", "pick", "next", "tools", "held"}
        assert env.observation_space.contains(observation)
        widths.add(len(environment_state(observation)))
        env.close()
    assert widths == {len(pyramid_sim.environment_names(9, 6, False, False))} == {22}
    root = tmp_path / "d"
    pyramid_sim.record(
        "pyramid-even", out=root, layers=1, episodes=1, fps=10, cameras=(), linger=0.0,
        action_mode="anchored", brick_poses=False, all_goals=False,
    )  # fmt: skip
    doc = json.loads((root / "meta/pyramid_sim/dataset.json").read_text())
    assert doc["all_goals"] is False and doc["brick_poses"] is False
    info = json.loads((root / "meta/info.json").read_text())
    assert info["features"]["observation.environment_state"]["shape"] == [22]
