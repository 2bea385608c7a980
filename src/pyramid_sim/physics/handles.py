"""Name-to-address lookups of a compiled scene, written once: the loop, the spawner, the
monitors and the tests all index MjData through these."""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

from ..robots import RobotDescription
from . import names as c


def qpos_addresses(model: mujoco.MjModel, joints: tuple[str, ...]) -> np.ndarray:
    """qpos addresses of the named joints in `model`."""
    return np.array([model.joint(j).qposadr[0] for j in joints])


def dof_addresses(model: mujoco.MjModel, joints: tuple[str, ...]) -> np.ndarray:
    """dof addresses of the named joints in `model`."""
    return np.array([model.joint(j).dofadr[0] for j in joints])


class SceneHandles:
    """Addresses of the arms' joints, actuators, fingers, tool sites and zone bodies, and of
    every brick in the magazine (by slot)."""

    def __init__(self, model: mujoco.MjModel, robot: RobotDescription, n_bricks: int) -> None:
        arms = robot.arms
        self.arm_qpos = {a: qpos_addresses(model, arms[a].joints) for a in c.ARMS}
        self.arm_dofs = {a: dof_addresses(model, arms[a].joints) for a in c.ARMS}
        # Each arm joint's servo is named as the joint it drives.
        self.arm_actuators = {
            a: np.array([model.actuator(j).id for j in arms[a].joints]) for a in c.ARMS
        }
        self.gripper = {a: model.actuator(arms[a].gripper_actuator).id for a in c.ARMS}
        self.finger_qpos = {a: list(qpos_addresses(model, arms[a].finger_joints)) for a in c.ARMS}
        self.finger_gains = robot.finger_gains  # m of gap a unit of each finger's travel
        self.tcp_site = {a: model.site(arms[a].tcp_site).id for a in c.ARMS}
        self.zone_bodies = {a: [model.body(b).id for b in arms[a].zone_bodies] for a in c.ARMS}
        joints = [model.joint(c.brick_name(i) + "joint") for i in range(n_bricks)]
        self.brick_qpos = [j.qposadr[0] for j in joints]
        self.brick_dofs = [j.dofadr[0] for j in joints]
        self.brick_body = [model.body(c.brick_name(i) + "brick").id for i in range(n_bricks)]
        # The control vector's layout: the arm joint targets then the gripper gap, per arm.
        self.ctrl_index = np.concatenate(
            [np.append(self.arm_actuators[a], self.gripper[a]) for a in c.ARMS]
        )

    @property
    def n_bricks(self) -> int:
        return len(self.brick_body)

    def place_brick(
        self,
        data: mujoco.MjData,
        slot: int,
        position: Sequence[float] | np.ndarray,
        quat: Sequence[float] | np.ndarray | None = None,
    ) -> None:
        """Put the brick in `slot` at `position` (and `quat`), at rest."""
        q, v = self.brick_qpos[slot], self.brick_dofs[slot]
        data.qpos[q : q + 3] = position
        if quat is not None:
            data.qpos[q + 3 : q + 7] = quat
        data.qvel[v : v + 6] = 0.0
