"""What the physics loop watches every physics step, at a few array copies a step, and
whether MuJoCo raised a warning.

Each step copies the spans of qvel, qpos, ctrl and qfrc_gravcomp that hold the arms, and the
arm-arm contact count, into one row of a buffer; the buffer is reduced when full and at the end.
The torque is the one demanded: the servo's unclamped output worked out from its gain and bias
plus the gravity compensation the joint carries (MuJoCo's `actuator_force` is already clamped
to the limit, so it could never show an excess). Per-step
Python work is the price the build pays over bare `mj_step`, so it is kept to these copies
(a contiguous slice copies in a third of the time of a fancy index).
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ..robots import RobotDescription
from . import names as c

ROWS = 500  # physics steps buffered between reductions (1 s at 2 ms)


class _Span:
    """A contiguous view over the addresses `index` of one MjData array, and their columns."""

    def __init__(self, array: np.ndarray, index: np.ndarray) -> None:
        lo, hi = int(index.min()), int(index.max()) + 1
        self.view = array[lo:hi]  # a view into MjData: no lookup per step
        self.columns = np.asarray(index) - lo
        self.buffer = np.zeros((ROWS, hi - lo))

    def rows(self, n: int, part: slice = slice(None)) -> np.ndarray:
        return self.buffer[:n, self.columns[part]]


@dataclass(frozen=True)
class JointLimits:
    """What the monitor holds the state to, in the order of the addresses it is given."""

    velocity: np.ndarray  # rad/s, per arm joint
    torque: np.ndarray  # N m, per arm joint
    finger_low: np.ndarray  # m, per finger joint
    finger_high: np.ndarray


class StepMonitor:
    """Peaks of joint speed and demanded torque (as fractions of the arm's limits), finger
    travel past its joint range, and the number of arm-arm contacts, over every physics step.
    `dofs`, `qpos` and `actuators` list the arm joints in one order (actuator k drives the joint
    at qpos[k] and dof k)."""

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        dofs: np.ndarray,
        qpos: np.ndarray,
        actuators: np.ndarray,
        fingers: np.ndarray,
        limits: JointLimits,
    ) -> None:
        self._speed = _Span(data.qvel, dofs)
        # The arm joints and the fingers lie in one stretch of qpos: one copy a step.
        self._qpos = _Span(data.qpos, np.concatenate([qpos, fingers]))
        self._angles, self._fingers = slice(0, len(qpos)), slice(len(qpos), None)
        self._ctrl = _Span(data.ctrl, actuators)
        self._gravity = _Span(data.qfrc_gravcomp, dofs)
        # A position servo's force before clamping: gain * ctrl + b0 + b1 * q + b2 * qdot.
        self._gain = model.actuator_gainprm[actuators, 0]
        self._bias = model.actuator_biasprm[actuators, :3].T
        self._warnings = data.warning.number  # counts, kept up by MuJoCo
        self._no_warnings = bytes(self._warnings.nbytes)
        # Contact counts MuJoCo keeps: the arms with each other, then with the robot's body.
        self._contact_adr = [int(model.sensor(c.ARM_ARM_SENSOR).adr[0])] + [
            int(model.sensor_adr[s])
            for s in range(model.nsensor)
            if model.sensor(s).name.startswith(c.ARM_BODY_SENSOR)
        ]
        self._contacts = _Span(data.sensordata, np.array(self._contact_adr))
        self._row = 0
        self._finger_low, self._finger_high = limits.finger_low, limits.finger_high
        self._inv_vel = 1.0 / np.asarray(limits.velocity)
        self._inv_torque = 1.0 / np.asarray(limits.torque)
        self.torque_joint: int | None = None  # arm joint (0-based, both arms) of the peak
        self.speed_joint: int | None = None  # the same, of the speed's peak
        self.speed_ratio = 0.0
        self.torque_ratio = 0.0
        self.finger_excess = 0.0  # m past either end of the finger joints' range
        self.arm_arm_contacts = 0
        self.arm_body_contacts = 0  # an arm against the robot's own body (torso, head)

    def record(self) -> bool:
        """Copy the state after one physics step into the buffers; True if MuJoCo raised a
        warning (NaN or a huge value in the state, a full contact buffer...). Comparing the
        counters' bytes costs 0.2 us, so this is checked every physics step."""
        row = self._row
        self._speed.buffer[row] = self._speed.view
        self._qpos.buffer[row] = self._qpos.view
        self._ctrl.buffer[row] = self._ctrl.view
        self._gravity.buffer[row] = self._gravity.view
        self._contacts.buffer[row] = self._contacts.view
        self._row = row + 1
        if self._row == ROWS:
            self.flush()
        return self._warnings.tobytes() != self._no_warnings

    def flush(self) -> None:
        """Fold the buffered steps into the peaks (also call it at the end of a run)."""
        n, self._row = self._row, 0
        if n == 0:
            return
        v, f = self._speed.rows(n), self._qpos.rows(n, self._fingers)
        b0, b1, b2 = self._bias
        servo = (
            self._gain * self._ctrl.rows(n) + b0 + b1 * self._qpos.rows(n, self._angles) + b2 * v
        )
        ratio = np.abs(servo + self._gravity.rows(n)) * self._inv_torque
        per_joint = (np.abs(v) * self._inv_vel).max(axis=0)
        if float(per_joint.max()) > self.speed_ratio:
            self.speed_ratio, self.speed_joint = float(per_joint.max()), int(per_joint.argmax())
        peak = float(ratio.max())
        if peak > self.torque_ratio:
            self.torque_ratio, self.torque_joint = peak, int(ratio.max(axis=0).argmax())
        over = max(float((f - self._finger_high).max()), float((self._finger_low - f).max()))
        self.finger_excess = max(self.finger_excess, over)
        counts = self._contacts.rows(n).sum(axis=0)
        self.arm_arm_contacts += int(counts[0])
        self.arm_body_contacts += int(counts[1:].sum())


def joint_limits(model: mujoco.MjModel, robot: RobotDescription) -> JointLimits:
    """Both arms' limits from the robot's description, left arm first; the fingers' ranges as
    the compiled model has them."""
    arms = [robot.arms[a] for a in c.ARMS]
    fingers = [model.joint(j).id for arm in arms for j in arm.finger_joints]
    low, high = model.jnt_range[fingers].T
    return JointLimits(
        velocity=np.concatenate([arm.velocity_limits for arm in arms]),
        torque=np.concatenate([arm.torque_limits for arm in arms]),
        finger_low=low.copy(),
        finger_high=high.copy(),
    )
