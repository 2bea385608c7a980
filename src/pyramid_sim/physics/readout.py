"""What the loop hands over at the end of a build: its measurements."""

from __future__ import annotations

from typing import TYPE_CHECKING

import mujoco
import numpy as np

from ..core.measurements import Measurements
from .contacts import contact_frictions

if TYPE_CHECKING:
    from .loop import BuildLoop


def measurements(loop: BuildLoop, failure: str | None, wall: float) -> Measurements:
    """The final state of every brick and every figure the loop and its monitors kept."""
    d, custody = loop.data, loop.custody
    qadr = loop.handles.brick_qpos
    n = len(qadr)
    warnings = {
        mujoco.mjtWarning(i).name: int(d.warning[i].number)
        for i in range(len(d.warning))
        if d.warning[i].number
    }
    return Measurements(
        plan=loop.plan,
        slot_of=dict(custody.slot_of),
        final_pos=np.array([d.qpos[q : q + 3] for q in qadr]).reshape(n, 3),
        final_quat=np.array([d.qpos[q + 3 : q + 7] for q in qadr]).reshape(n, 4),
        slip_mm=dict(custody.slip_mm),
        drops=tuple(custody.drops),
        knocks=tuple(custody.knocks),
        sim_time=float(d.time),
        wall_time=wall,
        arm_arm_contacts=loop.monitor.arm_arm_contacts,
        arm_body_contacts=loop.monitor.arm_body_contacts,
        zone_violations=loop.zone_violations,
        finger_limit_mm=loop.monitor.finger_excess * 1000.0,
        joint_speed_ratio=loop.monitor.speed_ratio,
        joint_torque_ratio=loop.monitor.torque_ratio,
        warnings=warnings,
        failure=failure,
        torque_joint=loop.monitor.torque_joint,
        speed_joint=loop.monitor.speed_joint,
        idle_motion_mm=custody.idle_motion * 1000.0,
        contact_friction=contact_frictions(loop.model, loop.handles, loop.config.robot_spec),
        closest_arm_m=loop.clearance.closest,
        closest_arm_time=loop.clearance.closest_time,
        physics_steps=loop.steps,
    )
