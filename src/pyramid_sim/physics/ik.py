"""Differential IK for both arms with mink, on an arms-only copy of the scene.

Solving on a model without the free bricks is about four times faster (FINDINGS.md); joint names
are shared with the full scene, so the solution maps over by name.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import mink
import numpy as np

from ..choices import Arm
from ..config import SimConfig
from ..core.poses import Pose, tcp_quaternion, yaw_of
from ..errors import UnreachableError
from . import names as c
from .handles import qpos_addresses
from .ik_plan import SpanPlan, ramp_split, span_gain
from .ik_qp import BrakingCollisionLimit, IKProblem, solve_smooth, solver_scratch
from .ik_terms import (
    FRAME_GAIN,
    arms_model,
    frame_task,
    guarded_pairs,
    joint_ranges,
    velocity_bounds,
    velocity_change,
)

# A solve that cuts neither error by 1 % in 200 steps has stalled (`DualArmIK.solve`).
STALL_STEPS, STALL_SHRINK = 200, 0.99


class DualArmIK:
    """One mink problem for both arms: a TCP frame task per arm, a light posture task, joint
    position, velocity and acceleration limits, and a minimum distance between the arms."""

    def __init__(
        self,
        config: SimConfig,
        posture_cost: float | None = None,
        damping: float = 1e-2,
        limit_acceleration: bool = True,
    ) -> None:
        self.damping = damping
        self.robot = robot = config.robot_description
        arms = robot.arms
        self.model = arms_model(config)
        self.configuration = mink.Configuration(self.model)
        self.dt = config.motion.control_dt
        self.qadr = {arm: qpos_addresses(self.model, arms[arm].joints) for arm in c.ARMS}
        self.tasks = {arm: frame_task(arms[arm].tcp_site) for arm in c.ARMS}
        # The same gain, so frame and posture tasks balance where they did at gain 1.
        cost = robot.posture_cost if posture_cost is None else posture_cost
        self.posture = mink.PostureTask(self.model, cost=cost, gain=FRAME_GAIN)
        position_limit = mink.ConfigurationLimit(self.model)
        velocity_limit = velocity_bounds(self.model, robot)
        # Collision safety beyond the scheduler: the QP will not close the gap between the
        # arms' links below the minimum distance, whatever the targets ask.
        self._collision = BrakingCollisionLimit(
            self.model, guarded_pairs(self.model, robot), config.motion.arm_min_distance
        )
        self.limits = [position_limit, velocity_limit, self._collision]  # as mink takes them
        # The most a step's dq may change from one step to the next.
        limited = robot if limit_acceleration else None
        self._max_ddq = velocity_change(self.model, limited, self.dt) * self.dt
        self._scratch = solver_scratch(self._collision.limit.max_num_contacts, self.model.nv)
        self.task_list = [*self.tasks.values(), self.posture]
        self.problem = IKProblem(
            self.configuration, self.task_list, damping, position_limit, velocity_limit, self.dt
        )
        self._targets: dict[str, Pose] = {}
        self.velocity = np.zeros(self.model.nv)
        self._span = 1  # the span the task gains are set for
        self._plan: SpanPlan | None = None  # the last solve's, while it covers several steps
        self.q_min, self.q_max = joint_ranges(self.model, robot)
        self.reset_home()

    def home(self, arm: Arm) -> np.ndarray:
        return np.array(self.robot.arms[arm].home)

    def reset_home(self) -> None:
        """Both arms at their home postures."""
        self.reset(self.home("left"), self.home("right"))

    def reset(self, left_q: np.ndarray, right_q: np.ndarray) -> None:
        """Put both arms at the given joint positions; posture pulls towards the home pose."""
        home = self.model.qpos0.copy()
        for arm in c.ARMS:
            home[self.qadr[arm]] = self.home(arm)
        self.posture.set_target(home)
        q = self.model.qpos0.copy()
        q[self.qadr["left"]] = left_q
        q[self.qadr["right"]] = right_q
        self.configuration.update(q)
        self.velocity = np.zeros(self.model.nv)
        self._plan = None
        for arm in c.ARMS:
            self.tasks[arm].set_target(
                self.configuration.get_transform_frame_to_world(
                    self.robot.arms[arm].tcp_site, "site"
                )
            )
            self._targets.pop(arm, None)

    def arm_q(self, arm: Arm) -> np.ndarray:
        return self.configuration.q[self.qadr[arm]].copy()

    def tcp_pose(self, arm: Arm) -> Pose:
        """Where the IK's model has the arm's tool centre now."""
        data = self.configuration.data
        site = data.site(self.robot.arms[arm].tcp_site)
        x, y, z = site.xpos
        return Pose(float(x), float(y), float(z), yaw_of(site.xmat.reshape(3, 3)))

    def set_target(self, arm: Arm, pose: Pose) -> None:
        """Aim the arm's frame task at `pose` (called every control step; a repeat is free)."""
        if self._targets.get(arm) == pose:
            return
        self._targets[arm] = pose
        wxyz_xyz = np.array([*tcp_quaternion(pose.yaw), pose.x, pose.y, pose.z])
        self.tasks[arm].set_target(mink.SE3(wxyz_xyz))

    @property
    def q(self) -> np.ndarray:
        """The joint positions commanded for this control step."""
        return self.configuration.q if self._plan is None else self._plan.q

    def step(self, span: int = 1) -> bool:
        """One solve for the next `span` control steps: joint velocities from the QP over
        span x dt, and the joint positions they lead to at each of those steps (`q`, then
        `coast()` to the next). A span of several steps is refused (False, nothing moved)
        unless the arms surely stay beyond the collision limit's reach throughout: the
        targets were for its end, so the caller aims again and steps once.

        Each control step's change of velocity stays within the arm's acceleration limits
        (`solve_velocity`, ik_plan): a sudden reversal (near the shoulder singularity) would
        shake the brick loose."""
        if self._plan is not None:
            self._cut_plan(self._plan)
        velocity = self.solve_velocity(span)
        if span > 1 and not self._stays_clear(span, velocity):
            return False  # near once the new speed is in
        if span == 1:
            q_next = self.configuration.integrate(velocity, self.dt)
        else:
            ranges = (self.q_min, self.q_max)
            q0 = self.configuration.q
            self._plan = SpanPlan(q0, self.velocity, velocity, self.dt, span, ranges)
            q_next = self._plan.rows[-1]
        # The clip may overrule the QP's braking at a joint limit: keep the limits exact.
        np.minimum(np.maximum(q_next, self.q_min, out=q_next), self.q_max, out=q_next)
        self.velocity = velocity
        self.configuration.update(q_next)
        return True

    def _cut_plan(self, plan: SpanPlan) -> None:
        """Leave the plan where it has got to (the configuration stood at its end)."""
        if not plan.done:
            self.configuration.update(plan.q)
            self.velocity = plan.velocities[plan.row].copy()
        self._plan = None

    @property
    def planned(self) -> bool:
        """Whether the last step covered several control steps (`coast` goes on along it)."""
        return self._plan is not None

    def coast(self) -> bool:
        """Move on to the next control step of the last `step(span)`'s plan, without solving;
        False (and nothing done) once the plan is used up."""
        return self._plan is not None and self._plan.advance()

    def may_span(self, span: int) -> bool:
        """Whether a step over `span` control steps may be granted: not if the arms could come
        within the collision limit's reach at their present speed (`step` checks the new)."""
        return self._stays_clear(span, self.velocity)

    def _stays_clear(self, span: int, velocity: np.ndarray) -> bool:
        """Whether a span towards `velocity` keeps the arms out of the collision limit's reach
        (a joint moves at most the larger of its last and new speed for the span)."""
        motion = np.maximum(np.abs(self.velocity), np.abs(velocity)) * (span * self.dt)
        return self._collision.stays_clear(self.configuration.data, motion)

    def _set_span(self, span: int) -> None:
        """The tasks' gains for a step over `span` control steps (`span_gain`)."""
        if span != self._span:
            self._span = span
            for task in self.task_list:
                task.gain = span_gain(FRAME_GAIN, span)

    def solve_velocity(self, span: int = 1) -> np.ndarray:
        """Joint velocities from the QP of mink's tasks and limits (`IKProblem`), each
        joint's change of velocity within its acceleration limit (`solve_smooth`).
        NoSolutionFound if the QP has no solution. Over a `span` of control steps the QP's
        step is the span's whole motion, the velocity ramping to the new one (ik_plan)."""
        self._set_span(span)
        H, c = self.problem.objective()
        seconds = self.dt * span
        drift: float | np.ndarray
        if span == 1:  # no ramp
            drift, late, box = 0.0, self.dt, self.problem.bounds()
        else:
            early, late = ramp_split(self.dt, span)
            drift = early * self.velocity
            box = self.problem.bounds(late, drift)
        G, h = self._collision.active_rows(self.configuration, seconds)
        last = self.velocity * seconds  # dq if v stayed v0
        change = self._max_ddq * (span * late / self.dt)  # late x (acceleration x seconds)
        step = solve_smooth(H, c, box, (G, h), (last - change, last + change), self._scratch)
        return (step - drift) / late

    def error(self, arm: Arm) -> tuple[float, float]:
        """Position (m) and orientation (rad) error of the arm's frame task."""
        err = self.tasks[arm].compute_error(self.configuration)
        return math.sqrt(err[:3] @ err[:3]), math.sqrt(err[3:] @ err[3:])

    def error_of(self, arm: Arm) -> Callable[[], float]:
        """The arm's position error, asked when wanted."""
        return lambda: self.error(arm)[0]

    def solve(self, arm: Arm, pose: Pose, max_steps: int = 1500, tol: float = 1e-3) -> np.ndarray:
        """Converge on `pose` for one arm by repeated steps; UnreachableError if it stalls."""
        return converge(self, arm, pose, max_steps, tol)


def converge(ik: DualArmIK, arm: Arm, pose: Pose, max_steps: int, tol: float) -> np.ndarray:
    """`ik.solve`: step towards `pose` until within `tol` (and 0.01 rad); UnreachableError once
    it has stalled: after `max_steps`, or STALL_STEPS in which neither error shrank by
    STALL_SHRINK (an unreachable pose's error is flat within 200 steps: `reach` waits a fifth
    as long on one)."""
    ik.set_target(arm, pose)
    pos_err = float("inf")
    window = (pos_err, pos_err)
    for k in range(1, max_steps + 1):
        try:
            ik.step()
        except mink.NoSolutionFound:
            break
        pos_err, rot_err = ik.error(arm)
        if pos_err < tol and rot_err < 0.01:
            return ik.arm_q(arm)
        if k % STALL_STEPS == 0:
            if pos_err > STALL_SHRINK * window[0] and rot_err > STALL_SHRINK * window[1]:
                break
            window = (pos_err, rot_err)
    raise UnreachableError(
        f"{arm} arm cannot reach ({pose.x:.3f}, {pose.y:.3f}, {pose.z:.3f}) yaw "
        f"{pose.yaw:.2f}: {pos_err * 1000:.1f} mm short"
    )
