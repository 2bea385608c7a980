"""A task spec taken whole: the environment made from a spec is the one made from its
keywords, bit for bit, and `evaluate` scores on a spec given whole."""

import numpy as np
import pytest

import pyramid_sim
from pyramid_sim.learning.env.env import BuildEnv


def test_a_spec_whole_and_its_keywords_make_the_same_episode():
    keywords = {"layers": 1, "fps": 10, "action_mode": "anchored", "brick_poses": False}
    by_name = BuildEnv("pyramid-even", **keywords)
    whole = BuildEnv(pyramid_sim.TaskSpec("pyramid-even", **keywords))
    for env in (by_name, whole):
        env.reset(seed=7)
    a, b = (env.step(env.expert_action())[0] for env in (by_name, whole))
    assert a.keys() == b.keys() and "bricks" not in a
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
    with pytest.raises(pyramid_sim.ConfigError, match="beside a whole TaskSpec"):
        BuildEnv(whole.task_spec, fps=25)


def test_evaluate_takes_a_spec_whole():
    spec = pyramid_sim.TaskSpec("pyramid-even", layers=1, fps=10, action_mode="waypoint")
    scored = pyramid_sim.evaluate("zero", spec, episodes=1, max_steps=3)
    assert scored.scores["successes"] == 0 and scored.scores["episodes"] == 1
    assert scored.scores["bricks"] == 2
