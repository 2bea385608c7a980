"""The build as a Gymnasium environment: it passes Gymnasium's own checker, the scripted
expert rolled out in it builds what `build` builds, the same seed gives the same episode,
random actions end an episode with a reason rather than an error, and two environments step
side by side in an AsyncVectorEnv."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pyramid_sim

ENV = pyramid_sim.ENV_ID


def _rollout(env, seed: int, steps: int | None = None):
    """The expert's episode from `seed`: every observation's state and bricks, rewards, and
    the last step's flags and info."""
    obs, _ = env.reset(seed=seed)
    states, rewards = [obs["state"]], []
    n = 0
    while True:
        obs, reward, terminated, truncated, info = env.step(env.unwrapped.expert_action())
        states.append(obs["state"])
        rewards.append(reward)
        n += 1
        if terminated or truncated or (steps is not None and n >= steps):
            return np.array(states), obs, rewards, terminated, truncated, info


def test_gymnasiums_checker_passes():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    check_env(env.unwrapped, skip_render_check=True)
    env.close()


def test_the_expert_builds_what_build_builds():
    env = gymnasium.make(ENV, structure="pyramid-even", layers=2, robot="panda")
    _, obs, rewards, terminated, truncated, info = _rollout(env, seed=3)
    assert terminated and not truncated and info["is_success"] and info["failure"] is None
    assert sum(rewards) == 6 and info["bricks_placed"] == 6
    built = pyramid_sim.build("pyramid-even", layers=2, seed=3)
    assert built.success
    final = {b["index"]: b for b in info["result"]["bricks"]}
    for brick in built.bricks:
        ours = np.array(final[brick.index]["final"]["position"])
        assert np.linalg.norm(ours - np.array(brick.final.position)) < 0.0005, brick.index
    env.close()


def test_the_same_seed_gives_the_same_episode_bit_for_bit():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    first, obs1, rewards1, *_ = _rollout(env, seed=7, steps=400)
    second, obs2, rewards2, *_ = _rollout(env, seed=7, steps=400)
    assert np.array_equal(first, second) and rewards1 == rewards2
    assert np.array_equal(obs1["bricks"], obs2["bricks"])
    other, *_ = _rollout(env, seed=8, steps=400)  # the spawn jitter of another seed
    assert other.shape == first.shape
    env.close()


def test_random_actions_end_an_episode_with_a_reason_never_an_error():
    env = gymnasium.make(ENV, structure="pyramid", layers=1)
    env.reset(seed=0)
    env.action_space.seed(0)
    ended = None
    for _ in range(200):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs) and reward >= 0
        if terminated or truncated:
            ended = info
            break
    if ended is not None:  # a random arm flails: it ends naming why
        assert ended["failure"] and "result" in ended and not ended["is_success"]
    env.close()


def test_two_environments_step_in_an_async_vector_env():
    envs = gymnasium.vector.AsyncVectorEnv(
        [lambda: gymnasium.make(ENV, structure="pyramid", layers=1)] * 2
    )
    obs, _ = envs.reset(seed=[1, 2])
    assert obs["state"].shape == (2, 16) and obs["bricks"].shape[0] == 2
    for _ in range(3):
        obs, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
    assert rewards.shape == (2,) and not truncated.any()
    envs.close()


def test_a_bad_setting_is_refused_when_the_environment_is_made():
    with pytest.raises(pyramid_sim.ConfigError, match="brick friction"):
        gymnasium.make(ENV, structure="pyramid", layers=1, friction=-1)


def test_rgb_array_renders_the_overview_camera():
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    env = gymnasium.make(
        ENV, structure="pyramid", layers=1, render_mode="rgb_array", render_size=(120, 160)
    )
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (120, 160, 3) and frame.dtype == np.uint8 and frame.mean() > 60
    env.close()


def test_cameras_asked_for_are_observed_at_their_size():
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    cameras = ("overview", "left_wrist", "right_wrist")
    env = gymnasium.make(ENV, structure="pyramid", layers=1, cameras=cameras, image_size=(48, 64))
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs) and tuple(obs["images"]) == cameras
    for image in obs["images"].values():
        assert image.shape == (48, 64, 3) and image.dtype == np.uint8 and image.std() > 5
    obs, *_ = env.step(env.unwrapped.expert_action())
    assert set(obs["images"]) == set(cameras)
    env.close()
    with pytest.raises(pyramid_sim.ConfigError, match="cameras: unknown 'nose'"):
        gymnasium.make(ENV, structure="pyramid", layers=1, cameras=("nose",))


def test_an_expert_episode_is_kept_at_the_datasets_rate():
    """A frame every 100 / fps control steps, each with the observation before its action,
    the reward of the steps it spans, what each arm was doing; the last one done."""
    import os

    from pyramid_sim.learning.episode import PRIMITIVES, expert_episode

    os.environ.setdefault("MUJOCO_GL", "egl")
    env = gymnasium.make(ENV, structure="pyramid", layers=1, image_size=(32, 32)).unwrapped
    frames = []
    end = expert_episode(
        env, seed=0, fps=25, cameras=("overview", "left_wrist"), on_frame=frames.append
    )
    assert end.success and end.failure is None and end.frames == len(frames)
    steps = round(end.result["sim_time_s"] / 0.01)
    assert len(frames) == -(-steps // 4)  # one frame every 4 control steps, the first at 0
    assert [f.done for f in frames].count(True) == 1 and frames[-1].done
    assert sum(f.reward for f in frames) == 1.0
    assert frames[0].state.dtype == np.float32 and frames[0].action.shape == (16,)
    assert set(frames[0].images) == {"overview", "left_wrist"}
    doing = {PRIMITIVES[p] for f in frames for p in f.primitive}
    assert {"hover", "grip", "release"} <= doing
    assert {b for f in frames for b in f.brick} == {-1, 0}
    env.close()


def test_the_time_limit_truncates_an_episode():
    env = gymnasium.make(
        ENV, structure="pyramid", layers=1, config=pyramid_sim.SimConfig(max_sim_time=1.0)
    )
    _, _, rewards, terminated, truncated, info = _rollout(env, seed=0)
    assert truncated and not terminated and not info["is_success"]
    assert 1.0 < info["sim_time_s"] < 1.02 and "within 1 s" in info["failure"]
    env.close()


def test_end_effector_actions_go_through_the_builds_own_ik():
    """action_mode="ee": each arm's tool-pose change and finger gap. The expert's moves as
    such actions still build the structure; the checker passes."""
    env = gymnasium.make(ENV, structure="pyramid", layers=1, action_mode="ee")
    assert env.action_space.shape == (10,)
    check_env(env.unwrapped, skip_render_check=True)
    _, obs, rewards, terminated, truncated, info = _rollout(env, seed=0)
    assert terminated and info["is_success"] and sum(rewards) == 1
    env.close()
    with pytest.raises(pyramid_sim.ConfigError, match="action mode: unknown 'torque'"):
        gymnasium.make(ENV, structure="pyramid", layers=1, action_mode="torque")


@pytest.mark.parametrize("fault", ["contact", "speed", "torque", "off_table"])
def test_each_episode_failure_fires_and_is_named(fault):
    """What ends an episode though a build would go on: each one, made to happen."""
    from pyramid_sim.learning.outcome import episode_failure

    env = gymnasium.make(ENV, structure="pyramid", layers=1).unwrapped
    env.reset(seed=0)
    loop = env.loop
    assert episode_failure(loop, reduce=True) is None
    if fault == "contact":
        loop.monitor.arm_arm_contacts = 1
    elif fault == "speed":
        loop.monitor.speed_ratio = 1.2
    elif fault == "torque":
        loop.monitor.torque_ratio = 1.3
    else:
        loop.custody.feed_spot()  # a brick on the spot, then knocked to the floor
        q = loop.handles.brick_qpos[0]
        loop.data.qpos[q + 2] = -0.5
    words = {
        "contact": "arm-arm contact",
        "speed": "1.20 of its velocity limit",
        "torque": "1.30 of its torque limit",
        "off_table": "slot 0) left the table",
    }
    assert words[fault] in episode_failure(loop, reduce=False)
    env.close()
