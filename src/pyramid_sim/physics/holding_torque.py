"""The torque an arm needs to hold a brick still at a plan's poses, as a share of its limits.

Standing still, a joint's servo and its gravity compensation together carry the weight of
every link beyond it and of the brick in the hand; what is left of the limit is all the arm
has to move with. Baxter's shoulder s1 spends 40-46 of its 50 N m so wherever the `layout`
variation puts a structure near the edge of its reach, and any motion then took it past the
limit (docs/notes/2026-11-28-baxter-holding.md). Turning the elbow about the
shoulder-wrist line changes that load by under 6 % (the load is set by how far the hand
stands out from the shoulder), so no posture of the IK frees it.

Every pose is weighed as if the hand held its brick: a bound from above, exact where it
matters (the far poses are the place's, where the brick is held).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ..config import SimConfig
from ..core.plan import Plan
from .reach import ReachChecker, plan_poses

GRAVITY = 9.81  # m/s^2


@dataclass(frozen=True)
class HoldingLoad:
    """The largest share of a joint's torque limit a plan's holding takes, and where."""

    share: float  # of the joint's limit, gravity compensation and servo together
    joint: str
    where: str  # the pose, as `plan_poses` names it

    def describe(self) -> str:
        return f"{self.where}: {self.joint} holds the arm and its brick at {self.share:.2f}"


def holding_load(checker: ReachChecker, plan: Plan, config: SimConfig) -> HoldingLoad:
    """The worst static share over every pose of `plan`, each in the posture the reach
    check's IK solved it in, the brick's weight hung at the tool centre."""
    model = checker.ik.model
    data = mujoco.MjData(model)
    weight = np.array([0.0, 0.0, config.brick.mass * GRAVITY])
    jacobian = np.zeros((3, model.nv))
    worst = HoldingLoad(0.0, "", "")
    for arm_name, what, pose in plan_poses(plan, config):
        arm = config.robot_description.arms[arm_name]
        dofs = np.array([model.joint(j).dofadr[0] for j in arm.joints])
        data.qpos[:] = checker.posture(arm_name, pose)
        data.qvel[:] = 0.0
        mujoco.mj_forward(model, data)  # at rest, qfrc_bias is the links' weight
        mujoco.mj_jacSite(model, data, jacobian, None, model.site(arm.tcp_site).id)
        torque = data.qfrc_bias[dofs] + jacobian[:, dofs].T @ weight
        shares = np.abs(torque) / np.asarray(arm.torque_limits)
        k = int(shares.argmax())
        if shares[k] > worst.share:
            worst = HoldingLoad(float(shares[k]), arm.joints[k].split("/")[-1], what)
    return worst
