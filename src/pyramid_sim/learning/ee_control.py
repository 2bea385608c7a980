"""The environment's `action_mode="ee"`: each arm's tool-pose change and finger gap, turned
into the joint command by the build's own IK, with its joint, speed, acceleration and
collision limits."""

from __future__ import annotations

import math

import numpy as np
from gymnasium import spaces

from ..core.poses import Pose
from ..physics import names as c
from ..physics.loop import BuildLoop
from .layout import Layout

MAX_STEP = 0.01  # m a control step along each axis: 1 m/s, above any free move's speed
MAX_TURN = 0.05  # rad a control step: 5 rad/s, above any hand's turn rate
FIELDS = ("dx", "dy", "dz", "dyaw", "gripper")


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


class EndEffectorControl:
    """Actions of (dx, dy, dz, dyaw, gripper gap) per arm, left first, moving each arm's
    tool-centre target from where it was aimed the step before."""

    def __init__(self, layout: Layout) -> None:
        self.gaps = [i for i, name in enumerate(layout.names) if name.endswith("/gripper")]
        low, high = [], []
        for gap in self.gaps:
            low += [-MAX_STEP] * 3 + [-MAX_TURN, layout.low[gap]]
            high += [MAX_STEP] * 3 + [MAX_TURN, layout.high[gap]]
        self.space = spaces.Box(np.array(low), np.array(high), dtype=np.float64)
        self.names = tuple(f"{arm}/{f}" for arm in c.ARMS for f in FIELDS)
        self.targets: dict[str, Pose] = {}

    def reset(self, loop: BuildLoop) -> None:
        """Aim each arm where its tool centre is."""
        self.targets = {arm: loop.ik.tcp_pose(arm) for arm in c.ARMS}

    def command(self, loop: BuildLoop, action: np.ndarray) -> np.ndarray:
        """The joint command for `action`: the IK aimed at the moved targets and stepped once
        (mink.NoSolutionFound if it has no motion within the limits)."""
        for k, arm in enumerate(c.ARMS):
            dx, dy, dz, dyaw, _ = action[5 * k : 5 * k + 5]
            t = self.targets[arm]
            self.targets[arm] = Pose(t.x + dx, t.y + dy, t.z + dz, _wrap(t.yaw + dyaw))
            loop.ik.set_target(arm, self.targets[arm])
        loop.ik.step()
        command = loop.command().copy()
        command[self.gaps] = action[[4, 9]]
        return command

    def expert(self, loop: BuildLoop) -> np.ndarray | None:
        """The scripted builder's next move as such an action; None once it is done."""
        if not loop.expert_targets():
            return None
        action: list[float] = []
        for arm in c.ARMS:
            runner, t = loop.dispatch.runners[arm], self.targets[arm]
            p = runner.pose
            action += [p.x - t.x, p.y - t.y, p.z - t.z, _wrap(p.yaw - t.yaw), runner.gap]
        return np.array(action)

    def hold(self, loop: BuildLoop) -> np.ndarray:
        """Stay where aimed, the hands as they are commanded."""
        gaps = loop.data.ctrl[loop.handles.ctrl_index][self.gaps]
        return np.array([0.0, 0.0, 0.0, 0.0, gaps[0], 0.0, 0.0, 0.0, 0.0, gaps[1]])
