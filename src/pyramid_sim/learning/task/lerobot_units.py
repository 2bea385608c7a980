"""A robot's state and commands as lerobot records that robot: the names its follower gives
each motor (`left_shoulder_pan.pos`, ..., `right_gripper.pos` for the SO-101 pair) in its
units (joints in degrees, the gripper 0 to 100 over the jaw's joint range), so a dataset
recorded here lines up feature by feature with one recorded on the real pair. A robot without
lerobot names (the Panda pair, Baxter) keeps pyramid_sim's names and SI units: radians, and
the gripper's gap in metres. Each entry is affine: lerobot = scale * (ours - offset)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...choices import ARMS
from ...robots import RobotDescription


@dataclass(frozen=True)
class LerobotUnits:
    """The names, and the affine map between our values and lerobot's, entry by entry."""

    names: tuple[str, ...]
    robot_type: str
    scale: np.ndarray
    offset: np.ndarray

    def to_lerobot(self, ours: np.ndarray) -> np.ndarray:
        return np.asarray(self.scale * (np.asarray(ours, np.float64) - self.offset), np.float32)

    def from_lerobot(self, theirs: np.ndarray) -> np.ndarray:
        return np.asarray(np.asarray(theirs, np.float64) / self.scale + self.offset)


def own_units(names: tuple[str, ...], robot_type: str) -> LerobotUnits:
    """Entries kept in pyramid_sim's own units (metres, radians): a robot without lerobot's
    names, and hand poses and gaps (the `ee` and `waypoint` actions), no motor's."""
    n = len(names)
    return LerobotUnits(names, robot_type, np.ones(n), np.zeros(n))


def robot_type(robot: RobotDescription) -> str:
    """The `robot_type` a recording of `robot` names in its info.json: lerobot's own for a
    robot it has, else ours (`panda_bimanual`)."""
    return robot.lerobot_robot_type or f"{robot.name}_bimanual"


def lerobot_units(robot: RobotDescription, names: tuple[str, ...]) -> LerobotUnits:
    """The units of `robot`'s state and command, whose entries are `names` (each arm's joints,
    then its gripper, left arm first, as the environment's layout has them)."""
    n = len(names)
    if not robot.lerobot_motors:
        return own_units(names, robot_type(robot))
    per_arm = len(robot.lerobot_motors)
    assert n == per_arm * len(ARMS), (names, robot.lerobot_motors)
    (gain,) = robot.finger_gains  # one jaw: its gap is gain x its joint angle
    low, high = robot.lerobot_gripper_span
    scale, offset, lerobot_names = [], [], []
    for arm in ARMS:
        for motor in robot.lerobot_motors:
            lerobot_names.append(f"{arm}_{motor}.pos")
            if motor == "gripper":  # the gap (m) -> the jaw's place in its range, 0 to 100
                scale.append(100.0 / (gain * (high - low)))
                offset.append(gain * low)
            else:  # radians -> degrees
                scale.append(180.0 / math.pi)
                offset.append(0.0)
    return LerobotUnits(tuple(lerobot_names), robot_type(robot), np.array(scale), np.array(offset))
