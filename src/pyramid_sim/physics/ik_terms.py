"""The IK's terms as the robot defines them: the arms-only model it solves on, the frame tasks,
the velocity and acceleration bounds (with margins under the real limits), and the geom groups
the collision limit keeps apart."""

from __future__ import annotations

from functools import lru_cache

import mink
import mujoco
import numpy as np

from ..choices import RobotName
from ..config import SimConfig
from ..robots import RobotDescription
from . import names as c
from .clearance import arm_geoms, colliding_geoms
from .handles import dof_addresses
from .scene import build_spec

# mink gives the QP's terms and daqp solves it (see ik_qp).
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
    spec = build_spec(SimConfig.for_robot(robot, timestep=timestep), 0, with_bricks=False)
    for geom in [g for g in spec.geoms if not (g.contype or g.conaffinity)]:
        spec.delete(geom)  # drawn only: the IK never looks at them, its kinematics skip them
    return spec.compile()


def frame_task(site: str) -> mink.FrameTask:
    """The task that puts an arm's tool centre (`site`) at its target pose."""
    return mink.FrameTask(
        frame_name=site,
        frame_type="site",
        position_cost=1.0,
        orientation_cost=1.0,
        lm_damping=1e-3,
        gain=FRAME_GAIN,
    )


def velocity_bounds(model: mujoco.MjModel, robot: RobotDescription) -> mink.VelocityLimit:
    """The arm joints' velocity limits with a margin under the real ones: the servos overshoot
    the IK's velocity a little."""
    velocities = {
        j: (ARM_VELOCITY_MARGIN if i < 4 else VELOCITY_MARGIN) * v
        for arm in c.ARMS
        for i, (j, v) in enumerate(zip(robot.arms[arm].joints, robot.arms[arm].velocity_limits))
    }
    return mink.VelocityLimit(model, velocities)


def velocity_change(model: mujoco.MjModel, robot: RobotDescription | None, dt: float) -> np.ndarray:
    """The most each dof's velocity may change in one step: its acceleration limit times dt
    (unbounded for the fingers, or everywhere without a `robot`)."""
    max_dv = np.full(model.nv, np.inf)
    if robot is None:
        return max_dv
    for arm in c.ARMS:
        dofs = dof_addresses(model, robot.arms[arm].joints)
        max_dv[dofs] = np.array(robot.arms[arm].acceleration_limits) * dt
    return max_dv


def guarded_pairs(
    model: mujoco.MjModel, robot: RobotDescription
) -> list[tuple[list[int], list[int]]]:
    """The geom groups the IK keeps apart: the arms' guarded links from each other, and from
    the robot's own body (torso, head) if it has one."""
    arms = robot.arms
    guarded = [arm_geoms(model, arms[arm], arms[arm].guarded_bodies) for arm in c.ARMS]
    pairs = [(guarded[0], guarded[1])]
    if robot.static_bodies:
        body = colliding_geoms(model, {model.body(b).id for b in robot.static_bodies})
        pairs += [(arm, body) for arm in guarded]
    return pairs


def joint_ranges(model: mujoco.MjModel, robot: RobotDescription) -> tuple[np.ndarray, np.ndarray]:
    """The low and high ends of every qpos coordinate: the arm joints' ranges, both arms, and
    unbounded elsewhere (so a clamp is two whole-array passes)."""
    ids = [model.joint(j).id for a in c.ARMS for j in robot.arms[a].joints]
    low, high = np.full(model.nq, -np.inf), np.full(model.nq, np.inf)
    low[model.jnt_qposadr[ids]], high[model.jnt_qposadr[ids]] = model.jnt_range[ids].T
    return low, high
