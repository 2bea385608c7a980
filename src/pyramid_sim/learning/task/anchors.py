"""The `anchored` action mode's frames: each hand's waypoint given from what it works on. Pure:
no MuJoCo.

A waypoint in the world asks a learner for the brick's or the target's place to a few
millimetres out of the tens of centimetres they move from one episode to the next; the same
waypoint given as an offset from the pick location or from the arm's next target is nearly the
same number in every episode (a hover is a fixed height above its anchor), so the place is
copied from the observation by the environment, not regressed by the network. An arm's action
is (anchor, x, y, z, yaw, gap): `anchor` names the frame (0 the table, 1 the pick location, 2
the arm's next target; rounded), x, y, z the offset from its place (m, world axes), yaw the
turn from its yaw (the table's is 0). The anchors are the step's observation's `pick` and
`next`: what the policy saw when it chose the action.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence

import numpy as np

ANCHORS = ("table", "pick", "next")  # an action's `anchor`: 0, 1, 2
FIELDS = ("anchor", "x", "y", "z", "yaw", "gripper")
RADIUS = 0.03  # m across the table within which a waypoint is given from the pick or a target


def next_targets(
    orders: Sequence[Sequence[int]], goals: np.ndarray, placed: Collection[int]
) -> np.ndarray:
    """Each arm's next target (x, y, z, yaw), left first: the first of the arm's targets
    (`orders`: its build-order indices) that holds no brick yet, its last once all do, zeros
    for an arm that places none. The build order and which arm places which brick are the
    task's: the observation says which target each arm works towards."""
    rows = []
    for order in orders:
        waiting = [i for i in order if i not in placed]
        rows.append(goals[waiting[0] if waiting else order[-1]] if order else np.zeros(4))
    return np.array(rows, dtype=np.float64).reshape(len(orders), 4)


def anchor_poses(pick: np.ndarray, nexts: np.ndarray) -> np.ndarray:
    """Each arm's anchors (arms x 3 x 4: table, pick, next target), from an observation's
    `pick` and `next`."""
    return np.array([[np.zeros(4), np.asarray(pick), row] for row in np.asarray(nexts)])


def to_world(action: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """The waypoint action (x, y, z, yaw, gap per arm) an anchored `action` asks for."""
    world = []
    for k, frames in enumerate(anchors):
        anchor, x, y, z, yaw, gap = (float(v) for v in action[6 * k : 6 * k + 6])
        base = frames[int(np.clip(round(anchor), 0, len(ANCHORS) - 1))]
        world += [base[0] + x, base[1] + y, base[2] + z, base[3] + yaw, gap]
    return np.array(world)


def to_anchored(world: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """The anchored action for a waypoint action (float32): each hand's waypoint from the
    nearest of its pick location and next target within `RADIUS` across the table, else from
    the table."""
    action = []
    for k, frames in enumerate(anchors):
        pose, gap = np.asarray(world[5 * k : 5 * k + 4], dtype=np.float64), world[5 * k + 4]
        reach = np.hypot(*(frames[1:, :2] - pose[:2]).T)
        anchor = 1 + int(np.argmin(reach)) if reach.min() < RADIUS else 0
        offset = pose - frames[anchor]
        offset[3] = math.remainder(offset[3], 2 * math.pi) if anchor else pose[3]
        action += [anchor, *offset, gap]
    return np.array(action, dtype=np.float32)
