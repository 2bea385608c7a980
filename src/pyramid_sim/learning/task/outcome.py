"""What a step of the environment earns and what ends its episode: targets that have come to
hold a brick at rest (the reward), and failures the build's own stops do not end on at once
(a brick off the table, arm-arm contact, a joint past its speed or torque limit)."""

from __future__ import annotations

import math
from copy import deepcopy
from typing import Any

import numpy as np

from ...output.judge import judge, placement_errors, within
from ...output.result import Tolerances
from ...physics.loop import BuildLoop
from .layout import brick_index

REST_SPEED = 1e-3  # m/s: a brick slower than this is at rest
OFF_TABLE = 0.05  # m below the table top: a brick down there has left it


class PlacementWatch:
    """The targets of a build that hold a brick at rest within the tolerances: found once it
    comes to rest there, lost again if it is knocked out of them (success is every target
    held at once, as the build's own judge sees the bricks at its end)."""

    def __init__(self, loop: BuildLoop, tolerances: Tolerances = Tolerances()) -> None:
        h = loop.handles  # addresses are the same in every episode's compiled scene
        self.tolerances = tolerances
        self._lin_vel = np.array([[v, v + 1, v + 2] for v in h.brick_dofs])
        self._xy = brick_index(h)[:, :2]
        self._pose_q = np.array([np.arange(q, q + 7) for q in h.brick_qpos])  # each slot's
        self._checked = np.zeros((len(h.brick_qpos), 7))  # its pose when last found in place
        self.placed: dict[int, int] = {}  # build-order index -> slot of the brick resting there

    @property
    def count(self) -> int:
        return len(self.placed)

    def update(self, loop: BuildLoop) -> int:
        """How many targets have newly come to hold a brick at rest, less those whose brick
        was moved out of the tolerances: the full check only for a resting brick across from
        a target, and for each held target's brick."""
        d, h = loop.data, loop.handles
        spawned = loop.spawner.next_slot
        speeds = np.linalg.norm(d.qvel[self._lin_vel[:spawned]], axis=1)
        lost = self._lost(loop)
        resting = np.flatnonzero(speeds <= REST_SPEED)
        if resting.size == 0:
            return -lost
        xy = d.qpos[self._xy[resting]]
        near = self.tolerances.xy_mm / 1000.0
        newly = 0
        for target in loop.plan.bricks:
            if target.index in self.placed:
                continue
            pose = target.target.pose
            for slot in resting[np.hypot(xy[:, 0] - pose.x, xy[:, 1] - pose.y) <= near]:
                q = h.brick_qpos[slot]
                errors = placement_errors(d.qpos[q : q + 3], d.qpos[q + 3 : q + 7], pose)
                if within(self.tolerances, *errors):
                    self.placed[target.index] = int(slot)
                    self._checked[slot] = d.qpos[self._pose_q[slot]]
                    newly += 1
                    break
        return newly - lost

    def occupied(self, loop: BuildLoop) -> dict[int, int]:
        """The targets that hold a brick: those placed, and those a brick sits on outside the
        tolerances, its centre within half a brick's width across the table and half its
        height up or down. A brick set down 7 mm off is there all the same: told its target
        was still free, a policy set its next brick onto that one, and a joint's torque ended
        the episode (docs/notes/2026-12-05-occupied-targets.md). Where the brick is, not
        whether it is at rest: a hand setting a brick down on it shakes it, and a target that
        came free while it shook sent the hand down onto it. A brick a finger pad touches holds
        none: carried down onto a target, it passes through those stacked above it. Only
        `placed` is scored. By build-order index, the magazine slot of the brick there."""
        taken = dict(self.placed)
        in_hand = loop.custody.holds.touched(loop.data)
        free = np.array([s for s in range(loop.spawner.next_slot) if s not in in_hand], dtype=int)
        centres = loop.data.qpos[self._pose_q[free, :3]]
        brick = loop.config.brick
        for target in loop.plan.bricks:
            if target.index in taken:
                continue
            pose = target.target.pose
            across = np.hypot(centres[:, 0] - pose.x, centres[:, 1] - pose.y)
            level = np.abs(centres[:, 2] - pose.z) <= brick.height / 2
            there = np.flatnonzero((across <= brick.width / 2) & level)
            if there.size:
                taken[target.index] = int(free[there[0]])
        return taken

    def _lost(self, loop: BuildLoop) -> int:
        """Forget the targets whose brick has left the tolerances; how many. Only a brick
        whose pose changed since it was last found in place is judged again: this runs every
        control step, and a resting brick (most of a structure) has not moved at all."""
        if not self.placed:
            return 0
        d, lost = loop.data, 0
        slots = np.fromiter(self.placed.values(), dtype=int)
        now = d.qpos[self._pose_q[slots]]
        moved = np.any(now != self._checked[slots], axis=1)
        indices = list(self.placed)
        for k in np.flatnonzero(moved):
            index, slot = indices[k], slots[k]
            pose = loop.plan.bricks[index].target.pose
            if within(self.tolerances, *placement_errors(now[k, :3], now[k, 3:], pose)):
                self._checked[slot] = now[k]
            else:
                del self.placed[index]
                lost += 1
        return lost


def episode_failure(loop: BuildLoop, reduce: bool) -> str | None:
    """A failure that ends an episode though the build's own stops go on (a build recovers
    from a drop; an episode ends on a brick off the table); `reduce` folds the joint
    monitor's buffer first (every few steps: a limit broken is told soon after)."""
    monitor, top = loop.monitor, loop.config.layout.table_top_z
    if reduce:
        monitor.flush()
    if monitor.arm_arm_contacts:
        return f"arm-arm contact at t = {loop.data.time:.3f} s"
    if monitor.speed_ratio > 1.0:
        return f"a joint moved at {monitor.speed_ratio:.2f} of its velocity limit"
    if monitor.torque_ratio > 1.0:
        return f"a joint demanded {monitor.torque_ratio:.2f} of its torque limit"
    for slot in range(loop.spawner.next_slot):  # every brick set on the spot so far
        z = loop.data.qpos[loop.handles.brick_qpos[slot] + 2]
        if z < top - OFF_TABLE or not math.isfinite(z):
            return f"a brick (magazine slot {slot}) left the table"
    return None


def episode_info(env: Any, failure: str | None, success: bool | None) -> dict[str, Any]:
    """A BuildEnv's info, the same keys after reset and every step; `result` (result.json's
    document) once the episode has ended, empty before (a dict either way: a vector env
    gathers infos by their type)."""
    loop = env.loop
    result: dict[str, Any] = {}
    if env.ended:
        loop.custody.slot_of.update(
            {i: s for i, s in env.placing.placed.items() if i not in loop.custody.slot_of}
        )
        result = judge(loop.finish(failure, 0.0), loop.config).to_dict()
    return {
        "sim_time_s": float(loop.data.time),
        "bricks_placed": env.placing.count,
        "failure": failure,
        "is_success": bool(success),
        "command_lag": env.generator.peak_lag,
        "seed": env.seed_of_episode,
        "randomization": deepcopy(env.drawn),
        "result": result,
    }
