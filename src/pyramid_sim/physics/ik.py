"""Differential IK for both arms with mink, on an arms-only copy of the scene.

Solving on a model without the free bricks is about four times faster (FINDINGS.md); joint names
are shared with the full scene, so the solution maps over by name.
"""

from __future__ import annotations

import math
from ctypes import c_int
from functools import lru_cache

import daqp
import mink
import mujoco
import numpy as np

from ..choices import Arm, RobotName
from ..config import SimConfig
from ..core.poses import Pose, tcp_quaternion, yaw_of
from ..errors import UnreachableError
from . import names as c
from .clearance import arm_geoms, colliding_geoms
from .handles import dof_addresses, qpos_addresses
from .ik_qp import NO_BOUND, BrakingCollisionLimit, IKProblem
from .scene import build_spec

# mink gives the QP's terms (see ik_qp); daqp solves it, called directly: qpsolvers' generic
# wrapper around it cost a sixth of a solve.
VELOCITY_MARGIN = 0.9
# The shoulder and elbow (an arm's first four joints) move the heavy links on lightly damped
# servos, which ring past a command that rises at its acceleration bound: a wider margin there
# (docs/performance.md).
ARM_VELOCITY_MARGIN = 0.82
# Share of the frame error the QP removes in one step. At 1 (mink's default) the solution asks
# for the whole error every 10 ms; against the acceleration bound that over-corrects and rings
# (an arm reaching across to the far side rang +-20 mm over the spawn spot); 0.5 settles.
FRAME_GAIN = 0.5


def arms_model(config: SimConfig) -> mujoco.MjModel:
    """The scene without bricks, for the IK: compiled once per robot and timestep in a process
    (the arms' kinematics do not change with the brick or grip settings a sweep varies)."""
    return _arms_model(config.robot, config.timestep)


@lru_cache(maxsize=4)
def _arms_model(robot: RobotName, timestep: float) -> mujoco.MjModel:
    spec = build_spec(SimConfig(robot=robot, timestep=timestep), 0, with_bricks=False)
    for geom in [g for g in spec.geoms if not (g.contype or g.conaffinity)]:
        spec.delete(geom)  # drawn only: the IK never looks at them, its kinematics skip them
    return spec.compile()


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
        self.tasks = {
            arm: mink.FrameTask(
                frame_name=arms[arm].tcp_site,
                frame_type="site",
                position_cost=1.0,
                orientation_cost=1.0,
                lm_damping=1e-3,
                gain=FRAME_GAIN,
            )
            for arm in c.ARMS
        }
        # The same gain, so frame and posture tasks balance where they did at gain 1.
        cost = robot.posture_cost if posture_cost is None else posture_cost
        self.posture = mink.PostureTask(self.model, cost=cost, gain=FRAME_GAIN)
        # A margin under the real limits: the servos overshoot the IK's velocity a little.
        velocities = {
            j: (ARM_VELOCITY_MARGIN if i < 4 else VELOCITY_MARGIN) * v
            for arm in c.ARMS
            for i, (j, v) in enumerate(zip(arms[arm].joints, arms[arm].velocity_limits))
        }
        position_limit = mink.ConfigurationLimit(self.model)
        velocity_limit = mink.VelocityLimit(self.model, velocities)
        # Collision safety beyond the scheduler: the QP will not close the gap between the
        # arms' links below the minimum distance, whatever the targets ask.
        self._collision = BrakingCollisionLimit(
            self.model, self._guarded_pairs(), config.motion.arm_min_distance
        )
        self.limits = [position_limit, velocity_limit, self._collision]  # as mink takes them
        # The most a step's dq may change from one step to the next.
        self._max_ddq = self._velocity_change(limit_acceleration) * self.dt
        rows = self._collision.limit.max_num_contacts
        self._free = np.full(rows, -NO_BOUND)  # the collision rows' lower bounds
        self._sense = np.zeros(self.model.nv + rows, dtype=c_int)
        self.task_list = [*self.tasks.values(), self.posture]
        self.problem = IKProblem(
            self.configuration, self.task_list, damping, position_limit, velocity_limit, self.dt
        )
        self._targets: dict[str, Pose] = {}
        self.velocity = np.zeros(self.model.nv)
        joint_ids = [self.model.joint(j).id for a in c.ARMS for j in arms[a].joints]
        self.limited_q = self.model.jnt_qposadr[joint_ids]
        self.q_low, self.q_high = self.model.jnt_range[joint_ids].T
        self.reset_home()

    def _velocity_change(self, limited: bool) -> np.ndarray:
        """The most each dof's velocity may change in one step: its acceleration limit times
        dt (unbounded for the fingers, or everywhere if not `limited`)."""
        max_dv = np.full(self.model.nv, np.inf)
        for arm in c.ARMS if limited else ():
            dofs = dof_addresses(self.model, self.robot.arms[arm].joints)
            max_dv[dofs] = np.array(self.robot.arms[arm].acceleration_limits) * self.dt
        return max_dv

    def _guarded_pairs(self) -> list[tuple[list[int], list[int]]]:
        """The geom groups the IK keeps apart: the arms' guarded links from each other, and
        from the robot's own body (torso, head) if it has one."""
        arms, model = self.robot.arms, self.model
        guarded = [arm_geoms(model, arms[arm], arms[arm].guarded_bodies) for arm in c.ARMS]
        pairs = [(guarded[0], guarded[1])]
        if self.robot.static_bodies:
            body = colliding_geoms(model, {model.body(b).id for b in self.robot.static_bodies})
            pairs += [(arm, body) for arm in guarded]
        return pairs

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

    def step(self) -> None:
        """One control step: solve for joint velocities and integrate them over dt.

        The change of velocity stays within the arm's acceleration limits (see `solve_velocity`): a
        sudden reversal (near the shoulder singularity) would shake the brick loose.
        """
        velocity = self.solve_velocity()
        q_next = self.configuration.integrate(velocity, self.dt)
        # The clip may overrule the QP's braking at a joint limit: keep the limits exact.
        q_next[self.limited_q] = np.clip(q_next[self.limited_q], self.q_low, self.q_high)
        self.velocity = velocity
        self.configuration.update(q_next)

    def solve_velocity(self) -> np.ndarray:
        """Joint velocities from the QP of mink's tasks and limits (`IKProblem`).

        Each joint's change of velocity is bounded by its acceleration limit inside the QP, so
        a stop short of the other arm is planned within what the arm can do. When that makes
        the QP infeasible (an approach too fast to brake in time, or braking at a joint limit)
        it is solved without the bounds and its answer clipped to them, unless the clipped
        answer would close on the other arm: then the collision limit wins over smoothness.
        NoSolutionFound if the QP has no solution even so."""
        H, c = self.problem.objective()
        low, high = self.problem.bounds()
        G, h = self._collision.active_rows(self.configuration, self.dt)
        free, sense = self._free[: h.size], self._sense[: h.size + low.size]
        last = self.velocity * self.dt
        accel_low, accel_high = last - self._max_ddq, last + self._max_ddq
        step, _, exitflag, _ = daqp.solve(
            H,
            c,
            G,
            np.concatenate([np.minimum(high, accel_high), h]),
            np.concatenate([np.maximum(low, accel_low), free]),
            sense,
        )
        if exitflag > 0:
            return step / self.dt
        step, _, exitflag, _ = daqp.solve(
            H, c, G, np.concatenate([high, h]), np.concatenate([low, free]), sense
        )
        if exitflag <= 0:
            raise mink.NoSolutionFound("daqp")
        clipped = np.clip(step, accel_low, accel_high)
        if np.all(G @ clipped <= h + 1e-9):
            return clipped / self.dt
        return step / self.dt

    def error(self, arm: Arm) -> tuple[float, float]:
        """Position (m) and orientation (rad) error of the arm's frame task."""
        err = self.tasks[arm].compute_error(self.configuration)
        return math.sqrt(err[:3] @ err[:3]), math.sqrt(err[3:] @ err[3:])

    def solve(self, arm: Arm, pose: Pose, max_steps: int = 1500, tol: float = 1e-3) -> np.ndarray:
        """Converge on `pose` for one arm by repeated steps; raise UnreachableError if it stalls."""
        self.set_target(arm, pose)
        pos_err = float("inf")
        for _ in range(max_steps):
            try:
                self.step()
            except mink.NoSolutionFound:
                break
            pos_err, rot_err = self.error(arm)
            if pos_err < tol and rot_err < 0.01:
                return self.arm_q(arm)
        raise UnreachableError(
            f"{arm} arm cannot reach ({pose.x:.3f}, {pose.y:.3f}, {pose.z:.3f}) yaw "
            f"{pose.yaw:.2f}: {pos_err * 1000:.1f} mm short"
        )
