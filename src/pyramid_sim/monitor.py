"""What the physics loop watches every physics step, at a few array copies a step.

Each step's joint speeds, actuator torques, finger positions and arm-arm contact count are
copied into a buffer row; the buffer is reduced once per control step. Per-step Python work is
the cost the build pays over bare `mj_step`, so it is kept to the copies.
"""

from __future__ import annotations

import mujoco
import numpy as np

from . import constants as c


class StepMonitor:
    """Peaks of joint speed and torque (as fractions of the Panda's limits), finger travel past
    its joint range, and the number of arm-arm contacts, over every physics step."""

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        dofs: np.ndarray,
        actuators: np.ndarray,
        fingers: np.ndarray,
        finger_stroke: float,
        substeps: int,
    ) -> None:
        self._qvel, self._qpos = data.qvel, data.qpos  # views into MjData: no per-step lookup
        self._force, self._sensors = data.actuator_force, data.sensordata
        self._dofs, self._acts, self._fingers = dofs, actuators, fingers
        self._contact_adr = int(model.sensor(c.ARM_ARM_SENSOR).adr[0])
        self.stroke = finger_stroke
        self._v = np.zeros((substeps, len(dofs)))
        self._t = np.zeros((substeps, len(actuators)))
        self._f = np.zeros((substeps, len(fingers)))
        self._n = np.zeros(substeps)
        self._inv_vel = 1.0 / np.tile(c.JOINT_VELOCITY_LIMITS, len(dofs) // 7)
        self._inv_torque = 1.0 / np.tile(c.JOINT_TORQUE_LIMITS, len(actuators) // 7)
        self.speed_ratio = 0.0
        self.torque_ratio = 0.0
        self.finger_excess = 0.0  # m past either end of the finger joints' range
        self.arm_arm_contacts = 0

    def record(self, k: int) -> None:
        """Copy physics step `k` (of this control step) into the buffers."""
        np.take(self._qvel, self._dofs, out=self._v[k])
        np.take(self._force, self._acts, out=self._t[k])
        np.take(self._qpos, self._fingers, out=self._f[k])
        self._n[k] = self._sensors[self._contact_adr]

    def reduce(self, steps: int) -> None:
        """Fold the first `steps` recorded rows into the running peaks."""
        v, t, f = self._v[:steps], self._t[:steps], self._f[:steps]
        self.speed_ratio = max(self.speed_ratio, float((np.abs(v) * self._inv_vel).max()))
        self.torque_ratio = max(self.torque_ratio, float((np.abs(t) * self._inv_torque).max()))
        over = max(float(f.max()) - self.stroke, -float(f.min()))
        self.finger_excess = max(self.finger_excess, over)
        self.arm_arm_contacts += int(self._n[:steps].sum())
