"""What each action mode needs beside the joint modes' parts: the hand modes' controller (the
`ee` mode's pose changes or the `waypoint` and `anchored` modes' poses, through the IK), how
lerobot records their actions, and which of an action's entries move an arm."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from gymnasium import spaces

from ...choices import HAND_ACTION_MODES, WAYPOINT_MODES
from ...config import SimConfig
from ...physics.motion_generator import (
    ACCELERATION_SHARE,
    JERK_TIME,
    JOINT_JERK_TIME,
    MotionGenerator,
    arm_motion,
)
from ..task.layout import Layout
from ..task.lerobot_units import LerobotUnits, own_units
from ..task.spaces import joint_space
from .anchored_actions import anchored_names, anchored_space
from .ee_control import EndEffectorControl, end_effector
from .relative_actions import relative_space
from .waypoint_control import WaypointControl, waypoints

if TYPE_CHECKING:
    from .env import BuildEnv


def action_parts(
    action_mode: str, config: SimConfig, layout: Layout, steps: int, units: LerobotUnits
) -> tuple[EndEffectorControl | WaypointControl, LerobotUnits, spaces.Box]:
    """The hands' controller for `action_mode` (an `ee` one serves the joint modes' expert
    too), the units lerobot records its actions in (the joint command's `units`, or a hand's
    pose) and the action space."""
    if action_mode in WAYPOINT_MODES:
        control: EndEffectorControl | WaypointControl = waypoints(config, layout, steps)
    else:
        control = end_effector(config, layout, steps)
    if action_mode == "anchored":
        return control, own_units(anchored_names(), units.robot_type), anchored_space(control.space)
    if action_mode in HAND_ACTION_MODES:
        return control, own_units(control.names, units.robot_type), control.space
    space = relative_space(layout) if action_mode == "relative" else joint_space(layout)
    return control, units, space


def moved_entries(env: BuildEnv) -> np.ndarray:
    """Which of the action's entries move an arm (True), not a hand's fingers or yaw: the
    joints, or in the hand modes each hand's x, y and z (what DART's noise and the
    perturbations offset)."""
    if env.action_mode in HAND_ACTION_MODES:
        moved = ("x", "y", "z", "dx", "dy", "dz")
        return np.array([name.split("/")[-1] in moved for name in env.action_units.names])
    return env.layout.joints


def mode_motion(config: SimConfig, action_mode: str) -> MotionGenerator:
    """The motion generator for `action_mode`: behind the IK (the hand modes) it follows the
    IK closely, at the robot's own acceleration share where it sets one (Baxter's, whose
    shoulder has less torque to spare); fed a policy's joint targets straight, it is their
    only filter, and reaches its jerk slower (docs/learning.md, "The joint modes'
    filtering")."""
    if action_mode not in HAND_ACTION_MODES:
        return arm_motion(config, JOINT_JERK_TIME)
    share = config.robot_description.hand_modes_acceleration_share
    return arm_motion(config, JERK_TIME, ACCELERATION_SHARE if share is None else share)
