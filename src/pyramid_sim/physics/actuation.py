"""What a build sends its actuators, a part of the loop it is given (physics/parts.py): the
IK's joint solution and the hands' gaps as one command, ramped across a control step's physics
steps, each step watched by the monitor and handed to the hooks."""

from __future__ import annotations

import mujoco
import numpy as np

from ..config import SimConfig
from . import names as c
from .handles import SceneHandles
from .hooks import BuildHooks
from .ik import DualArmIK
from .monitor import StepMonitor
from .sag import SagOffset


class Actuation:
    """The command in `handles.ctrl_index` order (each arm's joints, then its gripper), aimed
    past the sag where the servos sag, and the physics steps towards it."""

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        handles: SceneHandles,
        ik: DualArmIK,
        config: SimConfig,
        monitor: StepMonitor,
    ) -> None:
        self.model, self.data, self.ik, self.monitor = model, data, ik, monitor
        self._index = handles.ctrl_index
        self._ramp = np.arange(1, config.substeps + 1)[:, None] / config.substeps
        self._ik_q = np.concatenate([ik.qadr[a] for a in c.ARMS])
        joints = len(ik.qadr["left"])
        self._command = np.zeros(len(handles.ctrl_index))
        self._gap = np.array([joints, 2 * joints + 1])
        self._q = np.setdiff1d(np.arange(len(handles.ctrl_index)), self._gap)
        robot = config.robot_description
        self._sag = None if robot.gravity_compensation else SagOffset(ik.model, robot)
        self._next_frame = 0.0  # sim time of the hooks' next frame

    def command(self, gaps: list[float]) -> np.ndarray:
        """The IK's joint solution and the hands' `gaps` (left first) as a command (a view,
        rewritten each control step)."""
        command = self._command
        command[self._q] = self.ik.q[self._ik_q]
        if self._sag is not None:  # servos that sag: aim past the target by the sag
            command[self._q] += self._sag(self.ik.q[self._ik_q])
        command[self._gap] = gaps
        return command

    def step(self, command: np.ndarray, hooks: BuildHooks) -> tuple[bool, int]:
        """The joint and gripper targets, ramped across the physics steps (stepped targets
        jolt the held brick): whether MuJoCo raised a warning, and the steps taken."""
        m, d, ctrl = self.model, self.data, self.data.ctrl
        change = np.zeros_like(ctrl)
        change[self._index] = command - ctrl[self._index]
        ramp = ctrl + change * self._ramp
        warned = False
        for k in range(len(ramp)):
            ctrl[:] = ramp[k]
            mujoco.mj_step(m, d)
            warned = self.monitor.record()
            if warned:
                break
            if hooks.on_step is not None:
                hooks.on_step(d)
            if (
                hooks.on_frame is not None
                and hooks.frame_dt is not None
                and d.time >= self._next_frame - 1e-9
            ):
                hooks.on_frame(m, d)
                self._next_frame += hooks.frame_dt
        return warned, k + 1
