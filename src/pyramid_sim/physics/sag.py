"""Commands that allow for a servo's sag: an arm whose servos hold its weight by their
position error (no gravity compensation, as the SO-101's STS3215) stops short of every
target by the gravity torque over the servo's stiffness. The builder aims past the target by
that much, from the model's own gravity at the IK's joints: a controller's choice a real arm's
driver could make the same way. The physics is unchanged; the command is what moves."""

from __future__ import annotations

import mujoco
import numpy as np

from ..choices import ARMS
from ..robots import RobotDescription
from .handles import qpos_addresses


class SagOffset:
    """Per arm joint, the gravity torque at given joint values over the servo's kp."""

    def __init__(self, model: mujoco.MjModel, robot: RobotDescription) -> None:
        self.model, self.data = model, mujoco.MjData(model)
        joints = tuple(j for a in ARMS for j in robot.arms[a].joints)
        self.qadr = np.array(qpos_addresses(model, joints))
        self.dofadr = np.array([model.joint(j).dofadr[0] for j in joints])
        self.kp = np.array([k for a in ARMS for k in robot.arms[a].kp])

    def __call__(self, q: np.ndarray) -> np.ndarray:
        """The offsets for both arms' joint values `q` (left then right, as the command)."""
        self.data.qpos[self.qadr] = q
        mujoco.mj_kinematics(self.model, self.data)
        mujoco.mj_comPos(self.model, self.data)
        self.data.qvel[:] = 0.0
        mujoco.mj_rne(self.model, self.data, 0, self.data.qfrc_bias)
        return np.asarray(self.data.qfrc_bias[self.dofadr] / self.kp)
