"""A failed episode's record says where it failed: the brick and the primitive (the script's
step where the expert drives, the scene's reading where anything else does), read from the
simulation as the episode ends, and evaluation.json carries it."""

import json

from gymnasium.wrappers import TimeLimit

import pyramid_sim
from pyramid_sim.learning.env.env import BuildEnv
from pyramid_sim.learning.evaluation.episodes import run_episode
from pyramid_sim.learning.expert.policy import ExpertPolicy

TASK = {"layers": 1}  # two bricks, the left arm's first
PUSH_AT = 130  # environment steps: the left hand has gripped the first brick and lifts it


class PushedExpert:
    """The expert, its left hand pushed down with 120 N from step `PUSH_AT`: the episode ends
    on a torque limit in the middle of the first pick."""

    def __init__(self, env):
        self.env, self.expert, self.steps = env.unwrapped, ExpertPolicy(env), 0

    def reset(self):
        self.expert.reset()
        self.steps = 0

    def act(self, observation):
        self.steps += 1
        if self.steps == PUSH_AT:
            loop = self.env.loop
            hand = loop.model.site(loop.config.robot_description.arms["left"].tcp_site).bodyid
            loop.data.xfrc_applied[hand, 2] = -120.0
        return self.expert.act(observation)


def test_a_torque_limit_in_the_experts_pick_records_its_brick_and_step():
    env = TimeLimit(BuildEnv("pyramid-even", **TASK), max_episode_steps=400)
    row = run_episode(env, PushedExpert(env), seed=100_000)
    env.close()
    assert "torque limit" in row["failure"] and not row["truncated"]
    at = row["failed_at"]
    assert at["read"] == "script" and at["phase"] == 1  # lockstep: the left arm picks
    assert (at["brick"], at["layer"], at["arm"]) == (0, 0, "left")
    assert at["primitive"] in ("pick grip", "pick retract"), at


def test_a_step_limit_records_where_each_reading_stood(tmp_path):
    """The expert cut short in its first move, and `zero` (no script: the scene read) holding
    still: each on the first brick, its arm reaching for it."""
    for policy in ("expert", "zero"):
        out = tmp_path / policy
        pyramid_sim.evaluate(policy, "pyramid-even", out=out, episodes=1, max_steps=20, **TASK)
        at = json.loads((out / "evaluation.json").read_text())["rows"][0]["failed_at"]
        expected = {"brick": 0, "layer": 0, "arm": "left"}
        assert {k: at[k] for k in expected} == expected
        if policy == "expert":
            assert (at["read"], at["primitive"], at["phase"]) == ("script", "pick hover", 1)
        else:
            assert (at["read"], at["primitive"], at["phase"]) == ("scene", "reaching", None)
        assert (out / "evaluation.png").stat().st_size > 10_000
