"""What the physics loop measured in one build, before it is judged (output/judge.py).

Pure: numbers and records handed over by the loop, so judging and reporting need no MuJoCo.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .incidents import Drop, Knock
from .plan import Plan


@dataclass(frozen=True)
class Measurements:
    """The final state and every figure the loop kept, per magazine slot where per brick."""

    plan: Plan
    slot_of: dict[int, int]  # build-order index -> magazine slot of the brick that was placed
    final_pos: np.ndarray  # (slots, 3)
    final_quat: np.ndarray  # (slots, 4)
    slip_mm: dict[int, float]  # build-order index -> peak slip in the hand
    drops: tuple[Drop, ...]
    knocks: tuple[Knock, ...]
    sim_time: float
    wall_time: float
    arm_arm_contacts: int
    arm_body_contacts: int  # an arm against the robot's own body (torso, head)
    zone_violations: int
    finger_limit_mm: float
    joint_speed_ratio: float
    joint_torque_ratio: float  # demanded: the servo's unclamped output plus gravity compensation
    torque_joint: int | None  # which arm joint (0-6 left, 7-13 right) demanded the most
    speed_joint: int | None  # which arm joint moved the fastest for its limit
    warnings: dict[str, int]
    failure: str | None
    idle_motion_mm: float  # the furthest a brick moved before an arm reached for it
    contact_friction: dict[str, float]  # sliding friction of brick-brick, -table, pad-brick
    closest_arm_m: float
    closest_arm_time: float | None
    physics_steps: int
    ik_solves: int  # control steps on which the IK solved (in free motion one covers several)

    @property
    def dropped(self) -> set[int]:
        """Build-order indices of the bricks that were dropped at least once."""
        return {d.brick for d in self.drops}
