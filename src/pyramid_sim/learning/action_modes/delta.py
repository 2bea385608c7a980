"""The environment's `action_mode="delta"`: each hand's pose change from where the hand is
measured at the step's start (dx, dy, dz in m, dyaw in rad) and its finger gap, as robomimic's
and LIBERO's delta end-effector controllers take it. The continuous track: every step commands
the hand a little further, and nothing in the action is copied from the observation.

A change is at most `SHARE` of the hand's free speed over a step across (of its turn rate in
yaw), as a real arm's delta controller bounds it: a delta that points at a move's end far away
saturates, and one near a brick's place is the few millimetres left, which is where a
learner's precision is asked. The bound is a step and a half of travel, not less, so that the
controller's own speed limit governs the motion: the hand lags its target behind the motion
generator, and a change bounded at 0.75 of a step's travel, given from the lagging hand, held
the target back and made the motion stop and go (the expert built 2 of 6 held-out layouts,
the others ending on a joint's torque; 20 of 20 at 1.5). The hand goes to the pose the change makes as the `waypoint`
mode's hand goes to a waypoint (the same controller, IK, limits and hands): a step's change is
turned into that waypoint at the step's start, from the tools the policy observed. Unlike the
`ee` mode, whose change moves a target the policy does not see (it leads the tool by up to a
centimetre), a delta's label is the expert's waypoint less what the observation holds."""

from __future__ import annotations

import math
from functools import partial
from typing import Any

import numpy as np
from gymnasium import spaces

from ...physics import names as c
from ...physics.loop import BuildLoop
from ..task.lerobot_units import own_units
from .hand_mode import hand_moved
from .mode import ExpertMove, ModeParts, Waypoints
from .waypoint import WaypointMode

FIELDS = ("dx", "dy", "dz", "dyaw", "gripper")
SHARE = 1.5  # of the hand's free speed (and its turn rate) over a step: a change's bound
# s: the step the bound is taken over, at the least. The hand lags its target by about this
# much travel whatever the rate, so at 25 steps a second a step's own travel held the target
# back as 0.75 of a step did at 10: the Panda pair's expert ran to the time limit on every
# seed, where over 0.1 s it builds 10 of 10
SPAN = 0.1


def to_waypoint(action: np.ndarray, tools: np.ndarray) -> np.ndarray:
    """The waypoint action (x, y, z, yaw, gap per arm) a delta `action` asks for from the
    hands at `tools` (x, y, z, yaw each, left first)."""
    world = []
    for k, tool in enumerate(tools):
        dx, dy, dz, dyaw, gap = (float(v) for v in action[5 * k : 5 * k + 5])
        world += [tool[0] + dx, tool[1] + dy, tool[2] + dz, tool[3] + dyaw, gap]
    return np.array(world)


def to_delta(world: np.ndarray, tools: np.ndarray, reach: float, turn: float) -> np.ndarray:
    """The delta action (float32) toward a waypoint action from the hands at `tools`: the way
    there, no longer than `reach` (m) across and `turn` (rad) in yaw."""
    action: list[float] = []
    for k, tool in enumerate(tools):
        x, y, z, yaw, gap = (float(v) for v in world[5 * k : 5 * k + 5])
        way = np.array([x - tool[0], y - tool[1], z - tool[2]])
        length = float(np.linalg.norm(way))
        if length > reach:
            way *= reach / length
        dyaw = max(-turn, min(turn, math.remainder(yaw - float(tool[3]), 2 * math.pi)))
        action += [*way, dyaw, gap]
    return np.array(action, dtype=np.float32)


class DeltaMode(WaypointMode):
    """The waypoint mode, each hand's waypoint given as a bounded change from its measured
    tool pose: the tools of the observation the policy saw last (`see`)."""

    fields = FIELDS

    def __init__(self, parts: ModeParts) -> None:
        super().__init__(parts)
        motion = parts.config.hand_motion
        span = max(parts.steps * parts.config.motion.control_dt, SPAN)
        self.reach, self.turn = SHARE * motion.speed * span, SHARE * motion.turn_rate * span
        low, high = [], []
        for k in range(len(c.ARMS)):
            gap = 5 * k + 4
            low += [-self.reach] * 3 + [-self.turn, self.control.space.low[gap]]
            high += [self.reach] * 3 + [self.turn, self.control.space.high[gap]]
        self.space = spaces.Box(np.array(low, np.float32), np.array(high, np.float32))
        self.names = tuple(f"{arm}/{f}" for arm in c.ARMS for f in FIELDS)
        self.units = own_units(self.names, parts.units.robot_type)  # metres and radians
        self.moved = hand_moved(self.names, ("dx", "dy", "dz"))
        self.tools = np.zeros((len(c.ARMS), 4))  # each hand's, from `see`

    def see(self, observation: dict[str, Any]) -> None:
        self.tools = np.array(observation["tools"], dtype=np.float64)

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        return to_waypoint(action, self.tools)

    def _delta(self, world: np.ndarray, tools: np.ndarray) -> np.ndarray:
        return to_delta(world, tools, self.reach, self.turn)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return self._delta(self.control.hold(loop), self.tools)

    def expert(self, move: ExpertMove) -> np.ndarray:
        return self._delta(self.control.expert(move.loop), self.tools)

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        tools = self.tools.copy()  # the hands this action was given from: a new step sees others
        return to_waypoint(action, tools), partial(self._delta, tools=tools)
