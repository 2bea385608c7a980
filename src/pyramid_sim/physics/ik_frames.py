"""The frame tasks' weighted residuals computed straight from the IK's `MjData`: the frame's
Jacobian from MuJoCo (`mj_jacSite`, `mj_jacBody` or `mj_jacGeom`) and its pose error through
mink's own compiled Lie operations. It is the arithmetic of `mink.FrameTask.compute_qp_residual`,
bit for bit, without its Python scaffolding (a name lookup and fresh arrays a call). Where mink
would not use those operations (not built, or `MINK_DISABLE_NATIVE` set), mink's own path is
taken."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TypeGuard

import mink
import mujoco
import numpy as np
from mink import constants

try:  # mink's compiled Lie operations, under the same switch as mink's own use of them
    if os.environ.get("MINK_DISABLE_NATIVE", ""):
        raise ImportError
    from mink.lie import _lie_ops_c as lie
except ImportError:
    lie = None  # type: ignore[assignment]


def plain_frame_task(task: mink.Task) -> TypeGuard[mink.FrameTask]:
    """Whether `task` is mink's own FrameTask, whose terms these are (a subclass may change
    them)."""
    return type(task) is mink.FrameTask


def frame_id(model: mujoco.MjModel, task: mink.FrameTask) -> int:
    """The task's frame as an id, refused with mink's own errors as mink refuses it."""
    kind, name = task.frame_type, task.frame_name
    if kind not in constants.SUPPORTED_FRAMES:
        raise mink.UnsupportedFrame(kind, constants.SUPPORTED_FRAMES)
    if isinstance(name, str):
        found = mujoco.mj_name2id(model, constants.FRAME_TO_ENUM[kind], name)
    else:
        found = int(name)
    if not 0 <= found < getattr(model, constants.FRAME_TO_COUNT_ATTR[kind]):
        raise mink.InvalidFrame(name, kind, model)
    return found


class FrameResiduals:
    """Writes the weighted residuals of mink frame tasks into given rows: per task, the
    cost-weighted Jacobian and the cost-weighted error times minus the gain, as
    `mink.Task._weighted_residual` gives them."""

    def __init__(self, configuration: mink.Configuration, tasks: Sequence[mink.FrameTask]) -> None:
        self.configuration = configuration
        model, data = configuration.model, configuration.data
        self.tasks = list(tasks)
        self.fast = lie is not None
        self._jacobian = np.zeros((6, model.nv))
        self._frames = []
        for task in self.tasks:
            kind, index = task.frame_type, frame_id(model, task)
            pos = getattr(data, constants.FRAME_TO_POS_ATTR[kind])[index]
            mat = getattr(data, constants.FRAME_TO_XMAT_ATTR[kind])[index]
            self._frames.append((task, index, pos, mat, constants.FRAME_TO_JAC_FUNC[kind]))

    def write(self, W: np.ndarray, e: np.ndarray, rows: Sequence[slice]) -> float:
        """Task k's rows of `W` and `e` at `rows[k]`, for the configuration's present state
        (as `Configuration.update` leaves it); the tasks' summed Levenberg-Marquardt terms."""
        if not self.fast:
            return self._write_with_mink(W, e, rows)
        configuration, jacobian, mu = self.configuration, self._jacobian, 0.0
        model, data = configuration.model, configuration.data
        for (task, index, pos, mat, jac_func), r in zip(self._frames, rows):
            if task.transform_target_to_world is None:
                raise mink.TargetNotSet(type(task).__name__)
            target = task.transform_target_to_world.wxyz_xyz
            frame = lie.xmat_xpos_to_wxyz_xyz(mat, pos)
            jac_func(model, data, jacobian[:3], jacobian[3:], index)
            # mink's frame Jacobian in the local frame, and its error's: -jlog(T_tb) A_fw J.
            local = lie.se3_rotation_adjoint_from_xmat(mat) @ jacobian
            tb = lie.se3_inverse_multiply(target, frame)
            weighted = task.cost * (-task.gain * lie.se3_rminus(target, frame))
            e[r] = weighted
            W[r] = task.cost[:, None] * (-lie.se3_jlog(tb) @ local)
            mu += task.lm_damping * float(weighted @ weighted)
        return mu

    def _write_with_mink(self, W: np.ndarray, e: np.ndarray, rows: Sequence[slice]) -> float:
        mu = 0.0
        for task, r in zip(self.tasks, rows):
            W[r], e[r], task_mu = task.compute_qp_residual(self.configuration)
            mu += task_mu
        return mu
