"""An episode asked to linger goes on after its success for that long, its reward spent, so a
recording films the last release and the hands leaving; a failure in that time takes the
success back; without it, the episode ends at the success, as an evaluation's does."""

import gymnasium
import numpy as np
import pytest

import pyramid_sim

ENV = pyramid_sim.ENV_ID


def _to_success(env, seed=0):
    """The expert's steps up to the first whose info says the build succeeded."""
    env.reset(seed=seed)
    rewards = []
    while True:
        obs, reward, terminated, truncated, info = env.step(env.expert_action())
        rewards.append(reward)
        if info["is_success"] or terminated or truncated:
            return obs, rewards, terminated, info


def test_an_episode_lingers_as_long_as_asked_and_films_the_hands_leaving():
    """Each episode of one environment (a recording's worker films many)."""
    env = gymnasium.make(ENV, structure="pyramid-even", layers=1, fps=10, linger=1.0).unwrapped
    for seed in (0, 1):
        obs, rewards, terminated, info = _to_success(env, seed)
        assert info["is_success"] and not terminated and sum(rewards) == 2
        hands_then = obs["tools"][:, 2].copy()
        after = 0
        while not terminated:
            obs, reward, terminated, truncated, info = env.step(env.expert_action())
            after += 1
            assert reward == 0.0 and not truncated
        assert after == 10 and info["is_success"] and info["failure"] is None, seed
        assert info["result"]["bricks_placed"] == 2
        assert (obs["tools"][:, 2] - hands_then).max() > 0.03  # the last hand rose off its brick
    env.close()


def test_without_linger_the_episode_ends_at_its_success():
    env = gymnasium.make(ENV, structure="pyramid-even", layers=1, fps=10).unwrapped
    _, rewards, terminated, info = _to_success(env)
    assert terminated and info["is_success"] and sum(rewards) == 2
    env.close()


def test_a_failure_while_lingering_takes_the_success_back():
    """A wild action after the build stood (no motion generator between it and the servos)."""
    env = gymnasium.make(
        ENV, structure="pyramid", layers=1, fps=10, linger=1.0, limit_commands=False
    ).unwrapped
    _, _, terminated, info = _to_success(env)
    assert info["is_success"] and not terminated
    _, _, terminated, _, info = env.step(env.action_space.high.astype(np.float32))
    assert terminated and not info["is_success"]
    assert "of its velocity limit" in info["failure"]
    env.close()


@pytest.mark.parametrize("linger", [-0.5, 10.5])
def test_a_linger_out_of_range_is_refused(linger):
    with pytest.raises(pyramid_sim.ConfigError, match=r"linger: .* accepted \[0, 10\]"):
        gymnasium.make(ENV, structure="pyramid", layers=1, linger=linger)
