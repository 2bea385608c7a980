"""The environment's `action_mode="absolute"`: each hand's pose in the world frame (x, y, z,
yaw) and its finger gap, as robomimic's absolute pose controller takes it (the form Diffusion
Policy trains on). The continuous track: each step's target is near the hand, and nothing in
the action is copied from the observation.

A target is bounded as the `delta` mode's change is: at most a step and a half of the hand's
travel (of its turn in yaw) from the hand as measured at the step's start, the rest of the way
cut off. The expert's label is the bounded target itself, so a policy learns where the hand
goes this step, in the world. Unlike a delta, an error in one target of a chunk is not carried
into the next: each target is a place, not a change from the last."""

from __future__ import annotations

from functools import partial

import numpy as np

from ...physics.loop import BuildLoop
from ..task.lerobot_units import own_units
from .delta import DeltaMode, to_delta, to_waypoint
from .hand_mode import hand_moved
from .mode import ExpertMove, ModeParts, Waypoints
from .waypoint import FIELDS


class AbsoluteMode(DeltaMode):
    """The `delta` mode's bound and controller, its actions the bounded target in the world:
    the waypoint mode's space and entries."""

    fields = FIELDS

    def __init__(self, parts: ModeParts) -> None:
        super().__init__(parts)
        self.space = self.control.space
        self.names = self.control.names
        self.units = own_units(self.names, parts.units.robot_type)  # metres and radians
        self.moved = hand_moved(self.names, ("x", "y", "z"))

    def _bounded(self, world: np.ndarray, tools: np.ndarray) -> np.ndarray:
        """`world`'s waypoints cut to the bound from the hands at `tools` (float32)."""
        return to_waypoint(to_delta(world, tools, self.reach, self.turn), tools).astype(np.float32)

    def target(self, action: np.ndarray, state: np.ndarray) -> np.ndarray:
        return self._bounded(action, self.tools)

    def held(self, loop: BuildLoop, state: np.ndarray) -> np.ndarray:
        return self._bounded(self.control.hold(loop), self.tools)

    def expert(self, move: ExpertMove) -> np.ndarray:
        return self._bounded(self.control.expert(move.loop), self.tools)

    def waypoints(self, action: np.ndarray) -> Waypoints | None:
        tools = self.tools.copy()  # the hands this action was given from: a new step sees others
        return self._bounded(action, tools), partial(self._bounded, tools=tools)
