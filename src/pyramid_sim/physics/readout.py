"""What the loop hands over at the end of a build: its measurements."""

from __future__ import annotations

import mujoco
import numpy as np

from ..core.measurements import Measurements
from .contacts import contact_frictions
from .parts import BuildParts


def measurements(
    parts: BuildParts, physics_steps: int, ik_solves: int, failure: str | None, wall: float
) -> Measurements:
    """The final state of every brick and every figure the parts kept."""
    d, custody, monitor = parts.data, parts.custody, parts.monitor
    qadr = parts.handles.brick_qpos
    n = len(qadr)
    warnings = {
        mujoco.mjtWarning(i).name: int(d.warning[i].number)
        for i in range(len(d.warning))
        if d.warning[i].number
    }
    return Measurements(
        plan=parts.plan,
        slot_of=dict(custody.slot_of),
        final_pos=np.array([d.qpos[q : q + 3] for q in qadr]).reshape(n, 3),
        final_quat=np.array([d.qpos[q + 3 : q + 7] for q in qadr]).reshape(n, 4),
        slip_mm=dict(custody.slip_mm),
        drops=tuple(custody.drops),
        knocks=tuple(custody.knocks),
        sim_time=float(d.time),
        wall_time=wall,
        arm_arm_contacts=monitor.arm_arm_contacts,
        arm_body_contacts=monitor.arm_body_contacts,
        zone_violations=parts.zones.violations,
        finger_limit_mm=monitor.finger_excess * 1000.0,
        joint_speed_ratio=monitor.speed_ratio,
        joint_torque_ratio=monitor.torque_ratio,
        warnings=warnings,
        failure=failure,
        torque_joint=monitor.torque_joint,
        speed_joint=monitor.speed_joint,
        idle_motion_mm=custody.idle_motion * 1000.0,
        contact_friction=contact_frictions(
            parts.model, parts.handles, parts.config.robot_description
        ),
        closest_arm_m=parts.clearance.closest,
        closest_arm_time=parts.clearance.closest_time,
        physics_steps=physics_steps,
        ik_solves=ik_solves,
    )
