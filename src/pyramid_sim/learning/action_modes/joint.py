"""The environment's `action_mode="joint"`: both arms' joint targets and finger gaps, in the
state's layout (`task/layout.Layout`). The target goes to the motion generator, which is then
the only filter between a policy's jitter and the servos, and reaches its jerk slower than
behind the IK (docs/notes/2026-11-28-learning.md, "The joint modes' filtering"); with the generator
off, a
step's targets are joined by a spline (target_spline.py)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from gymnasium import spaces

from ...physics.loop import BuildLoop
from ...physics.motion_generator import ACCELERATION_SHARE, JOINT_JERK_TIME
from ...robots import RobotDescription
from ..task.spaces import joint_space
from .mode import ExpertMove, ModeParts, Waypoints
from .target_spline import spline_ramp


class JointMode:
    """Actions of joint targets and finger gaps, each arm's joints then its gap, left first."""

    moved_unit = "rad"
    hand_poses = False

    def __init__(self, parts: ModeParts) -> None:
        self.layout, self.steps = parts.layout, parts.steps
        self.raw = not parts.limit_commands  # no generator: the spline joins the targets
        self.space: spaces.Box = joint_space(parts.layout)
        self.names, self.units = parts.layout.names, parts.units
        self.moved = parts.layout.joints
        self.jerk_time = JOINT_JERK_TIME
        self.acceleration_share = ACCELERATION_SHARE
        self._ramp: Callable[[float], np.ndarray] | None = None
        self._last: tuple[np.ndarray, np.ndarray] = (np.zeros(0), np.zeros(0))

    @classmethod
    def size(cls, robot: RobotDescription) -> int:
        return sum(len(arm.joints) + 1 for arm in robot.arms.values())

    def reset(self, loop: BuildLoop) -> None:
        held = loop.data.ctrl[loop.handles.ctrl_index].copy()
        self._last = (held, held)  # the last target, and where the ramp left the command

    def see(self, observation: dict[str, Any]) -> None:
        return None

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        if self.raw:
            self._ramp, self._last = spline_ramp(*self._last, action, self.steps)
        return action

    def command(self, loop: BuildLoop, target: np.ndarray, share: float) -> np.ndarray:
        return target if self._ramp is None else self._ramp(share)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return loop.data.ctrl[loop.handles.ctrl_index].astype(np.float32)

    def expert(self, move: ExpertMove) -> np.ndarray:
        assert move.joints is not None  # the builder's own IK solves for the joint modes
        return move.joints

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        return None
