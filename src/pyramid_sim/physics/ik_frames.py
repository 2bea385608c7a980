"""The frame tasks' weighted residuals computed straight from the IK's `MjData`: the frame's
Jacobian from MuJoCo (`mj_jacSite`, `mj_jacBody` or `mj_jacGeom`) and its pose error through
mink's own compiled Lie operations. It is the arithmetic of `mink.FrameTask.compute_qp_residual`,
bit for bit, without its Python scaffolding (a name lookup and fresh arrays a call), which cost
a few percent of a build. With a mink that lacks those operations, mink's own path is taken."""

from __future__ import annotations

from collections.abc import Sequence

import mink
import mujoco
import numpy as np

try:  # mink's compiled Lie operations, which its FrameTask uses when present
    from mink.lie import _lie_ops_c as lie
except ImportError:  # a mink built without them
    lie = None  # type: ignore[assignment]

_JACOBIAN = {"site": mujoco.mj_jacSite, "body": mujoco.mj_jacBody, "geom": mujoco.mj_jacGeom}
_POSE = {
    "site": ("site_xpos", "site_xmat"),
    "body": ("xpos", "xmat"),
    "geom": ("geom_xpos", "geom_xmat"),
}


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
            kind = task.frame_type
            frame_id = mujoco.mj_name2id(model, mujoco.mju_str2Type(kind), task.frame_name)
            pos, mat = (getattr(data, name)[frame_id] for name in _POSE[kind])
            self._frames.append((task, frame_id, pos, mat, _JACOBIAN[kind]))

    def write(self, W: np.ndarray, e: np.ndarray, rows: Sequence[slice]) -> float:
        """Task k's rows of `W` and `e` at `rows[k]`, for the configuration's present state
        (as `Configuration.update` leaves it); the tasks' summed Levenberg-Marquardt terms."""
        if not self.fast:
            return self._write_with_mink(W, e, rows)
        configuration, jacobian, mu = self.configuration, self._jacobian, 0.0
        model, data = configuration.model, configuration.data
        for (task, frame_id, pos, mat, jac_func), r in zip(self._frames, rows):
            if task.transform_target_to_world is None:
                raise mink.TargetNotSet(type(task).__name__)
            target = task.transform_target_to_world.wxyz_xyz
            frame = lie.xmat_xpos_to_wxyz_xyz(mat, pos)
            jac_func(model, data, jacobian[:3], jacobian[3:], frame_id)
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
