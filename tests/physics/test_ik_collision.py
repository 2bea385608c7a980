"""Collision safety beyond the scheduler: the IK keeps the arms apart whatever it is asked."""

import mujoco
import numpy as np
import pytest

from pyramid_sim.config import MotionConfig, SimConfig
from pyramid_sim.core.poses import Pose
from pyramid_sim.core.primitives import clear_pose
from pyramid_sim.physics import names as c
from pyramid_sim.physics.clearance import arm_geoms
from pyramid_sim.physics.handles import SceneHandles
from pyramid_sim.physics.ik import DualArmIK
from pyramid_sim.robots.panda import PANDA

pytestmark = pytest.mark.physics


def _closest_approach_when_both_hands_aim_at_one_point(min_distance: float) -> float:
    config = SimConfig(motion=MotionConfig(arm_min_distance=min_distance))
    ik = DualArmIK(config)
    for arm in c.ARMS:
        ik.solve(arm, clear_pose(arm, PANDA))
    model, data = ik.model, ik.configuration.data
    pairs = [
        (a, b)
        for a in arm_geoms(model, PANDA.arms["left"], PANDA.arms["left"].guarded_bodies)
        for b in arm_geoms(model, PANDA.arms["right"], PANDA.arms["right"].guarded_bodies)
    ]
    fromto = np.zeros(6)
    for arm in c.ARMS:
        ik.set_target(arm, Pose(0.5, 0.0, 0.3, 0.0))
    closest = np.inf
    for _ in range(300):
        ik.step()
        closest = min(
            closest, *(mujoco.mj_geomDistance(model, data, a, b, 1.0, fromto) for a, b in pairs)
        )
    return closest


@pytest.mark.parametrize("min_distance", [0.05, 0.02])
def test_the_ik_keeps_the_arms_apart(min_distance):
    assert _closest_approach_when_both_hands_aim_at_one_point(min_distance) >= min_distance - 1e-3


def test_without_a_margin_the_arms_would_meet():
    assert _closest_approach_when_both_hands_aim_at_one_point(0.0) < 0.005


def test_the_closest_approach_is_measured_from_the_physics():
    """ArmClearance on the physics model: arms turned into each other overlap (negative
    distance); at their clear poses they stand far apart."""
    from pyramid_sim.physics.clearance import ArmClearance
    from pyramid_sim.physics.scene import build_scene

    model = build_scene(SimConfig(), 1).model
    data = mujoco.MjData(model)
    ik = DualArmIK(SimConfig())
    q = {arm: ik.solve(arm, clear_pose(arm, PANDA)) for arm in c.ARMS}
    handles = SceneHandles(model, PANDA, 1)
    for arm in c.ARMS:
        data.qpos[handles.arm_qpos[arm]] = q[arm]
    mujoco.mj_forward(model, data)
    apart = ArmClearance(model, data, PANDA)
    apart.update()
    assert 0.3 < apart.closest < 1.0  # 0.44 m, elbow to fingertips
    reach = [1.2, 0.0, -0.6, 0.0, 1.9, 0.785]
    for arm, yaw in (("left", -1.57), ("right", 1.57)):
        data.qpos[handles.arm_qpos[arm]] = [yaw, *reach]
    mujoco.mj_forward(model, data)
    apart.update()
    assert apart.closest < 0.0 and apart.closest_time == 0.0
