"""The `anchored` action mode's frames: each hand's waypoint given from what it works on. Pure:
no MuJoCo.

A waypoint in the world asks a learner for the brick's or the target's place to a few
millimetres out of the tens of centimetres they move from one episode to the next; the same
waypoint given as an offset from the pick location or from the arm's next target is nearly the
same number in every episode (a hover is a fixed height above its anchor), so the place is
copied from the observation by the environment, not regressed by the network. An arm's action
is (anchor, x, y, z, yaw, gap): `anchor` names the frame (0 the pick location, 1 the arm's
collision-clear pose, 2 the arm's next target), x, y, z the offset from its place (m, world
axes), yaw the turn from its yaw. The anchors are the step's observation's `pick` and `next`
(and the robot's fixed clear pose): what the policy saw when it chose the action.

The order is the task's: an arm goes from the pick to its clear pose and from there to its
target and back, so every change of frame is to a neighbour, and an anchor between two
integers (a regression unsure which part of the task it is in) is a point between the two
frames, not a third frame: within `DEAD` of an integer the frame is that one exactly, between
it slides linearly from one to the next.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Sequence

import numpy as np

ANCHORS = ("pick", "clear", "next")  # an action's `anchor`: 0, 1, 2
FIELDS = ("anchor", "x", "y", "z", "yaw", "gripper")
RADIUS = 0.03  # m across the table within which a waypoint is given from the pick or a target
DEAD = 0.15  # of an anchor's unit around each integer that is that frame exactly


def next_targets(
    orders: Sequence[Sequence[int]],
    goals: np.ndarray,
    placed: Collection[int],
    tools: np.ndarray | None = None,
    carrying: Sequence[bool] | None = None,
) -> np.ndarray:
    """Each arm's next target (x, y, z, yaw), left first: the first of the arm's targets
    (`orders`: its build-order indices) that holds no brick yet, its last once all do, zeros
    for an arm that places none. The build order and which arm places which brick are the
    task's: the observation says which target each arm works towards.

    With the hands' `tools` (x, y, ... each), an arm whose hand is still within `RADIUS`
    across the table of the target it placed last works on it yet: its release and the rise
    off the brick are given from that target, not from a clear pose tens of centimetres away
    (whose offset to the brick changes with the layout, and which a learner cannot regress to
    the millimetres that keep its fingers off the brick it has just let go). A hand
    `carrying` a brick (one that sits on no target) is on its way to its next target,
    wherever it is: one stacked over the target the arm placed last lies within `RADIUS` of
    it, and the hand carrying its brick down there was given the target below
    (docs/notes/2026-12-05-occupied-targets.md)."""
    rows = []
    for k, order in enumerate(orders):
        waiting = [i for i in order if i not in placed]
        done = [i for i in order if i in placed]
        row = goals[waiting[0] if waiting else order[-1]] if order else np.zeros(4)
        on_its_way = carrying is not None and bool(carrying[k])
        if tools is not None and waiting and done and not on_its_way:
            last = goals[done[-1]]
            if np.hypot(*(tools[k][:2] - last[:2])) < RADIUS:
                row = last
        rows.append(row)
    return np.array(rows, dtype=np.float64).reshape(len(orders), 4)


def anchor_poses(pick: np.ndarray, clears: np.ndarray, nexts: np.ndarray) -> np.ndarray:
    """Each arm's anchors (arms x 3 x 4: pick location, clear pose, next target), from an
    observation's `pick` and `next` and the arms' clear poses (x, y, z, yaw each)."""
    return np.array([[np.asarray(pick), clear, row] for clear, row in zip(clears, nexts)])


def frame_at(anchor: float, frames: np.ndarray) -> np.ndarray:
    """The frame (x, y, z, yaw) an anchor value names: an integer's within `DEAD` of it, and
    a linear slide between two neighbours' between them."""
    value = float(np.clip(anchor, 0, len(ANCHORS) - 1))
    low = min(int(value), len(ANCHORS) - 2)
    share = float(np.clip((value - low - DEAD) / (1 - 2 * DEAD), 0.0, 1.0))
    return (1 - share) * frames[low] + share * frames[low + 1]


def to_world(action: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """The waypoint action (x, y, z, yaw, gap per arm) an anchored `action` asks for."""
    world = []
    for k, frames in enumerate(anchors):
        anchor, x, y, z, yaw, gap = (float(v) for v in action[6 * k : 6 * k + 6])
        base = frame_at(anchor, frames)
        world += [base[0] + x, base[1] + y, base[2] + z, base[3] + yaw, gap]
    return np.array(world)


def _near(yaw: float, reference: float) -> float:
    """`yaw` turned by whole turns to within half a turn of `reference` (as it is if it is)."""
    return (
        yaw
        if abs(yaw - reference) <= math.pi
        else reference + math.remainder(yaw - reference, 2 * math.pi)
    )


def to_anchored(world: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """The anchored action for a waypoint action (float32): each hand's waypoint from the
    nearer of its pick location and next target within `RADIUS` across the table, else from
    its clear pose.

    The yaw's offset is the hand's yaw less the frame's, each taken within half a turn of
    the arm's clear pose's yaw (its reference), not wrapped to a half turn either way: an arm
    that sets its brick down with its hand turned half round from the brick's yaw (the
    SO-101 pair's right) would otherwise be labelled +pi and -pi by turns, which a regression
    averages into a hand turned across the brick. Where both yaws lie within half a turn of
    the reference (the Panda pair's), the offset is the plain difference, as it was."""
    action = []
    for k, frames in enumerate(anchors):
        pose, gap = np.asarray(world[5 * k : 5 * k + 4], dtype=np.float64), world[5 * k + 4]
        reach = np.hypot(*(frames[[0, 2], :2] - pose[:2]).T)
        anchor = (0, 2)[int(np.argmin(reach))] if reach.min() < RADIUS else 1
        offset = pose - frames[anchor]
        reference = float(frames[1][3])
        offset[3] = _near(float(pose[3]), reference) - _near(float(frames[anchor][3]), reference)
        action += [anchor, *offset, gap]
    return np.array(action, dtype=np.float32)
