"""The joint modes' expert damps the Panda's twist (joints 1 and 3 turned against each
other) in its IK: on seed 100038 of the 6-brick pyramid that turn, at full speed on the way
down to the third brick, swung the hand across the spot and a finger struck the brick."""

import dataclasses

import numpy as np
import pytest

import pyramid_sim.learning.expert.closure as closure
from pyramid_sim.config import SimConfig
from pyramid_sim.learning.env.env import BuildEnv
from pyramid_sim.learning.expert.twist_damping import TWIST_DAMPING, damp_twist
from pyramid_sim.learning.recording.episode import step_limit
from pyramid_sim.physics import names as c
from pyramid_sim.physics.handles import dof_addresses
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.robots import robot


def test_the_twist_damping_reaches_the_ik_objective_and_nothing_else():
    ik = DualArmIK(SimConfig())
    plain, c_plain = ik.problem.objective()
    damp_twist(ik)
    damp_twist(ik)  # again: replaces, does not add
    damped, c_damped = ik.problem.objective()
    expected = np.zeros_like(plain)
    for arm in c.ARMS:
        joints = robot("panda").arms[arm].joints
        first, third = dof_addresses(ik.model, (joints[0], joints[2]))
        expected[[first, third], [first, third]] = TWIST_DAMPING
        expected[[first, third], [third, first]] = -TWIST_DAMPING
    np.testing.assert_allclose(damped - plain, expected, atol=1e-12)
    np.testing.assert_array_equal(c_damped, c_plain)
    damp_twist(ik, 0.0)
    np.testing.assert_allclose(ik.problem.objective()[0], plain, atol=1e-12)


def test_a_twist_pair_outside_the_arm_is_refused():
    arm = robot("panda").arms["left"]
    with pytest.raises(ValueError, match="twist_pair"):
        dataclasses.replace(arm, twist_pair=(0, 7))


def _six_bricks(seed: int) -> dict:
    env = BuildEnv("pyramid-even", layers=2, variation="layout", action_mode="joint")
    env.reset(seed=seed)
    for _ in range(step_limit(len(env.plan.bricks), env.fps)):
        _, _, terminated, truncated, info = env.step(env.expert_action())
        if terminated or truncated:
            break
    env.close()
    return info


def test_the_expert_builds_where_the_twist_swung_the_hand():
    info = _six_bricks(100_038)
    assert info["is_success"], info["failure"]
    assert info["bricks_placed"] == 6


def test_without_the_damping_the_hand_strikes_the_brick(monkeypatch):
    monkeypatch.setattr(closure, "damp_twist", lambda ik: None)
    info = _six_bricks(100_038)
    assert not info["is_success"]
    assert "torque limit" in info["failure"]
    assert info["bricks_placed"] == 2
