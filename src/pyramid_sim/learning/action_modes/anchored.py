"""The environment's `action_mode="anchored"`: the `waypoint` mode's actions given from the
pick location, the arm's clear pose or its next target (task/anchors.py says why). The
waypoint's controller, hands and limits are the `waypoint` mode's: an anchored action is
turned into its waypoint at the step's start, with the anchors the policy observed."""

from __future__ import annotations

import math
from functools import partial
from typing import Any

import numpy as np
from gymnasium import spaces

from ...core.primitives import clear_pose
from ...physics import names as c
from ...physics.loop import BuildLoop
from ...robots import RobotDescription
from ..task.anchors import ANCHORS, FIELDS, anchor_poses, to_anchored, to_world
from ..task.lerobot_units import own_units
from .hand_mode import hand_moved
from .mode import ExpertMove, ModeParts, Waypoints
from .waypoint import REACH, WaypointMode


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


class AnchoredMode(WaypointMode):
    """The waypoint mode, each hand's waypoint given from one of its anchors: the frames of
    the observation the policy saw last (`see`)."""

    fields = FIELDS

    def __init__(self, parts: ModeParts) -> None:
        super().__init__(parts)
        self.space = anchored_space(self.control.space)
        self.names = anchored_names()
        self.units = own_units(self.names, parts.units.robot_type)
        self.moved = hand_moved(self.names, ("x", "y", "z"))
        self.clears = clear_frames(parts.config.robot_description)
        self.anchors = np.zeros((len(c.ARMS), len(ANCHORS), 4))  # each arm's, from `see`

    def see(self, observation: dict[str, Any]) -> None:
        self.anchors = anchor_poses(observation["pick"], self.clears, observation["next"])

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        return to_world(action, self.anchors)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return to_anchored(self.control.hold(loop), self.anchors)

    def expert(self, move: ExpertMove) -> np.ndarray:
        return to_anchored(self.control.expert(move.loop), self.anchors)

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        anchors = self.anchors  # the frames this action was given in: a new step sees others
        return to_world(action, anchors), partial(to_anchored, anchors=anchors)
