"""What the hand-pose modes (`ee`, `waypoint`, and those built on it) share: a controller that
turns each hand's pose into joint targets through the build's own IK, the motion generator
behind it, and entries in metres and radians."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from ...physics import names as c
from ...physics.loop import BuildLoop
from ...physics.motion_generator import JERK_TIME, hand_modes_share
from ...robots import RobotDescription
from ..task.lerobot_units import own_units
from .mode import ModeParts


def hand_moved(names: tuple[str, ...], fields: tuple[str, ...]) -> np.ndarray:
    """Which of a hand mode's entries (`names`, "arm/field") move an arm: its `fields`."""
    return np.array([name.split("/")[-1] in fields for name in names])


class HandPoseMode:
    """A mode whose `control` (an `EndEffectorControl` or a `WaypointControl`) has the action
    space, entries, a command each control step and what holding still is; the entries named
    by `moving` move an arm."""

    moved_unit = "m"
    hand_poses = True
    fields: tuple[str, ...] = ()  # each hand's entries

    def __init__(self, parts: ModeParts, control: Any, moving: tuple[str, ...]) -> None:
        self.control = control
        self.space: spaces.Box = self.control.space
        self.names = self.control.names
        self.units = own_units(self.names, parts.units.robot_type)  # metres and radians
        self.moved = hand_moved(self.names, moving)
        self.jerk_time = JERK_TIME  # behind the IK the generator follows it closely
        self.acceleration_share = hand_modes_share(parts.config.robot_description)

    @classmethod
    def size(cls, robot: RobotDescription) -> int:
        return len(cls.fields) * len(c.ARMS)

    def reset(self, loop: BuildLoop) -> None:
        self.control.reset(loop)

    def see(self, observation: dict[str, Any]) -> None:
        return None

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        return action

    def command(self, loop: BuildLoop, target: np.ndarray, share: float) -> np.ndarray:
        return self.control.command(loop, target)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return self.control.hold(loop).astype(np.float32)
