"""The parts a build's control step composes, made once from its plan and settings.

Each part takes only what it works on (the model and data, the scene's addresses, the parts it
talks to), so a test can make any one of them alone; `make_parts` makes them all, in the order
they depend on each other, with both arms at their outer clear poses.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from ..choices import Schedule
from ..config import SimConfig
from ..core.plan import Plan
from ..core.poses import Pose
from ..core.primitives import clear_pose
from ..core.zone import Zone, overlap_zones, shared_zone
from . import names as c
from .actuation import Actuation
from .clearance import ArmClearance
from .custody import BrickCustody
from .dispatch import ArmDispatch
from .handles import SceneHandles
from .ik import DualArmIK
from .monitor import StepMonitor, joint_limits
from .scene import build_scene, place_spawn
from .spawner import Spawner
from .zone_watch import ZoneWatch

# m: no brick, and no arm link, this near the spawn volume when a brick is set on the spot
SPOT_CLEARANCE, SPOT_ARM_CLEARANCE = 0.02, 0.10
ZONE_MARGIN = 0.04  # m around the bricks' footprints


@dataclass(frozen=True)
class BuildParts:
    """One build's model and state, and every part that reads or drives them."""

    plan: Plan
    config: SimConfig
    model: mujoco.MjModel
    data: mujoco.MjData
    handles: SceneHandles
    ik: DualArmIK
    spawner: Spawner
    custody: BrickCustody
    dispatch: ArmDispatch
    zones: ZoneWatch
    clearance: ArmClearance
    monitor: StepMonitor
    actuation: Actuation


def schedule_zones(schedule: Schedule, plan: Plan, config: SimConfig) -> dict[str, Zone]:
    """The zones the schedule hands out: one shared zone for the lockstep, the spot's and the
    structure's for the overlap schedule."""
    targets = [b.target.pose for b in plan.bricks]
    if schedule == "overlap":
        return overlap_zones(
            plan.spawn, targets, config.brick.length, config.brick.width, ZONE_MARGIN
        )
    return {"shared": shared_zone(plan.spawn, targets, config.brick.length / 2, ZONE_MARGIN)}


def step_monitor(
    model: mujoco.MjModel, data: mujoco.MjData, handles: SceneHandles, config: SimConfig
) -> StepMonitor:
    """The monitor of both arms' joints and fingers, left arm first."""
    h = handles
    return StepMonitor(
        model,
        data,
        dofs=np.concatenate([h.arm_dofs[a] for a in c.ARMS]),
        qpos=np.concatenate([h.arm_qpos[a] for a in c.ARMS]),
        actuators=np.concatenate([h.arm_actuators[a] for a in c.ARMS]),
        fingers=np.concatenate([h.finger_qpos[a] for a in c.ARMS]),
        limits=joint_limits(model, config.robot_description),
    )


def start_at_clear_poses(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    handles: SceneHandles,
    ik: DualArmIK,
    config: SimConfig,
) -> None:
    """Both arms at their outer clear poses, outside every zone, hands open; the IK there."""
    robot = config.robot_description
    ik.reset_home()
    start = {a: ik.solve(a, clear_pose(a, robot)) for a in c.ARMS}
    for a in c.ARMS:
        data.qpos[handles.arm_qpos[a]] = start[a]
        data.ctrl[handles.arm_actuators[a]] = start[a]
        opened = robot.open_gap()
        data.ctrl[handles.gripper[a]] = opened
        fingers = handles.finger_qpos[a]
        for q, gain in zip(fingers, robot.finger_gains):
            data.qpos[q] = opened / (len(fingers) * gain)  # each its share of the gap
    ik.reset(start["left"], start["right"])
    mujoco.mj_forward(model, data)


def make_parts(plan: Plan, config: SimConfig, model: mujoco.MjModel | None = None) -> BuildParts:
    """A freshly compiled scene for the plan (spare bricks in the magazine replace dropped
    ones that cannot be picked again) and its parts; or the parts on `model`, a scene compiled
    for `scene_key(config)`, its spawn spot placed for this plan."""
    if model is None:
        model = build_scene(config, len(plan.bricks) + config.spare_bricks).model
    else:
        place_spawn(model, config)
    data = mujoco.MjData(model)
    handles = SceneHandles(model, config.robot_description, len(plan.bricks) + config.spare_bricks)
    ik = DualArmIK(config)
    spawner = Spawner(
        model,
        config.robot_description,
        handles,
        plan.spawn,
        clearance=SPOT_CLEARANCE * config.robot_description.length_scale,  # at its scale
        arm_clearance=SPOT_ARM_CLEARANCE * config.robot_description.length_scale,
        jitter=config.layout.spawn_jitter_mm / 1000.0,
        seed=config.seed,
    )
    custody = BrickCustody(data, handles, spawner, len(plan.bricks), config)
    start_at_clear_poses(model, data, handles, ik, config)
    zones = schedule_zones(config.schedule, plan, config)
    tcp: dict[str, Pose] = {a: ik.tcp_pose(a) for a in c.ARMS}
    dispatch = ArmDispatch(plan, config, spawner, tcp, zones, data)
    watch = ZoneWatch(zones, data, handles)
    clearance = ArmClearance(model, data, config.robot_description)
    monitor = step_monitor(model, data, handles, config)
    return BuildParts(
        plan=plan,
        config=config,
        model=model,
        data=data,
        handles=handles,
        ik=ik,
        spawner=spawner,
        custody=custody,
        dispatch=dispatch,
        zones=watch,
        clearance=clearance,
        monitor=monitor,
        actuation=Actuation(model, data, handles, ik, config, monitor),
    )
