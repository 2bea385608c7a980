"""The IK's quadratic program, assembled from mink's tasks and limits without mink's general
path, which costs more than the physics step it drives.

mink stays the source of every term: the objective stacks the tasks' weighted residuals as
`mink.build_ik` does (the frame tasks' through mink's compiled operations on the IK's own
MjData, ik_frames; a posture task's Jacobian, the identity, taken once); the joint
position and velocity limits, whose rows are plus and minus unit vectors, become the solver's
box bounds (with the acceleration bounds, one pair per joint); and the collision limit gives
only the rows of the pairs within its detection distance, none while the arms are apart. The
QP has the same terms as mink's (tests/physics/test_ik_qp.py holds each to `mink.build_ik`'s).
"""

from __future__ import annotations

from collections.abc import Sequence
from ctypes import c_int

import daqp
import mink
import mujoco
import numpy as np

from .ik_frames import FrameResiduals, plain_frame_task
from .pair_gaps import PairGaps

NO_BOUND = 1e30  # what daqp takes for an absent bound
COLLISION_LOOKAHEAD = 0.10  # m beyond the minimum arm distance at which the limit takes effect
ARM_BRAKING = 4.0  # m/s^2: the arms may close on each other no faster than they can stop in time


class IKProblem:
    """The objective and bounds of one control step's QP, in the step `dq = v dt`."""

    def __init__(
        self,
        configuration: mink.Configuration,
        tasks: Sequence[mink.Task],
        damping: float,
        position_limit: mink.ConfigurationLimit,
        velocity_limit: mink.VelocityLimit,
        dt: float,
    ) -> None:
        self.configuration = configuration
        self.nv = nv = configuration.model.nv
        moving = [t for t in tasks if not isinstance(t, mink.PostureTask)]
        # A posture task's Jacobian is constant: its weighted rows and their part of H once.
        self._postures = [
            (t, t.cost[:, None] * t.compute_jacobian(configuration))
            for t in tasks
            if isinstance(t, mink.PostureTask)
        ]
        self._H0 = sum((wj.T @ wj for _, wj in self._postures), np.zeros((nv, nv)))
        self._H0.flat[:: nv + 1] += damping
        self._extra = np.zeros((nv, nv))  # set_extra_damping's
        self._position = position_limit
        # mink bounds each listed dof: -dt v_max <= dq <= dt v_max.
        self.dt = dt
        self._velocity_dofs = np.zeros(0, dtype=int)
        self._velocity_max = np.zeros(0)
        if velocity_limit.projection_matrix is not None:
            self._velocity_dofs = np.asarray(velocity_limit.indices)
            self._velocity_max = np.asarray(velocity_limit.limit, dtype=float)
        self._low, self._high = np.full(nv, -NO_BOUND), np.full(nv, NO_BOUND)
        self._high[self._velocity_dofs] = dt * self._velocity_max
        self._low[self._velocity_dofs] = -dt * self._velocity_max
        self._to_upper = np.empty(nv)
        self._from_lower = np.empty(nv)
        # The moving tasks' weighted Jacobians and errors, stacked in the tasks' order into
        # arrays kept from call to call: mink's frame tasks' rows from ik_frames, any other
        # task's from mink.
        ends = np.cumsum([0] + [t.cost.size for t in moving])
        rows = [slice(a, b) for a, b in zip(ends[:-1], ends[1:])]
        self._W, self._e = np.zeros((ends[-1], nv)), np.zeros(ends[-1])
        frame = [plain_frame_task(t) for t in moving]
        self._frames = FrameResiduals(configuration, [t for t in moving if plain_frame_task(t)])
        self._frame_rows = [r for r, f in zip(rows, frame) if f]
        self._others = [(t, r) for t, r, f in zip(moving, rows, frame) if not f]

    def set_extra_damping(self, damping: np.ndarray) -> None:
        """A damping term `dq' damping dq` in the objective beside the uniform one (in place
        of any set before)."""
        self._H0 += damping - self._extra
        self._extra = damping.copy()

    def objective(self) -> tuple[np.ndarray, np.ndarray]:
        """(H, c) of `1/2 dq'H dq + c'dq`: the tasks' weighted residuals stacked, plus the
        damping and each task's Levenberg-Marquardt term on the diagonal (mink's sum)."""
        configuration = self.configuration
        W, e = self._W, self._e
        mu = self._frames.write(W, e, self._frame_rows)
        for task, rows in self._others:
            W[rows], e[rows], task_mu = task.compute_qp_residual(configuration)
            mu += task_mu
        H = W.T @ W + self._H0
        c = -(e @ W)
        for task, wj in self._postures:
            error = task.cost * (-task.gain * task.compute_error(configuration))
            c -= error @ wj
            mu += task.lm_damping * float(error @ error)
        H.flat[:: self.nv + 1] += mu
        return H, c

    def bounds(
        self, dt: float | None = None, offset: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) on dq from the position limit (its gain times the way left to each end)
        and the velocity limit (dq = offset + v dt within +-v_max, `dt` the problem's own and
        no offset if None); unbounded dofs get +-NO_BOUND."""
        if dt is None and offset is None:
            low, high = self._low.copy(), self._high.copy()
        else:
            low, high = np.full(self.nv, -NO_BOUND), np.full(self.nv, NO_BOUND)
            dofs = self._velocity_dofs
            step = (self.dt if dt is None else dt) * self._velocity_max
            centre = 0.0 if offset is None else offset[dofs]
            high[dofs] = centre + step
            low[dofs] = centre - step
        limit = self._position
        if limit.projection_matrix is None:
            return low, high
        q, m = self.configuration.q, limit.model
        mujoco.mj_differentiatePos(m, self._to_upper, 1.0, q, limit.upper)
        mujoco.mj_differentiatePos(m, self._from_lower, 1.0, limit.lower, q)
        dofs = limit.indices
        high[dofs] = np.minimum(high[dofs], limit.gain * self._to_upper[dofs])
        low[dofs] = np.maximum(low[dofs], -limit.gain * self._from_lower[dofs])
        return low, high


Scratch = tuple[np.ndarray, np.ndarray, np.ndarray]


def solver_scratch(rows: int, nv: int) -> Scratch:
    """The solver's upper and lower bounds (the box, then the rows; the rows' lower bounds
    absent) and the constraints' senses, made once (`solve_smooth`)."""
    size = nv + rows
    return np.zeros(size), np.full(size, -NO_BOUND), np.zeros(size, dtype=c_int)


def solve_smooth(
    H: np.ndarray,
    c: np.ndarray,
    box: tuple[np.ndarray, np.ndarray],
    rows: tuple[np.ndarray, np.ndarray],
    smooth: tuple[np.ndarray, np.ndarray],
    scratch: Scratch,
) -> np.ndarray:
    """The step minimising `1/2 dq'H dq + c'dq` within the `box` (low, high), the `rows`
    (G dq <= h) and the `smooth` bounds (the acceleration limits' low and high).

    With the smooth bounds in the QP a stop short of the other arm is planned within what the
    arm can do. When they make it infeasible (an approach too fast to brake in time, or
    braking at a joint limit) it is solved without them and its answer clipped to them,
    unless the clipped answer would break the rows (close on the other arm): then the
    collision limit wins over smoothness. mink.NoSolutionFound if it has no solution even so.
    daqp is called directly: qpsolvers' generic wrapper cost a sixth of a solve. `scratch`:
    `solver_scratch`'s arrays, for at least as many rows."""
    (low, high), (G, h), (smooth_low, smooth_high) = box, rows, smooth
    nv, size = low.size, low.size + h.size
    upper, lower, sense = (a[:size] for a in scratch)
    np.minimum(high, smooth_high, out=upper[:nv])
    np.maximum(low, smooth_low, out=lower[:nv])
    upper[nv:] = h
    step, _, exitflag, _ = daqp.solve(H, c, G, upper, lower, sense)
    if exitflag > 0:
        return step
    upper[:nv], lower[:nv] = high, low
    step, _, exitflag, _ = daqp.solve(H, c, G, upper, lower, sense)
    if exitflag <= 0:
        raise mink.NoSolutionFound("daqp")
    clipped = np.clip(step, smooth_low, smooth_high)
    return clipped if np.all(G @ clipped <= h + 1e-9) else step


class BrakingCollisionLimit(mink.Limit):
    """mink's collision avoidance limit, reshaped so the arms can always stop in time.

    mink bounds each step's approach by a share of the gap left (gain x gap / dt), which allows
    full speed until just short of the minimum and then an instant stop; the arm's
    acceleration bounds cannot follow (with both hands sent to one point, and the velocity
    clipped to those bounds after the QP, the links met 50-80 mm deep). Here the approach speed
    is bounded by sqrt(2 a gap), the speed from which the arms stop within the gap braking at a
    modest `ARM_BRAKING` (the same test: the links stay 49.8 mm apart; mink's own bound, with
    the acceleration bounds in the QP, 43.5 mm)."""

    def __init__(
        self, model: mujoco.MjModel, pairs: list[tuple[list[int], list[int]]], minimum: float
    ) -> None:
        # gain 1 and dt 1 below make mink's bound the bare gap left above the minimum.
        self.limit = mink.CollisionAvoidanceLimit(
            model,
            pairs,
            gain=1.0,
            minimum_distance_from_collisions=minimum,
            collision_detection_distance=minimum + COLLISION_LOOKAHEAD,
        )
        geoms = np.array(self.limit.geom_id_pairs, dtype=int).reshape(-1, 2)
        self.gaps = PairGaps(model, geoms[:, 0], geoms[:, 1])
        self._no_rows = (np.zeros((0, model.nv)), np.zeros(0))

    def compute_qp_inequalities(
        self, configuration: mink.Configuration, dt: float
    ) -> mink.limits.Constraint:
        """mink's rows with each bound reshaped to the braking speed over the gap left."""
        constraint = self.limit.compute_qp_inequalities(configuration, 1.0)
        assert constraint.G is not None and constraint.h is not None  # mink: None if inactive
        gap = np.maximum(constraint.h, 0.0)
        return mink.limits.Constraint(G=constraint.G, h=dt * np.sqrt(2.0 * ARM_BRAKING * gap))

    def stays_clear(self, data: mujoco.MjData, motion: np.ndarray) -> bool:
        """Whether every guarded pair surely stays beyond the detection distance, where the
        limit has no rows, while each joint moves by at most `motion` (per qpos address): a
        pair closes by at most that motion times its joints' levers (`PairGaps.closing`)."""
        reach = self.limit.collision_detection_distance + self.gaps.closing(motion)
        return not self.gaps.may_be_within(data, reach)

    def active_rows(
        self, configuration: mink.Configuration, dt: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """The rows of `G dq <= h` that bind anything: none while every pair is surely beyond
        the detection distance (mink measures no pair farther), else mink's rows without those
        it marks with an infinite bound."""
        if not self.gaps.may_be_within(configuration.data, self.limit.collision_detection_distance):
            return self._no_rows
        constraint = self.compute_qp_inequalities(configuration, dt)
        assert constraint.G is not None and constraint.h is not None
        keep = np.isfinite(constraint.h)
        return constraint.G[keep], constraint.h[keep]
