"""Name-to-address lookups of a compiled scene, written once: the loop, the spawner, the
monitors and the tests all index MjData through these."""

from __future__ import annotations

import mujoco
import numpy as np

from . import names as c


def arm_qpos_addresses(model: mujoco.MjModel, arm: str) -> np.ndarray:
    """qpos addresses of one arm's seven joints in `model`."""
    return np.array([model.joint(c.prefixed(arm, j)).qposadr[0] for j in c.ARM_JOINTS])


def arm_dof_addresses(model: mujoco.MjModel, arm: str) -> np.ndarray:
    """dof addresses of one arm's seven joints in `model`."""
    return np.array([model.joint(c.prefixed(arm, j)).dofadr[0] for j in c.ARM_JOINTS])


class SceneHandles:
    """Addresses of the arms' joints, actuators, fingers, tool sites and zone bodies, and of
    every brick in the magazine (by slot)."""

    def __init__(self, model: mujoco.MjModel, n_bricks: int) -> None:
        self.arm_qpos = {a: arm_qpos_addresses(model, a) for a in c.ARMS}
        self.arm_dofs = {a: arm_dof_addresses(model, a) for a in c.ARMS}
        self.arm_actuators = {
            a: np.array([model.actuator(c.prefixed(a, j)).id for j in c.ARM_JOINTS]) for a in c.ARMS
        }
        self.gripper = {a: model.actuator(c.prefixed(a, c.GRIPPER_ACTUATOR)).id for a in c.ARMS}
        self.finger_qpos = {
            a: [model.joint(c.prefixed(a, j)).qposadr[0] for j in c.FINGER_JOINTS] for a in c.ARMS
        }
        self.tcp_site = {a: model.site(c.prefixed(a, c.TCP_SITE)).id for a in c.ARMS}
        self.zone_bodies = {
            a: [model.body(c.prefixed(a, b)).id for b in c.ZONE_BODIES] for a in c.ARMS
        }
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

    def place_brick(self, data: mujoco.MjData, slot: int, position, quat=None) -> None:
        """Put the brick in `slot` at `position` (and `quat`), at rest."""
        q, v = self.brick_qpos[slot], self.brick_dofs[slot]
        data.qpos[q : q + 3] = position
        if quat is not None:
            data.qpos[q + 3 : q + 7] = quat
        data.qvel[v : v + 6] = 0.0
