"""A Panda's IK holds the arm's twist near home: joint 3 (the upper arm's roll, the one joint
a 7-joint arm has to spare) is pulled towards home harder than the rest. Without it, over a
6-brick build, the left arm drifted to a twisted shoulder (joints 1 and 3 far apart, joint 2
near upright) where the servo down to the spot swung joints 1 and 3 against each other, the
hand 15-25 mm sideways, and a finger struck the brick (docs/learning.md)."""

import dataclasses

import numpy as np

import pyramid_sim.config
from pyramid_sim.config import SimConfig
from pyramid_sim.learning.env.env import BuildEnv
from pyramid_sim.learning.recording.episode import step_limit
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.robots import robot

# The left arm's joints where it began the servo that struck the brick (seed 100038).
TWISTED = np.array([0.723, -0.243, -1.409, -2.574, -0.405, 2.494, -1.131])


def _unweighted(monkeypatch) -> None:
    """The Panda with every joint pulled towards home alike (as before the weights)."""
    arms = {
        a: dataclasses.replace(arm, posture_weights=()) for a, arm in robot("panda").arms.items()
    }
    plain = dataclasses.replace(robot("panda"), arms=arms)
    monkeypatch.setattr(pyramid_sim.config, "robot", lambda name: plain)


def _untwist() -> tuple[float, float]:
    """Joint 3 (rad) after 2 s of IK steps holding the left hand where the twisted arm has it,
    and how far (m) the hand then is from there."""
    ik = DualArmIK(SimConfig())
    ik.reset(TWISTED, ik.home("right"))
    hand = ik.tcp_pose("left")
    ik.set_target("left", hand)
    for _ in range(200):
        ik.step()
    now = ik.tcp_pose("left")
    return float(ik.arm_q("left")[2]), float(np.linalg.norm(now.position - hand.position))


def test_the_weight_on_the_twist_reaches_the_ik(monkeypatch):
    assert robot("panda").arms["left"].posture_weights[2] > 1.0
    joint3, off = _untwist()
    assert abs(joint3) < 0.05  # turned back to home's 0 from -1.41 ...
    assert off < 0.001  # ... in the null space: the hand where it was
    _unweighted(monkeypatch)
    joint3, _ = _untwist()
    assert joint3 < -1.2  # the twist stays


def _six_bricks(seed: int) -> dict:
    env = BuildEnv("pyramid-even", layers=2, variation="layout", action_mode="joint")
    env.reset(seed=seed)
    for _ in range(step_limit(len(env.plan.bricks), env.fps)):
        _, _, terminated, truncated, info = env.step(env.expert_action())
        if terminated or truncated:
            break
    env.close()
    return info


def test_the_expert_builds_six_bricks_where_the_twisted_arm_struck_one():
    info = _six_bricks(100_038)
    assert info["is_success"], info["failure"]
    assert info["bricks_placed"] == 6


def test_without_the_weight_the_twisted_arm_strikes_the_brick(monkeypatch):
    _unweighted(monkeypatch)
    info = _six_bricks(100_038)
    assert not info["is_success"]
    assert "torque limit" in info["failure"]
    assert info["bricks_placed"] == 2
