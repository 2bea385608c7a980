"""The environment's `action_mode="anchored"`: the `waypoint` mode's actions given from the
pick location, the arm's clear pose or its next target (task/anchors.py says why). The waypoint's controller,
hands and limits are the `waypoint` mode's: an anchored action is turned into its waypoint
at the step's start, with the anchors the policy observed."""

from __future__ import annotations

import math

import numpy as np
from gymnasium import spaces

from ...core.primitives import clear_pose
from ...physics import names as c
from ...robots import RobotDescription
from ..task.anchors import ANCHORS, FIELDS, to_anchored, to_world
from .waypoint_control import REACH


def anchored_space(waypoint: spaces.Box) -> spaces.Box:
    """Each arm's anchor (0 to 2), offset within the waypoint's reach either way, yaw within a
    turn either way, and gap as the waypoint mode's."""
    low, high = [], []
    for k in range(len(c.ARMS)):
        gap = 5 * k + 4
        low += [0.0, -REACH, -REACH, -REACH, -2 * math.pi, waypoint.low[gap]]
        high += [len(ANCHORS) - 1.0, REACH, REACH, REACH, 2 * math.pi, waypoint.high[gap]]
    return spaces.Box(np.array(low, np.float32), np.array(high, np.float32), dtype=np.float32)


def clear_frames(robot: RobotDescription) -> np.ndarray:
    """Each arm's collision-clear pose (x, y, z, yaw), left first: the anchored mode's frame 1."""
    return np.array([[*p.position, p.yaw] for p in (clear_pose(a, robot) for a in c.ARMS)])


def anchored_names() -> tuple[str, ...]:
    """An anchored action's entries, left arm first."""
    return tuple(f"{arm}/{f}" for arm in c.ARMS for f in FIELDS)


def hand_action(action_mode: str, waypoint: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """A waypoint action as `action_mode` gives it (float32)."""
    if action_mode == "anchored":
        return to_anchored(waypoint, anchors)
    return waypoint.astype(np.float32)


def waypoint_action(action_mode: str, action: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """The waypoint an action of `action_mode` asks for (a hand mode's action as it is)."""
    return to_world(action, anchors) if action_mode == "anchored" else action
